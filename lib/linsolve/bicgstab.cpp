#include "linsolve/bicgstab.hpp"

#include <cmath>
#include <limits>

namespace hm::linsolve {
namespace {

using Matrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

/// (A v)_i for row i.
inline double row_times(const Matrix& a, const Eigen::VectorXd& v, Eigen::Index i) {
  double s = 0.0;
  const int* col = a.innerIndexPtr();
  const double* val = a.valuePtr();
  for (int k = a.outerIndexPtr()[i]; k < a.outerIndexPtr()[i + 1]; ++k) s += val[k] * v[col[k]];
  return s;
}

}  // namespace

BicgstabResult bicgstab(const Matrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                        double tolerance, int max_iterations) {
  const Eigen::Index n = b.size();
  BicgstabResult out;
  Eigen::VectorXd r(n), r_hat(n), p(n), v(n), s(n), t(n);
  double b2 = 0.0, r2 = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : b2, r2)
  for (Eigen::Index i = 0; i < n; ++i) {
    r[i] = b[i] - row_times(a, x, i);
    r_hat[i] = r[i];
    p[i] = v[i] = 0.0;
    b2 += b[i] * b[i];
    r2 += r[i] * r[i];
  }
  if (b2 == 0.0) {
    x.setZero();
    out.converged = true;
    return out;
  }
  const double threshold2 = tolerance * tolerance * b2;
  const double eps2 =
      std::numeric_limits<double>::epsilon() * std::numeric_limits<double>::epsilon();
  double rho = 1.0, alpha = 1.0, omega = 1.0, rho_new = r2, r0_2 = r2;
  while (r2 > threshold2 && out.iterations < max_iterations) {
    if (std::abs(rho_new) < eps2 * r0_2) {  // r̂ ⟂ r: restart the shadow residual
      r0_2 = r2;
      rho_new = r2;
#pragma omp parallel for schedule(static)
      for (Eigen::Index i = 0; i < n; ++i) r_hat[i] = r[i];
    }
    const double beta = (rho_new / rho) * (alpha / omega);
    rho = rho_new;
    double rv = 0.0;
#pragma omp parallel for schedule(static)
    for (Eigen::Index i = 0; i < n; ++i) p[i] = r[i] + beta * (p[i] - omega * v[i]);
#pragma omp parallel for schedule(static) reduction(+ : rv)
    for (Eigen::Index i = 0; i < n; ++i) {
      v[i] = row_times(a, p, i);
      rv += r_hat[i] * v[i];
    }
    alpha = rho / rv;
    double s2 = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : s2)
    for (Eigen::Index i = 0; i < n; ++i) {
      s[i] = r[i] - alpha * v[i];
      s2 += s[i] * s[i];
    }
    double ts = 0.0, tt = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : ts, tt)
    for (Eigen::Index i = 0; i < n; ++i) {
      t[i] = row_times(a, s, i);
      ts += t[i] * s[i];
      tt += t[i] * t[i];
    }
    omega = tt > 0.0 ? ts / tt : 0.0;
    r2 = 0.0;
    rho_new = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : r2, rho_new)
    for (Eigen::Index i = 0; i < n; ++i) {
      x[i] += alpha * p[i] + omega * s[i];
      r[i] = s[i] - omega * t[i];
      r2 += r[i] * r[i];
      rho_new += r_hat[i] * r[i];
    }
    ++out.iterations;
    if (!std::isfinite(r2) || omega == 0.0) break;  // breakdown
  }
  out.residual = std::sqrt(r2 / b2);
  out.converged = std::isfinite(r2) && r2 <= threshold2;
  return out;
}

}  // namespace hm::linsolve
