// Flow solver throughput: particle-steps per second (points × steps / wall time) of a dam break,
// 2-D with about 20 000 points and 3-D with about 100 000, on 1 and 2 threads, with the share of
// each phase of the step. The dam break is run to t√(g/H) = 0.5 first (the column collapsing, so
// that the timed steps are not those of water at rest), then a fixed number of steps is timed.
//   BM_DamBreak<D>/<threads>/<ppe>   ppe 0: Jacobi (automatic's solver below amg_unknowns),
//                                    1: BoomerAMG (builds with PETSc only; its hierarchy on the
//                                    matrix without its small entries, the default amg_drop),
//                                    2: BoomerAMG kept across steps (ReusePolicy::across_steps),
//                                    3: BoomerAMG with its hierarchy on the whole matrix
//                                    (amg_drop = 0, as before the drop), 4: automatic, the
//                                    flow's default (ppe_solver_defaults: the choice between
//                                    BoomerAMG and Jacobi by their iterations)
#include <benchmark/benchmark.h>
#include <omp.h>

#include "ppe_cases.hpp"

namespace hm::ldd {
namespace {

/// The dam break (tests/ldd/ppe_cases.hpp) with the PPE of series `ppe`.
template <int D>
FlowSolver<D> dam_break(double dx, int ppe) {
  SolverOptions o = FlowOptions<D>{}.ppe;
  o.amg_unknowns = 0;  // automatic = Jacobi, ILU when it stalls
  if (ppe > 0) o.preconditioner = Preconditioner::boomeramg;
  o.reuse.across_steps = ppe == 2;
  if (ppe == 3) o.amg_drop = 0.0;
  if (ppe == 4) o = ppe_solver_defaults(D);
  return test::dam_break<D>(dx, o);
}

template <int D>
void BM_DamBreak(benchmark::State& state, double dx, int steps, int threads, int ppe) {
  omp_set_num_threads(threads);
  const bool amg = ppe > 0;
  if (amg && !is_available(Preconditioner::boomeramg)) {
    state.SkipWithError("built without PETSc");
    return;
  }
  auto flow = dam_break<D>(dx, ppe);
  const double settle = 0.5 / std::sqrt(9.81 / 0.3);  // t√(g/H) = 0.5
  while (flow.time() < settle) flow.step(flow.stable_dt(0.0).first);
  PhaseSeconds phases;
  long total_steps = 0;
  double points = 0, iterations = 0, passes = 0;
  const auto before = flow.ppe_counters();
  for (auto _ : state) {
    for (int s = 0; s < steps; ++s) {
      const auto m = flow.step(flow.stable_dt(0.0).first);
      phases += m.seconds;
      points += flow.points().size();
      iterations += m.ppe_iterations;
      passes += m.ppe_passes;
      ++total_steps;
    }
  }
  const double total = phases.total();
  constexpr const char* kLabels[] = {"jacobi", "boomeramg", "boomeramg, kept across steps",
                                     "boomeramg on the whole matrix", "automatic"};
  state.SetLabel(kLabels[ppe]);
  state.counters["points"] = points / total_steps;
  state.counters["particle_steps_per_s"] = points / total;
  state.counters["ppe_iterations"] = iterations / total_steps;
  state.counters["ppe_passes"] = passes / total_steps;
  state.counters["ppe_setups"] =
      static_cast<double>(flow.ppe_counters().setups - before.setups) / total_steps;
  state.counters["ppe_solve_s_per_step"] = phases.ppe_solve / static_cast<double>(total_steps);
  auto share = [&](const char* name, double seconds) { state.counters[name] = seconds / total; };
  share("advect", phases.advect);
  share("pbd", phases.pbd);
  share("neighbours", phases.neighbours);
  share("operators", phases.operators);
  share("free_surface", phases.free_surface);
  share("predictor", phases.predictor);
  share("ppe_assembly", phases.ppe_assembly);
  share("ppe_solve", phases.ppe_solve);
  share("corrector", phases.corrector);
}

// 2-D: dx = 3 mm → 20 000 fluid points; 3-D: dx = 7.8 mm → ~98 000 (+ wall nodes).
void BM_DamBreak2D(benchmark::State& state) {
  BM_DamBreak<2>(state, 0.003, 40, static_cast<int>(state.range(0)),
                 static_cast<int>(state.range(1)));
}
void BM_DamBreak3D(benchmark::State& state) {
  BM_DamBreak<3>(state, 0.0078, 5, static_cast<int>(state.range(0)),
                 static_cast<int>(state.range(1)));
}
// Where BoomerAMG starts to beat Jacobi over a run (the automatic rule, SolverOptions::
// amg_unknowns): the dam break on 1 thread, 2-D at 1 250 … 20 000 fluid points (40 steps),
// 3-D at 1 500 … 32 000 (10 steps).
//   BM_PpeBreakEven<D>/<fluid points>/<ppe>
template <int D>
void BM_PpeBreakEven(benchmark::State& state) {
  const auto points = static_cast<double>(state.range(0));
  const double dx = D == 2 ? std::sqrt(0.18 / points) : std::cbrt(0.027 / points);
  BM_DamBreak<D>(state, dx, D == 2 ? 40 : 10, 1, static_cast<int>(state.range(1)));
}

void threads_and_ppe(benchmark::internal::Benchmark* b) {
  for (int ppe = 0; ppe < 5; ++ppe)
    for (int threads = 1; threads <= 2; ++threads) b->Args({threads, ppe});
}

BENCHMARK(BM_DamBreak2D)
    ->Apply(threads_and_ppe)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();
BENCHMARK(BM_DamBreak3D)
    ->Apply(threads_and_ppe)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();
BENCHMARK(BM_PpeBreakEven<2>)
    ->ArgsProduct({{1250, 2500, 5000, 10000, 20000}, {0, 1, 2, 3}})
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();
BENCHMARK(BM_PpeBreakEven<3>)
    ->ArgsProduct({{1500, 4000, 13500, 32000}, {0, 1, 2, 3}})
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace
}  // namespace hm::ldd
