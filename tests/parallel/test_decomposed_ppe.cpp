// The PPE of decomposed points (run by ctest as `mpirun -np N`, N = 1…4): every process runs the
// same 2-D dam break for 20 steps, keeps its region's points and the ghosts within h, demotes
// its weak Neumann rows, sends the types and its unknowns' global numbers to the ghosts
// (parallel::Halo::refresh), assembles its block of rows (ldd::assemble_poisson_rows) and
// solves over the processes (linsolve::make_distributed_solver, BoomerAMG). Against
// assemble_poisson and a one-process solve of all the points in one piece: the same unknowns,
// every row's right-hand side to round-off, the pressure within 10× the tolerance, at most
// 1.5× the iterations; and the corrector's pressure gradient at the owned points, with the
// ghosts' pressures sent by their owners.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "flow_points.hpp"
#include "linsolve/petsc_solver.hpp"
#include "parallel/decomposition.hpp"
#include "ppe_cases.hpp"

namespace hm::ldd {
namespace {

using Vec2 = Vec<2>;

/// Sources for the PPE: smooth functions of position and normal, the same wherever a point is.
PoissonData data_for(const PointSet<2>& points, double dx) {
  PoissonData d;
  for (Index i = 0; i < points.size(); ++i) {
    const Vec2& x = points.position[i];
    d.source.push_back(1e4 * (1.0 + x.x() + 2.0 * x.y()));
    d.neumann.push_back(1000.0 * points.wall_normal[i].dot(Vec2(0.3, -9.81)));
    d.dirichlet.push_back(1000.0 * 9.81 * 0.5 * dx);
  }
  return d;
}

bool is_unknown(PointType t) {
  return t == PointType::interior || t == PointType::wall;
}

TEST(DecomposedPpe, GivesTheOnePiecePressure) {
  const auto p = parallel::processes();
  const double dx = 0.004;
  auto flow = test::dam_break<2>(dx, Preconditioner::automatic);
  for (int s = 0; s < 20; ++s) flow.step(flow.stable_dt(0.0).first);
  const double h = flow.support();
  const linsolve::Settings settings;  // tolerance 1e-6: the runs'

  // In one piece.
  PointSet<2> one = flow.points();
  const Neighbours one_nb = find_neighbours<2>(one.position, h);
  const Operators<2> one_ops = compute_operators<2>(one.position, one_nb);
  const PoissonSystem system = assemble_poisson<2>(one, one_nb, one_ops, data_for(one, dx), dx);
  auto serial = linsolve::make_solver(linsolve::Method::boomeramg, settings);
  ASSERT_TRUE(serial->setup(system.matrix));
  Eigen::VectorXd reference = Eigen::VectorXd::Zero(system.rhs.size());
  const auto one_report = serial->solve(system.rhs, reference);
  ASSERT_TRUE(one_report.converged);

  // This process's region and its ghosts.
  auto owned = test::dealt_points(flow.points(), p);
  parallel::Decomposition<2> decomposition(owned);
  const auto halo = decomposition.halo(owned, h);
  PointSet<2> local;
  std::vector<std::int64_t> ids;
  test::append(owned, local, ids);
  test::append(halo.ghosts(), local, ids);
  const auto n_owned = static_cast<Index>(owned.size());
  const Neighbours nb = find_neighbours<2>(local.position, h);
  const Operators<2> ops = compute_operators<2>(local.position, nb);

  // 1. Weak Neumann rows of the owned points; the types to the ghosts.
  demote_weak_neumann_rows<2>(local, nb, ops, dx, n_owned);
  test::refresh_types(halo, local, n_owned);
  // 2. Global unknown numbers: the owned unknowns in order after the lower ranks'.
  long mine = 0, before = 0, unknowns = 0;
  for (Index i = 0; i < n_owned; ++i) mine += is_unknown(local.type[i]);
  MPI_Exscan(&mine, &before, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(&mine, &unknowns, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (p.rank == 0) before = 0;
  std::vector<std::int64_t> global(static_cast<std::size_t>(local.size()), -1);
  std::vector<double> owned_values(static_cast<std::size_t>(n_owned));
  for (Index i = 0, next = static_cast<Index>(before); i < n_owned; ++i) {
    owned_values[i] = is_unknown(local.type[i]) ? next++ : -1.0;
    global[static_cast<std::size_t>(i)] = static_cast<std::int64_t>(owned_values[i]);
  }
  const auto ghost_values = halo.refresh(owned_values, 1);
  for (std::size_t g = 0; g < ghost_values.size(); ++g)
    global[static_cast<std::size_t>(n_owned) + g] = static_cast<std::int64_t>(ghost_values[g]);
  // 3. This process's rows, solved over the processes.
  const PoissonRows rows =
      assemble_poisson_rows<2>(local, nb, ops, data_for(local, dx), n_owned, global, unknowns);
  ASSERT_EQ(unknowns, system.matrix.rows());
  auto solver = linsolve::make_distributed_solver(linsolve::Method::boomeramg, settings);
  ASSERT_TRUE(solver->setup(rows.matrix)) << solver->setup_failure();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(rows.rhs.size());
  const auto report = solver->solve(rows.rhs, x);
  ASSERT_TRUE(report.converged) << report.failure;

  // Against the one piece, point by point.
  double rhs_difference = 0.0, pressure_difference = 0.0;
  for (Index r = 0; r < static_cast<Index>(rows.point_of.size()); ++r) {
    const auto id = static_cast<Index>(ids[static_cast<std::size_t>(rows.point_of[r])]);
    const Index u = system.unknown_of[id];
    ASSERT_GE(u, 0) << "point " << id << " is an unknown here, not in one piece";
    rhs_difference = std::max(
        rhs_difference, std::abs(rows.rhs[r] - system.rhs[u]) / (std::abs(system.rhs[u]) + 1.0));
    pressure_difference = std::max(pressure_difference, std::abs(x[r] - reference[u]));
  }
  const double scale = reference.cwiseAbs().maxCoeff();

  // The corrector's pressure gradient at the owned points, the ghosts' pressures sent by their
  // owners (Dirichlet points carry their value).
  const PoissonData local_data = data_for(local, dx), one_data = data_for(one, dx);
  std::vector<double> one_pressure(static_cast<std::size_t>(one.size()));
  for (Index i = 0; i < one.size(); ++i)
    one_pressure[i] = system.unknown_of[i] >= 0
                          ? reference[system.unknown_of[i]]
                          : one_data.dirichlet[i] * (one.type[i] != PointType::inactive);
  std::vector<double> pressure(static_cast<std::size_t>(local.size()), 0.0);
  for (Index i = 0; i < n_owned; ++i)
    pressure[i] = local.type[i] == PointType::inactive ? 0.0 : local_data.dirichlet[i];
  for (Index r = 0; r < static_cast<Index>(rows.point_of.size()); ++r)
    pressure[rows.point_of[r]] = x[r];
  const auto ghost_pressure =
      halo.refresh(std::vector<double>(pressure.begin(), pressure.begin() + n_owned), 1);
  std::copy(ghost_pressure.begin(), ghost_pressure.end(), pressure.begin() + n_owned);
  const auto grad = gradient<2>(local.position, nb, ops, pressure);
  const auto one_grad = gradient<2>(one.position, one_nb, one_ops, one_pressure);
  double gradient_difference = 0.0, gradient_scale = 0.0;
  for (Index i = 0; i < n_owned; ++i) {
    const auto id = static_cast<Index>(ids[static_cast<std::size_t>(i)]);
    gradient_difference = std::max(gradient_difference, (grad[i] - one_grad[id]).norm());
  }
  for (const auto& g : one_grad) gradient_scale = std::max(gradient_scale, g.norm());

  double largest[3] = {rhs_difference, pressure_difference / scale,
                       gradient_difference / gradient_scale},
         all[3] = {0.0, 0.0, 0.0};
  MPI_Allreduce(largest, all, 3, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  if (p.rank == 0)
    std::printf(
        "%d processes, %ld unknowns: %d iterations (one piece %d); right-hand sides within "
        "%.3g, pressure within %.3g of its largest (%.4g Pa), its gradient within %.3g\n",
        p.count, unknowns, report.iterations, one_report.iterations, all[0], all[1], scale, all[2]);
  EXPECT_LT(all[0], 1e-10);
  EXPECT_LT(all[1], 10 * settings.tolerance);
  EXPECT_LT(all[2], 10 * settings.tolerance);
  EXPECT_LE(report.iterations, 1.5 * one_report.iterations);
}

}  // namespace
}  // namespace hm::ldd
