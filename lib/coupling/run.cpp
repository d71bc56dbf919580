#include "coupling/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/errors.hpp"

namespace hm::coupling {
namespace {

/// Round-off allowance when a step aimed at an output time lands next to it [s].
double time_tolerance(double t) {
  return 1e-12 * std::max(1.0, std::abs(t));
}

/// Within this many stable steps of an output time, the gap is divided into equal steps.
constexpr double even_steps_before_output = 4.0;

/// The step from t towards `target` (the next output time) and what limits it.
template <int D>
std::pair<double, ldd::StepLimit> step_size(const ldd::FlowSolver<D>& solver,
                                            std::span<const WallMotion> motions, double body_speed,
                                            double t, double target) {
  const double gap = target - t;
  double wall_speed = std::max(max_wall_speed(motions, t), body_speed);
  auto [dt, limit] = solver.stable_dt(wall_speed);
  const bool moving = std::any_of(motions.begin(), motions.end(),
                                  [](const WallMotion& w) { return w.motion.has_value(); });
  if (moving) {  // the wall speed over the step: its start, middle and end
    const double h = std::min(dt, gap);
    wall_speed = std::max(
        {wall_speed, max_wall_speed(motions, t + 0.5 * h), max_wall_speed(motions, t + h)});
    std::tie(dt, limit) = solver.stable_dt(wall_speed);
  }
  if (gap <= dt) return {gap, ldd::StepLimit::output};
  if (gap < even_steps_before_output * dt)
    return {gap / std::ceil(gap / dt), ldd::StepLimit::output};
  return {dt, limit};
}

}  // namespace

template <int D>
void place_walls(std::span<ldd::WallMesh<D>> walls, std::span<const WallMotion> motions, double t) {
  HM_ASSERT(walls.size() == motions.size(), "{} walls but {} wall motions", walls.size(),
            motions.size());
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (!motions[w].motion) continue;
    HM_ASSERT(motions[w].x0.cols() == D &&
                  motions[w].x0.rows() == static_cast<Eigen::Index>(walls[w].vertices().size()),
              "wall '{}': {} × {} material vertices for a {}-D wall of {} vertices",
              walls[w].name(), motions[w].x0.rows(), motions[w].x0.cols(), D,
              walls[w].vertices().size());
    const motion::VertexKinematics k = motions[w].motion->kinematics(t, motions[w].x0);
    const auto x = ldd::points_of<D>(k.x), v = ldd::points_of<D>(k.v), a = ldd::points_of<D>(k.a);
    walls[w].move(x, v, a);
  }
}

double max_wall_speed(std::span<const WallMotion> motions, double t) {
  double speed = 0.0;
  for (const WallMotion& w : motions) {
    if (!w.motion || w.x0.rows() == 0) continue;
    const motion::VertexKinematics k = w.motion->kinematics(t, w.x0);
    speed = std::max(speed, k.v.rowwise().norm().maxCoeff());
  }
  return speed;
}

// ---- output clock -----------------------------------------------------------------------------

OutputClock::OutputClock(double start, double end, double interval)
    : start_(start), end_(end), interval_(interval), next_(end) {
  HM_ASSERT(end > start && interval >= 0.0, "output clock [{}, {}] every {}", start, end, interval);
  if (interval_ > 0.0 && start_ + interval_ < end_ - time_tolerance(end_))
    next_ = start_ + interval_;
}

bool OutputClock::due(double t) const {
  return !done_ && t >= next_ - time_tolerance(next_);
}

void OutputClock::advance_past(double t) {
  while (due(t)) {
    if (next_ == end_) {
      done_ = true;
      return;
    }
    ++k_;
    next_ = start_ + static_cast<double>(k_) * interval_;
    if (next_ >= end_ - time_tolerance(end_)) next_ = end_;
  }
}

const char* to_string(RunStatus status) {
  return status == RunStatus::completed ? "completed" : "diverged";
}

// ---- the loop ---------------------------------------------------------------------------------

void ModalHistory::record(double t, const Eigen::VectorXd& y_, const Eigen::VectorXd& v_,
                          const Eigen::VectorXd& F_) {
  time.push_back(t);
  y.push_back(y_);
  v.push_back(v_);
  F.push_back(F_);
}

template <int D>
RunResult run(ldd::FlowSolver<D>& solver, std::span<const WallMotion> motions,
              const TimeControl& time, const RunSinks<D>& sinks, std::span<FlexibleBody<D>> bodies,
              const RunResult* resume) {
  const double now0 = solver.time();
  if (!(time.end > now0))
    input_error("time.end = {} s must be after the start time {} s", time.end, now0);
  if (time.snapshot_interval < 0.0 || time.probe_interval < 0.0 || time.checkpoint_interval < 0.0)
    input_error(
        "time.snapshot_interval = {} s, time.probe_interval = {} s and "
        "time.checkpoint_interval = {} s must be ≥ 0",
        time.snapshot_interval, time.probe_interval, time.checkpoint_interval);
  HM_ASSERT(motions.size() == solver.walls().size(), "{} wall motions for {} walls", motions.size(),
            solver.walls().size());
  const auto started = std::chrono::steady_clock::now();
  RunResult r = resume ? *resume : RunResult{};
  const double t0 = resume ? resume->start_time : now0;
  r.start_time = t0;
  r.status = RunStatus::completed;
  r.divergence_report.clear();
  const double earlier_seconds = resume ? resume->wall_seconds : 0.0;
  OutputClock snapshots(t0, time.end, time.snapshot_interval);
  OutputClock probes(t0, time.end, time.probe_interval);
  OutputClock checkpoints(t0, time.end, time.checkpoint_interval);
  const bool probe_every_step = time.probe_interval == 0.0;
  const bool checkpointing = time.checkpoint_interval > 0.0 && sinks.checkpoint;

  const auto record_probes = [&] {
    if (!sinks.evaluate_probes) return;
    const double t = solver.time();
    if (!r.probes.time.empty() && r.probes.time.back() == t) return;
    std::vector<double> row = sinks.evaluate_probes(solver);
    if (sinks.probe_row) sinks.probe_row(t, row);
    r.probes.time.push_back(t);
    r.probes.rows.push_back(std::move(row));
  };
  const auto snapshot = [&](SnapshotKind kind) {
    if (!sinks.snapshot) return;
    sinks.snapshot(solver, kind);
    ++r.snapshots;
  };
  const auto record_modal = [&] {
    for (std::size_t b = 0; b < bodies.size(); ++b)
      r.modal[b].record(solver.time(), bodies[b].y(), bodies[b].v(), bodies[b].F());
  };

  if (resume) {
    HM_ASSERT(r.modal.size() == bodies.size(), "resume: {} modal histories for {} bodies",
              r.modal.size(), bodies.size());
    for (OutputClock* clock : {&snapshots, &probes, &checkpoints}) clock->advance_past(now0);
  } else {
    r.modal.resize(bodies.size());
    for (auto& body : bodies) body.start(solver);
    record_modal();
    record_probes();
    snapshot(SnapshotKind::regular);
  }
  try {
    while (!snapshots.done()) {  // the end time is the snapshot clock's last time
      const double t = solver.time();
      double target =
          probe_every_step ? snapshots.next() : std::min(snapshots.next(), probes.next());
      if (checkpointing && !checkpoints.done()) target = std::min(target, checkpoints.next());
      double body_speed = 0.0;
      for (const auto& body : bodies) body_speed = std::max(body_speed, body.max_speed());
      const auto [dt, limit] = step_size<D>(solver, motions, body_speed, t, target);
      place_walls<D>(solver.walls(), motions, t + dt);
      ldd::StepMonitor m;
      if (bodies.empty()) {
        m = solver.step(dt);
      } else {
        r.coupling.emplace_back();
        m = coupled_step<D>(solver, bodies, dt, r.coupling.back());
        record_modal();
      }
      m.limit = limit;
      r.phase_totals += m.seconds;
      r.monitors.push_back(m);
      if (sinks.progress) sinks.progress(m);
      const double now = solver.time();
      if (probe_every_step || probes.due(now)) {
        record_probes();
        probes.advance_past(now);
      }
      if (snapshots.due(now)) {
        snapshot(SnapshotKind::regular);
        snapshots.advance_past(now);
      }
      if (checkpointing && checkpoints.due(now)) {
        r.end_time = now;
        r.wall_seconds =
            earlier_seconds +
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        sinks.checkpoint(solver, bodies, r);
        checkpoints.advance_past(now);
      }
    }
  } catch (const ldd::FlowDiverged& e) {
    if (r.coupling.size() > r.monitors.size()) r.coupling.pop_back();  // the failed step's
    r.status = RunStatus::diverged;
    r.divergence_report = e.report().text();
    snapshot(SnapshotKind::diverged);
  } catch (const StructureFailed&) {
    // The flow as the failed step left it; the run ends with the structure's report (exit 3,
    // no results).
    snapshot(SnapshotKind::diverged);
    throw;
  }
  r.end_time = solver.time();
  r.wall_seconds =
      earlier_seconds +
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

template void place_walls<2>(std::span<ldd::WallMesh<2>>, std::span<const WallMotion>, double);
template void place_walls<3>(std::span<ldd::WallMesh<3>>, std::span<const WallMotion>, double);
template RunResult run<2>(ldd::FlowSolver<2>&, std::span<const WallMotion>, const TimeControl&,
                          const RunSinks<2>&, std::span<FlexibleBody<2>>, const RunResult*);
template RunResult run<3>(ldd::FlowSolver<3>&, std::span<const WallMotion>, const TimeControl&,
                          const RunSinks<3>&, std::span<FlexibleBody<3>>, const RunResult*);

}  // namespace hm::coupling
