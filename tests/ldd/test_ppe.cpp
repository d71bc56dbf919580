// Pressure Poisson equation: hydrostatics in box tanks given as wall meshes (2-D, 3-D), a closed
// box (no Dirichlet row), a manufactured mixed Dirichlet/Neumann problem at a measured order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <omp.h>

#include <Eigen/IterativeLinearSolvers>

#include "clouds.hpp"
#include "linsolve/bicgstab.hpp"
#include "linsolve/linear_solver.hpp"
#include "tank.hpp"

namespace hm::ldd {
namespace {

/// Every fluid point of the top layer is SURFACE and no other fluid point is.
template <int D>
void expect_top_layer_is_the_surface(const test::Column<D>& c, double top) {
  for (Index i = 0; i < c.points.size(); ++i) {
    if (c.points.kind[i] != PointKind::fluid) continue;
    const bool in_top = c.points.position[i][D - 1] > top - 0.5 * c.dx;
    EXPECT_EQ(c.points.type[i] == PointType::surface, in_top)
        << "point at " << c.points.position[i].transpose();
  }
}

// The OpenMP BiCGSTAB of the PPE (linsolve/bicgstab.hpp) on a real PPE matrix (the 2-D hydrostatic
// column, row-scaled, non-symmetric) with a random right-hand side: the residual it reports is
// the true one and meets the tolerance; the solution agrees with Eigen's BiCGSTAB (Jacobi) to the
// tolerance on 1 and 2 threads (whose sums differ by round-off, and so do their iteration
// counts: 221 and 229 here; Eigen 222).
TEST(LddPpe, ParallelBicgstabMatchesEigen) {
  const auto c = test::water_column<2>(Vec<2>(0.5, 0.4), 0.3, 0.005, 0.05);
  const auto& a = c.system.matrix;
  Eigen::VectorXd b = Eigen::VectorXd::Random(a.rows());
  const double tol = 1e-8;
  int iterations[2] = {0, 0};
  Eigen::VectorXd x[2];
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    x[threads - 1] = Eigen::VectorXd::Zero(a.rows());
    const auto r = linsolve::bicgstab(a, b, x[threads - 1], tol, 5000);
    ASSERT_TRUE(r.converged);
    const double true_residual = (b - a * x[threads - 1]).norm() / b.norm();
    EXPECT_NEAR(true_residual, r.residual, 1e-3 * tol);
    EXPECT_LE(true_residual, tol);
    iterations[threads - 1] = r.iterations;
  }
  Eigen::BiCGSTAB<Eigen::SparseMatrix<double, Eigen::RowMajor, int>,
                  Eigen::DiagonalPreconditioner<double>>
      eigen;
  eigen.setTolerance(tol);
  eigen.setMaxIterations(5000);
  eigen.compute(a);
  const Eigen::VectorXd reference = eigen.solve(b);
  const double difference =
      std::max((x[0] - reference).norm(), (x[1] - reference).norm()) / reference.norm();
  std::printf(
      "bicgstab on %ld unknowns: %d / %d iterations (1 / 2 threads), Eigen %ld; "
      "|x - x_eigen| / |x| = %.2e\n",
      static_cast<long>(a.rows()), iterations[0], iterations[1],
      static_cast<long>(eigen.iterations()), difference);
  EXPECT_LT(difference, 1e3 * tol);  // both solutions are within κ·tol of the exact one
}

TEST(LddPpe, Hydrostatics2D) {
  for (const auto pre : {Preconditioner::ilu, Preconditioner::jacobi}) {
    const auto c = test::water_column<2>(Vec<2>(0.5, 0.4), 0.3, 0.01, 0.05, pre);
    ASSERT_TRUE(c.report.converged);
    double top = 0;
    const double err = test::hydrostatic_error<2>(c, &top);
    std::printf("2-D %s: %d unknowns, %d iterations, residual %.2e, max error %.2e of rho g H\n",
                pre == Preconditioner::ilu ? "ILU" : "Jacobi", c.report.unknowns,
                c.report.iterations, c.report.residual, err);
    expect_top_layer_is_the_surface<2>(c, top);
    EXPECT_LT(err, 0.005);
  }
  {
    // For reference: the wall nodes above the surface as Dirichlet p = 0 nodes instead.
    const auto d =
        test::water_column<2>(Vec<2>(0.5, 0.4), 0.3, 0.01, 0.05, Preconditioner::ilu, 0.0, false);
    std::printf("2-D ILU, nodes above the surface Dirichlet: max error %.2e of rho g H\n",
                test::hydrostatic_error<2>(d));
  }
  // automatic with SolverOptions' own defaults (no BoomerAMG branch: amg_unknowns = 0) is
  // Jacobi; ILU takes over, from the same start, when Jacobi does not converge within
  // max_iterations (70 needed here, 20 allowed).
  const auto c = test::water_column<2>(Vec<2>(0.5, 0.4), 0.3, 0.01, 0.05);
  EXPECT_EQ(c.report.preconditioner, Preconditioner::jacobi);
  EXPECT_EQ(c.report.discarded_iterations, 0);
  EXPECT_LT(test::hydrostatic_error<2>(c), 0.005);
  SolverOptions few;
  few.max_iterations = 20;
  std::vector<double> p(c.points.pressure.size(), 0.0);
  const auto r = solve_poisson(c.system, p, few);
  EXPECT_EQ(r.preconditioner, Preconditioner::ilu);
  EXPECT_EQ(r.discarded_iterations, 20);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.iterations, 20);
  for (Index i = 0; i < c.points.size(); ++i)
    EXPECT_NEAR(p[i], c.points.pressure[i], 1e-4 * 9810.0 * 0.3);
  // Wall nodes above the top fluid layer are inactive (dry, or beyond the fluid), the others
  // carry Neumann rows.
  double top = -1e300;
  for (Index i = 0; i < c.points.size(); ++i)
    if (c.points.kind[i] == PointKind::fluid) top = std::max(top, c.points.position[i].y());
  for (Index i = 0; i < c.points.size(); ++i) {
    if (c.points.kind[i] != PointKind::wall) continue;
    const bool above = c.points.position[i].y() > top;
    EXPECT_EQ(c.points.type[i], above ? PointType::inactive : PointType::wall)
        << "wall node at " << c.points.position[i].transpose();
  }
}

TEST(LddPpe, Hydrostatics3D) {
  // 10 and 16 layers. The wall nodes above the surface are deactivated
  // (deactivate_wall_nodes_beyond_fluid); as Dirichlet p = 0 nodes, where the linear field is
  // −ρg dx/2, they gave an O(dx/H) error: 0.67 % of ρgH at 10 layers (printed for reference).
  for (const double depth : {0.125, 0.2}) {
    for (const bool beyond : {false, true}) {
      auto c = test::water_column<3>(Vec<3>(0.15, 0.125, 0.3), depth, 0.0125, 0.1,
                                     Preconditioner::ilu, 0.0, beyond);
      ASSERT_TRUE(c.report.converged);
      double top = 0;
      const double err = test::hydrostatic_error<3>(c, &top);
      std::printf(
          "3-D ILU, %.0f layers, nodes above the surface %s: %d unknowns, %d iterations, "
          "residual %.2e, max error %.2e of rho g H\n",
          depth / 0.0125, beyond ? "inactive" : "Dirichlet", c.report.unknowns, c.report.iterations,
          c.report.residual, err);
      expect_top_layer_is_the_surface<3>(c, top);
      if (!beyond) continue;
      EXPECT_LT(err, 0.005);
      // automatic with SolverOptions' own defaults: Jacobi, which solves as well.
      std::fill(c.points.pressure.begin(), c.points.pressure.end(), 0.0);
      const auto r = solve_poisson(c.system, c.points.pressure);
      EXPECT_EQ(r.preconditioner, Preconditioner::jacobi);
      ASSERT_TRUE(r.converged);
      std::printf("3-D automatic (Jacobi): %d iterations, max error %.2e of rho g H\n",
                  r.iterations, test::hydrostatic_error<3>(c));
      EXPECT_LT(test::hydrostatic_error<3>(c), 0.005);
    }
  }
}

}  // namespace
}  // namespace hm::ldd

namespace hm::ldd {
namespace {

// The algebraic-multigrid backends (builds with PETSc) on the PPE of jittered hydrostatic
// columns: the same hydrostatic error as Jacobi, and the same pressure within the tolerance
// (1e-6 relative residual: a few 1e-6 of ρgH), from a cold start.
TEST(LddPpe, AlgebraicMultigridGivesJacobisPressure) {
  if (!linsolve::is_available(linsolve::Method::boomeramg)) GTEST_SKIP() << "built without PETSc";
  for (const auto pre : {Preconditioner::boomeramg, Preconditioner::gamg}) {
    const auto jacobi_2d =
        test::water_column<2>(Vec<2>(0.5, 0.4), 0.3, 0.005, 0.05, Preconditioner::jacobi, 0.2);
    const auto amg_2d = test::water_column<2>(Vec<2>(0.5, 0.4), 0.3, 0.005, 0.05, pre, 0.2);
    const auto jacobi_3d = test::water_column<3>(Vec<3>(0.15, 0.125, 0.3), 0.2, 0.0125, 0.1,
                                                 Preconditioner::jacobi, 0.2);
    const auto amg_3d = test::water_column<3>(Vec<3>(0.15, 0.125, 0.3), 0.2, 0.0125, 0.1, pre, 0.2);
    auto difference = [](const auto& a, const auto& b, double rho_g_h) {
      double d = 0.0;
      for (std::size_t i = 0; i < a.points.pressure.size(); ++i)
        d = std::max(d, std::abs(a.points.pressure[i] - b.points.pressure[i]));
      return d / rho_g_h;
    };
    for (const SolveReport* r : {&amg_2d.report, &amg_3d.report}) {
      ASSERT_TRUE(r->converged) << to_string(pre) << ": " << r->failure;
      EXPECT_EQ(r->preconditioner, pre);
    }
    const double d2 = difference(amg_2d, jacobi_2d, 9810.0 * 0.3);
    const double d3 = difference(amg_3d, jacobi_3d, 9810.0 * 0.2);
    std::printf(
        "%s: 2-D %d unknowns %d iterations (Jacobi %d), max |p - p_jacobi| %.2e of rho g H; "
        "3-D %d unknowns %d iterations (Jacobi %d), %.2e\n",
        to_string(pre), amg_2d.report.unknowns, amg_2d.report.iterations,
        jacobi_2d.report.iterations, d2, amg_3d.report.unknowns, amg_3d.report.iterations,
        jacobi_3d.report.iterations, d3);
    EXPECT_LT(d2, 1e-4);
    EXPECT_LT(d3, 1e-4);
    EXPECT_NEAR(test::hydrostatic_error<2>(amg_2d), test::hydrostatic_error<2>(jacobi_2d), 1e-4);
    EXPECT_NEAR(test::hydrostatic_error<3>(amg_3d), test::hydrostatic_error<3>(jacobi_3d), 1e-4);
    EXPECT_LT(amg_2d.report.iterations, jacobi_2d.report.iterations);
  }
}

// The wall-tension release's re-solve: wall nodes fixed at p = 0 in the assembled system
// (fix_at_zero, the system keeps its size and the preconditioner built for it) give the pressure
// of the system assembled again with those nodes Dirichlet p = 0 — here the side-wall nodes
// in the upper half of a jittered 2-D column, solved to 1e-10.
TEST(LddPpe, FixingReleasedNodesInPlaceGivesTheReassembledSystemsPressure) {
  auto c = test::water_column<2>(Vec<2>(0.5, 0.4), 0.3, 0.005, 0.05, Preconditioner::jacobi, 0.2);
  std::vector<Index> released;
  for (Index i = 0; i < c.points.size(); ++i) {
    const auto& x = c.points.position[i];
    if (c.points.type[i] == PointType::wall && x.y() > 0.15 &&
        (x.x() < 0.1 * c.dx || x.x() > 0.5 - 0.1 * c.dx))
      released.push_back(i);
  }
  ASSERT_GT(released.size(), 20u);
  PpeOptions<2> po;
  po.gravity = Vec<2>(0.0, -9.81);
  po.dt = 1e-3;
  po.dx = c.dx;
  po.reference_density = c.n0;
  std::vector<Vec<2>> predicted(c.points.position.size(), po.dt * po.gravity);
  const auto data = ppe_data<2>(c.points, c.nb, c.ops, predicted, {}, po);
  SolverOptions so;
  so.tolerance = 1e-10;
  so.max_iterations = 20000;
  so.preconditioner = linsolve::is_available(linsolve::Method::boomeramg)
                          ? Preconditioner::boomeramg
                          : Preconditioner::jacobi;

  auto fixed = assemble_poisson<2>(c.points, c.nb, c.ops, data, c.dx);
  PoissonSolver solver(so);
  std::vector<double> p_fixed(c.points.pressure.size(), 0.0);
  ASSERT_TRUE(solver.solve(fixed, p_fixed).converged);
  ASSERT_TRUE(fix_at_zero(fixed, released));
  const auto unknowns = fixed.point_of.size();
  const auto r = solver.solve(fixed, p_fixed, /*keep_preconditioner=*/true);
  ASSERT_TRUE(r.converged) << r.failure;
  EXPECT_FALSE(r.setup) << "the re-solve set up a new preconditioner";

  for (const Index i : released) c.points.type[i] = PointType::surface;
  const auto reassembled = assemble_poisson<2>(c.points, c.nb, c.ops, data, c.dx);
  EXPECT_EQ(reassembled.point_of.size() + released.size(), unknowns);
  std::vector<double> p_reassembled(c.points.pressure.size(), 0.0);
  ASSERT_TRUE(solve_poisson(reassembled, p_reassembled, so).converged);

  const double rho_g_h = 9810.0 * 0.3;
  double difference = 0.0, at_released = 0.0;
  for (std::size_t i = 0; i < p_fixed.size(); ++i)
    difference = std::max(difference, std::abs(p_fixed[i] - p_reassembled[i]));
  for (const Index i : released) at_released = std::max(at_released, std::abs(p_fixed[i]));
  std::printf(
      "%zu nodes fixed at 0: %d iterations on the kept preconditioner (%s), max |dp| "
      "%.2e of rho g H, max |p| at them %.2e\n",
      released.size(), r.iterations, to_string(r.preconditioner), difference / rho_g_h,
      at_released / rho_g_h);
  EXPECT_LT(difference, 1e-7 * rho_g_h);
  EXPECT_LT(at_released, 1e-7 * rho_g_h);
}

// automatic from amg_unknowns on: BoomerAMG first, Jacobi tried on the next matrix, then the
// cheaper by iterations (Jacobi's against 32 + 4.5 × BoomerAMG's), the other tried again after
// 8, 16, 32 … matrices. A 2-D column of 3 600 points, 20 matrices (the system scaled by
// 1 + 1e-9 k: the same pressure, another matrix each time). From a warm start at the answer
// Jacobi needs almost nothing and wins; from a cold start it needs far more than BoomerAMG's
// setup and cycles and loses.
TEST(LddPpe, AutomaticChoosesTheCheaperSolverByItsIterations) {
  if (!linsolve::is_available(linsolve::Method::boomeramg)) GTEST_SKIP() << "built without PETSc";
  const auto c = test::water_column<2>(Vec<2>(0.5, 0.4), 0.3, 0.005, 0.05, Preconditioner::jacobi);
  SolverOptions o = ppe_solver_defaults(2);
  ASSERT_GE(static_cast<Index>(c.system.point_of.size()), o.amg_unknowns);
  for (const bool warm : {true, false}) {
    PoissonSolver solver(o);
    std::vector<Preconditioner> used;
    std::vector<int> iterations;
    for (int k = 0; k < 20; ++k) {
      PoissonSystem sys = c.system;
      sys.matrix *= 1.0 + 1e-9 * k;
      sys.rhs *= 1.0 + 1e-9 * k;
      std::vector<double> p = c.points.pressure;
      if (!warm) std::fill(p.begin(), p.end(), 0.0);
      const auto r = solver.solve(sys, p);
      ASSERT_TRUE(r.converged) << r.failure;
      used.push_back(r.preconditioner);
      iterations.push_back(r.iterations);
      for (std::size_t i = 0; i < p.size(); ++i)
        ASSERT_NEAR(p[i], c.points.pressure[i], 1e-4 * 9810.0 * 0.3);
    }
    std::string sequence;
    for (std::size_t k = 0; k < used.size(); ++k)
      sequence +=
          (used[k] == Preconditioner::boomeramg ? " B" : " J") + std::to_string(iterations[k]);
    std::printf("%s start, solver and iterations:%s\n", warm ? "warm" : "cold", sequence.c_str());
    EXPECT_EQ(used[0], Preconditioner::boomeramg);
    EXPECT_EQ(used[1], Preconditioner::jacobi);  // the first trial
    const auto winner = warm ? Preconditioner::jacobi : Preconditioner::boomeramg;
    const auto trials =
        std::count_if(used.begin() + 2, used.end(), [&](auto p) { return p != winner; });
    EXPECT_LE(trials, 2) << sequence;  // the loser tried again after 8, then 16 matrices
    EXPECT_EQ(used[2], winner) << sequence;
  }
}

TEST(LddPpe, ClosedBoxIsPinned) {
  // A closed tank full of water: every wall row is Neumann, nothing is Dirichlet; one point is
  // pinned and the pressure is ρg(z_pin − z) relative to it.
  test::Column<2> c;
  c.dx = 0.02;
  c.h = 2.5 * c.dx;
  c.walls.push_back(test::box_tank<2>(Vec<2>(0.3, 0.3), 0.1));
  for (const auto& p : seed_box<2>({Vec<2>::Zero(), Vec<2>(0.3, 0.3)}, c.dx, c.walls))
    c.points.add_fluid(p);
  add_wall_nodes<2>(c.points, c.walls[0], 0, c.dx);
  c.nb = find_neighbours<2>(c.points.position, c.h);
  EXPECT_EQ(deactivate_dry_wall_nodes<2>(c.points, c.nb), 0);
  FreeSurfaceOptions fs;
  fs.reference_density = lattice_number_density<2>(c.dx, c.h);
  EXPECT_EQ(deactivate_wall_nodes_beyond_fluid<2>(c.points, c.nb, fs), 0);
  c.ops = compute_operators<2>(c.points.position, c.nb);
  const auto rep = detect_free_surface<2>(c.points, c.nb, c.ops, fs);
  EXPECT_EQ(rep.surface + rep.contact_line, 0);
  PpeOptions<2> po;
  po.gravity = Vec<2>(0.0, -9.81);
  po.dt = 1e-3;
  po.dx = c.dx;
  std::vector<Vec<2>> predicted(c.points.position.size(), po.dt * po.gravity);
  const auto data = ppe_data<2>(c.points, c.nb, c.ops, predicted, {}, po);
  const auto sys = assemble_poisson<2>(c.points, c.nb, c.ops, data, c.dx);
  ASSERT_GE(sys.pinned, 0);
  const auto r = solve_poisson(sys, c.points.pressure);
  ASSERT_TRUE(r.converged);
  const double z0 = c.points.position[sys.pinned].y(), rho_g = 9810.0;
  double err = 0.0;
  for (Index i = 0; i < c.points.size(); ++i)
    err = std::max(err, std::abs(c.points.pressure[i] - rho_g * (z0 - c.points.position[i].y())));
  std::printf("closed box: %d iterations, max error %.2e of rho g H\n", r.iterations,
              err / (rho_g * 0.3));
  EXPECT_LT(err, 1e-4 * rho_g * 0.3);
}

/// Manufactured p = cos(2x) e^y + xy on the unit square: Neumann (n·∇p exact) on the wall nodes
/// of the bottom and the sides, Dirichlet (p exact) on the top fluid layer, ∇²p = −3 cos(2x) e^y.
double manufactured_error(int cells, double jitter) {
  const double dx = 1.0 / cells;
  auto p = [](const Vec<2>& x) { return std::cos(2 * x.x()) * std::exp(x.y()) + x.x() * x.y(); };
  auto grad = [](const Vec<2>& x) {
    return Vec<2>(-2 * std::sin(2 * x.x()) * std::exp(x.y()) + x.y(),
                  std::cos(2 * x.x()) * std::exp(x.y()) + x.x());
  };
  PointSet<2> pts;
  for (const auto& x : test::lattice<2>(Vec<2>::Zero(), Vec<2>::Ones(), dx, jitter, 5))
    pts.add_fluid(x);
  const auto walls = test::box_tank<2>(Vec<2>::Ones(), 0.25, {"xmin", "xmax", "ymin"});
  add_wall_nodes<2>(pts, walls, 0, dx);
  sort_spatially<2>(pts, 2.5 * dx);
  auto nb = find_neighbours<2>(pts.position, 2.5 * dx);
  const auto ops = compute_operators<2>(pts.position, nb);
  PoissonData data;
  for (Index i = 0; i < pts.size(); ++i) {
    const auto& x = pts.position[i];
    if (pts.kind[i] == PointKind::fluid && x.y() > 1.0 - dx) pts.type[i] = PointType::surface;
    data.source.push_back(-3 * std::cos(2 * x.x()) * std::exp(x.y()));
    data.neumann.push_back(pts.wall_normal[i].dot(grad(x)));
    data.dirichlet.push_back(p(x));
  }
  const auto sys = assemble_poisson<2>(pts, nb, ops, data, dx);
  EXPECT_EQ(sys.weak_neumann, 0);
  EXPECT_EQ(sys.pinned, -1);
  SolverOptions so;
  so.tolerance = 1e-10;
  const auto r = solve_poisson(sys, pts.pressure, so);
  EXPECT_TRUE(r.converged);
  double err = 0.0;
  for (Index i = 0; i < pts.size(); ++i)
    err = std::max(err, std::abs(pts.pressure[i] - p(pts.position[i])));
  std::printf("manufactured Poisson n=%d jitter %.1f: %d unknowns, %d iterations, max error %.3e\n",
              cells, jitter, r.unknowns, r.iterations, err);
  return err;
}

TEST(LddPpe, ManufacturedMixedPoissonConverges) {
  // Expected order 1: the Neumann rows use the one-sided eq. 6 gradient, exact for linear fields
  // only, so the flux condition has an O(h) truncation error; the interior (eq. 7 on the
  // lattice, WLS near the boundary) is at least as accurate.
  for (const double jitter : {0.0, 0.2}) {
    std::vector<double> h, e;
    for (int n : {16, 32, 64}) {
      h.push_back(1.0 / n);
      e.push_back(manufactured_error(n, jitter));
    }
    const double order = test::observed_order(h, e);
    std::printf("manufactured Poisson, jitter %.1f: observed order %.2f\n", jitter, order);
    EXPECT_GT(order, 1.0 - 0.1);
  }
}

}  // namespace
}  // namespace hm::ldd
