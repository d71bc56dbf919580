#pragma once
// Shared checks of the mode tests: the invariants every solve must satisfy (checked before any
// comparison with a reference, STYLE item 8) and the Timoshenko cantilever oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <unsupported/Eigen/MatrixFunctions>

#include "modal/modes.hpp"

namespace hm::modal::testing {

constexpr double kResidualLimit = 1e-8;
constexpr double kOrthogonalityLimit = 1e-10;

/// Converged, sorted, mass-orthonormal, small residuals, signs as documented.
inline void expect_mode_invariants(const ModeSet& modes) {
  EXPECT_EQ(modes.solver.status, "converged") << modes.solver.message;
  ASSERT_GT(modes.count(), 0);
  for (int i = 0; i < modes.count(); ++i) {
    EXPECT_LE(modes.residuals(i), kResidualLimit) << "mode " << i;
    if (i > 0) {
      EXPECT_LE(modes.eigenvalues(i - 1), modes.eigenvalues(i));
    }
    const Eigen::VectorXd phi = modes.shapes.col(i);
    const double largest = phi.cwiseAbs().maxCoeff();
    Eigen::Index first = 0;
    while (std::abs(phi(first)) < (1.0 - 1e-8) * largest) ++first;
    EXPECT_GT(phi(first), 0.0) << "sign convention of mode " << i;
  }
  EXPECT_LE(modes.orthogonality_error, kOrthogonalityLimit);
}

/// Non-dimensional natural frequencies Ω = ωL²√(ρA/EI) of a clamped-free Timoshenko beam with
/// r² = I/(AL²) (rotary inertia) and s² = EI/(κGAL²) (shear flexibility): the roots of the
/// 2×2 minor of the transfer matrix exp(A L) of the state (w/L, ψ, ML/EI, VL²/EI) that maps the
/// clamped-end unknowns (M₀, V₀) to the free-end conditions M(L) = V(L) = 0.
inline double timoshenko_determinant(double omega, double r2, double s2) {
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  const double o2 = omega * omega;
  a(0, 1) = 1.0;
  a(0, 3) = s2;
  a(1, 2) = 1.0;
  a(2, 3) = -1.0;
  a(2, 1) = -o2 * r2;
  a(3, 0) = -o2;
  const Eigen::Matrix4d t = a.exp();
  return t(2, 2) * t(3, 3) - t(2, 3) * t(3, 2);
}

inline std::vector<double> timoshenko_cantilever_roots(double r2, double s2, int count) {
  std::vector<double> roots;
  const double step = 0.01;
  double lo = step, f_lo = timoshenko_determinant(lo, r2, s2);
  while (static_cast<int>(roots.size()) < count) {
    const double hi = lo + step, f_hi = timoshenko_determinant(hi, r2, s2);
    if (f_lo * f_hi < 0.0) {
      double a = lo, b = hi, fa = f_lo;
      for (int it = 0; it < 200 && b - a > 1e-14 * b; ++it) {
        const double m = 0.5 * (a + b), fm = timoshenko_determinant(m, r2, s2);
        if (fa * fm <= 0.0) {
          b = m;
        } else {
          a = m;
          fa = fm;
        }
      }
      roots.push_back(0.5 * (a + b));
    }
    lo = hi;
    f_lo = f_hi;
  }
  return roots;
}

}  // namespace hm::modal::testing
