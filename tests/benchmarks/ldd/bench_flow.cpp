// Flow solver throughput: particle-steps per second (points × steps / wall time) of a dam break,
// 2-D with about 20 000 points and 3-D with about 100 000, on 1 and 2 threads, with the share of
// each phase of the step. The dam break is run to t√(g/H) = 0.5 first (the column collapsing, so that
// the timed steps are not those of water at rest), then a fixed number of steps is timed.
#include <benchmark/benchmark.h>
#include <omp.h>

#include "flow_cases.hpp"

namespace hm::ldd {
namespace {

template <int D>
FlowSolver<D> dam_break(double dx) {
  // Column H × 2H (H = 0.3 m) in a tank 4H long; 3-D: 0.15 m wide (Lobovsky-like).
  Vec<D> size, column;
  size[0] = 1.2;
  column[0] = 0.6;
  if constexpr (D == 3) {
    size[1] = 0.15;
    column[1] = 0.15;
  }
  size[D - 1] = 0.6;
  column[D - 1] = 0.3;
  const Box<D> fluid{Vec<D>::Zero(), column};
  std::vector<std::string> faces = D == 2 ? std::vector<std::string>{"xmin", "xmax", "ymin"}
                                          : std::vector<std::string>{"xmin", "xmax", "ymin",
                                                                     "ymax", "zmin"};
  std::vector<WallMesh<D>> walls;
  walls.push_back(test::box_tank<D>(size, 4 * dx, faces));
  FlowOptions<D> o;
  o.dx = dx;
  o.gravity[D - 1] = -9.81;
  auto x = seed_box<D>(fluid, dx, walls);
  return FlowSolver<D>(std::move(walls), x, {}, o);
}

template <int D>
void BM_DamBreak(benchmark::State& state, double dx, int steps) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  auto flow = dam_break<D>(dx);
  const double settle = 0.5 / std::sqrt(9.81 / 0.3);  // t√(g/H) = 0.5
  while (flow.time() < settle) flow.step(flow.stable_dt(0.0).first);
  PhaseSeconds phases;
  long total_steps = 0;
  double points = 0, iterations = 0;
  for (auto _ : state) {
    for (int s = 0; s < steps; ++s) {
      const auto m = flow.step(flow.stable_dt(0.0).first);
      phases += m.seconds;
      points += flow.points().size();
      iterations += m.ppe_iterations;
      ++total_steps;
    }
  }
  const double total = phases.total();
  state.counters["points"] = points / total_steps;
  state.counters["particle_steps_per_s"] = points / total;
  state.counters["ppe_iterations"] = iterations / total_steps;
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
void BM_DamBreak2D(benchmark::State& state) { BM_DamBreak<2>(state, 0.003, 40); }
void BM_DamBreak3D(benchmark::State& state) { BM_DamBreak<3>(state, 0.0078, 5); }

BENCHMARK(BM_DamBreak2D)->Arg(1)->Arg(2)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_DamBreak3D)->Arg(1)->Arg(2)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
}  // namespace hm::ldd
