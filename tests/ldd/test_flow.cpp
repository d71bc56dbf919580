// The flow solver, small versions of the acceptance cases (the full ones are pipelines
// and benchmarks): a jittered tank at rest (the regression test of spec §0.1 D4) in 2-D and 3-D,
// the Koshizuka & Oka dam break against the reference data, and the first sloshing mode of a
// rectangular tank against linear theory.
#include <gtest/gtest.h>

#include <cstdio>

#include "flow_cases.hpp"
#include "ldd/probes.hpp"

namespace hm::ldd {
namespace {

struct RestReport {
  double pressure_error = 0;  ///< max |p − ρg(H − z)| / ρgH, fluid points below the top layer
  double max_drift = 0;       ///< max |V/V0 − 1| of the volume monitor over the run
  double volume_change = 0;   ///< H/H0 − 1 from the surface height: the fluid's volume
  double spread = 0;          ///< spread of the elevation gauges (2dx apart) [m]
  double max_speed = 0;       ///< at the end [m/s]
  Index outside = 0;          ///< fluid points outside the tank
  long steps = 0;
};

template <int D>
RestReport rest(const Vec<D>& size, double depth, double dx, double end, double jitter,
                FlowOptions<D> options = {}) {
  Box<D> fluid{Vec<D>::Zero(), size};
  fluid.upper[D - 1] = depth;
  auto flow = test::water_in_tank<D>(size, fluid, dx, options, jitter);
  RestReport r;
  r.steps = test::run_until<D>(flow, end, &r.max_drift);
  const auto& p = flow.points();
  const auto [height, spread] = test::surface_height<D>(p, dx, size);
  r.spread = spread;
  r.volume_change = height / depth - 1;
  const double rho_g = 1000.0 * 9.81;
  for (Index i = 0; i < p.size(); ++i) {
    if (p.kind[i] != PointKind::fluid) continue;
    const auto& x = p.position[i];
    for (int a = 0; a < D; ++a)
      if (x[a] < 0.0 || (a < D - 1 && x[a] > size[a])) ++r.outside;
    r.max_speed = std::max(r.max_speed, p.velocity[i].norm());
    if (x[D - 1] > height - 1.5 * dx) continue;
    r.pressure_error = std::max(
        r.pressure_error, std::abs(p.pressure[i] - rho_g * (height - x[D - 1])) / (rho_g * height));
  }
  std::printf(
      "%d-D tank at rest, %.2f s, jitter %.1f dx, %d points: %ld steps, pressure error "
      "%.3f %% of rho g H, volume change %+.3f %% (volume monitor: max %.3f %%), surface "
      "spread %.2f mm (dx/4 = %.2f "
      "mm), max speed %.2e m/s, %d points outside\n",
      D, end, jitter, p.size(), r.steps, 100 * r.pressure_error, 100 * r.volume_change,
      100 * r.max_drift, 1e3 * r.spread, 250 * dx, r.max_speed, r.outside);
  return r;
}

// Issue acceptance: pressure within 1 % of ρg(H − z), volume drift < 0.5 %, surface flat to
// dx/4, no point outside. Without the XSPH stabiliser this tank blew up at 0.24 s (§0.1 D4).
TEST(LddFlow, JitteredTankAtRest2D) {
  const auto r = rest<2>(Vec<2>(0.5, 0.4), 0.3, 0.01, 2.0, 0.2);
  EXPECT_LT(r.pressure_error, 0.01);
  EXPECT_LT(std::abs(r.volume_change), 0.005);
  EXPECT_LT(r.spread, 0.25 * 0.01);
  EXPECT_EQ(r.outside, 0);
  EXPECT_LT(r.max_speed, 0.05);
}

// The same tank with the wall nodes weighted by the wall length they stand for
// (solver.wall_node_weights): sampled at dx or at dx/16, the same answer. Measured: volume change
// +0.167 / +0.166 %, pressure error 0.100 / 0.099 %. Unweighted, the volume grew with the
// sampling (+0.17 / +0.40 / +1.15 % at dx, dx/2, dx/4: every node added a mirrored lattice
// column to the shifting's concentration and pushed the fluid off the walls).
TEST(LddFlow, JitteredTankAtRestDoesNotDependOnTheWallSampling2D) {
  std::vector<RestReport> r;
  for (const double spacing : {1.0, 0.0625}) {
    FlowOptions<2> options;
    options.wall_node_weights = true;
    options.wall_node_spacing = spacing;
    r.push_back(rest<2>(Vec<2>(0.5, 0.4), 0.3, 0.01, 2.0, 0.2, options));
    EXPECT_LT(r.back().pressure_error, 0.01);
    EXPECT_LT(std::abs(r.back().volume_change), 0.005);
    EXPECT_LT(r.back().spread, 0.25 * 0.01);
    EXPECT_EQ(r.back().outside, 0);
    EXPECT_LT(r.back().max_speed, 0.05);
  }
  EXPECT_NEAR(r[1].volume_change, r[0].volume_change, 0.0005);
  EXPECT_NEAR(r[1].pressure_error, r[0].pressure_error, 0.0005);
}

TEST(LddFlow, JitteredTankAtRest3D) {
  const auto r = rest<3>(Vec<3>(0.2, 0.1, 0.3), 0.15, 0.0125, 1.0, 0.2);
  EXPECT_LT(r.pressure_error, 0.01);
  EXPECT_LT(std::abs(r.volume_change), 0.005);
  EXPECT_LT(r.spread, 0.25 * 0.0125);
  EXPECT_EQ(r.outside, 0);
  EXPECT_LT(r.max_speed, 0.05);
}

/// Surge front x/L at the times T = t√(2g/L) of `times` (probe band: the two layers above the
/// floor), the largest |volume drift| and the largest fluid speed [m/s].
std::vector<double> dam_break_front(int resolution, const std::vector<double>& times,
                                    double* max_drift, double* max_speed) {
  using KO = test::KoshizukaOka;
  auto flow = KO::flow(resolution);
  const double dx = KO::L / resolution;
  std::vector<double> z;
  for (double T : times) {
    const double end = T / KO::time_scale();
    while (flow.time() < end - 1e-12) {
      const double dt = bounded_step(flow.stable_dt(0.0).first, end - flow.time());
      const auto m = flow.step(dt);
      *max_drift = std::max(*max_drift, std::abs(m.volume_drift));
      *max_speed = std::max(*max_speed, m.max_speed);
    }
    z.push_back(probe_front<2>(flow.points(), Vec<2>(1, 0), 0.0, 2 * dx, dx) / KO::L);
  }
  return z;
}

// Koshizuka & Oka (1996). A converged 2-D inviscid model with an instantaneous gate runs ahead
// of the experiment (spec §0.2: +5…12 % at L/20, further ahead under refinement); the test
// checks convergence towards the MPS simulation of the same paper and prints the gap to the
// experiment. The three-resolution study (L/20, L/40, L/80) is the pipeline dambreak_koshizuka.
TEST(LddFlow, DamBreakFrontKoshizukaOka) {
  const std::string dir = HM_SOURCE_DIR "/data/reference/dambreak_koshizuka_oka_1996/";
  const auto experiment = test::read_xy_csv(dir + "pysph_ko1996_experiment_front.csv");
  const auto mps = test::read_xy_csv(dir + "pysph_ko1996_mps_front.csv");
  ASSERT_GE(experiment.size(), 8u);
  ASSERT_GE(mps.size(), 10u);
  const std::vector<double> times{1.0, 1.5, 2.0, 2.5, 2.9};
  double worst[2] = {0, 0};
  std::vector<double> drifts;
  int k = 0;
  // Before the wall impact no fluid can outrun the Ritter front speed 2√(gH) of an ideal dam
  // break (H = 2L): 3.38 m/s. Walls seen with no-slip in the PPE source drove the surge tip to
  // 5 m/s at L/40 (lib/ldd/operators.hpp, slip_velocity_gradient).
  const double ritter = 2 * std::sqrt(9.81 * 2 * test::KoshizukaOka::L);
  for (int resolution : {20, 40}) {
    double drift = 0, speed = 0;
    const auto z = dam_break_front(resolution, times, &drift, &speed);
    for (std::size_t q = 0; q < times.size(); ++q) {
      const double e_mps = z[q] / test::interpolate(mps, times[q]) - 1;
      const double e_exp = z[q] / test::interpolate(experiment, times[q]) - 1;
      worst[k] = std::max(worst[k], std::abs(e_mps));
      std::printf("L/%d T %.2f: front %.3f L, against MPS %+.1f %%, against experiment %+.1f %%\n",
                  resolution, times[q], z[q], 100 * e_mps, 100 * e_exp);
    }
    std::printf(
        "L/%d: max |error| against MPS %.1f %%, max volume drift %.2f %%, max speed %.2f m/s "
        "(Ritter %.2f m/s)\n",
        resolution, 100 * worst[k], 100 * drift, speed, ritter);
    EXPECT_LT(speed, ritter);
    drifts.push_back(drift);
    ++k;
  }
  EXPECT_LT(worst[1], worst[0]);  // converging to the reference
  EXPECT_LT(worst[1], 0.05);
  // The volume drift to T = 3 falls at first order (measured 3.5 % → 1.6 %; L/80 0.5 %).
  EXPECT_LT(drifts[1], 0.6 * drifts[0]);
  EXPECT_LT(drifts[1], 0.02);
}

// Output times must not change the flow: steps cut short to meet probe times every 1 ms (about
// 60 % more steps at L/20) leave the front at T = 2 within 0.5 % of the run with the solver's
// own steps (measured 0.07 %). With the XSPH ε applied per step regardless of its length they
// slowed it by 2.5 %.
TEST(LddFlow, DamBreakFrontDoesNotDependOnOutputTimes) {
  using KO = test::KoshizukaOka;
  const double end = 2.0 / KO::time_scale(), dx = KO::L / 20;
  auto front = [&](double interval) {
    auto flow = KO::flow(20);
    long steps = 0;
    double next = interval > 0 ? interval : end;
    while (flow.time() < end - 1e-12) {
      const double target = std::min(next, end);
      flow.step(bounded_step(flow.stable_dt(0.0).first, target - flow.time()));
      if (flow.time() >= target - 1e-12) next += interval;
      ++steps;
    }
    const double z = probe_front<2>(flow.points(), Vec<2>(1, 0), 0.0, 2 * dx, dx) / KO::L;
    std::printf("K&O L/20, outputs every %.3g s: %ld steps, front at T = 2: %.4f L\n", interval,
                steps, z);
    return std::pair{z, steps};
  };
  const auto [free_z, free_steps] = front(0.0);
  const auto [bounded_z, bounded_steps] = front(0.001);
  EXPECT_GT(bounded_steps, 1.3 * free_steps);
  EXPECT_NEAR(bounded_z / free_z, 1.0, 0.005);
}

// The hard case: the K&O dam break continued past the wall impact, the run-up, the plunging wave
// and its re-entry to t√(g/H) = 8 (H = 2L, T = t√(2g/L) = 16) without divergence, at L/20 and
// L/30; the largest volume drift (ldd/volume.hpp, the half-density region) must fall under
// refinement. The bound, < 2 %, holds at the finest resolution run, the pipeline
// dambreak_koshizuka at L/80: 1.27 % (L/40 2.66 %; measured with the default shifting).
TEST(LddFlow, DamBreakPastImpactToEightTimeUnits) {
  using KO = test::KoshizukaOka;
  const double end = 8.0 / std::sqrt(9.81 / (2 * KO::L));
  double drift[2] = {0, 0};
  int k = 0;
  for (int resolution : {20, 30}) {
    auto flow = KO::flow(resolution);
    long steps = 0;
    while (flow.time() < end - 1e-12) {
      const auto m = flow.step(bounded_step(flow.stable_dt(0.0).first, end - flow.time()));
      drift[k] = std::max(drift[k], std::abs(m.volume_drift));
      ++steps;
    }
    std::printf("K&O L/%d to t sqrt(g/H) = 8: %ld steps, max volume drift %.2f %%, %d escaped\n",
                resolution, steps, 100 * drift[k], flow.step(1e-6).escaped);
    ++k;
  }
  EXPECT_LT(drift[1], drift[0]);
  EXPECT_LT(drift[1], 0.05);
}

// A jet thrown over the right wall of an open tank (0.3 × 0.1 m, water 0.1 × 0.06 m moving at
// (1.5, 1.2) m/s next to it) lands behind the wall: those points have left the domain and are
// removed, never put back in front of the wall they did not cross — which teleported the K&O
// run-up jet into the fluid beside the right wall at L/80 (speed 320 m/s at t = 0.775 s).
TEST(LddFlow, JetOverAWallLeavesTheDomain) {
  const double dx = 0.005;
  std::vector<WallMesh<2>> walls;
  walls.push_back(test::box_tank<2>(Vec<2>(0.3, 0.1), 4 * dx, {"xmin", "xmax", "ymin"}));
  const Box<2> box{Vec<2>(0.2, 0.0), Vec<2>(0.3, 0.06)};
  const auto x = seed_box<2>(box, dx, walls);
  const std::vector<Vec<2>> u(x.size(), Vec<2>(1.5, 1.2));
  FlowOptions<2> o;
  o.dx = dx;
  o.gravity = Vec<2>(0, -9.81);
  FlowSolver<2> flow(std::move(walls), x, u, o);
  double speed = 0;
  Index behind = 0;
  while (flow.time() < 0.3) {
    const auto m = flow.step(flow.stable_dt(0.0).first);
    speed = std::max(speed, m.max_speed);
    const auto& p = flow.points();
    for (Index i = 0; i < p.size(); ++i)
      if (p.kind[i] == PointKind::fluid && p.position[i].x() > 0.3 && p.position[i].y() < 0.1)
        ++behind;
  }
  const auto escaped = flow.step(flow.stable_dt(0.0).first).escaped;
  std::printf("jet over a wall: %d of %zu points left the domain, max speed %.2f m/s\n", escaped,
              x.size(), speed);
  EXPECT_GT(escaped, 0);
  EXPECT_EQ(behind, 0);   // removed as soon as found behind the wall
  EXPECT_LT(speed, 4.0);  // the jet's own speed (|u0| = 1.9 m/s) plus the fall
}

/// Horizontal centre-of-mass offset of the fluid from the tank's centre line [m].
template <int D>
double centre_offset(const FlowSolver<D>& flow, double half_length) {
  double cx = 0;
  int n = 0;
  for (Index i = 0; i < flow.points().size(); ++i)
    if (flow.points().kind[i] == PointKind::fluid) {
      cx += flow.points().position[i].x();
      ++n;
    }
  return cx / n - half_length;
}

/// A first-mode sloshing wave (tank L × 2H, water H, surface H + a cos(πx/L)), L = 0.5 m,
/// H = 0.25 m, a = 0.02 m, dx = L/50.
FlowSolver<2> sloshing_wave(FlowOptions<2> o) {
  const double length = 0.5, depth = 0.25, a = 0.02, dx = length / 50;
  std::vector<WallMesh<2>> walls;
  walls.push_back(test::box_tank<2>(Vec<2>(length, 2 * depth), 4 * dx, {"xmin", "xmax", "ymin"}));
  const Box<2> box{Vec<2>::Zero(), Vec<2>(length, depth + a + dx)};
  std::vector<Vec<2>> fluid;
  for (const auto& x : seed_box<2>(box, dx, walls))
    if (x.y() < depth + a * std::cos(M_PI * x.x() / length)) fluid.push_back(x);
  o.dx = dx;
  o.gravity = Vec<2>(0, -9.81);
  return FlowSolver<2>(std::move(walls), fluid, {}, o);
}

// Implicit against explicit viscosity on a viscous sloshing wave (ν = 1e-3 m²/s, 1000× water:
// the explicit limit C_ν dx²/ν = 1e-2 s): with the same steps (Δt = 2 ms), the centre-of-mass
// history over one period must agree within 5 % of its amplitude (the viscosity itself removes
// 8 % of it over that time). Measured: 0.9 % at Δt = 2 ms, 0.1 % / 0.7 % at ν = 1e-6 / 1e-4;
// at Δt = 4 ms the two differed by 10.8 %: explicit viscosity at 0.4 of its C_ν limit is
// already inaccurate on the WLS rows next to walls, whose negative weights enlarge Σ|c_ij|.
TEST(LddFlow, ImplicitViscosityMatchesExplicit) {
  std::vector<double> history[2];
  int k = 0;
  for (const auto scheme : {ViscousScheme::explicit_euler, ViscousScheme::implicit_euler}) {
    FlowOptions<2> o;
    o.viscosity = 1e-3;
    o.viscous = scheme;
    // The same steps for both: the XSPH stabiliser acts per step, so different step counts
    // would differ by their smoothing, not by the viscous scheme.
    o.dt_max = 0.002;
    auto flow = sloshing_wave(o);
    for (int sample = 1; sample <= 8; ++sample) {
      const double t = 0.1 * sample;
      while (flow.time() < t - 1e-12) {
        flow.step(bounded_step(flow.stable_dt(0.0).first, t - flow.time()));
      }
      history[k].push_back(centre_offset(flow, 0.25));
    }
    ++k;
  }
  double scale = 0, diff = 0;
  for (std::size_t q = 0; q < history[0].size(); ++q) {
    scale = std::max(scale, std::abs(history[0][q]));
    diff = std::max(diff, std::abs(history[0][q] - history[1][q]));
  }
  std::printf(
      "viscous sloshing: max |explicit − implicit| centre offset %.3e m of %.3e m (%.1f %%)\n",
      diff, scale, 100 * diff / scale);
  EXPECT_LT(diff, 0.05 * scale);
}

// Linear sloshing: ω² = (πg/L) tanh(πH/L) for the first mode of a rectangular tank, L = 0.5 m,
// H = 0.25 m, initial surface H + a cos(πx/L) with a = 0.02 m. The period is taken from the
// zero crossings of the horizontal centre of mass, over whole periods (crossings k and k + 2),
// which cancels a constant offset of the signal.
TEST(LddFlow, LinearSloshingPeriod) {
  const double length = 0.5, depth = 0.25, a = 0.02, dx = length / 50;
  std::vector<WallMesh<2>> walls;
  walls.push_back(test::box_tank<2>(Vec<2>(length, 2 * depth), 4 * dx, {"xmin", "xmax", "ymin"}));
  const Box<2> box{Vec<2>::Zero(), Vec<2>(length, depth + a + dx)};
  std::vector<Vec<2>> fluid;
  for (const auto& x : seed_box<2>(box, dx, walls))
    if (x.y() < depth + a * std::cos(M_PI * x.x() / length)) fluid.push_back(x);
  FlowOptions<2> o;
  o.dx = dx;
  o.gravity = Vec<2>(0, -9.81);
  FlowSolver<2> flow(std::move(walls), fluid, {}, o);
  const double omega = std::sqrt(M_PI * 9.81 / length * std::tanh(M_PI * depth / length));
  const double period = 2 * M_PI / omega;
  std::vector<double> crossings;
  double previous = 0, previous_t = 0;
  while (flow.time() < 4 * period) {
    flow.step(bounded_step(flow.stable_dt(0.0).first, 4 * period - flow.time()));
    double cx = 0;
    int n = 0;
    for (Index i = 0; i < flow.points().size(); ++i)
      if (flow.points().kind[i] == PointKind::fluid) {
        cx += flow.points().position[i].x();
        ++n;
      }
    const double s = cx / n - 0.5 * length;
    if (flow.step_count() > 1 && (previous > 0) != (s > 0))
      crossings.push_back(previous_t + (flow.time() - previous_t) * previous / (previous - s));
    previous = s;
    previous_t = flow.time();
  }
  ASSERT_GE(crossings.size(), 5u);
  const std::size_t whole = (crossings.size() - 1) / 2;
  const double measured = (crossings[2 * whole] - crossings[0]) / static_cast<double>(whole);
  std::printf("sloshing: period %.4f s against %.4f s (%+.2f %%), %zu whole periods\n", measured,
              period, 100 * (measured / period - 1), whole);
  EXPECT_NEAR(measured / period, 1.0, 0.02);
}

// A spatial re-sort inside a step must keep each point's velocity at the step's start with it:
// the acceleration limit of the next step reads |Δu|/Δt per point. Paired with the re-sorted
// velocities, a dam break's acceleration jumped to |u_i − u_j|/Δt of unrelated points and the
// step after every re-sort was halved by the acceleration limit (K&O L/80: steps 26, 76, ...).
TEST(LddFlow, ResortKeepsTheAccelerationLimit) {
  auto flow = test::KoshizukaOka::flow(20);  // re-sorts every 25 steps
  double before = 0.0;
  for (int s = 1; s <= 26; ++s) {
    const auto [dt, limit] = flow.stable_dt(0.0);
    if (s == 25) before = dt;  // the step that re-sorts
    if (s == 26) {
      EXPECT_GT(dt, 0.9 * before) << "the step after a re-sort, limit " << to_string(limit);
    }
    flow.step(dt);
  }
}

}  // namespace
}  // namespace hm::ldd
