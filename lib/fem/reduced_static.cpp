#include "fem/reduced_static.hpp"

#include <algorithm>

#include "core/errors.hpp"
#include "core/log.hpp"
#include "fem/dense_newton.hpp"

namespace hm::fem {
namespace {

/// r(q) = f_r(q) − λ f_ext(q) and its Jacobian.
DenseEquations static_equations(const ReducedStvk& model, const ReducedStaticLoad& load,
                                double lambda) {
  return [&model, &load, lambda](const Eigen::VectorXd& q, bool jacobian) {
    ReducedEvaluation e = model.evaluate(q, jacobian);
    Eigen::VectorXd external = Eigen::VectorXd::Zero(q.size());
    if (load.dead.size() > 0) external += lambda * load.dead;
    if (load.follower) external += lambda * load.follower(q);
    DenseSystem s;
    s.residual = e.force - external;
    s.scale = std::max({e.force.norm(), external.norm(), 1e-300});
    if (jacobian) {
      s.jacobian = std::move(e.tangent);
      if (load.follower) {
        s.jacobian -= lambda * load.follower_stiffness(q);
        s.symmetric = false;
      }
    }
    return s;
  };
}

}  // namespace

ReducedStaticLoad project(const ReducedStvk& model, const StaticLoad& full) {
  ReducedStaticLoad out;
  if (full.dead.size() > 0) out.dead = model.project(full.dead);
  if (full.follower) {
    out.follower = [&model, f = full.follower](const Eigen::VectorXd& q) {
      return model.project(f(model.displacement(q)));
    };
    out.follower_stiffness = [&model, k = full.follower_stiffness](const Eigen::VectorXd& q) {
      const Eigen::MatrixXd& v = model.basis();
      return Eigen::MatrixXd(v.transpose() * (k(model.displacement(q)) * v));
    };
  }
  return out;
}

ReducedStaticResult solve_reduced_static(const ReducedStvk& model, const ReducedStaticLoad& load,
                                         const StaticOptions& options, std::string_view context) {
  HM_ASSERT(!load.follower || load.follower_stiffness, "a follower load needs its stiffness");
  ReducedStaticResult result;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.size()), previous = q;
  double lambda = 0.0, previous_lambda = 0.0;
  double increment = 1.0 / std::max(1, options.load_steps);
  int halvings = 0;
  while (lambda < 1.0) {
    const double target = std::min(1.0, lambda + increment);
    Eigen::VectorXd trial = q;
    if (lambda > previous_lambda)
      trial += (target - lambda) / (lambda - previous_lambda) * (q - previous);
    const NewtonReport report =
        dense_newton_solve(trial, static_equations(model, load, target), options.newton);
    result.newton_iterations += report.iterations;
    if (!report.converged) {
      if (++halvings > options.max_halvings)
        numerical_error("{}: the reduced static solve stopped at load factor {:.6g} of 1: {}",
                        context, lambda, report.failure);
      spdlog::debug("{}: load step to λ = {:.6g} failed ({}); halving it", context, target,
                    report.failure);
      increment *= 0.5;
      continue;
    }
    previous = q;
    previous_lambda = lambda;
    q = std::move(trial);
    lambda = target;
    result.residual = report.residual;
    ++result.load_steps;
  }
  result.q = q;
  result.strain_energy = model.strain_energy(q);
  return result;
}

}  // namespace hm::fem
