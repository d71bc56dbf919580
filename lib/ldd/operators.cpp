#include "ldd/operators.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "core/errors.hpp"

namespace hm::ldd {
namespace {

/// Number of unknowns of the second-order fit: gradient + upper Hessian.
template <int D>
constexpr int wls_size = D + D*(D + 1) / 2;

/// Monomials of the second-order fit at s = r/h: s_a, then ½ s_a² (a = 0..D−1), then s_a s_b (a<b).
template <int D>
Eigen::Matrix<double, wls_size<D>, 1> wls_basis(const Vec<D>& s) {
  Eigen::Matrix<double, wls_size<D>, 1> p;
  int k = 0;
  for (int a = 0; a < D; ++a) p[k++] = s[a];
  for (int a = 0; a < D; ++a) p[k++] = 0.5 * s[a] * s[a];
  for (int a = 0; a < D; ++a)
    for (int b = a + 1; b < D; ++b) p[k++] = s[a] * s[b];
  return p;
}

/// ω_j of a weight list (Operators::weight), 1 when the list is empty.
double weight_at(std::span<const double> omega, Index j) {
  return omega.empty() ? 1.0 : omega[j];
}

/// Per-thread scratch of compute_operators, kept across its points: a row's kernel weights
/// ω_j W_ij from its first pass (eq. 7 and the clamped eq. 7 read them) and the WLS fit's
/// weights and monomials (its coefficients read them): no second square root a pair.
template <int D>
struct RowScratch {
  std::vector<double> kernel, fit_weight;
  std::vector<Eigen::Matrix<double, wls_size<D>, 1>> monomials;
};

/// Second-order WLS Laplacian coefficients of point i into c (false if the fit is singular).
template <int D>
bool wls_laplacian(std::span<const Vec<D>> x, std::span<const Index> nbr, Index i, double h,
                   std::span<const double> omega, RowScratch<D>& scratch, double* c) {
  constexpr int K = wls_size<D>;
  if (static_cast<int>(nbr.size()) < K) return false;
  scratch.fit_weight.resize(nbr.size());
  scratch.monomials.resize(nbr.size());
  // The normal matrix's lower triangle, the one the Cholesky factorisation reads (each entry
  // the product the full outer product forms: (w p_a) p_b).
  Eigen::Matrix<double, K, K> G = Eigen::Matrix<double, K, K>::Zero();
  for (std::size_t k = 0; k < nbr.size(); ++k) {
    const Vec<D> s = (x[nbr[k]] - x[i]) / h;
    const auto p = wls_basis<D>(s);
    const double w = weight_at(omega, nbr[k]) * wendland_c2(s.norm());
    scratch.fit_weight[k] = w;
    scratch.monomials[k] = p;
    const Eigen::Matrix<double, K, 1> wp = w * p;
    for (int b = 0; b < K; ++b)
      for (int a = b; a < K; ++a) G(a, b) += wp[a] * p[b];
  }
  Eigen::Matrix<double, K, 1> e = Eigen::Matrix<double, K, 1>::Zero();
  e.template segment<D>(D).setOnes();  // ∇²f = Σ_a H_aa = Σ_a coefficient of ½ s_a², / h²
  // Cholesky; a pivot ratio below 1e-6 (condition ≳ 1e12) means the stencil cannot resolve
  // every second derivative (points on a line or plane): no fit.
  const Eigen::LLT<Eigen::Matrix<double, K, K>, Eigen::Lower> llt(G);
  if (llt.info() != Eigen::Success) return false;
  const auto pivots = llt.matrixLLT().diagonal();
  if (pivots.minCoeff() < 1e-6 * pivots.maxCoeff()) return false;
  const Eigen::Matrix<double, K, 1> y = llt.solve(e);
  for (std::size_t k = 0; k < nbr.size(); ++k)
    c[k] = scratch.fit_weight[k] * y.dot(scratch.monomials[k]) / (h * h);
  return true;
}

/// Eq. 7 coefficients of point i into c from each pair's kernel weight ω_j W_ij in `kernel`;
/// returns whether a modified weight was negative.
template <int D>
bool offset_laplacian(std::span<const Vec<D>> x, std::span<const Index> nbr, Index i,
                      const Vec<D>& Bo, std::span<const double> kernel, double* c) {
  double denominator = 0.0;
  bool negative = false;
  for (std::size_t k = 0; k < nbr.size(); ++k) {
    const Vec<D> r = x[nbr[k]] - x[i];
    const double w = kernel[k] * (1.0 - r.dot(Bo));
    negative = negative || w < 0.0;
    c[k] = w;
    denominator += w * r.squaredNorm();
  }
  // D_i is negative on strongly one-sided stencils (most modified weights negative); eq. 7 stays
  // exact for |r|² as long as D_i ≠ 0. Zero only on a degenerate stencil: the row stays zero.
  const double scale = denominator != 0.0 ? 2.0 * D / denominator : 0.0;
  for (std::size_t k = 0; k < nbr.size(); ++k) c[k] *= scale;
  return negative;
}

/// Eq. 7 with the modified weights clamped at zero and D_i recomputed (§1.7.2 option b): every
/// c_ij ≥ 0, so the row is diagonally dominant, at first-order accuracy. `kernel` holds each
/// pair's ω_j W_ij.
template <int D>
void clamped_offset_laplacian(std::span<const Vec<D>> x, std::span<const Index> nbr, Index i,
                              const Vec<D>& Bo, std::span<const double> kernel, double* c) {
  double denominator = 0.0;
  for (std::size_t k = 0; k < nbr.size(); ++k) {
    const Vec<D> r = x[nbr[k]] - x[i];
    const double w = std::max(0.0, kernel[k] * (1.0 - r.dot(Bo)));
    c[k] = w;
    denominator += w * r.squaredNorm();
  }
  const double scale = denominator > 0.0 ? 2.0 * D / denominator : 0.0;
  for (std::size_t k = 0; k < nbr.size(); ++k) c[k] *= scale;
}

/// Diagonal dominance of a Laplacian row: |Σ c_ij| / Σ |c_ij| (1 when every c_ij ≥ 0).
double dominance(const double* c, std::size_t n) {
  double sum = 0.0, absolute = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    sum += c[k];
    absolute += std::abs(c[k]);
  }
  return absolute > 0.0 ? std::abs(sum) / absolute : 1.0;
}

}  // namespace

template <int D>
Operators<D> compute_operators(std::span<const Vec<D>> x, const Neighbours& nb,
                               const OperatorOptions& opt, std::span<const double> omega) {
  const Index n = nb.points();
  HM_ASSERT(static_cast<std::size_t>(n) == x.size(), "operators: {} lists for {} points", n,
            x.size());
  const double h = nb.radius;
  const int min_neighbours = opt.min_neighbours > 0 ? opt.min_neighbours : (D == 2 ? 4 : 10);
  Operators<D> ops;
  ops.radius = h;
  ops.renormalisation.assign(static_cast<std::size_t>(n), Mat<D>::Zero());
  ops.offset.assign(static_cast<std::size_t>(n), Vec<D>::Zero());
  ops.number_density.assign(static_cast<std::size_t>(n), 0.0);
  ops.offset_ratio.assign(static_cast<std::size_t>(n), 0.0);
  ops.lambda_min.assign(static_cast<std::size_t>(n), 0.0);
  ops.flags.assign(static_cast<std::size_t>(n), 0);
  ops.laplacian.assign(nb.indices.size(), 0.0);
  HM_ASSERT(omega.empty() || omega.size() == x.size(), "operators: {} weights for {} points",
            omega.size(), x.size());
  ops.weight.assign(omega.begin(), omega.end());

  RowScratch<D> scratch;
#pragma omp parallel for schedule(dynamic, 128) firstprivate(scratch)
  for (Index i = 0; i < n; ++i) {
    const auto nbr = nb.of(i);
    double* c = ops.laplacian.data() + nb.offsets[i];  // the row's Laplacian coefficients
    scratch.kernel.resize(nbr.size());
    Mat<D> A = Mat<D>::Zero();
    Vec<D> o = Vec<D>::Zero();
    double density = 0.0, moment = 0.0;
    for (std::size_t k = 0; k < nbr.size(); ++k) {
      const Vec<D> r = x[nbr[k]] - x[i];
      const double d = r.norm(), w = ops.weight_of(nbr[k]) * wendland_c2(d / h);
      scratch.kernel[k] = w;
      A.noalias() += w * r * r.transpose();
      o += w * r;
      density += w;
      moment += w * d;
    }
    ops.number_density[i] = density;
    ops.offset[i] = o;
    ops.offset_ratio[i] = moment > 0.0 ? o.norm() / moment : 1.0;
    if (static_cast<int>(nbr.size()) < min_neighbours || A.trace() <= 0.0) {
      ops.flags[i] = op_isolated;  // no Laplacian: its coefficients stay zero
      continue;
    }
    const Mat<D> M = D * A / A.trace();
    // The closed form of a 2×2 / 3×3 symmetric matrix's eigenvalues: M's are in [0, D], and
    // only the smallest's place against λ_c matters (the iterative solver cost 2 % of a step).
    Eigen::SelfAdjointEigenSolver<Mat<D>> eigen;
    eigen.computeDirect(M, Eigen::EigenvaluesOnly);
    const double lambda = eigen.eigenvalues()[0];
    ops.lambda_min[i] = lambda;
    std::uint8_t flags = 0;
    if (lambda < opt.lambda_c) {
      flags |= op_degenerate;
      ops.renormalisation[i] = (A + opt.lambda_c * A.trace() / D * Mat<D>::Identity()).inverse();
    } else {
      ops.renormalisation[i] = A.inverse();
    }
    if (offset_laplacian<D>(x, nbr, i, ops.renormalisation[i] * o, scratch.kernel, c))
      flags |= op_negative;
    const bool want_wls = opt.laplacian == LaplacianScheme::wls_everywhere ||
                          (opt.laplacian == LaplacianScheme::wls_where_needed &&
                           ((flags & op_negative) || ops.offset_ratio[i] > opt.one_sided_offset));
    if (want_wls && wls_laplacian<D>(x, nbr, i, h, omega, scratch, c)) flags |= op_wls;
    // A row whose diagonal −Σc_ij is small against Σ|c_ij| (eq. 7 with D_i ≤ 0, a WLS fit on a
    // lopsided stencil, or eq. 7 with negative weights where the WLS fit failed) can make the
    // PPE locally near-singular: the K&O dam break at L/40 reached 10⁸ Pa and blew up from such
    // rows after the impact. Those rows take the clamped eq. 7 [CHOICE].
    const bool weak = opt.min_dominance > 0.0 && (dominance(c, nbr.size()) < opt.min_dominance ||
                                                  ((flags & op_negative) && !(flags & op_wls)));
    if (weak && !nbr.empty()) {
      clamped_offset_laplacian<D>(x, nbr, i, ops.renormalisation[i] * o, scratch.kernel, c);
      flags = static_cast<std::uint8_t>((flags & ~op_wls) | op_clamped);
    }
    ops.flags[i] = flags;
  }
  return ops;
}

template <int D>
std::vector<Vec<D>> gradient(std::span<const Vec<D>> x, const Neighbours& nb,
                             const Operators<D>& ops, std::span<const double> f) {
  const Index n = nb.points();
  std::vector<Vec<D>> g(static_cast<std::size_t>(n), Vec<D>::Zero());
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    if (ops.isolated(i)) continue;
    Vec<D> s = Vec<D>::Zero();
    for (Index j : nb.of(i)) {
      const Vec<D> r = x[j] - x[i];
      s += ops.weight_of(j) * wendland_c2(r.norm() / ops.radius) * (f[j] - f[i]) * r;
    }
    g[i] = ops.renormalisation[i] * s;
  }
  return g;
}

template <int D>
std::vector<double> divergence(std::span<const Vec<D>> x, const Neighbours& nb,
                               const Operators<D>& ops, std::span<const Vec<D>> u) {
  const Index n = nb.points();
  std::vector<double> div(static_cast<std::size_t>(n), 0.0);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    if (ops.isolated(i)) continue;
    Mat<D> grad = Mat<D>::Zero();  // Σ W (u_j − u_i) ⊗ r, then ∇·u = tr(grad B)
    for (Index j : nb.of(i)) {
      const Vec<D> r = x[j] - x[i];
      grad.noalias() +=
          ops.weight_of(j) * wendland_c2(r.norm() / ops.radius) * (u[j] - u[i]) * r.transpose();
    }
    div[i] = (grad * ops.renormalisation[i]).trace();
  }
  return div;
}

template <int D>
std::vector<Mat<D>> slip_velocity_gradient(const PointSet<D>& pts, const Neighbours& nb,
                                           const Operators<D>& ops, std::span<const Vec<D>> u) {
  const Index n = nb.points();
  std::vector<Mat<D>> grad(static_cast<std::size_t>(n), Mat<D>::Zero());
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    if (ops.isolated(i) || pts.kind[i] == PointKind::wall) continue;
    Mat<D> s = Mat<D>::Zero();  // Σ W (u_j − u_i) ⊗ r, then ∇u = s B
    for (Index j : nb.of(i)) {
      const Vec<D> r = pts.position[j] - pts.position[i];
      Vec<D> du = u[j] - u[i];
      if (pts.kind[j] == PointKind::wall) du = pts.wall_normal[j].dot(du) * pts.wall_normal[j];
      s.noalias() += ops.weight_of(j) * wendland_c2(r.norm() / ops.radius) * du * r.transpose();
    }
    grad[i] = s * ops.renormalisation[i];
  }
  return grad;
}

template <int D>
std::vector<double> laplacian(const Neighbours& nb, const Operators<D>& ops,
                              std::span<const double> f) {
  const Index n = nb.points();
  std::vector<double> lap(static_cast<std::size_t>(n), 0.0);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    double s = 0.0;
    for (auto k = nb.offsets[i]; k < nb.offsets[i + 1]; ++k)
      s += ops.laplacian[static_cast<std::size_t>(k)] * (f[nb.indices[k]] - f[i]);
    lap[i] = s;
  }
  return lap;
}

template Operators<2> compute_operators<2>(std::span<const Vec<2>>, const Neighbours&,
                                           const OperatorOptions&, std::span<const double>);
template Operators<3> compute_operators<3>(std::span<const Vec<3>>, const Neighbours&,
                                           const OperatorOptions&, std::span<const double>);
template std::vector<Vec<2>> gradient<2>(std::span<const Vec<2>>, const Neighbours&,
                                         const Operators<2>&, std::span<const double>);
template std::vector<Vec<3>> gradient<3>(std::span<const Vec<3>>, const Neighbours&,
                                         const Operators<3>&, std::span<const double>);
template std::vector<Mat<2>> slip_velocity_gradient<2>(const PointSet<2>&, const Neighbours&,
                                                       const Operators<2>&,
                                                       std::span<const Vec<2>>);
template std::vector<Mat<3>> slip_velocity_gradient<3>(const PointSet<3>&, const Neighbours&,
                                                       const Operators<3>&,
                                                       std::span<const Vec<3>>);
template std::vector<double> divergence<2>(std::span<const Vec<2>>, const Neighbours&,
                                           const Operators<2>&, std::span<const Vec<2>>);
template std::vector<double> divergence<3>(std::span<const Vec<3>>, const Neighbours&,
                                           const Operators<3>&, std::span<const Vec<3>>);
template std::vector<double> laplacian<2>(const Neighbours&, const Operators<2>&,
                                          std::span<const double>);
template std::vector<double> laplacian<3>(const Neighbours&, const Operators<3>&,
                                          std::span<const double>);

}  // namespace hm::ldd
