// The PPE's linear solvers on real PPE matrices: the systems a dam break assembles (a column
// H × 2H, H = 0.3 m, in a tank 4H long; 3-D 0.15 m wide), taken from the flow solver's own
// projection (FlowSolver::observe_ppe) a few steps after release, 2-D from 10 k to 1 M points
// and 3-D from 27 k to 500 k. For each backend: setup and solve seconds, iterations from a cold
// start (x = 0) and from the run's warm start, at the runs' tolerance (1e-6), and the relative
// residual recomputed from the matrix, independently of the solver ("true_residual").
//   BM_PpeSolve/<D>/<size>/<method>/<drop>   method 0 jacobi, 1 ilu, 2 boomeramg, 3 gamg;
//                                     drop (AMG only): amg_drop in hundredths, 0 or 5 (the
//                                     default: the hierarchy on the matrix without its small
//                                     entries, linsolve::amg_matrix)
//   BM_PpeReuse/<policy>              60 steps of the collapsing 2-D column (~40 k points):
//                                     0 a setup every step, 1 reuse across steps (growth 1.3)
// The machine's two cores: the native solvers run on OMP_NUM_THREADS threads, PETSc on one.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>

#include "linsolve/linear_solver.hpp"
#include "ppe_cases.hpp"

namespace hm::ldd {
namespace {

using test::CapturedPpe;
using test::dam_break;
using test::spacing_for;

constexpr double kSizes2D[] = {1e4, 4e4, 1.6e5, 6.4e5, 1e6};
constexpr double kSizes3D[] = {2.7e4, 1.25e5, 5e5};

/// The matrix as MatrixMarket coordinate real general (1-based), the right-hand side after it
/// as a second "array" block in the same file.
void write_matrix_market(const std::string& path, const linsolve::CsrMatrix& a,
                         const Eigen::VectorXd& b) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return;
  std::fprintf(f, "%%%%MatrixMarket matrix coordinate real general\n%ld %ld %ld\n",
               static_cast<long>(a.rows()), static_cast<long>(a.cols()),
               static_cast<long>(a.nonZeros()));
  for (Eigen::Index r = 0; r < a.rows(); ++r)
    for (linsolve::CsrMatrix::InnerIterator it(a, r); it; ++it)
      std::fprintf(f, "%ld %ld %.17g\n", static_cast<long>(r + 1), static_cast<long>(it.col() + 1),
                   it.value());
  std::fprintf(f, "%%%%MatrixMarket matrix array real general\n%ld 1\n",
               static_cast<long>(b.size()));
  for (Eigen::Index r = 0; r < b.size(); ++r) std::fprintf(f, "%.17g\n", b[r]);
  std::fclose(f);
}

template <int D>
const CapturedPpe& captured(int size_index) {
  static std::map<int, std::unique_ptr<CapturedPpe>> cache;
  auto& c = cache[size_index];
  if (c) return *c;
  const double points = D == 2 ? kSizes2D[size_index] : kSizes3D[size_index];
  c = std::make_unique<CapturedPpe>(test::capture_ppe<D>(spacing_for<D>(points)));
  if (const char* dir = std::getenv("HM_PPE_DUMP"))  // for experiments with other tools
    write_matrix_market(fmt::format("{}/ppe_{}d_{}.mtx", dir, D, size_index), c->matrix, c->rhs);
  return *c;
}

constexpr linsolve::Method kMethods[] = {linsolve::Method::jacobi, linsolve::Method::ilu,
                                         linsolve::Method::boomeramg, linsolve::Method::gamg};

template <int D>
void BM_PpeSolve(benchmark::State& state) {
  const auto method = kMethods[state.range(1)];
  if (!linsolve::is_available(method)) {
    state.SkipWithError("not built in");
    return;
  }
  const CapturedPpe& c = captured<D>(static_cast<int>(state.range(0)));
  const linsolve::Settings settings{.tolerance = 1e-6,
                                    .max_iterations = 20000,
                                    .amg_drop = 0.01 * static_cast<double>(state.range(2))};
  double setup = 0, cold = 0, warm = 0, residual = 0;
  int cold_iterations = 0, warm_iterations = 0;
  bool converged = true;
  for (auto _ : state) {
    auto solver = linsolve::make_solver(method, settings);
    if (!solver->setup(c.matrix)) {
      state.SkipWithError(solver->setup_failure().c_str());
      return;
    }
    setup = solver->setup_seconds();
    Eigen::VectorXd x = Eigen::VectorXd::Zero(c.rhs.size());
    const auto s0 = solver->solve(c.rhs, x);
    cold = s0.seconds;
    cold_iterations = s0.iterations;
    residual = linsolve::relative_residual(c.matrix, c.rhs, x);
    x = c.warm_start;
    const auto s1 = solver->solve(c.rhs, x);
    warm = s1.seconds;
    warm_iterations = s1.iterations;
    converged = s0.converged && s1.converged;
  }
  const bool amg = method == linsolve::Method::boomeramg || method == linsolve::Method::gamg;
  state.SetLabel(
      amg ? fmt::format("{}, amg_drop {}", linsolve::to_string(method), settings.amg_drop)
          : linsolve::to_string(method));
  if (amg)
    state.counters["amg_nnz_per_row"] =
        static_cast<double>(linsolve::amg_matrix(c.matrix, settings.amg_drop).nonZeros()) /
        static_cast<double>(c.rhs.size());
  state.counters["points"] = static_cast<double>(c.points);
  state.counters["unknowns"] = static_cast<double>(c.rhs.size());
  state.counters["nnz_per_row"] =
      static_cast<double>(c.matrix.nonZeros()) / static_cast<double>(c.rhs.size());
  state.counters["setup_s"] = setup;
  state.counters["cold_iterations"] = cold_iterations;
  state.counters["cold_solve_s"] = cold;
  state.counters["warm_iterations"] = warm_iterations;
  state.counters["warm_solve_s"] = warm;
  state.counters["true_residual"] = residual;
  state.counters["converged"] = converged;
}

void BM_PpeReuse(benchmark::State& state) {
  if (!linsolve::is_available(linsolve::Method::boomeramg)) {
    state.SkipWithError("built without PETSc");
    return;
  }
  const linsolve::ReusePolicy policy{.across_steps = state.range(0) == 1};
  long iterations = 0, steps = 0;
  double setup = 0, solve = 0;
  for (auto _ : state) {
    auto flow = dam_break<2>(spacing_for<2>(4e4), Preconditioner::boomeramg, policy);
    const double start = 0.5 / std::sqrt(9.81 / 0.3);  // t√(g/H) = 0.5: collapsing
    while (flow.time() < start) flow.step(flow.stable_dt(0.0).first);
    flow.observe_ppe([&](const PoissonSystem&, std::span<const double>, const SolveReport& r) {
      iterations += r.iterations + r.discarded_iterations;
      setup += r.setup_seconds;
      solve += r.solve_seconds;
    });
    const auto before = flow.ppe_counters();
    for (int s = 0; s < 60; ++s, ++steps) flow.step(flow.stable_dt(0.0).first);
    state.counters["setups"] = static_cast<double>(flow.ppe_counters().setups - before.setups);
    state.counters["rebuilds_after_growth"] = static_cast<double>(
        flow.ppe_counters().rebuilds_after_growth - before.rebuilds_after_growth);
  }
  state.SetLabel(policy.across_steps ? "reuse across steps" : "setup every step");
  state.counters["iterations_per_step"] = static_cast<double>(iterations) / steps;
  state.counters["setup_s_per_step"] = setup / steps;
  state.counters["solve_s_per_step"] = solve / steps;
}

/// Jacobi and ILU once; each AMG with its hierarchy on the whole matrix and on the dropped one.
void methods_at(benchmark::internal::Benchmark* b, int size, bool with_ilu) {
  b->Args({size, 0, 0});
  if (with_ilu) b->Args({size, 1, 0});
  for (int m = 2; m < 4; ++m)
    for (int drop : {0, 5}) b->Args({size, m, drop});
}
void sizes_2d(benchmark::internal::Benchmark* b) {
  for (int s = 0; s < 5; ++s) methods_at(b, s, s <= 2);  // ILU's serial factorisation: to 160 k
}
void sizes_3d(benchmark::internal::Benchmark* b) {
  for (int s = 0; s < 3; ++s) methods_at(b, s, s == 0);
}

BENCHMARK(BM_PpeSolve<2>)->Apply(sizes_2d)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_PpeSolve<3>)->Apply(sizes_3d)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_PpeReuse)->Arg(0)->Arg(1)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
}  // namespace hm::ldd
