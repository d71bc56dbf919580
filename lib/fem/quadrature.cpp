#include "fem/quadrature.hpp"

#include <cmath>

#include "core/errors.hpp"

namespace hm::fem {
namespace {

/// Adds the points of a fully symmetric orbit given by its barycentric coordinates.
void add_triangle_orbit(QuadratureRule& rule, double a, double w) {
  const double b = 1.0 - 2.0 * a;
  if (std::abs(a - b) < 1e-15) {  // centroid
    rule.points.emplace_back(a, a, 0.0);
    rule.weights.push_back(w);
    return;
  }
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(a, a, 0), Eigen::Vector3d(b, a, 0), Eigen::Vector3d(a, b, 0)}) {
    rule.points.push_back(p);
    rule.weights.push_back(w);
  }
}

/// Orbit of barycentric (a, a, a, 1−3a): 4 points.
void add_tet_orbit4(QuadratureRule& rule, double a, double w) {
  const double b = 1.0 - 3.0 * a;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(a, a, a), Eigen::Vector3d(b, a, a),
                                   Eigen::Vector3d(a, b, a), Eigen::Vector3d(a, a, b)}) {
    rule.points.push_back(p);
    rule.weights.push_back(w);
  }
}

/// Orbit of barycentric (a, a, b, b) with b = 1/2 − a: 6 points.
void add_tet_orbit6(QuadratureRule& rule, double a, double w) {
  const double b = 0.5 - a;
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(a, a, b), Eigen::Vector3d(a, b, a), Eigen::Vector3d(b, a, a),
        Eigen::Vector3d(b, b, a), Eigen::Vector3d(b, a, b), Eigen::Vector3d(a, b, b)}) {
    rule.points.push_back(p);
    rule.weights.push_back(w);
  }
}

QuadratureRule make_triangle_degree2() {
  QuadratureRule rule;
  rule.degree = 2;
  add_triangle_orbit(rule, 1.0 / 6.0, 1.0 / 6.0);
  return rule;
}

QuadratureRule make_triangle_degree4() {
  QuadratureRule rule;
  rule.degree = 4;
  add_triangle_orbit(rule, 0.445948490915964886, 0.223381589678011466 / 2);
  add_triangle_orbit(rule, 0.091576213509770743, 0.109951743655321868 / 2);
  return rule;
}

QuadratureRule make_tet_degree2() {
  QuadratureRule rule;
  rule.degree = 2;
  add_tet_orbit4(rule, (5.0 - std::sqrt(5.0)) / 20.0, 1.0 / 24.0);
  return rule;
}

QuadratureRule make_tet_degree5() {
  QuadratureRule rule;
  rule.degree = 5;
  add_tet_orbit4(rule, 0.0927352503108912264, 0.0122488405193936582);
  add_tet_orbit4(rule, 0.310885919263300610, 0.0187813209530026417);
  add_tet_orbit6(rule, 0.0455037041256496494, 0.00709100346284691107);
  return rule;
}

}  // namespace

const QuadratureRule& triangle_rule(int degree) {
  static const QuadratureRule degree2 = make_triangle_degree2();
  static const QuadratureRule degree4 = make_triangle_degree4();
  HM_ASSERT(degree >= 0 && degree <= 4, "no triangle rule of degree {}", degree);
  return degree <= 2 ? degree2 : degree4;
}

const QuadratureRule& tetrahedron_rule(int degree) {
  static const QuadratureRule degree2 = make_tet_degree2();
  static const QuadratureRule degree5 = make_tet_degree5();
  HM_ASSERT(degree >= 0 && degree <= 5, "no tetrahedron rule of degree {}", degree);
  return degree <= 2 ? degree2 : degree5;
}

}  // namespace hm::fem
