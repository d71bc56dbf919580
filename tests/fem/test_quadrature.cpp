// Quadrature rules integrate every monomial up to their stated degree exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "fem/quadrature.hpp"

namespace hm::fem {
namespace {

double factorial(int n) {
  return std::tgamma(n + 1.0);
}

double integrate(const QuadratureRule& rule, int a, int b, int c) {
  double sum = 0.0;
  for (std::size_t p = 0; p < rule.points.size(); ++p)
    sum += rule.weights[p] * std::pow(rule.points[p].x(), a) * std::pow(rule.points[p].y(), b) *
           std::pow(rule.points[p].z(), c);
  return sum;
}

TEST(Quadrature, TriangleRulesExactToTheirDegree) {
  for (int degree : {2, 4}) {
    const QuadratureRule& rule = triangle_rule(degree);
    EXPECT_GE(rule.degree, degree);
    for (double w : rule.weights) EXPECT_GT(w, 0.0);
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b) {
        const double exact = factorial(a) * factorial(b) / factorial(a + b + 2);
        EXPECT_NEAR(integrate(rule, a, b, 0), exact, 1e-15) << "x^" << a << " y^" << b;
      }
  }
}

TEST(Quadrature, TetrahedronRulesExactToTheirDegree) {
  for (int degree : {2, 4}) {
    const QuadratureRule& rule = tetrahedron_rule(degree);
    const int checked = rule.degree;  // the degree-4 request returns a degree-5 rule
    EXPECT_GE(checked, degree);
    for (double w : rule.weights) EXPECT_GT(w, 0.0);
    for (int a = 0; a <= checked; ++a)
      for (int b = 0; a + b <= checked; ++b)
        for (int c = 0; a + b + c <= checked; ++c) {
          const double exact =
              factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 3);
          EXPECT_NEAR(integrate(rule, a, b, c), exact, 1e-15)
              << "x^" << a << " y^" << b << " z^" << c;
        }
  }
}

}  // namespace
}  // namespace hm::fem
