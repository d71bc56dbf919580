#pragma once
// The pressure Poisson equation (spec §1.9), in two layers:
//  * a generic Poisson problem on the point cloud: interior rows Σ c_ij (p_j − p_i) = s_i
//    (Laplacian of eq. 7 / WLS), Neumann rows at wall nodes Σ (n_i·g_ij)(p_j − p_i) = q_i
//    (renormalised gradient eq. 6 along the wall normal), Dirichlet values at SURFACE and
//    ISOLATED points, eliminated to the right-hand side; every row scaled by its diagonal
//    (Neumann rows scale like 1/dx, interior rows like 1/dx²: D3). A system with no Dirichlet
//    value (a closed box) is singular: one interior point is pinned to p = 0.
//  * the PPE sources of the projection: s_i = (ρ/Δt) ∇·u*_i − α (ρ/Δt²)(n_i − n_0)/n_0 (the
//    volume term only at full-stencil points), q_i = ρ n_i·(g + ν∇²u − A^w)_i.
// Solved through the linear-solver seam (linsolve/): BiCGSTAB with Jacobi, which the unit
// diagonal makes the identity (the OpenMP BiCGSTAB of linsolve/bicgstab.hpp), ILU (Eigen's
// IncompleteLUT) or algebraic multigrid (PETSc: BoomerAMG, GAMG); by default Jacobi with an ILU
// fallback (see Preconditioner). Warm-started from the previous pressure; iterations and
// residual are returned, not thrown.
#include <array>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/SparseCore>

#include "ldd/operators.hpp"
#include "linsolve/system_solver.hpp"

namespace hm::ldd {

/// Right-hand sides of a Poisson problem, one value per point (the one its type uses).
struct PoissonData {
  std::vector<double> source;     ///< interior points: ∇²p [Pa/m²]
  std::vector<double> neumann;    ///< wall nodes: n·∇p [Pa/m]
  std::vector<double> dirichlet;  ///< surface / isolated points: p [Pa]
  /// Over processes: the owned wall nodes' Neumann rows, a coefficient per neighbour pair (as
  /// Neighbours::indices), computed once by demote_weak_neumann_rows for assemble_poisson_rows;
  /// empty: computed there.
  std::vector<double> wall_rows;
};

struct PoissonSystem {
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> matrix;  ///< row-scaled (unit diagonal)
  Eigen::VectorXd rhs;
  std::vector<Index> unknown_of;  ///< point → unknown, −1 for Dirichlet / inactive points
  std::vector<Index> point_of;    ///< unknown → point
  std::vector<double> dirichlet;  ///< per point, the value used where unknown_of is −1
  Index pinned = -1;              ///< point pinned to p = 0 (closed system), else −1
  Index weak_neumann = 0;         ///< wall rows turned Dirichlet (|Σ n·g_ij| < 0.2/dx)
};

/// Assembles the Poisson problem. Wall rows with |Σ_j n_i·g_ij| < 0.2/dx (one-point films, jet
/// tips) have no usable diagonal: they become SURFACE with p = 0 (points.type changes).
template <int D>
PoissonSystem assemble_poisson(PointSet<D>& points, const Neighbours& neighbours,
                               const Operators<D>& ops, const PoissonData& data, double dx);

/// The PPE over processes, where a process holds its owned points [0, owned) and after them
/// ghost copies of other processes' points within h (parallel/decomposition.hpp), in two steps
/// with an exchange between:
///  1. demote_weak_neumann_rows: the owned wall nodes whose Neumann row has no usable diagonal
///     become SURFACE (as assemble_poisson does; the rows kept in `wall_rows` when given, as
///     PoissonData::wall_rows); their owners' types must then reach the ghosts, and each point
///     its global unknown number (−1: Dirichlet or inactive);
///  2. assemble_poisson_rows: the rows of the owned unknowns, in the order of their points, with
///     global column numbers (sorted within each row) — this process's block of rows of the
///     system assemble_poisson builds from all the points in one piece (to round-off: the
///     neighbours are summed in another order).
/// Returns the number of rows demoted.
template <int D>
Index demote_weak_neumann_rows(PointSet<D>& points, const Neighbours& neighbours,
                               const Operators<D>& ops, double dx, Index owned,
                               std::vector<double>* wall_rows = nullptr);

struct PoissonRows {
  linsolve::CsrMatrix matrix;   ///< owned unknowns × all the processes' unknowns, unit diagonal
  Eigen::VectorXd rhs;          ///< of the owned unknowns
  std::vector<Index> point_of;  ///< row → (owned) point
};

template <int D>
PoissonRows assemble_poisson_rows(const PointSet<D>& points, const Neighbours& neighbours,
                                  const Operators<D>& ops, const PoissonData& data, Index owned,
                                  std::span<const std::int64_t> global_unknown,
                                  std::int64_t global_unknowns);

/// Makes `points` (unknowns of `system`) Dirichlet p = 0 without renumbering the unknowns: each
/// one's row becomes x = 0, its column stays (multiplying that 0). The solution is the one
/// assemble_poisson gives with those points Dirichlet p = 0 — no other row depends on a
/// neighbour's type — but the system keeps its size and all but those rows, so the
/// preconditioner built for it can serve the re-solve after wall tension is released. False
/// (nothing changed) for a pinned closed system, which must be assembled again (releasing a
/// point there ends the pinning).
bool fix_at_zero(PoissonSystem& system, std::span<const Index> points);

/// The PPE's linear solver (linsolve/linear_solver.hpp has the backends).
/// automatic: Jacobi, and ILU (IncompleteLUT) from the same warm start only if Jacobi does not
/// converge within max_iterations; from SolverOptions::amg_unknowns on (builds with PETSc),
/// BoomerAMG or that, whichever costs less in the run. Measured on hydrostatic tanks (Release, cold
/// start, tol 1e-6; tests/benchmarks/ldd BM_PpeIterations / BM_PpeSolve): Jacobi needs 5–10× more
/// iterations but is faster at every size — 2-D 1.7k / 25k / 98k points: 1.9 / 116 / 872 ms against
/// ILU 8.6 / 216 / 1398 ms; 3-D 9k / 53k / 240k points: 19 / 224 / 1271 ms against ILU 290 / 3420 /
/// 21 506 ms. IncompleteLUT factorises serially and its cost grows with the row length (3-D rows
/// hold ~60 entries). Eigen has no ILU(0), and IncompleteCholesky needs a symmetric matrix, which
/// the Neumann rows are not. boomeramg, gamg: PETSc's BiCGSTAB with algebraic multigrid (builds
/// with PETSc only), no fallback: their failure is the solve's.
enum class Preconditioner : std::uint8_t { jacobi, ilu, automatic, boomeramg, gamg };

/// "jacobi", "ilu", "automatic", "boomeramg", "gamg".
const char* to_string(Preconditioner preconditioner);
/// Whether this build can solve with `preconditioner` (boomeramg and gamg need PETSc).
bool is_available(Preconditioner preconditioner);

struct SolverOptions {
  Preconditioner preconditioner = Preconditioner::automatic;
  double tolerance = 1e-6;  ///< relative residual of the scaled system
  int max_iterations = 1000;
  double ilu_drop = 1e-4;  ///< IncompleteLUT drop tolerance
  int ilu_fill = 2;        ///< IncompleteLUT fill factor
  /// boomeramg, gamg: the hierarchy is built on the PPE matrix without its entries below
  /// amg_drop × their row's largest, lumped onto the diagonal (linsolve::amg_matrix).
  double amg_drop = 0.05;
  /// automatic, in builds with PETSc: for systems of at least this many unknowns, the cheaper
  /// of BoomerAMG (Jacobi as its fallback) and Jacobi (ILU as its fallback) by what each cost
  /// on the last matrix it served; below, Jacobi. 0: never BoomerAMG. The flow's default is
  /// measured per dimension: ppe_solver_defaults.
  Index amg_unknowns = 0;
  /// The costs compared, in Jacobi iterations on the same matrix, over all the solves of one
  /// matrix (a step's passes, the strong coupling's sub-iterations and added-mass solves):
  /// Jacobi's iterations against amg_setup_cost + amg_cycle_cost × BoomerAMG's iterations.
  /// Measured on the dam-break matrices (bench_ppe, 1 thread, amg_drop 0.05): a setup costs
  /// 30–36 Jacobi iterations in 2-D, 41–48 in 3-D; a BoomerAMG iteration 3.3–5.8. Counted in
  /// iterations, not seconds, so that a run's choices do not depend on the machine's load.
  double amg_setup_cost = 40.0;
  double amg_cycle_cost = 4.5;
  /// The backend not in use is tried again on one matrix after this many, an interval that
  /// doubles (up to max_probe_interval) each time the trial loses.
  int probe_interval = 8;
  int max_probe_interval = 256;
  /// Setups are always reused for an unchanged matrix; across_steps keeps a preconditioner
  /// for changed matrices of the same size too (linsolve::SystemSolver).
  linsolve::ReusePolicy reuse;
};

/// The flow solver's PPE options in `dimension` D: automatic choosing between BoomerAMG and
/// Jacobi from 2 000 unknowns in 2-D and from 5 000 in 3-D (amg_setup_cost 32 and 45).
/// Measured over whole runs of the collapsing dam break on 1 thread (bench_flow
/// BM_PpeBreakEven<D>), PPE seconds a step, Jacobi against BoomerAMG: 2-D 3.3 / 3.9 ms at 1.45 k
/// points (65 against 4.9 iterations), 8.4 / 7.1 at 2.7 k, 24 / 14 at 5.4 k, 173 / 59 at 20.8 k;
/// 3-D (the hierarchy on the dropped matrix, one setup for both passes of the tension release)
/// 13.8 / 14.2 ms at 1.5 k fluid points (5.2 k with the wall nodes), 44 / 36 at 4 k, 603 / 302
/// at 32 k, 873 / 537 at 96 k. The size alone does not decide: on the sloshing tank
/// (rhee_sloshing, 8.7 k unknowns, 32 Jacobi iterations a pass from the last step's pressure)
/// BoomerAMG's setups cost 261 s of PPE over the run against Jacobi's 163 s. Hence the choice
/// by iterations, in the run (PoissonSolver).
SolverOptions ppe_solver_defaults(int dimension);

/// The linear-solver strategy (primary, fallback, reuse) that `options` stand for on a system
/// of `unknowns` unknowns (automatic from amg_unknowns on: BoomerAMG's, one of the two
/// PoissonSolver chooses between).
linsolve::Strategy solver_strategy(const SolverOptions& options, Index unknowns);

struct SolveReport {
  bool converged = false;
  /// The preconditioner of the returned solution (never automatic); automatic → ilu means
  /// Jacobi did not converge and its iterations are not counted in `iterations`.
  Preconditioner preconditioner = Preconditioner::jacobi;
  /// Iterations of solves thrown away: the failed Jacobi attempt of automatic, a solve on a
  /// preconditioner kept from an earlier matrix that had grown too costly.
  int discarded_iterations = 0;
  int iterations = 0;
  double residual = 0.0;  ///< relative residual of the scaled system
  Index unknowns = 0;
  std::int64_t nonzeros = 0;
  bool setup = false;          ///< the preconditioner was set up for this solve
  double setup_seconds = 0.0;  ///< of that setup [s]
  double solve_seconds = 0.0;  ///< of the iterations [s]
  std::string failure;         ///< why it did not converge ("" when it did)
};

/// The PPE's solver over a run: one setup serves every solve of an unchanged matrix (the
/// strong-coupling re-solves, the per-mode added-mass solves), see linsolve::SystemSolver.
class PoissonSolver {
 public:
  explicit PoissonSolver(const SolverOptions& options = {});
  /// Solves the system; `pressure` (one value per point) is the warm start and receives the
  /// solution, with the Dirichlet values at Dirichlet points and 0 at inactive ones.
  /// With `keep_preconditioner`, a system changed in a few rows since the last solve (by
  /// fix_at_zero) reuses its preconditioner (linsolve::SystemSolver::solve).
  SolveReport solve(const PoissonSystem& system, std::vector<double>& pressure,
                    bool keep_preconditioner = false);
  const SolverOptions& options() const { return options_; }
  /// Over every solve so far.
  linsolve::SystemCounters counters() const;

 private:
  linsolve::SystemSolver& solver_for(Index unknowns);
  /// automatic from amg_unknowns on: the backend for `matrix` (the current one's while the
  /// matrix is the one it was last given or `same_matrix` says its rows were only fixed).
  linsolve::SystemSolver& chosen_backend(const linsolve::CsrMatrix& matrix, bool same_matrix);
  /// Records the finished matrix's cost and picks the backend of the next one.
  void choose_next_backend();
  double cost_of(const SolveReport& report) const;  ///< in Jacobi iterations

  /// automatic's choice between BoomerAMG (large_) and Jacobi (small_), over the run.
  struct BackendChoice {
    bool amg = true;  ///< the backend of the current matrix
    /// [Jacobi, BoomerAMG] on their last matrix, in Jacobi iterations; < 0: not yet solved
    std::array<double, 2> cost{-1.0, -1.0};
    std::array<int, 2> idle{0, 0};  ///< matrices since each last served
    double current_cost = 0.0;      ///< on the current matrix so far
    bool trial = false;             ///< the current matrix is a trial of the other
    bool started = false;           ///< a matrix has been solved
    int interval = 0;               ///< matrices before the next trial
  };

  SolverOptions options_;
  BackendChoice choice_;
  /// Made on first use: the one of the options, or automatic's below amg_unknowns (Jacobi) …
  std::unique_ptr<linsolve::SystemSolver> small_;
  std::unique_ptr<linsolve::SystemSolver> large_;  ///< … and from amg_unknowns on (BoomerAMG)
};

/// One solve with a solver of its own (no setup kept): PoissonSolver(options).solve(...).
SolveReport solve_poisson(const PoissonSystem& system, std::vector<double>& pressure,
                          const SolverOptions& options = {});

template <int D>
struct PpeOptions {
  double density = 1000.0;          ///< ρ [kg/m³]
  Vec<D> gravity = Vec<D>::Zero();  ///< g [m/s²]
  double dt = 0.0;                  ///< Δt [s], > 0
  double dx = 0.0;                  ///< initial spacing [m]
  double volume_relaxation = 0.05;  ///< α of §0.2 item 5 (0 disables)
  double reference_density = 0.0;   ///< n_0 (0 disables the volume term)
  /// τ [s] of the volume term, which is α ρ (n_i − n_0)/(n_0 Δt max(Δt, τ)): with τ = 0 it is
  /// the α ρ/Δt² of §0.2, which corrects a fixed fraction of the density error per step and
  /// puts a pressure ∝ 1/Δt² into the field — a step cut short for an output time (Δt 3.5×
  /// smaller) raised the hydrostatic error of a jittered tank from 0.15 % to 0.96 % of ρgH.
  /// With τ the typical step (the acceleration limit under gravity), shorter steps correct
  /// proportionally less per step, i.e. at a fixed rate in time [CHOICE].
  double volume_time_scale = 0.0;
};

/// Sources of the PPE. predicted: u* per point (wall nodes: U + Δt(g + ν∇²u), not U: D1);
/// viscous: ν∇²u per point [m/s²] (may be empty = 0). Dirichlet values are p_atm = 0.
template <int D>
PoissonData ppe_data(const PointSet<D>& points, const Neighbours& neighbours,
                     const Operators<D>& ops, std::span<const Vec<D>> predicted,
                     std::span<const Vec<D>> viscous, const PpeOptions<D>& options);

}  // namespace hm::ldd
