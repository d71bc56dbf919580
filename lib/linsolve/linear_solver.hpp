#pragma once
// The linear-solver seam: one object per kind of system (the pressure Poisson equation, the
// implicit viscosity), set up on a matrix, then solving for right-hand sides. Backends:
//  * jacobi    — BiCGSTAB with a Jacobi preconditioner, OpenMP (linsolve/bicgstab.hpp);
//  * ilu       — Eigen's BiCGSTAB with IncompleteLUT (serial factorisation);
//  * boomeramg — PETSc KSP BiCGSTAB preconditioned by hypre's BoomerAMG (HMIS coarsening,
//                extended+i interpolation: the usual start for non-symmetric matrices);
//  * gamg      — PETSc KSP BiCGSTAB preconditioned by PETSc's smoothed-aggregation GAMG.
// The PETSc backends exist only in builds with PETSc (available_methods()). Every solve returns
// its iterations, the relative residual and the seconds of setup and solve; a failure (no
// convergence, a breakdown, a setup that failed) is a status, never an exception or a NaN.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/SparseCore>

namespace hm::linsolve {

using CsrMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

enum class Method : std::uint8_t { jacobi, ilu, boomeramg, gamg };

/// "jacobi", "ilu", "boomeramg", "gamg".
const char* to_string(Method method);
/// The method named `name`, or nothing.
std::optional<Method> method_from_string(std::string_view name);
/// The methods this build provides (jacobi and ilu always; the PETSc ones with PETSc).
std::vector<Method> available_methods();
bool is_available(Method method);

struct Settings {
  double tolerance = 1e-6;  ///< relative residual ‖b − Ax‖/‖b‖ at which a solve stops
  int max_iterations = 1000;
  double ilu_drop = 1e-4;  ///< ilu: IncompleteLUT drop tolerance
  int ilu_fill = 2;        ///< ilu: IncompleteLUT fill factor
  /// boomeramg, gamg: the multigrid hierarchy is built on amg_matrix(A, amg_drop) rather than
  /// on A (0: on A itself). The Krylov iteration still solves with A, so the answer and its
  /// tolerance are unchanged; only the preconditioner is cheaper.
  double amg_drop = 0.05;
};

struct SolveStats {
  bool converged = false;
  int iterations = 0;
  double residual = 0.0;  ///< ‖b − Ax‖/‖b‖ as the backend measured it (0 when b = 0)
  double seconds = 0.0;   ///< wall-clock seconds of the solve
  /// Why it failed, when it did ("" when converged): no convergence, breakdown, setup failure.
  std::string failure;
};

/// A solver for one matrix at a time. setup() builds the preconditioner for a matrix, which the
/// solver keeps a reference to: it must stay alive and unchanged until the next setup() or
/// reuse_for(). solve() may be called any number of times after a setup.
class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  LinearSolver() = default;
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  virtual Method method() const = 0;
  /// Builds the preconditioner for `matrix` (square); false (and setup_failure()) if it failed.
  virtual bool setup(const CsrMatrix& matrix) = 0;
  /// Makes `matrix` (of the size of the last setup's) the operator, keeping the preconditioner
  /// built for the earlier one; false where the backend cannot (then call setup()).
  virtual bool reuse_for(const CsrMatrix& matrix) = 0;
  /// Solves A x = b from the guess in x (size of A).
  virtual SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) = 0;
  /// Wall-clock seconds of the last setup (or reuse_for).
  double setup_seconds() const { return setup_seconds_; }
  const std::string& setup_failure() const { return setup_failure_; }

 protected:
  double setup_seconds_ = 0.0;
  std::string setup_failure_;
};

/// A new solver of `method`; HM_ASSERT that the method is available (check is_available first).
std::unique_ptr<LinearSolver> make_solver(Method method, const Settings& settings);

/// The matrix the AMG backends build their hierarchy on: A without the off-diagonal entries
/// smaller in magnitude than `drop` × the largest off-diagonal of their row, each row's dropped
/// entries added to its diagonal, so that every row sum — and with it the constant vector, the
/// Laplacian's near null space — is kept. The LDD Laplacian couples a point to every neighbour
/// within the kernel's support, most of them with tiny weights: at drop = 0.05 a 3-D row keeps
/// 25 of its 75 entries, a 2-D row 9 of 21 (bench_ppe, the dam break's PPE). `a` may be the
/// rows first_row.. of a larger square matrix (one process's share): then row r's diagonal is
/// in column first_row + r.
CsrMatrix amg_matrix(const CsrMatrix& a, double drop, int first_row = 0);

/// Whether a and b are the same matrix, entry by entry (pattern and values, bit for bit).
bool same_matrix(const CsrMatrix& a, const CsrMatrix& b);

/// ‖b − Ax‖/‖b‖ recomputed from the matrix, independently of any solver (0 when b = 0).
double relative_residual(const CsrMatrix& a, const Eigen::VectorXd& b, const Eigen::VectorXd& x);

}  // namespace hm::linsolve
