#pragma once
// Point clouds for the LDD tests: lattices in boxes, jittered with a fixed seed.
#include <cmath>
#include <random>
#include <vector>

#include "ldd/common.hpp"

namespace hm::ldd::test {

/// Lattice points lo + (k + ½)dx inside [lo, hi] (cell centres), each coordinate jittered by a
/// uniform random amount in [−jitter·dx, jitter·dx].
template <int D>
std::vector<Vec<D>> lattice(const Vec<D>& lo, const Vec<D>& hi, double dx, double jitter = 0.0,
                            unsigned seed = 1) {
  Eigen::Matrix<int, D, 1> n;
  for (int a = 0; a < D; ++a) n[a] = static_cast<int>(std::floor((hi[a] - lo[a]) / dx + 1e-9));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * dx, jitter * dx);
  std::vector<Vec<D>> x;
  Eigen::Matrix<int, D, 1> k = Eigen::Matrix<int, D, 1>::Zero();
  while (true) {
    Vec<D> p;
    for (int a = 0; a < D; ++a) p[a] = lo[a] + (k[a] + 0.5) * dx + (jitter > 0 ? u(rng) : 0.0);
    x.push_back(p);
    int a = 0;
    while (a < D && ++k[a] == n[a]) k[a++] = 0;
    if (a == D) break;
  }
  return x;
}

/// Distance from x to the boundary of the box [lo, hi] (x inside).
template <int D>
double depth_in_box(const Vec<D>& x, const Vec<D>& lo, const Vec<D>& hi) {
  return std::min((x - lo).minCoeff(), (hi - x).minCoeff());
}

/// Least-squares slope of log(error) against log(spacing): the observed order.
inline double observed_order(const std::vector<double>& spacing, const std::vector<double>& error) {
  double mx = 0, my = 0;
  const double n = static_cast<double>(spacing.size());
  for (std::size_t k = 0; k < spacing.size(); ++k) {
    mx += std::log(spacing[k]) / n;
    my += std::log(error[k]) / n;
  }
  double sxy = 0, sxx = 0;
  for (std::size_t k = 0; k < spacing.size(); ++k) {
    sxy += (std::log(spacing[k]) - mx) * (std::log(error[k]) - my);
    sxx += (std::log(spacing[k]) - mx) * (std::log(spacing[k]) - mx);
  }
  return sxy / sxx;
}

}  // namespace hm::ldd::test
