#pragma once
// A sequence of linear systems of one kind (the PPE of every step, its re-solves and the
// added-mass solves), solved through the seam with
//  * setup reuse: a matrix equal to the last one set up (the strong-coupling sub-iterations, the
//    per-mode added-mass solves, the re-solve after wall tension is released when nothing was
//    released) is not set up again — checked exactly, entry by entry; with
//    ReusePolicy::across_steps, a different matrix of the same size keeps the earlier
//    preconditioner until a solve needs more than `growth` times the iterations of the solve
//    right after the last full setup (or fails), which triggers a setup and a re-solve;
//  * a fallback: a solve that fails with the primary method is solved again from the same guess
//    with the fallback method (today's "automatic": Jacobi, then ILU).
#include <memory>
#include <optional>
#include <string>

#include "linsolve/linear_solver.hpp"

namespace hm::linsolve {

struct ReusePolicy {
  bool across_steps = false;  ///< keep a preconditioner across different matrices of one size
  double growth = 1.3;        ///< rebuild when iterations exceed growth × those after a setup
  int max_age = 50;           ///< and at the latest after this many different matrices
};

struct Strategy {
  Method primary = Method::jacobi;
  std::optional<Method> fallback;  ///< solved with this when the primary fails
  ReusePolicy reuse;
};

/// What one solve of the sequence did.
struct SystemReport {
  Method method = Method::jacobi;  ///< of the returned solution
  bool converged = false;
  int iterations = 0;  ///< of the returned solution's solve
  int discarded_iterations =
      0;  ///< of solves thrown away (a stale preconditioner, a failed primary)
  double residual = 0.0;
  bool setup = false;   ///< a full setup was done for this solve
  bool reused = false;  ///< an earlier setup served (identical or stale matrix)
  double setup_seconds = 0.0;
  double solve_seconds = 0.0;
  std::string failure;  ///< when not converged: why (the last method's reason)
};

/// Counts over the sequence (for the monitors and the benchmarks).
struct SystemCounters {
  long solves = 0, setups = 0, identical_reuses = 0, stale_reuses = 0, rebuilds_after_growth = 0,
       fallbacks = 0;
};

class SystemSolver {
 public:
  SystemSolver(const Strategy& strategy, const Settings& settings);
  /// Solves a x = b from the guess in x. With `keep_preconditioner` a matrix of the last one's
  /// size that differs from it in a few rows (the PPE's re-solve after wall tension is
  /// released) is solved on the preconditioner already built, whatever the policy; it is set
  /// up afresh only if that solve fails or needs more than 2 × (iterations after the last
  /// setup) + 2.
  SystemReport solve(const CsrMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                     bool keep_preconditioner = false);
  const SystemCounters& counters() const { return counters_; }
  const Strategy& strategy() const { return strategy_; }
  /// Whether `a` is the matrix of the last setup or the last one solved (a setup serves it
  /// without being rebuilt).
  bool holds(const CsrMatrix& a) const;
  /// Forget the last setup (the next solve sets up).
  void invalidate() { ready_ = false; }

 private:
  bool same_as_set_up(const CsrMatrix& a) const;
  SystemReport solve_with_primary(const CsrMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                  bool keep_preconditioner);
  void full_setup(const CsrMatrix& a, SystemReport& report);

  Strategy strategy_;
  Settings settings_;
  std::unique_ptr<LinearSolver> primary_;
  std::unique_ptr<LinearSolver> fallback_;
  /// The matrix the primary was last given (the backends refer to it) and the one of the last
  /// full setup: one copy of the caller's matrix, shared while they are the same (a copy of a
  /// 3-D PPE matrix cost 2.4 % of a step).
  std::shared_ptr<const CsrMatrix> matrix_, set_up_matrix_;
  bool ready_ = false;
  bool stale_ = false;           ///< matrix_ is not the one the preconditioner was built for
  int age_ = 0;                  ///< different matrices served since the last full setup
  int baseline_iterations_ = 0;  ///< of the first solve after the last full setup
  SystemCounters counters_;
};

}  // namespace hm::linsolve
