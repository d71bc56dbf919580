#pragma once
// The internal force of a Saint Venant–Kirchhoff body restricted to a fixed basis, u = V q
// (V: n_dofs × r, full DOF vectors, q the reduced coordinates): f_r(q) = Vᵀ f(V q). With the
// body's quadrature it is exactly a cubic polynomial (Barbič & James 2005; Mignolet et al.
// 2013, JSV 332:2437):
//
//   f_r,i(q) = Σ_j K1_ij q_j + Σ_{j≤k} K2_i,jk q_j q_k + Σ_{j≤k≤l} K3_i,jkl q_j q_k q_l,
//
// the Taylor coefficient of each distinct monomial: K2_i,jk = ∂²f_r,i/∂q_j∂q_k, halved for
// j = k; K3_i,jkl = ∂³f_r,i/∂q_j∂q_k∂q_l divided by 2 when two indices are equal and by 6 when
// all three are. They come from the Green–Lagrange strain at each quadrature point, with
// H_j = ∇(V_j) the gradient of basis vector j,
//
//   E(q) = Σ_j L_j q_j + ½ Σ_jk Q_jk q_j q_k,   L_j = sym H_j,   Q_jk = sym(H_jᵀ H_k),
//   W(q) = Σ_points w · ½ E:ℂ₀:E,               f_r = ∂W/∂q,   K_r = ∂f_r/∂q,
//
// through three integrals ∫ L_i:ℂ₀:L_j (= K1 = VᵀK₀V), ∫ L_i:ℂ₀:Q_jk and ∫ Q_ij:ℂ₀:Q_kl, which
// are one Gram matrix G = Σ_points w Zᵀℂ₀Z of the columns Z = [L_j, Q_jk] (Voigt). G is
// accumulated per thread over a fixed partition of the cells (OpenMP) and summed in thread
// order: the tensors are reproducible bitwise for a given thread count. Memory while they are
// computed: (r + r(r+1)/2)² doubles per thread (r = 44: 8.5 MB).
//
// Exactness: the full model's StVK energy is ½E:ℂ₀:E in 3-D and in plane strain (E33 = 0). In
// plane stress it finds E33 with S33 = 0, which for StVK is linear, E33 = −λ(E11 + E22)/(λ + 2μ):
// the condensed energy is ½E:ℂ_ps:E with the plane-stress ℂ₀ the body already uses, so the
// tensors are exact there too (tests/fem/test_reduced.cpp checks all three). The neo-Hookean law
// is not a polynomial and is refused.
//
// Units: u = Vq [m]; with an M-orthonormal V (fem/reduced_basis.hpp) q is in m·√kg and f_r,
// Vᵀf, in N/√kg. The model owns a copy of V and its tensors; it keeps no reference to the body.
#include <array>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "fem/hyperelastic_body.hpp"

namespace hm::fem {

struct ReducedEvaluation {
  Eigen::VectorXd force;       ///< f_r(q)
  Eigen::MatrixXd tangent;     ///< ∂f_r/∂q, symmetric (only when asked for)
  double strain_energy = 0.0;  ///< W(q) [J]
};

class ReducedStvk {
 public:
  /// The tensors of `body` in the basis `basis` (n_dofs × r; zero at clamped DOFs for a clamped
  /// body). InputError naming `context` for a neo-Hookean body, a basis of the wrong height or
  /// none.
  ReducedStvk(const HyperelasticBody& body, Eigen::MatrixXd basis, std::string_view context);
  /// A model from stored tensors (fsi-modes' modes.h5): V (n_dofs × r), M_r, K1 (r × r), K2
  /// (r × r(r+1)/2), K3 (r × r(r+1)(r+2)/6) as the accessors below return them. InputError
  /// naming `context` when their sizes do not fit one r.
  ReducedStvk(Eigen::MatrixXd basis, Eigen::MatrixXd mass, Eigen::MatrixXd linear,
              Eigen::MatrixXd quadratic, Eigen::MatrixXd cubic, std::string_view context);

  Eigen::Index size() const { return basis_.cols(); }
  const Eigen::MatrixXd& basis() const { return basis_; }          ///< V
  const Eigen::MatrixXd& mass() const { return mass_; }            ///< M_r = VᵀMV
  const Eigen::MatrixXd& linear_stiffness() const { return k1_; }  ///< K1 = VᵀK₀V
  const Eigen::MatrixXd& quadratic() const { return k2_; }         ///< K2, r × r(r+1)/2
  const Eigen::MatrixXd& cubic() const { return k3_; }             ///< K3, r × r(r+1)(r+2)/6
  /// Column of K2 of the pair (j, k), j ≤ k: pairs in lexicographic order.
  Eigen::Index pair_index(Eigen::Index j, Eigen::Index k) const;
  /// The triples (j ≤ k ≤ l) of the columns of K3, in lexicographic order.
  const std::vector<std::array<int, 3>>& triples() const { return triples_; }

  ReducedEvaluation evaluate(const Eigen::VectorXd& q, bool tangent) const;
  Eigen::VectorXd force(const Eigen::VectorXd& q) const { return evaluate(q, false).force; }
  Eigen::MatrixXd tangent(const Eigen::VectorXd& q) const { return evaluate(q, true).tangent; }
  double strain_energy(const Eigen::VectorXd& q) const;

  /// Vᵀ f of a full DOF force [N] (a generalised force).
  Eigen::VectorXd project(const Eigen::VectorXd& full) const { return basis_.transpose() * full; }
  /// u = V q [m], full DOFs.
  Eigen::VectorXd displacement(const Eigen::VectorXd& q) const { return basis_ * q; }

  /// Wall time of the tensors [s] (0 for tensors given).
  double setup_seconds() const { return setup_seconds_; }

 private:
  Eigen::VectorXd quadratic_monomials(const Eigen::VectorXd& q) const;
  Eigen::VectorXd cubic_monomials(const Eigen::VectorXd& q) const;
  void coefficients_from(const Eigen::MatrixXd& gram);
  void list_triples();

  Eigen::MatrixXd basis_, mass_, k1_, k2_, k3_;
  std::vector<std::array<int, 3>> triples_;
  double setup_seconds_ = 0.0;
};

}  // namespace hm::fem
