#pragma once
// The reduced basis of the nonlinear modal structure model: V = [Φ, Θ], n_dofs × r, full DOF
// vectors (zero at clamped DOFs), M-orthonormal (VᵀMV = I):
//
// * Φ, the lowest linear modes, K₀ φ = λ M φ on the free DOFs, mass-normalised (φᵀMφ = 1,
//   units 1/√kg), ascending λ = ω² [rad²/s²], each with its largest entry positive;
// * Θ, the static modal derivatives of Idelsohn & Cardona (1985), θ_ij = −K₀⁻¹ d²f[φ_i, φ_j]
//   (i ≤ j), d²f the second derivative of the Saint Venant–Kirchhoff internal force at u = 0
//   (HyperelasticBody::second_derivative): the quadratic displacement a pair of modes drags with
//   it — the axial shortening of a bending beam, the content a linear-mode basis lacks.
//
// The candidates [Φ, Θ] are M-orthonormalised by modified Gram–Schmidt with one pass of
// re-orthogonalisation; a candidate whose M-norm after both passes is below `drop_tolerance` of
// its norm before is (numerically) in the span of those before it and is dropped (counted).
// K₀ is factorised once (CHOLMOD through fem::TangentSolver) for all derivatives.
//
// The modes come from any eigensolver (lib/modal for production meshes); lowest_modes() is a
// small shift-invert subspace iteration with Rayleigh–Ritz on the same factorisation, enough for
// the few modes a reduced model keeps.
#include <array>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "fem/dof_map.hpp"
#include "fem/hyperelastic_body.hpp"

namespace hm::fem {

/// Mass-normalised linear modes as full DOF vectors.
struct LinearModes {
  Eigen::MatrixXd shapes;       ///< n_dofs × count, φᵀMφ = I, zero at clamped DOFs [1/√kg]
  Eigen::VectorXd eigenvalues;  ///< λ = ω², ascending [rad²/s²]
  int iterations = 0;           ///< subspace iterations taken (0: from elsewhere)
};

/// The `count` lowest modes of K₀ φ = λ M φ on the free DOFs, by subspace iteration (block
/// max(2·count, count + 8), at most 300 iterations) to ‖λK₀⁻¹Mφ − φ‖_M ≤ tolerance (λ then to
/// about tolerance²). The residual stalls at round-off of the solves with K₀, ~1e-7 for a strip
/// of L/h = 100 (its K₀ has a condition number ~1e10), hence the default.
/// InputError naming `context` for a count outside [1, free DOFs]; NumericalError when K₀ is
/// singular (a body not clamped) or the iteration does not converge.
LinearModes lowest_modes(const HyperelasticBody& body, const DofMap& dofs, int count,
                         std::string_view context, double tolerance = 1e-6);

struct BasisOptions {
  int modes = 4;                 ///< linear modes kept, ≥ 1
  bool derivatives = true;       ///< add the modal derivatives θ_ij
  int derivative_modes = -1;     ///< derivatives of the first k modes only (−1: of all `modes`)
  double drop_tolerance = 1e-6;  ///< relative M-norm below which a candidate is dependent
};

/// InputError naming `context` for modes < 1, derivative_modes outside [−1, modes] or a drop
/// tolerance outside (0, 1).
void validate(const BasisOptions& options, std::string_view context);

struct ReducedBasis {
  Eigen::MatrixXd vectors;  ///< V, n_dofs × r, VᵀMV = I, zero at clamped DOFs [1/√kg]
  /// Where each column came from: {i, −1} the mode φ_i, {i, j} the derivative θ_ij.
  std::vector<std::array<int, 2>> origin;
  Eigen::VectorXd eigenvalues;  ///< λ of the modes (the first `mode_count` columns) [rad²/s²]
  int mode_count = 0;
  int derivative_count = 0;  ///< derivatives kept
  int dropped = 0;           ///< candidates dropped as linearly dependent
  Eigen::Index size() const { return vectors.cols(); }
};

/// V from given modes (mass-normalised, full DOF vectors, at least options.modes of them).
/// InputError naming `context` for invalid options or too few modes.
ReducedBasis build_reduced_basis(const HyperelasticBody& body, const DofMap& dofs,
                                 const LinearModes& modes, const BasisOptions& options,
                                 std::string_view context);
/// V with the modes from lowest_modes().
ReducedBasis build_reduced_basis(const HyperelasticBody& body, const DofMap& dofs,
                                 const BasisOptions& options, std::string_view context);

}  // namespace hm::fem
