#pragma once
// Static equilibrium of a geometrically nonlinear body, f(u) = λ f_ext(u), followed from λ = 0
// to 1 in load steps (each solved by Newton with line search from the last equilibrium,
// extrapolated), a step that fails being halved. f_ext = dead load + follower load; a follower
// load (one that turns with the body, e.g. an end moment) brings its own stiffness, which makes
// the Newton matrix unsymmetric.
#include <functional>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "fem/dof_map.hpp"
#include "fem/hyperelastic_body.hpp"
#include "fem/newton.hpp"

namespace hm::fem {

struct StaticLoad {
  Eigen::VectorXd dead;  ///< full DOF vector at λ = 1 [N]; empty: none
  /// A load that depends on the displacement, at λ = 1 [N]; empty: none.
  std::function<Eigen::VectorXd(const Eigen::VectorXd& u)> follower;
  /// ∂follower/∂u [N/m] (full DOFs); needed with a follower.
  std::function<Eigen::SparseMatrix<double>(const Eigen::VectorXd& u)> follower_stiffness;
};

struct StaticOptions {
  int load_steps = 10;   ///< equal increments of λ to start with
  int max_halvings = 8;  ///< of a failing increment, before giving up
  NewtonOptions newton;
};

struct StaticResult {
  Eigen::VectorXd u;           ///< full displacement [m]
  int load_steps = 0;          ///< increments taken
  int newton_iterations = 0;   ///< summed over the increments
  double residual = 0.0;       ///< of the last Newton solve [1]
  double strain_energy = 0.0;  ///< [J]
};

/// NumericalError naming `context`, the load factor reached and why (Newton's report: an
/// inverted cell, no convergence) when an increment fails after max_halvings halvings.
StaticResult solve_static(const HyperelasticBody& body, const DofMap& dofs, const StaticLoad& load,
                          const StaticOptions& options, std::string_view context);

}  // namespace hm::fem
