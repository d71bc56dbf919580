#include "fem/nonlinear_static.hpp"

#include <algorithm>

#include "core/errors.hpp"
#include "core/log.hpp"

namespace hm::fem {
namespace {

/// r(u) = f(u) − λ f_ext(u) and its Jacobian on the free DOFs.
NewtonEquations static_equations(const HyperelasticBody& body, const DofMap& dofs,
                                 const StaticLoad& load, double lambda) {
  return [&body, &dofs, &load, lambda](const Eigen::VectorXd& x, bool jacobian) {
    const Eigen::VectorXd u = dofs.full_values(x);
    EvaluationRequest request;
    request.tangent = jacobian;
    BodyEvaluation e = body.evaluate(u, request);
    Eigen::VectorXd external = Eigen::VectorXd::Zero(u.size());
    if (load.dead.size() > 0) external += lambda * load.dead;
    if (load.follower) external += lambda * load.follower(u);
    NewtonSystem s;
    s.residual = dofs.free_values(e.force - external);
    s.scale =
        std::max({dofs.free_values(e.force).norm(), dofs.free_values(external).norm(), 1e-300});
    s.min_det_f = e.min_det_f;
    s.worst_cell = e.worst_cell;
    if (jacobian) {
      Eigen::SparseMatrix<double> k = e.tangent;
      if (load.follower) {
        k -= lambda * load.follower_stiffness(u);
        s.symmetric = false;
      }
      s.jacobian = dofs.reduce(k);
    }
    return s;
  };
}

}  // namespace

StaticResult solve_static(const HyperelasticBody& body, const DofMap& dofs, const StaticLoad& load,
                          const StaticOptions& options, std::string_view context) {
  HM_ASSERT(!load.follower || load.follower_stiffness, "a follower load needs its stiffness");
  TangentSolver solver;
  StaticResult result;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(dofs.free_count()), previous = x;
  double lambda = 0.0, previous_lambda = 0.0;
  double increment = 1.0 / std::max(1, options.load_steps);
  int halvings = 0;
  while (lambda < 1.0) {
    const double target = std::min(1.0, lambda + increment);
    // Start from the secant extrapolation of the last two equilibria.
    Eigen::VectorXd trial = x;
    if (lambda > previous_lambda)
      trial += (target - lambda) / (lambda - previous_lambda) * (x - previous);
    const NewtonReport report =
        newton_solve(trial, static_equations(body, dofs, load, target), options.newton, solver);
    result.newton_iterations += report.iterations;
    if (!report.converged) {
      if (++halvings > options.max_halvings)
        numerical_error("{}: the static solve stopped at load factor {:.6g} of 1: {}", context,
                        lambda, report.failure);
      spdlog::debug("{}: load step to λ = {:.6g} failed ({}); halving it", context, target,
                    report.failure);
      increment *= 0.5;
      continue;
    }
    previous = x;
    previous_lambda = lambda;
    x = std::move(trial);
    lambda = target;
    result.residual = report.residual;
    ++result.load_steps;
  }
  result.u = dofs.full_values(x);
  result.strain_energy = body.strain_energy(result.u);
  return result;
}

}  // namespace hm::fem
