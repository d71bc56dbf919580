#include "linsolve/petsc_solver.hpp"

#ifdef HM_WITH_PETSC

#include <chrono>
#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <petscksp.h>

#include "core/errors.hpp"

namespace hm::linsolve {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// A PETSc call that failed: carried to the backend's boundary, where it becomes a status.
struct PetscFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void check(PetscErrorCode code, const char* call) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw PetscFailure(fmt::format("{} failed (PETSc error {}: {})", call, static_cast<int>(code),
                                 text ? text : "?"));
}

void finalize_petsc() {
  PetscBool finalized = PETSC_FALSE;
  PetscFinalized(&finalized);
  if (!finalized) PetscFinalize();
}

/// PETSc once per process: without its signal handlers (the stages handle SIGINT/SIGTERM
/// themselves), with errors returned rather than printed, finalised at exit.
void ensure_petsc() {
  static std::once_flag once;
  std::call_once(once, [] {
    PetscBool initialized = PETSC_FALSE;
    PetscInitialized(&initialized);
    if (initialized) return;
    static char program[] = "hydromodal", no_signals[] = "-no_signal_handler";
    static char* arguments[] = {program, no_signals, nullptr};
    int argc = 2;
    char** argv = arguments;
    check(PetscInitialize(&argc, &argv, nullptr, nullptr), "PetscInitialize");
    PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
    std::atexit(finalize_petsc);
  });
}

/// A unique options prefix per solver, so that the options one solver sets (BoomerAMG's
/// coarsening) never leak into another.
std::string next_prefix() {
  static int count = 0;
  return fmt::format("hm{}_", count++);
}

/// KSP BiCGSTAB with right preconditioning, so that the residual it tests is the true
/// ‖b − Ax‖ (as the native solvers do), relative to ‖b‖.
class PetscSolver final : public LinearSolver {
 public:
  PetscSolver(Method method, const Settings& s) : method_(method), settings_(s) {
    ensure_petsc();
    prefix_ = next_prefix();
  }
  ~PetscSolver() override { release(); }
  Method method() const override { return method_; }

  bool setup(const CsrMatrix& a) override {
    const auto start = Clock::now();
    setup_failure_.clear();
    try {
      release();
      check(KSPCreate(PETSC_COMM_SELF, &ksp_), "KSPCreate");
      check(KSPSetOptionsPrefix(ksp_, prefix_.c_str()), "KSPSetOptionsPrefix");
      check(KSPSetType(ksp_, KSPBCGS), "KSPSetType");
      check(KSPSetPCSide(ksp_, PC_RIGHT), "KSPSetPCSide");
      check(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
      check(
          KSPSetTolerances(ksp_, settings_.tolerance, 0.0, PETSC_DEFAULT, settings_.max_iterations),
          "KSPSetTolerances");
      check(KSPSetInitialGuessNonzero(ksp_, PETSC_TRUE), "KSPSetInitialGuessNonzero");
      configure_preconditioner();
      set_operators(a, /*with_preconditioner_matrix=*/true);
      check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
      check(KSPSetUp(ksp_), "KSPSetUp (the preconditioner's setup)");
      PC pc = nullptr;
      check(KSPGetPC(ksp_, &pc), "KSPGetPC");
      check(PCSetUp(pc), "PCSetUp");
    } catch (const PetscFailure& e) {
      setup_failure_ = e.what();
      release();
    }
    setup_seconds_ = seconds_since(start);
    return setup_failure_.empty();
  }

  bool reuse_for(const CsrMatrix& a) override {
    if (ksp_ == nullptr || a.rows() != rows_) return false;
    const auto start = Clock::now();
    try {
      PC pc = nullptr;
      check(KSPGetPC(ksp_, &pc), "KSPGetPC");
      check(PCSetReusePreconditioner(pc, PETSC_TRUE), "PCSetReusePreconditioner");
      set_operators(a, /*with_preconditioner_matrix=*/false);
    } catch (const PetscFailure& e) {
      setup_failure_ = e.what();
      release();
      return false;
    }
    setup_seconds_ = seconds_since(start);
    return true;
  }

  SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    SolveStats s;
    const auto start = Clock::now();
    if (ksp_ == nullptr) {
      s.failure = setup_failure_.empty() ? "solve before setup" : setup_failure_;
      return s;
    }
    if (b.squaredNorm() == 0.0) {  // the native solvers' convention: x = 0, converged
      x.setZero();
      s.converged = true;
      return s;
    }
    try {
      Vec pb = nullptr, px = nullptr;
      const auto n = static_cast<PetscInt>(b.size());
      check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, n, b.data(), &pb), "VecCreateSeqWithArray");
      check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, n, x.data(), &px), "VecCreateSeqWithArray");
      const PetscErrorCode code = KSPSolve(ksp_, pb, px);
      VecDestroy(&pb);
      VecDestroy(&px);
      check(code, "KSPSolve");
      PetscInt iterations = 0;
      PetscReal norm = 0.0;
      KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
      check(KSPGetIterationNumber(ksp_, &iterations), "KSPGetIterationNumber");
      check(KSPGetResidualNorm(ksp_, &norm), "KSPGetResidualNorm");
      check(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
      s.iterations = static_cast<int>(iterations);
      s.residual = norm / b.norm();
      s.converged = reason > 0 && x.allFinite();
      if (!s.converged) {
        const char* why = nullptr;
        KSPGetConvergedReasonString(ksp_, &why);
        s.failure = fmt::format("BiCGSTAB ({}) stopped: {} after {} iterations (residual {:.3g})",
                                to_string(method_), why ? why : "?", s.iterations, s.residual);
      }
    } catch (const PetscFailure& e) {
      s.converged = false;
      s.failure = e.what();
    }
    s.seconds = seconds_since(start);
    return s;
  }

 private:
  /// Sets this solver's option `name` to `value`, unless the user gave `-name` without a
  /// prefix (PETSC_OPTIONS="-pc_hypre_boomeramg_strong_threshold 0.7"): then to the user's.
  void set_option(const char* name, const char* value) {
    const std::string global = fmt::format("-{}", name);
    char user[256] = {};
    PetscBool given = PETSC_FALSE;
    check(PetscOptionsGetString(nullptr, nullptr, global.c_str(), user, sizeof user, &given),
          "PetscOptionsGetString");
    check(PetscOptionsSetValue(nullptr, fmt::format("-{}{}", prefix_, name).c_str(),
                               given ? user : value),
          "PetscOptionsSetValue");
  }

  void configure_preconditioner() {
    PC pc = nullptr;
    check(KSPGetPC(ksp_, &pc), "KSPGetPC");
    if (method_ == Method::boomeramg) {
      check(PCSetType(pc, PCHYPRE), "PCSetType(hypre)");
      check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType(boomeramg)");
      // Measured on dumped PPE matrices (bench_ppe, 1 thread): against hypre's defaults plus
      // HMIS/ext+i/P_max 4, a strong threshold of 0.5 with one level of aggressive coarsening
      // and one SOR/Jacobi sweep per level took the 3-D 140 k system from 2.0 + 1.2 s
      // (setup + solve, 4 iterations) to 0.83 + 0.57 s (6) and the 2-D 159 k from 0.62 to 0.47 s.
      set_option("pc_hypre_boomeramg_coarsen_type", "HMIS");
      set_option("pc_hypre_boomeramg_interp_type", "ext+i");
      set_option("pc_hypre_boomeramg_P_max", "4");
      set_option("pc_hypre_boomeramg_strong_threshold", "0.5");
      set_option("pc_hypre_boomeramg_agg_nl", "1");
      set_option("pc_hypre_boomeramg_grid_sweeps_all", "1");
      set_option("pc_hypre_boomeramg_relax_type_all", "SOR/Jacobi");
    } else {
      check(PCSetType(pc, PCGAMG), "PCSetType(gamg)");
      check(PCGAMGSetType(pc, PCGAMGAGG), "PCGAMGSetType(agg)");
      check(PCGAMGSetReuseInterpolation(pc, PETSC_TRUE), "PCGAMGSetReuseInterpolation");
      set_option("pc_gamg_sym_graph", "true");  // the PPE's rows are not symmetric
      set_option("mg_levels_ksp_type", "richardson");
      set_option("mg_levels_pc_type", "sor");
    }
    check(PCSetFromOptions(pc), "PCSetFromOptions");
  }

  /// `a` as a PETSc AIJ matrix (columns sorted row by row).
  static Mat petsc_matrix(const CsrMatrix& a) {
    HM_ASSERT(a.isCompressed() && a.rows() == a.cols(), "petsc: a square compressed matrix");
    Mat m = nullptr;
    const auto n = static_cast<PetscInt>(a.rows());
    check(MatCreate(PETSC_COMM_SELF, &m), "MatCreate");
    check(MatSetSizes(m, n, n, n, n), "MatSetSizes");
    check(MatSetType(m, MATSEQAIJ), "MatSetType");
    check(MatSeqAIJSetPreallocationCSR(m, a.outerIndexPtr(), a.innerIndexPtr(), a.valuePtr()),
          "MatSeqAIJSetPreallocationCSR");
    return m;
  }

  /// Makes `a` the operator. With `with_preconditioner_matrix` the hierarchy is (re)built on
  /// amg_matrix(a, amg_drop); without, the one built for an earlier matrix stays.
  void set_operators(const CsrMatrix& a, bool with_preconditioner_matrix) {
    if (matrix_ != nullptr) MatDestroy(&matrix_);
    matrix_ = petsc_matrix(a);
    rows_ = a.rows();
    if (with_preconditioner_matrix) {
      if (preconditioner_matrix_ != nullptr) MatDestroy(&preconditioner_matrix_);
      if (settings_.amg_drop > 0.0)
        preconditioner_matrix_ = petsc_matrix(amg_matrix(a, settings_.amg_drop));
    }
    check(KSPSetOperators(ksp_, matrix_,
                          preconditioner_matrix_ != nullptr ? preconditioner_matrix_ : matrix_),
          "KSPSetOperators");
  }

  void release() {
    if (ksp_ != nullptr) KSPDestroy(&ksp_);
    if (matrix_ != nullptr) MatDestroy(&matrix_);
    if (preconditioner_matrix_ != nullptr) MatDestroy(&preconditioner_matrix_);
    ksp_ = nullptr;
    matrix_ = nullptr;
    preconditioner_matrix_ = nullptr;
    rows_ = -1;
  }

  Method method_;
  Settings settings_;
  std::string prefix_;
  KSP ksp_ = nullptr;
  Mat matrix_ = nullptr;
  Mat preconditioner_matrix_ = nullptr;  ///< amg_matrix of the last setup's; null at amg_drop 0
  Eigen::Index rows_ = -1;
};

}  // namespace

bool petsc_available() {
  return true;
}

std::unique_ptr<LinearSolver> make_petsc_solver(Method method, const Settings& settings) {
  return std::make_unique<PetscSolver>(method, settings);
}

}  // namespace hm::linsolve

#else  // a build without PETSc

namespace hm::linsolve {

bool petsc_available() {
  return false;
}

std::unique_ptr<LinearSolver> make_petsc_solver(Method, const Settings&) {
  return nullptr;
}

}  // namespace hm::linsolve

#endif
