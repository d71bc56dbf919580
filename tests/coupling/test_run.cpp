// The time loop on small 2-D tanks: output times hit exactly, walls placed at t + Δt before the
// step (checked against the exact sway law), the time step bounded by the solver's stable step
// and the output times, divergence reported with a snapshot of the failed state.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "coupling/run.hpp"
#include "ldd/seeding.hpp"
#include "mesh/wall_mesher.hpp"

namespace hm::coupling {
namespace {

using ldd::Vec;

mesh::SurfaceMesh open_tank(double width, double height, double element) {
  mesh::WallOptions o;
  o.dim = 2;
  o.size = element;
  o.faces = {"xmin", "xmax", "ymin"};
  return mesh::mesh_rectangle_walls({Eigen::Vector2d::Zero(), Eigen::Vector2d(width, height)}, o);
}

struct Tank {
  mesh::SurfaceMesh surface;
  std::vector<WallMotion> motions;
  std::unique_ptr<ldd::FlowSolver<2>> flow;
};

/// Water 0.2 × depth m at dx in an open tank 0.2 × 0.15 m, optionally swaying.
Tank water_tank(double depth, double dx, std::optional<motion::RigidMotion> sway = {},
                ldd::FlowOptions<2> options = {}, Vec<2> velocity = Vec<2>::Zero()) {
  Tank t;
  t.surface = open_tank(0.2, 0.15, 2 * dx);
  std::vector<ldd::WallMesh<2>> walls;
  walls.emplace_back(t.surface, "tank");
  t.motions.push_back({t.surface.vertices, std::move(sway)});
  place_walls<2>(walls, t.motions, 0.0);
  const auto x = ldd::seed_box<2>({Vec<2>(0, 0), Vec<2>(0.2, depth)}, dx, walls);
  const std::vector<Vec<2>> u(x.size(), velocity);
  options.dx = dx;
  options.gravity = Vec<2>(0, -9.81);
  t.flow = std::make_unique<ldd::FlowSolver<2>>(std::move(walls), x, u, options);
  return t;
}

TEST(OutputClock, MultiplesOfTheIntervalThenTheEnd) {
  OutputClock clock(0.0, 0.35, 0.1);
  std::vector<double> times;
  while (!clock.done()) {
    times.push_back(clock.next());
    clock.advance_past(clock.next());
  }
  ASSERT_EQ(times.size(), 4u);
  EXPECT_DOUBLE_EQ(times[0], 0.1);
  EXPECT_DOUBLE_EQ(times[1], 0.2);
  EXPECT_DOUBLE_EQ(times[2], 0.30000000000000004);  // 3 × 0.1, not accumulated
  EXPECT_EQ(times[3], 0.35);
  OutputClock only_end(0.5, 1.0, 0.0);
  EXPECT_EQ(only_end.next(), 1.0);
  EXPECT_FALSE(only_end.due(1.0 - 1e-9));
  EXPECT_TRUE(only_end.due(1.0 - 1e-14));  // round-off of a step aimed at the end
  only_end.advance_past(1.0);
  EXPECT_TRUE(only_end.done());
  // An interval that does not divide the span: the last multiple below the end, then the end.
  OutputClock uneven(0.0, 0.1, 0.04);
  uneven.advance_past(0.04);
  EXPECT_DOUBLE_EQ(uneven.next(), 0.08);
  uneven.advance_past(0.09);  // skips past times already passed
  EXPECT_EQ(uneven.next(), 0.1);
}

TEST(PlaceWalls, SwayIsExactAtTheRequestedTime) {
  const double amplitude = 0.01, period = 0.5, t = 0.13;
  std::vector<WallMotion> motions{
      {open_tank(0.2, 0.15, 0.02).vertices,
       motion::sway_motion(2, Eigen::Vector3d::UnitX(), amplitude, period)}};
  std::vector<ldd::WallMesh<2>> walls;
  walls.emplace_back(open_tank(0.2, 0.15, 0.02), "tank");
  place_walls<2>(walls, motions, t);
  const double w = 2 * std::numbers::pi / period;
  const Vec<2> shift(amplitude * std::sin(w * t), 0.0);
  for (std::size_t k = 0; k < walls[0].vertices().size(); ++k) {
    const Vec<2> x0 = motions[0].x0.row(static_cast<Eigen::Index>(k)).transpose();
    EXPECT_LT((walls[0].vertices()[k] - (x0 + shift)).norm(), 1e-15);
  }
  EXPECT_NEAR(walls[0].velocity_at(0, Vec<2>(0.5, 0.5))[0], amplitude * w * std::cos(w * t), 1e-14);
  EXPECT_NEAR(walls[0].acceleration_at(0, Vec<2>(0.5, 0.5))[0],
              -amplitude * w * w * std::sin(w * t), 1e-12);
  EXPECT_NEAR(max_wall_speed(motions, t), amplitude * w * std::abs(std::cos(w * t)), 1e-14);
}

TEST(Run, OutputTimesAreHitAndEveryStepIsBounded) {
  Tank tank = water_tank(0.1, 0.01);
  auto& flow = *tank.flow;
  RunSinks<2> sinks;
  std::vector<double> snapshot_times;
  long rows = 0;
  sinks.evaluate_probes = [&](const ldd::FlowSolver<2>& s) {
    return std::vector<double>{s.time(), static_cast<double>(s.points().size())};
  };
  sinks.probe_row = [&](double, std::span<const double>) { ++rows; };
  sinks.snapshot = [&](const ldd::FlowSolver<2>& s, SnapshotKind kind) {
    EXPECT_EQ(kind, SnapshotKind::regular);
    snapshot_times.push_back(s.time());
  };
  // Before each step the loop asked the solver for its stable step: no step may exceed it.
  double stable_before = flow.stable_dt(0.0).first;
  sinks.progress = [&](const ldd::StepMonitor& m) {
    EXPECT_LE(m.dt, stable_before * (1 + 1e-12)) << "step " << m.step;
    if (m.limit != ldd::StepLimit::output) {
      EXPECT_LE(m.dt, stable_before);
    }
    stable_before = flow.stable_dt(0.0).first;
  };
  const RunResult r = run<2>(flow, tank.motions, {0.05, 0.02, 0.01}, sinks);
  EXPECT_EQ(r.status, RunStatus::completed);
  EXPECT_EQ(r.end_time, 0.05);
  // Probe rows at 0, 0.01, ..., 0.05; snapshots at 0, 0.02, 0.04, 0.05.
  ASSERT_EQ(r.probes.time.size(), 6u);
  EXPECT_EQ(rows, 6);
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_NEAR(r.probes.time[k], 0.01 * static_cast<double>(k), 1e-15);
    EXPECT_EQ(r.probes.rows[k][0], r.probes.time[k]);  // evaluated at the row's time
  }
  ASSERT_EQ(snapshot_times.size(), 4u);
  EXPECT_EQ(snapshot_times[0], 0.0);
  EXPECT_NEAR(snapshot_times[1], 0.02, 1e-15);
  EXPECT_NEAR(snapshot_times[2], 0.04, 1e-15);
  EXPECT_EQ(snapshot_times[3], 0.05);
  EXPECT_EQ(r.snapshots, 4);
  // Monitors: consecutive, Δt summing to the end time, some steps cut by an output time.
  double sum = 0.0;
  long output_limited = 0;
  for (std::size_t k = 0; k < r.monitors.size(); ++k) {
    EXPECT_EQ(r.monitors[k].step, static_cast<long>(k + 1));
    sum += r.monitors[k].dt;
    output_limited += r.monitors[k].limit == ldd::StepLimit::output;
  }
  EXPECT_NEAR(sum, 0.05, 1e-14);
  EXPECT_GT(output_limited, 0);
  EXPECT_GT(r.phase_totals.total(), 0.0);
  std::printf("tank at rest to 0.05 s: %zu steps, %ld cut by output times\n", r.monitors.size(),
              output_limited);
}

TEST(Run, MovingWallsArePlacedAtTheEndOfTheStepBeforeIt) {
  const double amplitude = 0.002, period = 0.2;
  Tank tank =
      water_tank(0.08, 0.01, motion::sway_motion(2, Eigen::Vector3d::UnitX(), amplitude, period));
  auto& flow = *tank.flow;
  const Vec<2> x0 = tank.motions[0].x0.row(0).transpose();
  RunSinks<2> sinks;
  double worst = 0.0;
  sinks.progress = [&](const ldd::StepMonitor& m) {
    // The step just taken ended at m.time: the walls it saw must be those of m.time.
    const double shift = amplitude * std::sin(2 * std::numbers::pi * m.time / period);
    worst = std::max(worst, (flow.walls()[0].vertices()[0] - x0 - Vec<2>(shift, 0)).norm());
  };
  const RunResult r = run<2>(flow, tank.motions, {0.05, 0.0, 0.0}, sinks);
  EXPECT_EQ(r.status, RunStatus::completed);
  EXPECT_LT(worst, 1e-15);
  // The peak wall speed A·2π/T = 0.063 m/s enters the CFL bound: Δt ≤ C·dx/U = 0.048 s holds
  // anyway here, so only check that no fluid point left the tank.
  EXPECT_EQ(r.monitors.back().escaped, 0);
}

TEST(Run, DivergenceStopsWithReportAndFailedSnapshot) {
  ldd::FlowOptions<2> options;
  options.speed_limit = 0.5;  // m/s; the water starts at 1 m/s
  Tank tank = water_tank(0.05, 0.01, {}, options, Vec<2>(1.0, 0.0));
  RunSinks<2> sinks;
  std::vector<SnapshotKind> kinds;
  sinks.snapshot = [&](const ldd::FlowSolver<2>&, SnapshotKind kind) { kinds.push_back(kind); };
  const RunResult r = run<2>(*tank.flow, tank.motions, {0.05, 0.0, 0.0}, sinks);
  EXPECT_EQ(r.status, RunStatus::diverged);
  EXPECT_NE(r.divergence_report.find("speed"), std::string::npos) << r.divergence_report;
  EXPECT_LT(r.end_time, 0.05);
  ASSERT_EQ(kinds.size(), 2u);
  EXPECT_EQ(kinds[0], SnapshotKind::regular);
  EXPECT_EQ(kinds[1], SnapshotKind::diverged);
  EXPECT_EQ(r.snapshots, 2);
}

TEST(Run, EndBeforeStartIsAnInputError) {
  Tank tank = water_tank(0.05, 0.01);
  try {
    run<2>(*tank.flow, tank.motions, {0.0, 0.0, 0.0}, {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("time.end = 0 s must be after the start time 0 s"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace hm::coupling
