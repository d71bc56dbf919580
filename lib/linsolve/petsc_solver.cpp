#include "linsolve/petsc_solver.hpp"

#ifdef HM_WITH_PETSC

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <mpi.h>
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

/// A process's rows as PETSc's AIJ formats hold them (each row's columns ascending): in one
/// process the whole matrix ("own"); over processes the columns of its own unknowns ("own",
/// numbered from its first row) and the others' (global numbers), as MATMPIAIJ's two blocks.
/// MatCreateSeqAIJWithArrays and MatCreateMPIAIJWithSplitArrays use them in place, so they
/// live as long as the matrix. Measured on the 3-D dam break (202 k fluid points):
/// MatSeqAIJSetPreallocationCSR and MatCreateMPIAIJWithArrays, which insert every row through
/// MatSetValues, cost about 0.2 s of a 4.8 s step in one process and 0.3–0.4 s of a 2.8 s step
/// over 2 (for the matrix and the AMG's).
struct AijArrays {
  std::vector<PetscInt> own_offsets, own_columns, other_offsets, other_columns;
  std::vector<PetscScalar> own_values, other_values;
};

/// `a`'s rows (global columns, ascending in each row) split at this process's columns
/// [first, first + count).
AijArrays split_rows(const CsrMatrix& a, PetscInt first, PetscInt count) {
  const auto rows = static_cast<std::size_t>(a.rows());
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const double* value = a.valuePtr();
  const auto own = [&](int column) { return column >= first && column < first + count; };
  AijArrays s;
  s.own_offsets.assign(rows + 1, 0);
  s.other_offsets.assign(rows + 1, 0);
  for (std::size_t r = 0; r < rows; ++r) {
    HM_ASSERT(std::is_sorted(inner + outer[r], inner + outer[r + 1]),
              "petsc: row {} of the matrix has its columns out of order", r);
    const auto mine = std::count_if(inner + outer[r], inner + outer[r + 1], own);
    s.own_offsets[r + 1] = s.own_offsets[r] + static_cast<PetscInt>(mine);
    s.other_offsets[r + 1] =
        s.other_offsets[r] + (outer[r + 1] - outer[r]) - static_cast<PetscInt>(mine);
  }
  s.own_columns.resize(static_cast<std::size_t>(s.own_offsets.back()));
  s.own_values.resize(s.own_columns.size());
  s.other_columns.resize(static_cast<std::size_t>(s.other_offsets.back()));
  s.other_values.resize(s.other_columns.size());
  for (std::size_t r = 0; r < rows; ++r) {
    auto o = static_cast<std::size_t>(s.own_offsets[r]),
         t = static_cast<std::size_t>(s.other_offsets[r]);
    for (int k = outer[r]; k < outer[r + 1]; ++k) {
      if (own(inner[k])) {
        s.own_columns[o] = inner[k] - first;
        s.own_values[o++] = value[k];
      } else {
        s.other_columns[t] = inner[k];
        s.other_values[t++] = value[k];
      }
    }
  }
  return s;
}

/// Whether PETSc's AIJ arrays have the types of a CsrMatrix's (Debian's PETSc: 32-bit indices,
/// real double): then one process's matrix is made on the CsrMatrix's own arrays, no copy.
/// Measured on the 3-D dam break (96 k points, 75 entries a row): a copy of the PPE matrix
/// cost 2.4 % of a step.
constexpr bool kPetscTakesCsrArrays =
    std::is_same_v<PetscInt, int> && std::is_same_v<PetscScalar, double>;

/// A unique options prefix per solver, so that the options one solver sets (BoomerAMG's
/// coarsening) never leak into another.
std::string next_prefix() {
  static int count = 0;
  return fmt::format("hm{}_", count++);
}

/// KSP BiCGSTAB with right preconditioning, so that the residual it tests is the true
/// ‖b − Ax‖ (as the native solvers do), relative to ‖b‖. In one process (PETSC_COMM_SELF) or
/// over all of them (`distributed`: PETSC_COMM_WORLD, each process holding a block of rows in
/// rank order; every call is then collective, and every decision that could differ between
/// processes — a zero right-hand side, a non-finite answer, a changed size — is agreed first).
class PetscSolver final : public LinearSolver {
 public:
  PetscSolver(Method method, const Settings& s, bool distributed)
      : method_(method), settings_(s), distributed_(distributed) {
    ensure_petsc();
    comm_ = distributed ? PETSC_COMM_WORLD : PETSC_COMM_SELF;
    prefix_ = next_prefix();
  }
  ~PetscSolver() override { release(); }
  Method method() const override { return method_; }

  bool setup(const CsrMatrix& a) override {
    const auto start = Clock::now();
    setup_failure_.clear();
    try {
      release();
      set_partition(a);
      check(KSPCreate(comm_, &ksp_), "KSPCreate");
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
    if (!all_agree(ksp_ != nullptr && a.rows() == rows_ && a.cols() == columns_)) return false;
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
    const double norm_b = std::sqrt(sum_over_processes(b.squaredNorm()));
    if (norm_b == 0.0) {  // the native solvers' convention: x = 0, converged
      x.setZero();
      s.converged = true;
      return s;
    }
    try {
      Vec pb = nullptr, px = nullptr;
      const auto n = static_cast<PetscInt>(b.size());
      check(VecCreateMPIWithArray(comm_, 1, n, columns_, b.data(), &pb), "VecCreateMPIWithArray");
      check(VecCreateMPIWithArray(comm_, 1, n, columns_, x.data(), &px), "VecCreateMPIWithArray");
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
      s.residual = norm / norm_b;
      s.converged = all_agree(reason > 0 && x.allFinite());
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

  /// The processes' sum of `value` (the value itself in one process).
  double sum_over_processes(double value) const {
    double sum = value;
    if (distributed_) MPI_Allreduce(&value, &sum, 1, MPI_DOUBLE, MPI_SUM, comm_);
    return sum;
  }
  /// Whether `condition` holds on every process.
  bool all_agree(bool condition) const {
    int all = condition ? 1 : 0;
    if (distributed_) {
      const int mine = all;
      MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_LAND, comm_);
    }
    return all != 0;
  }

  /// This process's rows of the global matrix: a's rows, after those of the lower ranks; a's
  /// columns are the global ones. PetscFailure unless the processes' rows add up to them.
  void set_partition(const CsrMatrix& a) {
    HM_ASSERT(a.isCompressed(), "petsc: a compressed matrix");
    rows_ = a.rows();
    columns_ = a.cols();
    first_row_ = 0;
    if (!distributed_) {
      if (rows_ != columns_)
        throw PetscFailure(fmt::format("a {} × {} matrix is not square", rows_, columns_));
      return;
    }
    long mine = static_cast<long>(rows_), before = 0, total = 0;
    MPI_Exscan(&mine, &before, 1, MPI_LONG, MPI_SUM, comm_);
    MPI_Allreduce(&mine, &total, 1, MPI_LONG, MPI_SUM, comm_);
    int rank = 0;
    MPI_Comm_rank(comm_, &rank);
    first_row_ = rank == 0 ? 0 : static_cast<Eigen::Index>(before);
    if (!all_agree(total == static_cast<long>(columns_)))
      throw PetscFailure(fmt::format(
          "the processes' rows add up to {} for a matrix of {} columns (every process must "
          "give its block of rows of the one square matrix)",
          total, columns_));
  }

  /// `a` (this process's rows; columns sorted row by row) as a PETSc AIJ matrix on `arrays`,
  /// which must outlive it — in one process, where PETSc's types allow, on `a`'s own arrays
  /// (`arrays` left empty): then `a` must outlive it, as the seam's setup() requires anyway.
  Mat petsc_matrix(const CsrMatrix& a, std::unique_ptr<AijArrays>& arrays) const {
    Mat m = nullptr;
    const auto n = static_cast<PetscInt>(a.rows()), global = static_cast<PetscInt>(columns_);
    if (distributed_) {
      arrays = std::make_unique<AijArrays>(split_rows(a, static_cast<PetscInt>(first_row_), n));
      auto& s = *arrays;
      check(MatCreateMPIAIJWithSplitArrays(comm_, n, n, global, global, s.own_offsets.data(),
                                           s.own_columns.data(), s.own_values.data(),
                                           s.other_offsets.data(), s.other_columns.data(),
                                           s.other_values.data(), &m),
            "MatCreateMPIAIJWithSplitArrays");
      return m;
    }
    if constexpr (kPetscTakesCsrArrays) {
      for (Eigen::Index r = 0; r < a.rows(); ++r)
        HM_ASSERT(std::is_sorted(a.innerIndexPtr() + a.outerIndexPtr()[r],
                                 a.innerIndexPtr() + a.outerIndexPtr()[r + 1]),
                  "petsc: row {} of the matrix has its columns out of order", r);
      arrays.reset();  // PETSc reads the arrays and never writes them: the casts are safe
      check(MatCreateSeqAIJWithArrays(comm_, n, n, const_cast<int*>(a.outerIndexPtr()),
                                      const_cast<int*>(a.innerIndexPtr()),
                                      const_cast<double*>(a.valuePtr()), &m),
            "MatCreateSeqAIJWithArrays");
      return m;
    }
    arrays = std::make_unique<AijArrays>(split_rows(a, 0, n));  // all of it "own"
    auto& s = *arrays;
    check(MatCreateSeqAIJWithArrays(comm_, n, n, s.own_offsets.data(), s.own_columns.data(),
                                    s.own_values.data(), &m),
          "MatCreateSeqAIJWithArrays");
    return m;
  }

  /// A matrix replaced, destroyed (then its arrays freed) once KSPSetOperators has let go.
  struct Replaced {
    Mat matrix = nullptr;
    std::unique_ptr<AijArrays> arrays;
    CsrMatrix source;  ///< the CsrMatrix under it, where it is on one (the AMG's)
    ~Replaced() {
      if (matrix != nullptr) MatDestroy(&matrix);
    }
  };

  /// Makes `a` the operator. With `with_preconditioner_matrix` the hierarchy is (re)built on
  /// amg_matrix(a, amg_drop); without, the one built for an earlier matrix stays.
  void set_operators(const CsrMatrix& a, bool with_preconditioner_matrix) {
    Replaced old_matrix, old_preconditioner_matrix;
    old_matrix.matrix = std::exchange(matrix_, nullptr);
    old_matrix.arrays = std::move(matrix_arrays_);
    matrix_ = petsc_matrix(a, matrix_arrays_);
    if (with_preconditioner_matrix) {
      old_preconditioner_matrix.matrix = std::exchange(preconditioner_matrix_, nullptr);
      old_preconditioner_matrix.arrays = std::move(preconditioner_arrays_);
      old_preconditioner_matrix.source.swap(preconditioner_source_);  // arrays kept as they are
      if (settings_.amg_drop > 0.0) {
        preconditioner_source_ = amg_matrix(a, settings_.amg_drop, static_cast<int>(first_row_));
        preconditioner_matrix_ = petsc_matrix(preconditioner_source_, preconditioner_arrays_);
      }
    }
    check(KSPSetOperators(ksp_, matrix_,
                          preconditioner_matrix_ != nullptr ? preconditioner_matrix_ : matrix_),
          "KSPSetOperators");
  }

  void release() {
    if (ksp_ != nullptr) KSPDestroy(&ksp_);
    if (matrix_ != nullptr) MatDestroy(&matrix_);
    if (preconditioner_matrix_ != nullptr) MatDestroy(&preconditioner_matrix_);
    matrix_arrays_.reset();
    preconditioner_arrays_.reset();
    preconditioner_source_ = CsrMatrix();
    ksp_ = nullptr;
    matrix_ = nullptr;
    preconditioner_matrix_ = nullptr;
    rows_ = -1;
    columns_ = -1;
  }

  Method method_;
  Settings settings_;
  bool distributed_ = false;
  MPI_Comm comm_ = MPI_COMM_NULL;
  std::string prefix_;
  KSP ksp_ = nullptr;
  Mat matrix_ = nullptr;
  Mat preconditioner_matrix_ = nullptr;  ///< amg_matrix of the last setup's; null at amg_drop 0
  std::unique_ptr<AijArrays> matrix_arrays_, preconditioner_arrays_;  ///< under the matrices
  CsrMatrix preconditioner_source_;  ///< amg_matrix of the last setup's (under its matrix)
  Eigen::Index rows_ = -1;           ///< this process's rows of the last matrix
  Eigen::Index columns_ = -1;        ///< the global matrix's rows and columns
  Eigen::Index first_row_ = 0;
};

}  // namespace

bool petsc_available() {
  return true;
}

std::unique_ptr<LinearSolver> make_petsc_solver(Method method, const Settings& settings) {
  return std::make_unique<PetscSolver>(method, settings, /*distributed=*/false);
}

std::unique_ptr<LinearSolver> make_distributed_solver(Method method, const Settings& settings) {
  HM_ASSERT(method == Method::boomeramg || method == Method::gamg,
            "a distributed solver is boomeramg or gamg, not {}", to_string(method));
  return std::make_unique<PetscSolver>(method, settings, /*distributed=*/true);
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

std::unique_ptr<LinearSolver> make_distributed_solver(Method, const Settings&) {
  return nullptr;
}

}  // namespace hm::linsolve

#endif
