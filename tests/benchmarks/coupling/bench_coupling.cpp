// Cost of the two-way coupling (coupling/flexible_body.hpp) on a light body: a piston wall on a
// spring closing a 2-D water layer 0.2 m × 0.1 m (m_a/m_s = 10, wet frequency 10 Hz; the case of
// tests/coupling/test_flexible_body.cpp), dx = H/80 (about 12 800 points). Reported per step:
// the coupling's own share of the wall time (loads, modal forces, CFPI, wall updates; with and
// without the added-mass solves), the pressure solves of the strong scheme's sub-iterations,
// and the step's cost against the same flow with the piston held fixed (one solve a step).
#include <benchmark/benchmark.h>
#include <omp.h>

#include <chrono>

#include "piston.hpp"

namespace hm::coupling {
namespace {

void BM_StrongCoupling(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  test::Piston p = test::piston(test::H / 80, 10.0, 10.0, CouplingScheme::strong);
  p.flow->walls()[1].set_releases_tension(false);
  p.bodies[0].start(*p.flow);
  std::vector<CouplingMonitor> monitors;
  const auto step = [&] {
    const double dt = p.flow->stable_dt(p.bodies[0].max_speed()).first;
    return coupled_step<2>(*p.flow, p.bodies, dt, monitors);
  };
  for (int s = 0; s < 20; ++s) step();  // the piston under way
  double coupling = 0, added = 0, solves = 0, wall = 0, fixed = 0;
  long steps = 0;
  for (auto _ : state) {
    for (int s = 0; s < 40; ++s) {
      const auto t0 = std::chrono::steady_clock::now();
      step();
      wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      coupling += monitors[0].seconds;
      added += monitors[0].added_mass_seconds;
      solves += monitors[0].iterations;
      ++steps;
    }
  }
  // The same flow with the piston held where it is: one pressure solve a step.
  for (int s = 0; s < 40; ++s) {
    const double dt = p.flow->stable_dt(0.0).first;
    const auto t0 = std::chrono::steady_clock::now();
    p.flow->step(dt);
    fixed += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  state.counters["points"] = static_cast<double>(p.flow->points().size());
  state.counters["coupling_share"] = (coupling - added) / wall;
  state.counters["with_added_mass_share"] = coupling / wall;
  state.counters["solves_per_step"] = solves / static_cast<double>(steps);
  state.counters["step_vs_fixed_wall"] = (wall / static_cast<double>(steps)) / (fixed / 40.0);
}

BENCHMARK(BM_StrongCoupling)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace
}  // namespace hm::coupling
