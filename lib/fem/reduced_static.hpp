#pragma once
// Static equilibrium of the reduced Saint Venant–Kirchhoff model (fem/reduced_stvk.hpp),
// f_r(q) = λ Vᵀ f_ext(V q), followed from λ = 0 to 1 in load steps as the full solve
// (fem/nonlinear_static.hpp) does: Newton (dense, fem/dense_newton.hpp) from the secant
// extrapolation of the last two equilibria, a failing step halved. The reduced equations are the
// Galerkin projection of the full ones on span(V): their solution differs from the full one only
// by what the basis cannot represent.
#include <functional>
#include <string_view>

#include <Eigen/Core>

#include "fem/nonlinear_static.hpp"
#include "fem/reduced_stvk.hpp"

namespace hm::fem {

/// Generalised loads (Vᵀ of full loads, fem::ReducedStvk::project).
struct ReducedStaticLoad {
  Eigen::VectorXd dead;  ///< at λ = 1; empty: none
  /// A load that depends on the state, at λ = 1, and its Jacobian ∂/∂q; empty: none.
  std::function<Eigen::VectorXd(const Eigen::VectorXd& q)> follower;
  std::function<Eigen::MatrixXd(const Eigen::VectorXd& q)> follower_stiffness;
};

/// The projection of a full load: dead Vᵀf, follower Vᵀf(Vq) with Jacobian Vᵀ(∂f/∂u)V. The
/// result calls `full`'s functions: whatever they refer to must outlive it.
ReducedStaticLoad project(const ReducedStvk& model, const StaticLoad& full);

struct ReducedStaticResult {
  Eigen::VectorXd q;  ///< reduced coordinates
  int load_steps = 0;
  int newton_iterations = 0;
  double residual = 0.0;       ///< of the last Newton solve [1]
  double strain_energy = 0.0;  ///< W(q) [J]
};

/// NumericalError naming `context`, the load factor reached and Newton's report when an
/// increment fails after options.max_halvings halvings. `model` is borrowed for the call.
ReducedStaticResult solve_reduced_static(const ReducedStvk& model, const ReducedStaticLoad& load,
                                         const StaticOptions& options, std::string_view context);

}  // namespace hm::fem
