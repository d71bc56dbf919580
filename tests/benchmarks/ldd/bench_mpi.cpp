// The PPE solved over processes: run as `mpirun -np N bench_mpi` (N = 1…4; as root with
// OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1, beyond the cores with
// --oversubscribe). Every process captures the same dam-break PPE system (bench_ppe's, three
// steps after release), keeps its block of rows (the points are in spatial order: a block is a
// region of the column) and solves it with linsolve::make_distributed_solver (PETSc MPIAIJ,
// BiCGSTAB + BoomerAMG, tolerance 1e-6, amg_drop 0.05). Reported by rank 0: the process count,
// setup and solve seconds (the slowest process's), iterations from a cold start and from the
// run's warm start, and the residual recomputed from the whole matrix.
//   BM_DistributedPpe/<D>/<points>   2-D 40 k and 160 k, 3-D 27 k and 125 k fluid points
#include <benchmark/benchmark.h>
#include <mpi.h>

#include <algorithm>
#include <map>
#include <memory>

#include "linsolve/petsc_solver.hpp"
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

double slowest(double seconds) {
  double max = seconds;
  MPI_Allreduce(&seconds, &max, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return max;
}

template <int D>
void BM_DistributedPpe(benchmark::State& state) {
  const auto processes = linsolve::processes();
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
    setup = slowest(solver->setup_seconds());
    Eigen::VectorXd x = Eigen::VectorXd::Zero(rows);
    const auto s0 = solver->solve(c.rhs.segment(first, rows), x);
    cold = slowest(s0.seconds);
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
    warm = slowest(s1.seconds);
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

BENCHMARK(BM_DistributedPpe<2>)->Arg(40000)->Arg(160000)->Iterations(1)->UseRealTime();
BENCHMARK(BM_DistributedPpe<3>)->Arg(27000)->Arg(125000)->Iterations(1)->UseRealTime();

/// The other processes run the same benchmarks (the solves are collective) and report nothing.
class Silent : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>&) override {}
};

}  // namespace
}  // namespace hm::ldd

int main(int argc, char** argv) {
  const auto processes = hm::linsolve::processes();
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
