#pragma once
// Point sets for the RBF tests (rows are points, metres).
#include <cmath>
#include <numbers>
#include <random>

#include "rbf/point_cloud.hpp"

namespace hm::rbf::test {

/// n quasi-uniform points on the sphere of radius r (Fibonacci lattice), rotated by `twist` rad
/// about z so that two lattices of equal size do not coincide.
inline Points fibonacci_sphere(Eigen::Index n, double r = 1.0, double twist = 0.0) {
  Points x(n, 3);
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (Eigen::Index i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (static_cast<double>(i) + 0.5) / static_cast<double>(n);
    const double rho = std::sqrt(1.0 - z * z), phi = golden * static_cast<double>(i) + twist;
    x.row(i) << r * rho * std::cos(phi), r * rho * std::sin(phi), r * z;
  }
  return x;
}

/// m × m grid on [0, L]², jittered by up to `jitter` × spacing, embedded in the plane z = z0 (3-D)
/// or returned as 2-D points.
inline Points jittered_grid(Eigen::Index m, double L, double jitter, int dim, double z0 = 0.0,
                            unsigned seed = 1) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double h = L / static_cast<double>(m - 1);
  Points x(m * m, dim);
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j) {
      const Eigen::Index k = i * m + j;
      x(k, 0) = static_cast<double>(i) * h + jitter * h * u(gen);
      x(k, 1) = static_cast<double>(j) * h + jitter * h * u(gen);
      if (dim == 3) x(k, 2) = z0;
    }
  return x;
}

/// n random points uniformly in [lo, hi]^dim.
inline Points random_box(Eigen::Index n, int dim, double lo, double hi, unsigned seed = 7) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  Points x(n, dim);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int k = 0; k < dim; ++k) x(i, k) = u(gen);
  return x;
}

}  // namespace hm::rbf::test
