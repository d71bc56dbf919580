#include "fem/reduced_stvk.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <vector>

#include <cblas.h>
#include <Eigen/Cholesky>

#include "core/errors.hpp"

namespace hm::fem {
namespace {

using mesh::Index;

/// Engineering-strain Voigt vector of sym(X) in the order of material.hpp: X_II on the
/// diagonal, X_IJ + X_JI off it.
template <int D>
Eigen::Matrix<double, D == 2 ? 3 : 6, 1> strain_voigt(const Eigen::Matrix<double, D, D>& x) {
  if constexpr (D == 2) {
    return {x(0, 0), x(1, 1), x(0, 1) + x(1, 0)};
  } else {
    Eigen::Matrix<double, 6, 1> v;
    v << x(0, 0), x(1, 1), x(2, 2), x(1, 2) + x(2, 1), x(0, 2) + x(2, 0), x(0, 1) + x(1, 0);
    return v;
  }
}

/// Column of the pair (j, k), j ≤ k, among the r(r+1)/2 pairs in lexicographic order.
Eigen::Index pair_column(Eigen::Index r, Eigen::Index j, Eigen::Index k) {
  if (j > k) std::swap(j, k);
  return j * r - j * (j - 1) / 2 + (k - j);
}

/// The factors of G of one cell's quadrature points: for each point √w·Cᵀ[L_j, Q_jk] (Voigt,
/// ℂ₀ = CCᵀ by Cholesky), stored transposed (m × voigt per point) into `out` from column `at`
/// on, so that G = Σ out·outᵀ. Returns the next free column.
template <int D>
Eigen::Index cell_columns(const HyperelasticBody& body, const Eigen::MatrixXd& basis,
                          const Eigen::MatrixXd& c_factor, Index cell, Eigen::MatrixXd& out,
                          Eigen::Index at) {
  constexpr int V = D == 2 ? 3 : 6;
  const mesh::StructureMesh& mesh = body.mesh();
  const Eigen::Index r = basis.cols();
  const int nodes = mesh.nodes_per_cell();
  // The cell's rows of V, per component i: nodes × r.
  std::array<Eigen::MatrixXd, D> local;
  for (int i = 0; i < D; ++i) {
    local[static_cast<std::size_t>(i)].resize(nodes, r);
    for (int a = 0; a < nodes; ++a)
      local[static_cast<std::size_t>(i)].row(a) = basis.row(D * mesh.cells(cell, a) + i);
  }
  std::vector<Eigen::Matrix<double, D, D>> h(static_cast<std::size_t>(r));
  Eigen::Matrix<double, V, Eigen::Dynamic> z(V, r + r * (r + 1) / 2);
  for (const HyperelasticBody::QuadraturePoint& point :
       body.quadrature()[static_cast<std::size_t>(cell)]) {
    // H_j(i, J) = Σ_a V_j(a, i) ∂N_a/∂X_J.
    for (int i = 0; i < D; ++i) {
      const Eigen::MatrixXd rows = point.grad.transpose() * local[static_cast<std::size_t>(i)];
      for (Eigen::Index j = 0; j < r; ++j) h[static_cast<std::size_t>(j)].row(i) = rows.col(j);
    }
    for (Eigen::Index j = 0; j < r; ++j) {
      const auto& hj = h[static_cast<std::size_t>(j)];
      z.col(j) = strain_voigt<D>(hj);
      for (Eigen::Index k = j; k < r; ++k)
        z.col(r + pair_column(r, j, k)) = strain_voigt<D>(
            Eigen::Matrix<double, D, D>(hj.transpose() * h[static_cast<std::size_t>(k)]));
    }
    out.middleCols(at, V).noalias() = std::sqrt(point.weight) * z.transpose() * c_factor;
    at += V;
  }
  return at;
}

/// gram += A·Aᵀ (lower triangle) with A the first `columns` columns of `a`. BLAS dsyrk rather than
/// Eigen's rankUpdate: Eigen is built for the baseline x86-64 (SSE2) while OpenBLAS picks the
/// machine's kernels at run time; measured 3.4× faster on this 2-core EPYC (350 × 768 blocks).
void add_rank_update(Eigen::MatrixXd& gram, const Eigen::MatrixXd& a, Eigen::Index columns) {
  if (columns == 0) return;
  const auto n = static_cast<int>(gram.rows()), k = static_cast<int>(columns);
  cblas_dsyrk(CblasColMajor, CblasLower, CblasNoTrans, n, k, 1.0, a.data(),
              static_cast<int>(a.rows()), 1.0, gram.data(), n);
}

/// G = Σ over all cells of the points' Zᵀℂ₀Z·w, returned symmetric (both triangles). In chunks
/// of cells: the chunk's columns built in parallel (OpenMP over its cells, each writing its own
/// columns), then one rank-k update by BLAS, which runs its own threads. The sum's order does
/// not depend on the thread count.
template <int D>
Eigen::MatrixXd gram_matrix(const HyperelasticBody& body, const Eigen::MatrixXd& basis) {
  constexpr int V = D == 2 ? 3 : 6;
  const Eigen::MatrixXd c_factor =
      Eigen::LLT<Eigen::MatrixXd>(body.small_strain_tangent()).matrixL();
  const Eigen::Index r = basis.cols(), m = r + r * (r + 1) / 2;
  const Index cells = body.mesh().cells.rows();
  const auto per_cell =
      static_cast<Eigen::Index>(V * (body.quadrature().empty() ? 0 : body.quadrature()[0].size()));
  constexpr Index kChunk = 256;
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(m, m);
  Eigen::MatrixXd columns(m, kChunk * per_cell);
  for (Index begin = 0; begin < cells; begin += kChunk) {
    const Index count = std::min(kChunk, cells - begin);
#pragma omp parallel for schedule(static)
    for (Index c = 0; c < count; ++c)
      cell_columns<D>(body, basis, c_factor, begin + c, columns, c * per_cell);
    add_rank_update(gram, columns, count * per_cell);
  }
  gram.triangularView<Eigen::StrictlyUpper>() = gram.transpose();
  return gram;
}

/// How many distinct orderings the monomial q_j q_k q_l (j ≤ k ≤ l) has: 6, 3 or 1.
double orderings(int j, int k, int l) {
  if (j == l) return 1.0;
  if (j == k || k == l) return 3.0;
  return 6.0;
}

}  // namespace

ReducedStvk::ReducedStvk(const HyperelasticBody& body, Eigen::MatrixXd basis,
                         std::string_view context)
    : basis_(std::move(basis)) {
  const auto begin = std::chrono::steady_clock::now();
  if (body.model().law != MaterialLaw::saint_venant_kirchhoff)
    input_error(
        "{}: the reduced polynomial model needs the saint_venant_kirchhoff law; the body's law "
        "is {}",
        context, to_string(body.model().law));
  if (basis_.rows() != body.dof_count() || basis_.cols() < 1)
    input_error("{}: a basis of {} × {} is invalid for a body of {} DOFs", context, basis_.rows(),
                basis_.cols(), body.dof_count());
  list_triples();
  coefficients_from(body.dim() == 2 ? gram_matrix<2>(body, basis_) : gram_matrix<3>(body, basis_));
  mass_ = basis_.transpose() * (body.mass() * basis_);
  setup_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
}

ReducedStvk::ReducedStvk(Eigen::MatrixXd basis, Eigen::MatrixXd mass, Eigen::MatrixXd linear,
                         Eigen::MatrixXd quadratic, Eigen::MatrixXd cubic, std::string_view context)
    : basis_(std::move(basis)),
      mass_(std::move(mass)),
      k1_(std::move(linear)),
      k2_(std::move(quadratic)),
      k3_(std::move(cubic)) {
  const Eigen::Index r = basis_.cols();
  const auto fits = [r](const Eigen::MatrixXd& m, Eigen::Index columns) {
    return m.rows() == r && m.cols() == columns;
  };
  if (r < 1 || !fits(mass_, r) || !fits(k1_, r) || !fits(k2_, r * (r + 1) / 2) ||
      !fits(k3_, r * (r + 1) * (r + 2) / 6))
    input_error(
        "{}: reduced tensors of sizes M_r {} × {}, K1 {} × {}, K2 {} × {}, K3 {} × {} do not fit "
        "a basis of {} vectors (r × r, r × r(r+1)/2, r × r(r+1)(r+2)/6)",
        context, mass_.rows(), mass_.cols(), k1_.rows(), k1_.cols(), k2_.rows(), k2_.cols(),
        k3_.rows(), k3_.cols(), r);
  list_triples();
}

void ReducedStvk::list_triples() {
  const int r = static_cast<int>(basis_.cols());
  for (int j = 0; j < r; ++j)
    for (int k = j; k < r; ++k)
      for (int l = k; l < r; ++l) triples_.push_back({j, k, l});
}

Eigen::Index ReducedStvk::pair_index(Eigen::Index j, Eigen::Index k) const {
  return pair_column(size(), j, k);
}

void ReducedStvk::coefficients_from(const Eigen::MatrixXd& gram) {
  const Eigen::Index r = size();
  // ∫ L_i:ℂ:L_j, ∫ L_i:ℂ:Q_jk and ∫ Q_ab:ℂ:Q_cd.
  k1_ = gram.topLeftCorner(r, r);
  auto lq = [&](Eigen::Index i, Eigen::Index j, Eigen::Index k) {
    return gram(i, r + pair_column(r, j, k));
  };
  auto qq = [&](Eigen::Index a, Eigen::Index b, Eigen::Index c, Eigen::Index d) {
    return gram(r + pair_column(r, a, b), r + pair_column(r, c, d));
  };
  // f2_i = ½ Σ_jk T_ijk q_j q_k with T_ijk = ∂³W/∂q_i∂q_j∂q_k = R_i,jk + R_j,ik + R_k,ij.
  k2_.resize(r, r * (r + 1) / 2);
  for (Eigen::Index j = 0; j < r; ++j)
    for (Eigen::Index k = j; k < r; ++k)
      for (Eigen::Index i = 0; i < r; ++i)
        k2_(i, pair_column(r, j, k)) =
            (j == k ? 0.5 : 1.0) * (lq(i, j, k) + lq(j, i, k) + lq(k, i, j));
  // f3_i = (1/6) Σ_jkl U_ijkl q_j q_k q_l with U_ijkl = ∂⁴W/∂q⁴ = P_ij,kl + P_ik,jl + P_il,jk.
  k3_.resize(r, static_cast<Eigen::Index>(triples_.size()));
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const auto [j, k, l] = triples_[t];
    const double weight = orderings(j, k, l) / 6.0;
    for (Eigen::Index i = 0; i < r; ++i)
      k3_(i, static_cast<Eigen::Index>(t)) =
          weight * (qq(i, j, k, l) + qq(i, k, j, l) + qq(i, l, j, k));
  }
}

Eigen::VectorXd ReducedStvk::quadratic_monomials(const Eigen::VectorXd& q) const {
  const Eigen::Index r = size();
  Eigen::VectorXd m(r * (r + 1) / 2);
  Eigen::Index p = 0;
  for (Eigen::Index j = 0; j < r; ++j)
    for (Eigen::Index k = j; k < r; ++k) m[p++] = q[j] * q[k];
  return m;
}

Eigen::VectorXd ReducedStvk::cubic_monomials(const Eigen::VectorXd& q) const {
  Eigen::VectorXd m(static_cast<Eigen::Index>(triples_.size()));
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const auto [j, k, l] = triples_[t];
    m[static_cast<Eigen::Index>(t)] = q[j] * q[k] * q[l];
  }
  return m;
}

ReducedEvaluation ReducedStvk::evaluate(const Eigen::VectorXd& q, bool tangent) const {
  HM_ASSERT(q.size() == size(), "{} reduced coordinates for a basis of {}", q.size(), size());
  const Eigen::VectorXd f1 = k1_ * q, f2 = k2_ * quadratic_monomials(q),
                        f3 = k3_ * cubic_monomials(q);
  ReducedEvaluation out;
  out.force = f1 + f2 + f3;
  // W is the sum of homogeneous parts of degree 2, 3, 4 with gradients f1, f2, f3 (Euler).
  out.strain_energy = q.dot(f1) / 2.0 + q.dot(f2) / 3.0 + q.dot(f3) / 4.0;
  if (!tangent) return out;
  // ∂(q_j q_k)/∂q and ∂(q_j q_k q_l)/∂q, a block of the columns of one leading j (K2) or
  // (j, k) (K3) at a time: the columns of K2 with j fixed run over k = j…r−1, those of K3 with
  // (j, k) fixed over l = k…r−1.
  const Eigen::Index r = size();
  Eigen::MatrixXd t = k1_;
  for (Eigen::Index j = 0, p = 0; j < r; p += r - j, ++j) {
    const auto block = k2_.middleCols(p, r - j);
    t.col(j).noalias() += block * q.segment(j, r - j);
    t.rightCols(r - j) += q[j] * block;
  }
  Eigen::Index column = 0;
  for (Eigen::Index j = 0; j < r; ++j)
    for (Eigen::Index k = j; k < r; column += r - k, ++k) {
      const auto block = k3_.middleCols(column, r - k);
      const Eigen::VectorXd bq = block * q.segment(k, r - k);
      t.col(j) += q[k] * bq;
      t.col(k) += q[j] * bq;
      t.rightCols(r - k) += (q[j] * q[k]) * block;
    }
  out.tangent = 0.5 * (t + t.transpose());
  return out;
}

double ReducedStvk::strain_energy(const Eigen::VectorXd& q) const {
  return evaluate(q, false).strain_energy;
}

}  // namespace hm::fem
