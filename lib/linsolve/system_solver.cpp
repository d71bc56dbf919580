#include "linsolve/system_solver.hpp"

#include <algorithm>

#include "core/errors.hpp"

namespace hm::linsolve {

SystemSolver::SystemSolver(const Strategy& strategy, const Settings& settings)
    : strategy_(strategy), settings_(settings) {
  HM_ASSERT(is_available(strategy.primary), "linear solver {} is not built in",
            to_string(strategy.primary));
  primary_ = make_solver(strategy.primary, settings);
  if (strategy.fallback && *strategy.fallback != strategy.primary)
    fallback_ = make_solver(*strategy.fallback, settings);
}

bool SystemSolver::same_as_set_up(const CsrMatrix& a) const {
  return ready_ && same_matrix(a, *set_up_matrix_);
}

bool SystemSolver::holds(const CsrMatrix& a) const {
  return same_as_set_up(a) || (ready_ && same_matrix(a, *matrix_));
}

void SystemSolver::full_setup(const CsrMatrix& a, SystemReport& report) {
  if (&a != matrix_.get()) matrix_ = std::make_shared<const CsrMatrix>(a);
  ready_ = primary_->setup(*matrix_);
  set_up_matrix_ = matrix_;
  stale_ = false;
  age_ = 0;
  baseline_iterations_ = 0;
  report.setup = true;
  report.setup_seconds += primary_->setup_seconds();
  ++counters_.setups;
}

SystemReport SystemSolver::solve_with_primary(const CsrMatrix& a, const Eigen::VectorXd& b,
                                              Eigen::VectorXd& x, bool keep_preconditioner) {
  SystemReport report;
  report.method = strategy_.primary;
  const bool identical = same_as_set_up(a);
  bool stale = false;
  if (identical && stale_) {
    // Back from a matrix it served stale (a few rows fixed, keep_preconditioner) to the one
    // its preconditioner was built for: the strong coupling's next sub-iteration.
    matrix_ = set_up_matrix_;
    stale_ = false;
    if (primary_->reuse_for(*matrix_)) {
      report.reused = true;
      ++counters_.identical_reuses;
    } else {
      full_setup(*matrix_, report);
    }
  } else if (identical) {
    report.reused = true;
    ++counters_.identical_reuses;
  } else if (ready_ && a.rows() == matrix_->rows() &&
             (keep_preconditioner ||
              (strategy_.reuse.across_steps && age_ < strategy_.reuse.max_age))) {
    matrix_ = std::make_shared<const CsrMatrix>(a);
    stale = primary_->reuse_for(*matrix_);
    if (stale) {
      stale_ = true;
      ++age_;
      report.reused = true;
      report.setup_seconds += primary_->setup_seconds();
      ++counters_.stale_reuses;
    } else {
      full_setup(*matrix_, report);
    }
  } else {
    full_setup(a, report);
  }
  if (!ready_) {
    report.failure = primary_->setup_failure();
    return report;
  }
  const Eigen::VectorXd guess = x;
  SolveStats s = primary_->solve(b, x);
  report.solve_seconds += s.seconds;
  const double allowed = keep_preconditioner ? 2.0 * baseline_iterations_ + 2.0
                                             : strategy_.reuse.growth * baseline_iterations_;
  const bool grown = stale && baseline_iterations_ > 0 && s.iterations > allowed;
  if (stale && (!s.converged || grown)) {
    // The kept preconditioner no longer pays: set up for this matrix and solve again.
    report.discarded_iterations += s.iterations;
    ++counters_.rebuilds_after_growth;
    full_setup(*matrix_, report);
    x = guess;
    if (!ready_) {
      report.failure = primary_->setup_failure();
      return report;
    }
    s = primary_->solve(b, x);
    report.solve_seconds += s.seconds;
  }
  if (report.setup && s.converged) baseline_iterations_ = s.iterations;
  report.converged = s.converged;
  report.iterations = s.iterations;
  report.residual = s.residual;
  report.failure = s.failure;
  return report;
}

SystemReport SystemSolver::solve(const CsrMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                 bool keep_preconditioner) {
  HM_ASSERT(a.rows() == a.cols() && b.size() == a.rows() && x.size() == a.rows(),
            "linear system: matrix {}×{}, rhs {}, guess {}", a.rows(), a.cols(), b.size(),
            x.size());
  ++counters_.solves;
  const Eigen::VectorXd guess = x;
  SystemReport report = solve_with_primary(a, b, x, keep_preconditioner);
  if (report.converged || !fallback_) return report;
  // The primary failed: the fallback from the same guess, set up for this matrix.
  ++counters_.fallbacks;
  report.discarded_iterations += report.iterations;
  x = guess;
  report.method = fallback_->method();
  if (!fallback_->setup(*matrix_)) {
    report.converged = false;
    report.iterations = 0;
    report.failure = fallback_->setup_failure();
    return report;
  }
  report.setup_seconds += fallback_->setup_seconds();
  const SolveStats s = fallback_->solve(b, x);
  report.solve_seconds += s.seconds;
  report.converged = s.converged;
  report.iterations = s.iterations;
  report.residual = s.residual;
  report.failure = s.failure;
  return report;
}

}  // namespace hm::linsolve
