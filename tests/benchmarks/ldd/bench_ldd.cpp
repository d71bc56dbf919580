// LDD core per phase, in points per second: neighbour search, operators, free surface, PPE
// assembly, PPE solve (ILU-BiCGSTAB, cold start) — a water column at rest in a box tank, 2-D
// with ~100 000 points and 3-D with ~200 000 points, 1 and 2 threads (second argument).
// PPE iterations against N: BM_PpeIterations*, counter "iterations".
#include <benchmark/benchmark.h>
#include <omp.h>

#include <map>
#include <memory>

#include "tank.hpp"

namespace hm::ldd {
namespace {

template <int D>
test::Column<D>& column() {
  // 2-D: 1.0 × 0.4 m of water at dx = 2 mm → 100 000 fluid points (+ wall nodes).
  // 3-D: 0.6 × 0.6 × 0.56 m at dx = 1 cm → 201 600 fluid points (+ wall nodes).
  static std::unique_ptr<test::Column<D>> c;
  if (!c) {
    if constexpr (D == 2)
      c = std::make_unique<test::Column<2>>(
          test::water_column<2>(Vec<2>(1.0, 0.6), 0.4, 0.002, 0.1));
    else
      c = std::make_unique<test::Column<3>>(
          test::water_column<3>(Vec<3>(0.6, 0.6, 0.8), 0.56, 0.01, 0.1));
  }
  return *c;
}

template <int D>
void set_up(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  state.counters["points"] = column<D>().points.size();
}

template <int D>
void BM_Neighbours(benchmark::State& state) {
  auto& c = column<D>();
  set_up<D>(state);
  for (auto _ : state) {
    auto nb = find_neighbours<D>(c.points.position, c.h);
    benchmark::DoNotOptimize(nb.indices.data());
  }
  state.SetItemsProcessed(state.iterations() * c.points.size());
}

template <int D>
void BM_Operators(benchmark::State& state) {
  auto& c = column<D>();
  set_up<D>(state);
  for (auto _ : state) {
    auto ops = compute_operators<D>(c.points.position, c.nb);
    benchmark::DoNotOptimize(ops.laplacian.data());
  }
  state.SetItemsProcessed(state.iterations() * c.points.size());
}

template <int D>
void BM_FreeSurface(benchmark::State& state) {
  auto& c = column<D>();
  set_up<D>(state);
  FreeSurfaceOptions fs;
  fs.reference_density = c.n0;
  for (auto _ : state) benchmark::DoNotOptimize(detect_free_surface<D>(c.points, c.nb, c.ops, fs));
  state.SetItemsProcessed(state.iterations() * c.points.size());
}

template <int D>
PpeOptions<D> ppe_options(const test::Column<D>& c) {
  PpeOptions<D> po;
  po.gravity = Vec<D>::Zero();
  po.gravity[D - 1] = -9.81;
  po.dt = 1e-3;
  po.dx = c.dx;
  po.reference_density = c.n0;
  return po;
}

template <int D>
void BM_PpeAssembly(benchmark::State& state) {
  auto& c = column<D>();
  set_up<D>(state);
  const auto po = ppe_options<D>(c);
  std::vector<Vec<D>> predicted(c.points.position.size(), po.dt * po.gravity);
  for (auto _ : state) {
    const auto data = ppe_data<D>(c.points, c.nb, c.ops, predicted, {}, po);
    auto sys = assemble_poisson<D>(c.points, c.nb, c.ops, data, c.dx);
    benchmark::DoNotOptimize(sys.rhs.data());
  }
  state.SetItemsProcessed(state.iterations() * c.points.size());
}

/// Benchmark argument → preconditioner: 0 ILU, 1 Jacobi, 2 automatic (what the default picks).
constexpr Preconditioner kPreconditioners[] = {Preconditioner::ilu, Preconditioner::jacobi,
                                               Preconditioner::automatic};

template <int D>
void BM_PpeSolve(benchmark::State& state) {
  auto& c = column<D>();
  set_up<D>(state);
  SolverOptions so;
  so.preconditioner = kPreconditioners[state.range(1)];
  SolveReport r;
  for (auto _ : state) {
    std::vector<double> p(c.points.pressure.size(), 0.0);
    r = solve_poisson(c.system, p, so);
  }
  state.counters["iterations"] = r.iterations;
  state.counters["converged"] = r.converged;
  state.counters["ilu"] = r.preconditioner == Preconditioner::ilu;
  state.SetItemsProcessed(state.iterations() * c.points.size());
}

template <int D>
void BM_PpeIterations(benchmark::State& state) {
  omp_set_num_threads(2);
  const double dx = 1.0 / static_cast<double>(state.range(0));
  const Preconditioner pre = kPreconditioners[state.range(1)];
  for (auto _ : state) {
    const auto c = D == 2 ? test::water_column<D>(Vec<D>::Constant(1.0), 0.6, dx, 0.1, pre)
                          : test::water_column<D>(Vec<D>::Constant(1.0), 0.6, dx, 0.25, pre);
    state.counters["points"] = c.points.size();
    state.counters["iterations"] = c.report.iterations;
    state.counters["solve_s"] = c.times.solve;
  }
}

#define HM_PHASES(D)                                                                          \
  BENCHMARK(BM_Neighbours<D>)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();  \
  BENCHMARK(BM_Operators<D>)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();   \
  BENCHMARK(BM_FreeSurface<D>)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime(); \
  BENCHMARK(BM_PpeAssembly<D>)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime(); \
  BENCHMARK(BM_PpeSolve<D>)                                                                   \
      ->Args({1, 0})                                                                          \
      ->Args({2, 0})                                                                          \
      ->Args({2, 1})                                                                          \
      ->Args({2, 2})                                                                          \
      ->Unit(benchmark::kMillisecond)                                                         \
      ->UseRealTime();
HM_PHASES(2)
HM_PHASES(3)
BENCHMARK(BM_PpeIterations<2>)
    ->ArgsProduct({{50, 100, 200, 400}, {0, 1}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PpeIterations<3>)
    ->ArgsProduct({{10, 20, 40}, {0, 1}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace hm::ldd
