// The PPE of a real run solved over processes (run by ctest as `mpirun -np N`, N = 1…4): every
// process builds the same 2-D dam break (bench_ppe's, ~40 k points) and captures the same PPE
// system three steps after release; each keeps a block of its rows (the points are in
// spatial order, so a block is a region of the column) and solves through
// linsolve::make_distributed_solver (PETSc MPIAIJ, BiCGSTAB + BoomerAMG). Against the one-process
// solve of the whole system: the answer within 10× the tolerance, the residual recomputed from
// the whole matrix below the tolerance, and at most 1.5× the iterations.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "linsolve/petsc_solver.hpp"
#include "parallel/decomposition.hpp"
#include "ppe_cases.hpp"

namespace hm::ldd {
namespace {

/// Process `rank`'s block of n rows among `count`: [first, first + rows).
std::pair<int, int> block(int n, int rank, int count) {
  const int base = n / count, extra = n % count;
  return {rank * base + std::min(rank, extra), base + (rank < extra ? 1 : 0)};
}

TEST(DistributedPpe, GivesTheOneProcessAnswerInAsManyIterations) {
  const auto processes = parallel::processes();
  const test::CapturedPpe system = test::capture_ppe<2>(test::spacing_for<2>(4e4));
  const auto n = static_cast<int>(system.matrix.rows());
  ASSERT_GT(n, 35000);
  const linsolve::Settings settings;  // tolerance 1e-6, amg_drop 0.05: the runs' own

  auto serial = linsolve::make_solver(linsolve::Method::boomeramg, settings);
  ASSERT_TRUE(serial->setup(system.matrix)) << serial->setup_failure();
  Eigen::VectorXd reference = Eigen::VectorXd::Zero(n);
  const auto one = serial->solve(system.rhs, reference);
  ASSERT_TRUE(one.converged) << one.failure;

  const auto [first, rows] = block(n, processes.rank, processes.count);
  const linsolve::CsrMatrix mine = system.matrix.middleRows(first, rows);
  auto distributed = linsolve::make_distributed_solver(linsolve::Method::boomeramg, settings);
  ASSERT_TRUE(distributed->setup(mine)) << distributed->setup_failure();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(rows);
  const auto many = distributed->solve(system.rhs.segment(first, rows), x);
  ASSERT_TRUE(many.converged) << many.failure;

  // The whole answer on every process, its residual recomputed from the whole matrix.
  std::vector<int> counts(static_cast<std::size_t>(processes.count)),
      starts(static_cast<std::size_t>(processes.count));
  for (int r = 0; r < processes.count; ++r)
    std::tie(starts[static_cast<std::size_t>(r)], counts[static_cast<std::size_t>(r)]) =
        block(n, r, processes.count);
  Eigen::VectorXd whole(n);
  MPI_Allgatherv(x.data(), rows, MPI_DOUBLE, whole.data(), counts.data(), starts.data(), MPI_DOUBLE,
                 MPI_COMM_WORLD);
  const double residual = linsolve::relative_residual(system.matrix, system.rhs, whole);
  const double difference = (whole - reference).norm() / reference.norm();
  if (processes.rank == 0)
    std::printf(
        "%d unknowns on %d processes: %d iterations (one process: %d), residual %.3g, "
        "‖x − x₁‖/‖x₁‖ = %.3g, setup %.3f s, solve %.3f s\n",
        n, processes.count, many.iterations, one.iterations, residual, difference,
        distributed->setup_seconds(), many.seconds);
  EXPECT_LE(residual, settings.tolerance);
  EXPECT_LE(difference, 10 * settings.tolerance);
  EXPECT_LE(many.iterations, 1.5 * one.iterations);
  EXPECT_NEAR(many.residual, residual, 0.05 * settings.tolerance);
}

TEST(DistributedPpe, RefusesRowsThatDoNotMakeUpTheMatrix) {
  const auto processes = parallel::processes();
  // Every process gives 3 rows of a matrix of 3 × count + 1 columns: one row is missing.
  const int columns = 3 * processes.count + 1;
  linsolve::CsrMatrix a(3, columns);
  for (int r = 0; r < 3; ++r) a.insert(r, 3 * processes.rank + r) = 1.0;
  a.makeCompressed();
  auto solver = linsolve::make_distributed_solver(linsolve::Method::boomeramg, {});
  EXPECT_FALSE(solver->setup(a));
  EXPECT_NE(solver->setup_failure().find("add up to"), std::string::npos)
      << solver->setup_failure();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
  EXPECT_FALSE(solver->solve(Eigen::VectorXd::Ones(3), x).converged);
}

}  // namespace
}  // namespace hm::ldd
