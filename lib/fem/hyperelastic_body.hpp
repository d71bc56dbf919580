#pragma once
// A geometrically nonlinear elastic body, total Lagrangian: every integral is over the reference
// configuration, the displacement u (full node-major DOF vector [m]) is the unknown, and
//
//   internal force   f(u) = ∫ B(F)ᵀ S(E) dV₀,   F = I + ∂u/∂X,  E = (FᵀF − I)/2,
//   tangent          K(u) = ∫ B(F)ᵀ ℂ B(F) dV₀ + ∫ (∇N S ∇Nᵀ) ⊗ I dV₀   (material + geometric),
//
// with δE = B(F) δu (fem/hyperelastic.hpp for S, ℂ). Elements and quadrature are those of the
// linear model (tri6 / tet10, the degree-2 rule of its stiffness, the degree-4 rule of its mass),
// so K(0) is the linear stiffness K₀ bitwise in structure and to round-off in value, and the
// mass is the linear model's consistent mass. 2-D integrals are per the section's thickness.
//
// Damping of the β part of Rayleigh damping is a viscous stress on the strain rate,
// f_d = β ∫ B(F)ᵀ ℂ₀ Ė dV₀ with Ė = B(F) u̇ — objective: a rigid rotation of the deformed body
// is not damped (β K₀ u̇ would damp it) — and equal to β K₀ u̇ at small displacement.
//
// The energy-conserving force between two states u₀, u₁ is the discrete gradient of Gonzalez
// (2000): f = ∫ B(F_m)ᵀ S_alg dV₀, F_m = (F₀ + F₁)/2,
//   S_alg = S(E_m) + [W(E₁) − W(E₀) − S(E_m):ΔE] / (ΔE:ΔE) · ΔE,   E_m = (E₀ + E₁)/2,
// so that (u₁ − u₀)ᵀ f = ∫ W(E₁) − W(E₀) exactly; for Saint Venant–Kirchhoff the bracket is
// zero and the force is Simo & Tarnow's (1992).
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "fem/hyperelastic.hpp"
#include "fem/pattern.hpp"
#include "mesh/types.hpp"

namespace hm::fem {

/// What evaluate() is asked for. The tangent is returned as
///   stiffness_weight·∂f/∂u + damping_weight·β·K_mat(u) + mass_weight·M
/// (the Newton matrix of a time step), only when `tangent` is set.
struct EvaluationRequest {
  bool tangent = false;
  double stiffness_weight = 1.0;
  double damping_weight = 0.0;
  double mass_weight = 0.0;
  /// Velocity u̇ [m/s] for the viscous force (nullptr or β = 0: none).
  const Eigen::VectorXd* velocity = nullptr;
  double beta = 0.0;  ///< Rayleigh β [s]
  /// Displacement u₀ at the start of the step: the energy-conserving force between u₀ and u
  /// (nullptr: the force at u). The tangent is then ∂f/∂u (exact for StVK; for neo-Hookean the
  /// discrete-gradient correction is left out of it, which slows Newton only).
  const Eigen::VectorXd* start = nullptr;
};

struct BodyEvaluation {
  Eigen::VectorXd force;                ///< internal (+ viscous) force [N]
  Eigen::SparseMatrix<double> tangent;  ///< [N/m] (weights as requested)
  bool symmetric = true;                ///< false for the energy-conserving tangent
  double strain_energy = 0.0;           ///< ∫ W(E(u)) dV₀ [J]
  double damping_power = 0.0;           ///< u̇ᵀ f_d [W]
  double min_det_f = 1.0;               ///< smallest J over the quadrature points
  mesh::Index worst_cell = -1;          ///< the cell of min_det_f
  bool inverted() const { return !(min_det_f > 0.0); }
};

class HyperelasticBody {
 public:
  /// InputError naming `context` for an invalid model or mesh, or a cell inverted in the
  /// reference configuration.
  HyperelasticBody(mesh::StructureMesh mesh, const HyperelasticModel& model,
                   std::string_view context);

  int dim() const { return mesh_.dim; }
  Eigen::Index dof_count() const { return dim() * mesh_.node_count(); }
  const mesh::StructureMesh& mesh() const { return mesh_; }
  const HyperelasticModel& model() const { return model_; }

  BodyEvaluation evaluate(const Eigen::VectorXd& u, const EvaluationRequest& request = {}) const;
  /// f(u) alone.
  Eigen::VectorXd internal_force(const Eigen::VectorXd& u) const { return evaluate(u).force; }
  double strain_energy(const Eigen::VectorXd& u) const;

  /// Second derivative of the Saint Venant–Kirchhoff internal force at u = 0 in the directions
  /// a and b, d²f/du²[a, b] [N/m²] — the right-hand side of the static modal derivatives
  /// (K₀ θ_ab = −d²f[a, b]). Uses ℂ₀ whatever the law (exact for StVK).
  Eigen::VectorXd second_derivative(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;
  /// d²f/du²[a_i, a_j] of every pair i ≤ j of the columns of `directions` (n_dofs × k), as the
  /// columns of an n_dofs × k(k+1)/2 matrix in the order (0,0), (0,1), …, (0,k−1), (1,1), …:
  /// one pass over the mesh for all pairs (the gradients of each direction are formed once per
  /// quadrature point, not once per pair) [N/m²].
  Eigen::MatrixXd second_derivatives(const Eigen::MatrixXd& directions) const;

  const Eigen::SparseMatrix<double>& mass() const { return mass_; }                   ///< M [kg]
  const Eigen::SparseMatrix<double>& linear_stiffness() const { return stiffness_; }  ///< K₀
  /// The consistent nodal force of a uniform acceleration g [m/s²] (gravity): M·T·g [N].
  Eigen::VectorXd body_force(const Eigen::VectorXd& g) const;

  /// Quadrature data of the stiffness rule, per cell: reference gradients dN/dX (nodes × dim)
  /// and weights w·det J·thickness [m³ or m²·m]. (The reduced tensors integrate with them.)
  struct QuadraturePoint {
    Eigen::MatrixXd grad;
    double weight = 0.0;
  };
  const std::vector<std::vector<QuadraturePoint>>& quadrature() const { return quadrature_; }
  /// ℂ₀, the Voigt small-strain elasticity (the tangent of either law at E = 0) [Pa].
  const Eigen::MatrixXd& small_strain_tangent() const { return tangent0_; }

 private:
  template <int D>
  BodyEvaluation evaluate_dim(const Eigen::VectorXd& u, const EvaluationRequest& request) const;
  template <int D>
  Eigen::VectorXd second_derivative_dim(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;
  template <int D>
  Eigen::MatrixXd second_derivatives_dim(const Eigen::MatrixXd& directions) const;

  mesh::StructureMesh mesh_;
  HyperelasticModel model_;
  Lame lame_;
  BlockPattern pattern_;
  std::vector<std::vector<mesh::Index>> colours_;
  std::vector<std::vector<QuadraturePoint>> quadrature_;
  Eigen::MatrixXd tangent0_;
  std::vector<double> mass_values_;  ///< M in pattern order
  Eigen::SparseMatrix<double> mass_, stiffness_;
};

}  // namespace hm::fem
