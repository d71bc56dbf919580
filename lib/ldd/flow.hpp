#pragma once
// The LDD free-surface flow solver: one time step n → n+1 (spec §1.3 with the §0.2 recipe,
// CHOICE-B fixed wall nodes). The caller moves the walls to t^{n+1} first (prescribed motion or
// the structure), then calls step(Δt):
//   1. wall nodes follow their walls (position, normal, velocity, acceleration at t^{n+1});
//   2. ADVECT fluid points r ← r + Δt u^n;
//   3. CLEARANCE against the wall meshes: a point closer than d0/2 to a wall is put back at d0/2,
//      its velocity towards the wall (relative to the wall) removed; a point behind a wall it
//      did not cross this step (a jet over an open wall end) has left the domain and is removed;
//   4. PBD (§1.4): Jacobi iterations of the repulsive pair constraint |r_ij| ≥ d0 (fluid–fluid,
//      both move) and |r_ij| ≥ d0/2 (fluid–wall node, the fluid point moves), clearance after
//      each; then, with solver.shifting > 0, Fickian shifting down the concentration gradient
//      (wall nodes standing for mirrored lattice columns, points within h of the free surface
//      left alone), which refills what PBD cannot (a drained stagnation corner); the velocity is
//      carried to the shifted position, u ← u + (∇u)·δr, with ∇u seen through slip walls;
//   5. NEIGHBOURS within h; dry wall nodes and wall nodes beyond the fluid inactive; pairs through
//      thin walls cut;
//   6. OPERATORS (eqs. 6–9, WLS Laplacian on one-sided stencils, Tikhonov on degenerate ones);
//   7. FREE SURFACE (§1.8, hysteresis on the previous types; a sheet one point thick is surface
//      on both faces, whatever the wall nodes beside it);
//   8. PREDICTOR u* = u + Δt(g + ν∇²u), viscosity explicit or implicit (no-slip wall velocity in
//      the viscous term only);
//   9. PPE (§1.9) with the relaxed volume source, its divergence through slip walls (across a
//      wall node only the normal velocity difference counts: the node's tangential velocity is
//      the no-slip condition of the viscous term, and in the divergence it drove a sliding
//      surge tip past the Ritter speed); wall nodes in tension become Dirichlet and the system
//      is solved again (§0.2 item 6), except on walls that keep tension (flexible bodies);
//  10. CORRECTOR u = u* − (Δt/ρ)∇p; isolated points are ballistic;
//  11. SMOOTHING (the stabiliser of §0.1 D4): XSPH over fluid neighbours only, renormalised,
//      u_i += ε' Σ_j (W_ij/Σ_k W_ik)(u_j − u_i) — walls exert no friction through it; ε' =
//      ε·min(1, Δt/Δt_stable), so a step cut short for an output time smooths less;
//  12. monitors: ∇·u after the step, volume from the number density, escaped points.
// What each item does at one point is a kernel of ldd/kernels.hpp (or of the operator, free-
// surface and PPE modules), run over the points by the driver of ldd/point_loop.hpp; this class
// holds the state and the order of the items.
// SI units: m, s, kg/m³, Pa (gauge), m²/s.
#include <array>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "ldd/exchange.hpp"
#include "ldd/free_surface.hpp"
#include "ldd/kernels.hpp"
#include "ldd/ppe.hpp"
#include "ldd/walls.hpp"

namespace hm::ldd {

/// How the viscous term of the predictor is integrated (§1.10).
enum class ViscousScheme : std::uint8_t {
  explicit_euler,  ///< u* = u + Δt(g + ν∇²u); adds the limit Δt ≤ C_ν dx²/ν
  implicit_euler,  ///< (I − Δtν∇²)u* = u + Δt g, one sparse solve per component
};

/// What set the time step (§1.11).
enum class StepLimit : std::uint8_t { cfl, viscous, acceleration, maximum, output };
const char* to_string(StepLimit limit);

/// The step to take towards an output time `remaining` [s] ahead, given the stable step `dt`:
/// `remaining` when it fits, else `dt`, but never leaving a remainder under dt/2 (then
/// remaining/2). The pressure of a projection carries (ρ/Δt)∇·u of the advected points, so a
/// sliver of a step cut off before an output time shows up in the pressure: measured on the 3-D
/// jittered tank, a 35× shorter last step raised the pointwise hydrostatic error from 1.6 % to 9 %.
double bounded_step(double dt, double remaining);

template <int D>
struct FlowOptions {
  // Physics
  double density = 1000.0;          ///< ρ [kg/m³]
  double viscosity = 1e-6;          ///< ν, kinematic [m²/s] (0: inviscid)
  Vec<D> gravity = Vec<D>::Zero();  ///< g [m/s²]
  // Discretisation
  double dx = 0.0;              ///< initial point spacing [m], > 0
  double support_factor = 2.5;  ///< h = support_factor · dx
  /// Largest spacing of the wall nodes along a wall, in units of dx (add_wall_nodes); nodes
  /// also sit at every vertex of a wall mesh.
  double wall_node_spacing = 1.0;
  /// Whether wall nodes enter the operators with the wall measure they stand for
  /// (wall_node_weights) instead of weight 1: the answer then no longer depends on how densely
  /// a wall is sampled.
  bool wall_node_weights = false;
  ViscousScheme viscous = ViscousScheme::explicit_euler;
  // PBD (§1.4)
  int pbd_iterations = 4;
  double pbd_relaxation = 1.5;  ///< ω of the Jacobi iteration
  double pbd_distance = 0.95;   ///< d0 / dx
  double pbd_clamp = 0.1;       ///< largest shift per iteration / dx
  /// A of the Fickian shifting after PBD (Lind et al. 2012, with the coefficient of Skillen et
  /// al. 2013): δr_i = −A dx |u_i| Δt ∇C_i, C_i = n_i/n0 over fluid neighbours; 0 disables.
  double shifting = 2.0;
  // Stabiliser and volume
  double smoothing = 0.5;            ///< ε of the XSPH smoothing (0 disables)
  double volume_relaxation = 0.05;   ///< α of the PPE volume source (0 disables)
  bool release_wall_tension = true;  ///< wall nodes with p < 0 → Dirichlet, solve again
  /// Surface points get p = −ρ(g·ν)dx/2, the pressure half a spacing below a free surface
  /// (§5 item 7), instead of p = 0.
  bool surface_offset = true;
  /// Interior points with a number density below this fraction of the lattice's n0 are made
  /// Dirichlet (spray, films); 0 disables.
  double sparse_density = 0.6;
  OperatorOptions operators{.min_dominance = 0.3};
  FreeSurfaceOptions free_surface;  ///< reference_density is set by the solver
  SolverOptions ppe = ppe_solver_defaults(D);
  // Time step (§1.11)
  double cfl = 0.3;                   ///< C_u
  double viscous_number = 0.1;        ///< C_ν (explicit viscosity only)
  double acceleration_number = 0.25;  ///< C_a
  double dt_max = 1e-2;               ///< [s]
  double dt_min = 1e-7;               ///< a step below this is divergence [s]
  /// Speed above which the run counts as diverged [m/s]; 0: 50·√(|g|·L), L the wall box diagonal.
  double speed_limit = 0.0;
  int resort_interval = 25;  ///< steps between spatial re-sorts of the points
};

/// Wall-clock seconds spent in each phase of a step.
struct PhaseSeconds {
  double advect = 0, pbd = 0, neighbours = 0, operators = 0, free_surface = 0, predictor = 0,
         ppe_assembly = 0, ppe_solve = 0, corrector = 0;
  /// The phases in this order, comma-separated (results.h5 phase_names).
  static constexpr const char* names =
      "advect,pbd,neighbours,operators,free_surface,predictor,ppe_assembly,ppe_solve,corrector";
  static constexpr std::size_t count = 9;
  std::array<double, count> values() const {
    return {advect,    pbd,          neighbours, operators, free_surface,
            predictor, ppe_assembly, ppe_solve,  corrector};
  }
  /// From values() (at least count entries).
  static PhaseSeconds from_values(std::span<const double> v);
  double total() const;
  PhaseSeconds& operator+=(const PhaseSeconds& o);
};

/// What one step did (the per-step monitors of the run).
struct StepMonitor {
  long step = 0;
  double time = 0.0;                 ///< t^{n+1} [s]
  double dt = 0.0;                   ///< [s]
  StepLimit limit = StepLimit::cfl;  ///< set by the caller, which chose dt
  int ppe_iterations = 0;
  int ppe_passes = 0;  ///< solves (1 + re-solves after releasing wall tension)
  double ppe_residual = 0.0;
  bool ppe_converged = true;
  std::string ppe_failure;      ///< why the PPE did not converge: solver, reason ("" when it did)
  double max_divergence = 0.0;  ///< max |∇·u^{n+1}| over interior fluid points [1/s]
  /// V/V0 − 1 of the volume the fluid fills (ldd/volume.hpp, the half-density region), V0 the
  /// initial volume scaled by the share of points still in the domain (escaped points carry
  /// their volume away). Measured at steps 1, 11, 21, …; the last value in between.
  double volume_drift = 0.0;
  double max_speed = 0.0;  ///< max |u| of fluid points [m/s]
  Index escaped = 0;       ///< fluid points removed so far (left the wall box)
  Index fluid = 0, surface = 0, isolated = 0, wall_active = 0;
  PhaseSeconds seconds;
};

/// The run diverged: which step, which criterion, the worst points.
struct DivergenceReport {
  long step = 0;
  double time = 0.0;
  std::string criterion;
  std::vector<std::string> worst_points;  ///< one line per point: index, position, value
  std::string text() const;
};

class FlowDiverged : public NumericalError {
 public:
  explicit FlowDiverged(DivergenceReport report);
  const DivergenceReport& report() const { return report_; }

 private:
  DivergenceReport report_;
};

/// Everything FlowSolver carries from one step to the next (a checkpoint): restoring it into a
/// solver built from the same scene continues the run exactly as if it had not stopped.
template <int D>
struct FlowState {
  PointSet<D> points;
  std::vector<std::int64_t> id;  ///< per point (FlowSolver::ids); empty: the points' order
  /// The last step's lists (PBD of the next step starts from them); none (offsets {0}) in the
  /// state of a distributed flow, whose lists were its processes': restore rebuilds them.
  Neighbours neighbours;
  std::vector<Mat<D>> velocity_gradient;
  std::vector<double> wall_distance, acceleration;
  /// Wall vertex positions [m], velocities [m/s], accelerations [m/s²], one list per wall.
  std::vector<std::vector<Vec<D>>> wall_x, wall_v, wall_a;
  double time = 0.0;
  long step = 0;
  Index escaped = 0;
  double last_volume_drift = 0.0, initial_volume = 0.0, last_max_wall_speed = 0.0,
         last_max_speed = 0.0;
  Index initial_fluid = 0;
};

/// How a solve of the PPE within a step treats the wall nodes in tension (walls that release
/// tension: WallMesh::releases_tension).
enum class TensionRelease : std::uint8_t {
  /// From the step's own types: nodes in tension are released (Dirichlet p = 0) and the system
  /// solved again (§0.2 item 6).
  fresh,
  /// The nodes the step's fresh solves fixed at p = 0 (in their re-solve) stay fixed and no
  /// other is released: the PPE is then linear in the walls' motion, as the strong coupling's
  /// quasi-Newton iteration assumes.
  kept,
};

template <int D>
class FlowSolver {
 public:
  /// Fluid points at `fluid` (velocities `velocity`, may be empty = at rest) in the walls, which
  /// are at their time-t0 positions. Wall nodes are sampled on every wall (thin walls on both
  /// sides). Runs the set-up part of a step (neighbours, operators, free surface, and a PPE with
  /// Δt = the first step) so that pressure is available at t0. InputError on bad options.
  /// With `processes` (ldd/exchange.hpp), the run is one of several processes that each build
  /// the same flow from the same scene: each then keeps and computes the points of its region,
  /// with ghosts of the others' within h; every call below is then collective. A distributed
  /// flow's walls are on every process, whole (moved alike by each, for a structure too); the
  /// implicit viscosity and the PPE observer are for one process (InputError / not called).
  FlowSolver(std::vector<WallMesh<D>> walls, std::span<const Vec<D>> fluid,
             std::span<const Vec<D>> velocity, const FlowOptions<D>& options, double t0 = 0.0,
             std::shared_ptr<PointExchange<D>> processes = nullptr);

  /// The walls; move them to t^{n+1} (WallMesh::move) before step().
  std::vector<WallMesh<D>>& walls() { return walls_; }
  const std::vector<WallMesh<D>>& walls() const { return walls_; }

  /// The largest stable Δt from the current state (§1.11) and what limits it. `wall_speed`:
  /// the largest wall speed over the coming step [m/s] (the walls' motion is known to the
  /// caller).
  std::pair<double, StepLimit> stable_dt(double wall_speed) const;

  /// One step to t + dt; the walls must already be at t + dt. Throws FlowDiverged.
  /// The same as begin_step(dt); solve_pressure(); finish_step().
  StepMonitor step(double dt);

  /// The step in three parts, for a structure whose wall kinematics depend on the pressure
  /// (strong coupling re-solves the PPE with new wall velocities and accelerations):
  /// begin_step does items 1–8 of the file comment (the walls already at t + dt),
  /// solve_pressure item 9 (repeatable, after refresh_wall_kinematics), finish_step 10–12.
  void begin_step(double dt);
  void solve_pressure(TensionRelease release = TensionRelease::fresh);
  StepMonitor finish_step();
  /// Within a step: re-reads the wall nodes' velocity and acceleration from the walls (moved by
  /// the caller with the same positions) and the wall nodes' u* that the PPE sees.
  void refresh_wall_kinematics();
  /// The pressure [Pa] per point the PPE gives for the wall-node accelerations `acceleration`
  /// [m/s², one per point, zero for fluid points] alone: no gravity, no velocity, no volume
  /// term, p = 0 at the free surface — the added-mass response of the fluid (spec §3.5), for a
  /// wall whose velocity changes by Δt·acceleration over the step (so that the wall nodes' u*
  /// does not change, see predict). Uses the current neighbours and point types: call between
  /// begin_step and finish_step, or after a step.
  std::vector<double> acceleration_pressure(std::span<const Vec<D>> acceleration);
  /// The state between steps (see FlowState); not within a step. Distributed: collective, every
  /// process's points on process 0 (in id order), an empty state on the others.
  FlowState<D> state() const;
  /// Continues from `state` (taken from a solver of the same scene: same walls and options).
  /// InputError when the walls do not match. Distributed: collective, every process given the
  /// whole state (of a run on any number of processes); each keeps its region's points.
  void restore(FlowState<D> state);
  /// Whether a step is between begin_step and finish_step.
  bool in_step() const { return pending_dt_ > 0.0; }

  /// The points this process holds: [0, owned()) its own, the rest ghost copies of other
  /// processes' points (none in a flow of one process).
  const PointSet<D>& points() const { return points_; }
  /// The points this process computes, [0, owned()) (ldd/point_loop.hpp): all of them in a flow
  /// of one process.
  Index owned() const { return exchange_ ? owned_ : points_.size(); }
  /// Each point's id, unique over the run and kept for its life: the fluid points numbered in
  /// the order of the constructor's `fluid`, then the wall nodes.
  const std::vector<std::int64_t>& ids() const { return id_; }
  /// The processes of a distributed flow (null: one process).
  const PointExchange<D>* processes() const { return exchange_.get(); }
  /// The points to write: a distributed flow's, every process's own on process 0 in id order
  /// (none on the others; collective), a flow's of one process, its own.
  PointSet<D> output_points() const;
  /// What the last step's migration did (a distributed flow).
  const Migration& last_migration() const { return last_migration_; }
  const Neighbours& neighbours() const { return neighbours_; }
  const Operators<D>& operators() const { return ops_; }
  const FlowOptions<D>& options() const { return options_; }
  double time() const { return time_; }
  long step_count() const { return step_; }
  double dx() const { return options_.dx; }
  double support() const { return options_.support_factor * options_.dx; }
  double reference_density() const { return n0_; }
  /// Velocity gradient (∇u)_ab = ∂u_a/∂x_b per point after the last step [1/s].
  const std::vector<Mat<D>>& velocity_gradient() const { return grad_u_; }
  /// Called after every PPE solve of a step's projection with the system, the pressure it was
  /// warm-started from (per point) and the report: for dumping and measuring real PPE matrices.
  using PpeObserver = std::function<void(
      const PoissonSystem& system, std::span<const double> warm_start, const SolveReport& report)>;
  void observe_ppe(PpeObserver observer) { ppe_observer_ = std::move(observer); }
  /// Setup reuse and fallbacks of the PPE solver over the run so far.
  linsolve::SystemCounters ppe_counters() const { return ppe_solver_.counters(); }

 private:
  void advect(double dt);
  /// What the per-point kernels read (ldd/kernels.hpp).
  kernels::Cloud<D> cloud() const { return {points_, neighbours_, ops_}; }
  void keep_clear_of_walls(bool all_points);
  void regularise_positions(double dt);
  void shift_down_concentration_gradient(double dt, std::vector<Vec<D>>& total);
  void transport_velocity(std::span<const Vec<D>> shift);
  void move_points(std::span<const Vec<D>> shift, std::vector<Vec<D>>& total);
  double typical_step() const;
  void rebuild_neighbours();
  /// The wall nodes' quadrature weights for the operators (options().wall_node_weights).
  void update_node_weights();
  void classify_points();
  /// `fluid_density`: the free surface's report's (FreeSurfaceReport::fluid_density).
  void mark_sparse_points_as_surface(std::span<const double> fluid_density);
  std::vector<Vec<D>> predict(double dt, std::vector<Vec<D>>& viscous);
  void solve_implicit_viscosity(double dt, std::vector<Vec<D>>& predicted,
                                const std::vector<Vec<D>>& viscous);
  double volume_drift() const;
  /// The volume the fluid fills [m^D] (ldd/volume.hpp) and the fluid points, over every process.
  std::pair<double, std::int64_t> measured_volume() const;
  void set_surface_pressure(std::vector<double>& dirichlet) const;
  bool releases_tension(Index wall_node) const;  ///< its wall's releases_tension()
  void project(double dt, std::span<const Vec<D>> predicted, std::span<const Vec<D>> viscous,
               TensionRelease release, StepMonitor& m);
  void correct(double dt, std::span<const Vec<D>> predicted);
  void smooth_velocity(double dt, double stable_step);
  void update_monitors(double dt, std::span<const Vec<D>> old_velocity, StepMonitor& m);
  void remove_escaped_points();
  void resort();
  void resort_by(std::span<const Index> order);
  std::pair<Vec<D>, Vec<D>> wall_box() const;  ///< the walls' present bounding box [m]
  void check_divergence(const StepMonitor& m) const;

  // A distributed flow (exchange_ set); each a no-op in one process.
  /// Owned points to the owners of the regions they are in (regions redrawn when the load
  /// drifted), optionally sorted spatially, and the new ghosts; the neighbour lists go.
  void redistribute(bool sort);
  /// All the points held (the set-up, a restore): this process keeps every count-th.
  void keep_every_processes_share();
  TravellingPoints<D> travelling_owned_points() const;
  /// Every process's points with their per-point state into `s` on process 0, in id order.
  void gather_on_first(FlowState<D>& s) const;
  void append(const TravellingPoints<D>& block);
  /// The ghosts' entries of a per-point field from their owners.
  void refresh_ghosts(std::vector<double>& field) const;
  void refresh_ghosts(std::vector<Vec<D>>& field) const;
  void refresh_ghost_types();
  double largest(double value) const;  ///< over the processes
  std::int64_t total(std::int64_t value) const;
  void project_distributed(PoissonData& data, TensionRelease release, StepMonitor& m);
  /// This process's rows of the PPE of `data`, their unknowns numbered over the processes (weak
  /// Neumann rows demoted: points_.type changes).
  struct DistributedPoisson {
    PoissonRows rows;
    std::vector<std::int64_t> global;  ///< per point held, its global unknown (−1: none)
  };
  DistributedPoisson assemble_distributed(PoissonData& data);
  /// The distributed PPE solver made ready for `matrix` (set up, or reused when it is the
  /// matrix last set up on every process); false when the setup failed.
  bool set_up_distributed(const linsolve::CsrMatrix& matrix);
  void solve_distributed_acceleration_pressure(PoissonData& data, std::vector<double>& pressure);

  FlowOptions<D> options_;
  std::vector<WallMesh<D>> walls_;
  PoissonSolver ppe_solver_;               ///< keeps its setup while the matrix does not change
  linsolve::SystemSolver viscous_solver_;  ///< the implicit viscosity's (§1.10)
  PpeObserver ppe_observer_;
  std::shared_ptr<PointExchange<D>> exchange_;  ///< null: one process
  std::unique_ptr<linsolve::LinearSolver> distributed_ppe_;
  std::unique_ptr<linsolve::CsrMatrix> distributed_matrix_;  ///< of the last distributed setup
  Index owned_ = 0;               ///< distributed: points [0, owned_) are this process's
  std::vector<std::int64_t> id_;  ///< per point, see ids()
  Migration last_migration_;
  PointSet<D> points_;
  Neighbours neighbours_;
  Operators<D> ops_;
  std::vector<double> node_weight_;    ///< ω per point for the operators; empty: all 1
  std::vector<Mat<D>> grad_u_;         ///< ∇u per point from the last step (Taylor transport)
  std::vector<double> wall_distance_;  ///< lower bound of each fluid point's wall clearance [m]
  std::vector<double> acceleration_;   ///< |Δu/Δt| of the last step per point [m/s²]
  std::vector<Vec<D>> step_start_;     ///< positions before this step's advection [m]
  std::vector<char> outside_;          ///< found behind a wall it did not cross (this step)
  double n0_ = 0.0;
  static constexpr long volume_interval = 10;  ///< steps between volume measurements
  double last_volume_drift_ = 0.0;
  double initial_volume_ = 0.0;  ///< fluid_volume at t0 [m^D]
  Index initial_fluid_ = 0;
  double time_ = 0.0;
  long step_ = 0;
  Index escaped_ = 0;
  double speed_limit_ = 0.0;
  double last_max_wall_speed_ = 0.0;
  double last_max_speed_ = 0.0;
  // The step in progress (begin_step → finish_step).
  double pending_dt_ = 0.0, pending_stable_step_ = 0.0;
  StepMonitor pending_;
  std::vector<Vec<D>> pending_old_velocity_, pending_predicted_, pending_viscous_;
  std::vector<PointType> pending_types_;  ///< types before the PPE (tension release changes them)
  std::vector<Index> released_;  ///< wall nodes the step's fresh solves fixed at p = 0 (owned)
};

}  // namespace hm::ldd
