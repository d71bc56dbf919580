#pragma once
// THE time loop of fsi-simulate (LDD-SPEC §1.11, §4): one place where a flow is advanced from its
// start time to the end time, for rigid walls that are fixed or in prescribed motion.
//
// Each step:
//   1. Δt = min(solver.stable_dt(w), time to the next output time), w the largest wall speed
//      over the coming step; when the output bound wins the step's limit is StepLimit::output.
//      within four stable steps of the output time the gap is divided into ceil(gap/Δt) equal
//      steps, so no sliver step is taken just before an output time (a short step also changes
//      the PPE's volume source, ldd/ppe.hpp);
//   2. the walls in motion are moved to t + Δt (positions, velocities, accelerations exact,
//      WallMesh::move) BEFORE solver.step(Δt);
//   3. after the step: a probe row at probe times (every step when probe_interval = 0) and a
//      snapshot at snapshot times; every StepMonitor is kept.
// Output times are start + k·interval (k = 1, 2, ...) and the end time; the start time gets a
// probe row and a snapshot before the first step. On ldd::FlowDiverged the loop stops, writes one
// snapshot of the failed state (SnapshotKind::diverged; the regular snapshots already written
// stay) and returns RunStatus::diverged with the report text. SI units: s, m, m/s.
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "coupling/flexible_body.hpp"
#include "ldd/flow.hpp"
#include "motion/rigid_motion.hpp"

namespace hm::coupling {

/// One wall's prescribed kinematics: its material vertex positions and its motion.
struct WallMotion {
  motion::Vertices x0;  ///< n × dim material positions [m] (vertex order of the wall)
  std::optional<motion::RigidMotion> motion;  ///< empty: the wall is fixed at x0
};

/// Moves every wall with a motion to its state at time t [s] (position, velocity, acceleration).
/// `walls` and `motions` are parallel (same order, same vertex counts).
template <int D>
void place_walls(std::span<ldd::WallMesh<D>> walls, std::span<const WallMotion> motions, double t);

/// Largest vertex speed of the moving walls at time t [m/s] (0 when none moves).
double max_wall_speed(std::span<const WallMotion> motions, double t);

struct TimeControl {
  double end = 0.0;                ///< [s], after the solver's start time
  double snapshot_interval = 0.0;  ///< [s]; 0: snapshots at the start and the end only
  double probe_interval = 0.0;     ///< [s]; 0: a probe row after every step
  /// [s]; 0: no checkpoints. Checkpoint times bound the steps like the other output times, so a
  /// run restarted from one takes the same steps as the run that wrote it.
  double checkpoint_interval = 0.0;
};

/// Times start + k·interval (k ≥ 1) below the end, then the end itself; interval 0: the end only.
class OutputClock {
 public:
  OutputClock(double start, double end, double interval);
  double next() const { return next_; }
  bool done() const { return done_; }
  /// Whether time t has reached next() (within round-off of the step that aimed at it).
  bool due(double t) const;
  /// Moves next() past t.
  void advance_past(double t);

 private:
  double start_, end_, interval_, next_;
  long k_ = 1;
  bool done_ = false;
};

enum class SnapshotKind { regular, diverged };
enum class RunStatus { completed, diverged };
const char* to_string(RunStatus status);

/// Where the loop's outputs go; every member may be empty (the output is then not produced).
template <int D>
struct RunSinks {
  /// One row of probe values of the current state (the column order of the caller).
  std::function<std::vector<double>(const ldd::FlowSolver<D>&)> evaluate_probes;
  /// A probe row at time t [s] (e.g. to the CSV file; the series is also kept in RunResult).
  std::function<void(double t, std::span<const double> values)> probe_row;
  std::function<void(const ldd::FlowSolver<D>&, SnapshotKind)> snapshot;
  /// After every step (progress bar, logs).
  std::function<void(const ldd::StepMonitor&)> progress;
  /// At checkpoint times (TimeControl::checkpoint_interval), after that time's probes and
  /// snapshot: the whole state to continue from (the result so far included).
  std::function<void(const ldd::FlowSolver<D>&, std::span<const FlexibleBody<D>>,
                     const struct RunResult&)>
      checkpoint;
};

struct ProbeSeries {
  std::vector<double> time;               ///< [s]
  std::vector<std::vector<double>> rows;  ///< one row of values per time
};

/// A flexible body's modal state over a run: the start and every step end.
struct ModalHistory {
  std::vector<double> time;              ///< [s]
  std::vector<Eigen::VectorXd> y, v, F;  ///< per time: coordinates, velocities, forces
  void record(double t, const Eigen::VectorXd& y_, const Eigen::VectorXd& v_,
              const Eigen::VectorXd& F_);
};

struct RunResult {
  RunStatus status = RunStatus::completed;
  double start_time = 0.0;  ///< [s] the run's first start (kept across restarts)
  /// Per step, one monitor per flexible body (empty without bodies).
  std::vector<std::vector<CouplingMonitor>> coupling;
  std::vector<ModalHistory> modal;  ///< per flexible body
  std::string divergence_report;    ///< ldd::DivergenceReport::text() of a diverged run
  std::vector<ldd::StepMonitor> monitors;
  ProbeSeries probes;
  ldd::PhaseSeconds phase_totals;  ///< summed over the steps [s]
  double end_time = 0.0;           ///< physical time reached [s]
  double wall_seconds = 0.0;       ///< wall-clock time of the loop [s]
  long snapshots = 0;              ///< snapshots written (the diverged one included)
};

/// Runs `solver` from its current time to time.end with the walls in `motions` (parallel to
/// solver.walls()) and the flexible `bodies` (their walls' motions are ignored: the modes move
/// them), started here (FlexibleBody::start) and stepped by coupled_step. `resume`: the result
/// so far of a run restarted from a checkpoint (solver and bodies restored to its time): the
/// loop continues it (its outputs, monitors and output clocks) instead of starting. InputError when
/// time.end is not after the solver's time or an interval is negative; FlowDiverged is caught
/// and reported in the result (other errors propagate).
template <int D>
RunResult run(ldd::FlowSolver<D>& solver, std::span<const WallMotion> motions,
              const TimeControl& time, const RunSinks<D>& sinks,
              std::span<FlexibleBody<D>> bodies = {}, const RunResult* resume = nullptr);

}  // namespace hm::coupling
