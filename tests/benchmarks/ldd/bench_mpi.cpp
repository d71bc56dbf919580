// The PPE solved over processes: run as `mpirun -np N bench_mpi` (N = 1…4; as root with
// OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1, beyond the cores with
// --oversubscribe). Every process captures the same dam-break PPE system (bench_ppe's, three
// steps after release), keeps its block of rows (the points are in spatial order: a block is a
// region of the column) and solves it with linsolve::make_distributed_solver (PETSc MPIAIJ,
// BiCGSTAB + BoomerAMG, tolerance 1e-6, amg_drop 0.05). Reported by rank 0: the process count,
// setup and solve seconds (the slowest process's), iterations from a cold start and from the
// run's warm start, and the residual recomputed from the whole matrix.
//   BM_DistributedPpe/<D>/<points>   2-D 40 k and 160 k, 3-D 27 k and 125 k fluid points
// And the points' decomposition (parallel::Decomposition, Zoltan RCB) of a jittered lattice
// column, then 20 steps of every point moving up to 0.2 dx: per step, the seconds of migration
// and of the ghost exchange within h = 2.1 dx (a new halo), of one refresh of D + 1 fields along
// it (velocity and pressure), the points migrated, the ghost points and halo bytes the largest
// process receives (id, position and 3 fields a point), against its owned points.
//   BM_Decomposition/<D>/<points>    3-D 200 k and 1 M points
// And the flow itself over the processes (FlowSolver with parallel::FlowExchange; one process:
// the flow without an exchange, as fsi-simulate runs it): the dam break of ppe_cases.hpp
// (BoomerAMG), a few steps to warm up, then `steps` steps; per step the wall seconds, each
// phase's seconds (the slowest process's), PPE iterations, points migrated, and the largest
// process's owned points and ghosts; particle-steps/s over the fluid points.
//   BM_DistributedFlow/<D>/<points>  2-D 20 k, 3-D 200 k fluid points
#include <benchmark/benchmark.h>
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <type_traits>

#include "dealt_points.hpp"
#include "linsolve/petsc_solver.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/flow_exchange.hpp"
#include "ppe_cases.hpp"

namespace hm::ldd {
namespace {

template <int D>
const test::CapturedPpe& captured(double points) {
  static std::map<double, std::unique_ptr<test::CapturedPpe>> cache;
  auto& c = cache[points];
  if (!c)
    c = std::make_unique<test::CapturedPpe>(test::capture_ppe<D>(test::spacing_for<D>(points)));
  return *c;
}

/// The largest of the processes' values (the slowest process's seconds, the largest share).
template <typename T>
T largest(T value) {
  static_assert(std::is_same_v<T, double> || std::is_same_v<T, long>);
  T max = value;
  MPI_Allreduce(&value, &max, 1, std::is_same_v<T, double> ? MPI_DOUBLE : MPI_LONG, MPI_MAX,
                MPI_COMM_WORLD);
  return max;
}

template <int D>
void BM_DistributedPpe(benchmark::State& state) {
  const auto processes = parallel::processes();
  const auto& c = captured<D>(static_cast<double>(state.range(0)));
  const auto n = static_cast<int>(c.rhs.size());
  const int base = n / processes.count, extra = n % processes.count;
  const int first = processes.rank * base + std::min(processes.rank, extra);
  const int rows = base + (processes.rank < extra ? 1 : 0);
  const linsolve::CsrMatrix mine = c.matrix.middleRows(first, rows);
  const linsolve::Settings settings;
  double setup = 0, cold = 0, warm = 0, residual = 0;
  int cold_iterations = 0, warm_iterations = 0;
  for (auto _ : state) {
    auto solver = linsolve::make_distributed_solver(linsolve::Method::boomeramg, settings);
    if (!solver->setup(mine)) {
      state.SkipWithError(solver->setup_failure().c_str());
      return;
    }
    setup = largest(solver->setup_seconds());
    Eigen::VectorXd x = Eigen::VectorXd::Zero(rows);
    const auto s0 = solver->solve(c.rhs.segment(first, rows), x);
    cold = largest(s0.seconds);
    cold_iterations = s0.iterations;
    Eigen::VectorXd whole(n);
    std::vector<int> counts(static_cast<std::size_t>(processes.count)),
        starts(static_cast<std::size_t>(processes.count));
    for (int r = 0; r < processes.count; ++r) {
      starts[static_cast<std::size_t>(r)] = r * base + std::min(r, extra);
      counts[static_cast<std::size_t>(r)] = base + (r < extra ? 1 : 0);
    }
    MPI_Allgatherv(x.data(), rows, MPI_DOUBLE, whole.data(), counts.data(), starts.data(),
                   MPI_DOUBLE, MPI_COMM_WORLD);
    residual = linsolve::relative_residual(c.matrix, c.rhs, whole);
    x = c.warm_start.segment(first, rows);
    const auto s1 = solver->solve(c.rhs.segment(first, rows), x);
    warm = largest(s1.seconds);
    warm_iterations = s1.iterations;
  }
  state.counters["processes"] = processes.count;
  state.counters["unknowns"] = n;
  state.counters["setup_s"] = setup;
  state.counters["cold_iterations"] = cold_iterations;
  state.counters["cold_solve_s"] = cold;
  state.counters["warm_iterations"] = warm_iterations;
  state.counters["warm_solve_s"] = warm;
  state.counters["true_residual"] = residual;
}

template <int D>
void BM_Decomposition(benchmark::State& state) {
  const auto processes = parallel::processes();
  const double points = static_cast<double>(state.range(0));
  const double dx = D == 2 ? std::sqrt(0.18 / points) : std::cbrt(0.027 / points);
  constexpr int steps = 20;
  double migrate_s = 0.0, ghosts_s = 0.0, refresh_s = 0.0, imbalance = 0.0;
  long migrated = 0, ghosts = 0, owned = 0;
  for (auto _ : state) {
    auto block = parallel::test::dealt_lattice<D>(dx, processes);
    parallel::Decomposition<D> decomposition(block);
    imbalance = decomposition.imbalance(block);
    for (int step = 0; step < steps; ++step) {
      for (std::size_t i = 0; i < block.size(); ++i)
        block.position[i] += parallel::test::displacement<D>(block.id[i] * (step + 2), 0.2 * dx);
      auto start = std::chrono::steady_clock::now();
      migrated += decomposition.migrate(block).sent;
      migrate_s +=
          largest(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      start = std::chrono::steady_clock::now();
      const auto halo = decomposition.halo(block, 2.1 * dx);
      ghosts_s +=
          largest(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      ghosts = std::max(ghosts, largest(halo.received()));
      // One field exchange of a step's phase: velocity and pressure.
      const std::vector<double> fields(block.size() * (D + 1), 1.0);
      start = std::chrono::steady_clock::now();
      const auto refreshed = halo.refresh(fields, D + 1);
      refresh_s +=
          largest(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      owned = largest(static_cast<long>(block.size()));
    }
  }
  state.counters["processes"] = processes.count;
  state.counters["points"] = points;
  state.counters["imbalance"] = imbalance;
  state.counters["owned_largest"] = static_cast<double>(owned);
  state.counters["ghosts_largest"] = static_cast<double>(ghosts);
  state.counters["halo_bytes_largest"] =
      static_cast<double>(ghosts) * (8.0 + 8.0 * (D + parallel::test::kWidth));
  state.counters["migrated_per_step"] = static_cast<double>(migrated) / steps;
  state.counters["migrate_s_per_step"] = migrate_s / steps;
  state.counters["ghosts_s_per_step"] = ghosts_s / steps;
  state.counters["refresh_s"] = refresh_s / steps;
}

template <int D>
void BM_DistributedFlow(benchmark::State& state) {
  const auto processes = parallel::processes();
  const double points = static_cast<double>(state.range(0));
  const int warm_up = 3, steps = static_cast<int>(state.range(1));
  SolverOptions ppe = FlowOptions<D>{}.ppe;
  ppe.preconditioner = Preconditioner::boomeramg;
  std::shared_ptr<PointExchange<D>> exchange;
  if (processes.count > 1) exchange = std::make_shared<parallel::FlowExchange<D>>();
  auto flow = test::dam_break<D>(test::spacing_for<D>(points), ppe, exchange);
  for (int s = 0; s < warm_up; ++s) flow.step(flow.stable_dt(0.0).first);
  PhaseSeconds phases;
  long iterations = 0, migrated = 0, ghosts = 0, owned = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    MPI_Barrier(MPI_COMM_WORLD);
    const auto start = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s) {
      const auto m = flow.step(flow.stable_dt(0.0).first);
      phases += m.seconds;
      iterations += m.ppe_iterations;
      migrated += flow.last_migration().sent;
      ghosts = std::max(ghosts, largest(static_cast<long>(flow.points().size() - flow.owned())));
      owned = std::max(owned, largest(static_cast<long>(flow.owned())));
    }
    MPI_Barrier(MPI_COMM_WORLD);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  long fluid = 0;
  for (Index i = 0; i < flow.owned(); ++i) fluid += flow.points().kind[i] == PointKind::fluid;
  MPI_Allreduce(MPI_IN_PLACE, &fluid, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  state.counters["processes"] = processes.count;
  state.counters["fluid_points"] = static_cast<double>(fluid);
  state.counters["s_per_step"] = seconds / steps;
  state.counters["particle_steps_per_s"] = static_cast<double>(fluid) * steps / seconds;
  state.counters["ppe_iterations_per_step"] = static_cast<double>(iterations) / steps;
  state.counters["migrated_per_step"] = static_cast<double>(migrated) / steps;
  state.counters["owned_largest"] = static_cast<double>(owned);
  state.counters["ghosts_largest"] = static_cast<double>(ghosts);
  const auto v = phases.values();
  const char* names[] = {"advect",    "pbd",          "neighbours", "operators", "free_surface",
                         "predictor", "ppe_assembly", "ppe_solve",  "corrector"};
  for (std::size_t k = 0; k < PhaseSeconds::count; ++k)
    state.counters[std::string(names[k]) + "_s"] = largest(v[k]) / steps;
  // Each process's share, for the balance of the regions (stderr, in rank order).
  long wall = 0, active_wall = 0, surface = 0;
  for (Index i = 0; i < flow.owned(); ++i) {
    const bool is_wall = flow.points().kind[i] == PointKind::wall;
    wall += is_wall;
    active_wall += is_wall && flow.points().type[i] != PointType::inactive;
    surface += !is_wall && flow.points().type[i] == PointType::surface;
  }
  for (int rank = 0; rank < processes.count; ++rank) {
    MPI_Barrier(MPI_COMM_WORLD);
    if (rank != processes.rank) continue;
    std::fprintf(
        stderr, "process %d: %ld fluid (%ld surface), %ld wall nodes (%ld active); s a step:", rank,
        static_cast<long>(flow.owned()) - wall, surface, wall, active_wall);
    for (std::size_t k = 0; k < PhaseSeconds::count; ++k)
      std::fprintf(stderr, " %s %.3f", names[k], v[k] / steps);
    std::fprintf(stderr, "\n");
  }
}

BENCHMARK(BM_DistributedFlow<2>)->Args({20000, 20})->Iterations(1)->UseRealTime();
BENCHMARK(BM_DistributedFlow<3>)->Args({210000, 5})->Iterations(1)->UseRealTime();
BENCHMARK(BM_DistributedPpe<2>)->Arg(40000)->Arg(160000)->Iterations(1)->UseRealTime();
BENCHMARK(BM_DistributedPpe<3>)->Arg(27000)->Arg(125000)->Iterations(1)->UseRealTime();
BENCHMARK(BM_Decomposition<3>)->Arg(200000)->Arg(1000000)->Iterations(1)->UseRealTime();

/// The other processes run the same benchmarks (the solves are collective) and report nothing.
class Silent : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>&) override {}
};

}  // namespace
}  // namespace hm::ldd

int main(int argc, char** argv) {
  const auto processes = hm::parallel::processes();
  benchmark::Initialize(&argc, argv);
  if (processes.rank == 0) {
    benchmark::RunSpecifiedBenchmarks();
  } else {
    hm::ldd::Silent silent;
    benchmark::RunSpecifiedBenchmarks(&silent);
  }
  benchmark::Shutdown();
  return 0;
}
