#include "fem/dense_newton.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/LU>

namespace hm::fem {
namespace {

/// The first trial x + δ, shortened (secant on the slope g(s) = δᵀ r(x + sδ), at most 4 times)
/// while g changes sign at more than 0.8 |g(0)|: for a symmetric Jacobian g is the energy's
/// derivative along δ, and a full step far past its minimum is pulled back.
DenseSystem line_search(Eigen::VectorXd& x, const Eigen::VectorXd& step, const DenseSystem& system,
                        const DenseEquations& equations, const NewtonOptions& options) {
  const double slope0 = step.dot(system.residual);
  const bool descent = options.line_search && system.symmetric && slope0 < 0.0;
  double fraction = 1.0;
  DenseSystem trial = equations(x + step, true);
  for (int search = 0; descent && search < 4; ++search) {
    const double slope = step.dot(trial.residual);
    if (slope <= 0.0 || std::abs(slope) <= 0.8 * std::abs(slope0)) break;
    fraction *= std::clamp(slope0 / (slope0 - slope), 0.1, 0.9);
    trial = equations(x + fraction * step, true);
  }
  x += fraction * step;
  return trial;
}

}  // namespace

NewtonReport dense_newton_solve(Eigen::VectorXd& x, const DenseEquations& equations,
                                const NewtonOptions& options) {
  NewtonReport report;
  DenseSystem system = equations(x, true);
  for (int iteration = 0;; ++iteration) {
    const double norm = system.residual.norm();
    report.iterations = iteration;
    report.residual = norm / system.scale;
    if (!std::isfinite(norm)) {
      report.failure = "the residual is not finite";
      return report;
    }
    if (report.residual <= options.tolerance) {
      report.converged = true;
      return report;
    }
    if (iteration >= options.max_iterations) {
      report.failure = fmt::format("no convergence in {} iterations (residual {:.3e} > {:.1e})",
                                   options.max_iterations, report.residual, options.tolerance);
      return report;
    }
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(system.jacobian);
    if (!(lu.rcond() > 1e-14)) {
      report.failure = fmt::format("the Newton matrix is singular (rcond {:.2e})", lu.rcond());
      return report;
    }
    const Eigen::VectorXd step = -lu.solve(system.residual);
    if (step.norm() <= options.increment_tolerance * x.norm()) {
      x += step;
      report.iterations = iteration + 1;
      report.converged = true;
      return report;
    }
    system = line_search(x, step, system, equations, options);
  }
}

}  // namespace hm::fem
