// The flow's per-point kernels (ldd/kernels.hpp), each on its own against what it must give
// exactly (a pair pushed to d0, a flat wall's mirrored lattice, a quadratic's Laplacian, the
// hydrostatic surface pressure), and the point-loop driver (ldd/point_loop.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "clouds.hpp"
#include "ldd/free_surface.hpp"
#include "ldd/kernels.hpp"
#include "ldd/point_loop.hpp"

namespace hm::ldd {
namespace {

using Vec2 = Vec<2>;

/// Fluid points at `x` (at rest) with their neighbour lists and operators.
struct Scene {
  PointSet<2> points;
  Neighbours neighbours;
  Operators<2> ops;
  kernels::Cloud<2> cloud() const { return {points, neighbours, ops}; }
  void update(double h) {
    neighbours = find_neighbours<2>(points.position, h);
    ops = compute_operators<2>(points.position, neighbours);
  }
};

Scene fluid_scene(const std::vector<Vec2>& x, double h) {
  Scene s;
  for (const auto& p : x) s.points.add_fluid(p);
  s.update(h);
  return s;
}

/// The index of the point nearest to `target`.
Index nearest(const PointSet<2>& p, const Vec2& target) {
  Index best = 0;
  for (Index i = 1; i < p.size(); ++i)
    if ((p.position[i] - target).norm() < (p.position[best] - target).norm()) best = i;
  return best;
}

// --- PBD ----------------------------------------------------------------------------------

TEST(LddKernels, PbdMovesAPairTooCloseToTheDistanceD0) {
  const double d0 = 0.01, d = 0.007;
  Scene s = fluid_scene({Vec2(0.0, 0.0), Vec2(d, 0.0)}, 0.02);
  const kernels::PbdParameters p{
      .distance = d0, .wall_distance = 0.5 * d0, .relaxation = 1.0, .clamp = 1.0};
  const auto a = kernels::pbd_displacement(s.cloud(), 0, p);
  const auto b = kernels::pbd_displacement(s.cloud(), 1, p);
  ASSERT_TRUE(a && b);
  // Each moves half the gap, away from the other: the pair ends exactly d0 apart.
  EXPECT_NEAR((*a - Vec2(-0.5 * (d0 - d), 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(((s.points.position[1] + *b) - (s.points.position[0] + *a)).norm(), d0, 1e-15);
}

TEST(LddKernels, PbdClampsAndLeavesPointsWithoutACloseNeighbour) {
  const double d0 = 0.01;
  Scene s = fluid_scene({Vec2(0.0, 0.0), Vec2(0.002, 0.0), Vec2(0.05, 0.0)}, 0.02);
  const kernels::PbdParameters p{
      .distance = d0, .wall_distance = 0.5 * d0, .relaxation = 1.0, .clamp = 0.001};
  const auto a = kernels::pbd_displacement(s.cloud(), 0, p);
  ASSERT_TRUE(a);
  EXPECT_NEAR(a->norm(), 0.001, 1e-15);                      // 0.004 wanted, clamped
  EXPECT_FALSE(kernels::pbd_displacement(s.cloud(), 2, p));  // alone
}

TEST(LddKernels, PbdMovesOnlyTheFluidPointAwayFromAWallNode) {
  const double d0 = 0.01;
  Scene s;
  s.points.add_fluid(Vec2(0.0, 0.003));
  s.points.add_wall_node(Vec2(0.0, 0.0), Vec2(0.0, 1.0), WallHost<2>{});
  s.update(0.02);
  const kernels::PbdParameters p{
      .distance = d0, .wall_distance = 0.5 * d0, .relaxation = 1.0, .clamp = 1.0};
  const auto a = kernels::pbd_displacement(s.cloud(), 0, p);
  ASSERT_TRUE(a);
  EXPECT_NEAR((*a - Vec2(0.0, 0.002)).norm(), 0.0, 1e-15);   // to d0/2 from the node, in full
  EXPECT_FALSE(kernels::pbd_displacement(s.cloud(), 1, p));  // a wall node never moves
}

// --- Shifting -----------------------------------------------------------------------------

/// A lattice of spacing dx over [0, 1]×[0, 0.3] above a floor y = 0 sampled by wall nodes
/// under every lattice column (normal +y).
Scene lattice_on_floor(double dx, double h, bool with_floor) {
  Scene s;
  for (const auto& x : test::lattice<2>(Vec2(0.0, 0.0), Vec2(1.0, 0.3), dx)) s.points.add_fluid(x);
  if (with_floor)
    for (double x = 0.5 * dx; x < 1.0; x += dx)
      s.points.add_wall_node(Vec2(x, 0.0), Vec2(0.0, 1.0), WallHost<2>{});
  s.update(h);
  return s;
}

TEST(LddKernels, ConcentrationGradientVanishesBesideAFlatWallThroughItsMirroredColumns) {
  const double dx = 0.01, h = 2.1 * dx, n0 = lattice_number_density<2>(dx, h);
  const Scene floor = lattice_on_floor(dx, h, true), bare = lattice_on_floor(dx, h, false);
  for (const double y : {0.5 * dx, 1.5 * dx, 2.5 * dx}) {
    const Vec2 at(0.5 + 0.5 * dx, y);
    bool near_surface = false;
    const Vec2 with = kernels::concentration_gradient(floor.cloud(), nearest(floor.points, at), h,
                                                      dx, n0, near_surface);
    const Vec2 without = kernels::concentration_gradient(bare.cloud(), nearest(bare.points, at), h,
                                                         dx, n0, near_surface);
    EXPECT_LT(with.norm(), 1e-10 / dx) << "y = " << y;
    // Fluid alone, the layers within h of the floor see a deficit below them, pointing up.
    if (y < h) {
      EXPECT_GT(without.y(), 1e6 * with.norm()) << "y = " << y;
    }
    EXPECT_FALSE(near_surface);
  }
}

TEST(LddKernels, FickianShiftLeavesPointsNearTheSurfaceAndClamps) {
  const double dx = 0.01, h = 2.1 * dx, n0 = lattice_number_density<2>(dx, h);
  Scene s = lattice_on_floor(dx, h, false);
  for (Index i = 0; i < s.points.size(); ++i) s.points.velocity[i] = Vec2(1.0, 0.0);
  const kernels::ShiftParameters p{
      .coefficient = 2.0, .dx = dx, .dt = 1e-3, .max_shift = 1e-6, .h = h, .n0 = n0};
  const Index bottom = nearest(s.points, Vec2(0.5 + 0.5 * dx, 0.5 * dx));
  // Down the gradient: a point of the first layer over the (missing) floor moves down, clamped.
  const Vec2 shift = kernels::fickian_shift(s.cloud(), bottom, p);
  EXPECT_NEAR(shift.norm(), 1e-6, 1e-18);
  EXPECT_LT(shift.y(), 0.0);
  s.points.type[bottom] = PointType::surface;
  EXPECT_EQ(kernels::fickian_shift(s.cloud(), bottom, p), Vec2::Zero());
  // A point whose neighbour is on the surface is not shifted either.
  s.points.type[bottom] = PointType::interior;
  s.points.type[nearest(s.points, Vec2(0.5 + 1.5 * dx, 0.5 * dx))] = PointType::surface;
  EXPECT_EQ(kernels::fickian_shift(s.cloud(), bottom, p), Vec2::Zero());
}

// --- Wall clearance -----------------------------------------------------------------------

WallMesh<2> floor_wall() {
  mesh::SurfaceMesh m;
  m.dim = 2;
  m.vertices.resize(2, 2);
  m.vertices << -1.0, 0.0, 1.0, 0.0;  // normal ẑ × (b − a) = +y
  m.cells.resize(1, 2);
  m.cells << 0, 1;
  return WallMesh<2>(m, "floor");
}

TEST(LddKernels, WallClearancePutsAPointBackAndRemovesItsVelocityIntoTheWall) {
  std::vector<WallMesh<2>> walls;
  walls.push_back(floor_wall());
  const double clearance = 0.005;
  const auto c =
      kernels::wall_clearance<2>(walls, Vec2(0.1, 0.002), Vec2(0.3, -0.2), nullptr, clearance);
  EXPECT_NEAR((c.position - Vec2(0.1, clearance)).norm(), 0.0, 1e-15);
  EXPECT_EQ(c.velocity, Vec2(0.3, 0.0));  // tangential kept, normal removed
  EXPECT_EQ(c.nearest, clearance);
  EXPECT_FALSE(c.outside);
  // Moving away from the wall keeps its velocity; far from it, nothing changes.
  EXPECT_EQ(kernels::wall_clearance<2>(walls, Vec2(0.1, 0.002), Vec2(0.0, 0.2), nullptr, clearance)
                .velocity,
            Vec2(0.0, 0.2));
  const auto far =
      kernels::wall_clearance<2>(walls, Vec2(0.1, 0.2), Vec2(0.0, -1.0), nullptr, clearance);
  EXPECT_EQ(far.position, Vec2(0.1, 0.2));
  EXPECT_NEAR(far.nearest, 0.2, 1e-15);
}

TEST(LddKernels, WallClearanceTellsAPointThatCameThroughFromOneThatWasOutside) {
  std::vector<WallMesh<2>> walls;
  walls.push_back(floor_wall());
  const double clearance = 0.005;
  // Crossed the floor this step: put back in front.
  const Vec2 above(0.1, 0.01), below(0.1, -0.01), further_below(0.1, -0.02);
  const auto crossed = kernels::wall_clearance<2>(walls, below, Vec2::Zero(), &above, clearance);
  EXPECT_FALSE(crossed.outside);
  EXPECT_NEAR(crossed.position.y(), clearance, 1e-15);
  // Behind it already at the step's start: the wall swept over it; put back in front too.
  EXPECT_FALSE(
      kernels::wall_clearance<2>(walls, below, Vec2::Zero(), &further_below, clearance).outside);
  // From beyond the wall's open end (x = 1) to behind it, round the end, crossing nothing: it
  // left the domain; outside, not moved.
  const Vec2 beyond_the_end(1.5, 0.01), behind(0.99, -0.05);
  const auto outside =
      kernels::wall_clearance<2>(walls, behind, Vec2::Zero(), &beyond_the_end, clearance);
  EXPECT_TRUE(outside.outside);
  EXPECT_EQ(outside.position, behind);
  EXPECT_NEAR(outside.nearest, 0.05, 1e-15);
}

// --- Classification, predictor, surface pressure, corrector, smoothing --------------------

TEST(LddKernels, SparsePointsAreThoseWithFewNeighbours) {
  const double dx = 0.01, h = 2.1 * dx, n0 = lattice_number_density<2>(dx, h);
  const Scene s = lattice_on_floor(dx, h, false);
  const Index middle = nearest(s.points, Vec2(0.5, 0.15));
  EXPECT_FALSE(kernels::is_sparse(s.cloud(), middle, 0.5 * n0, 0.25 * n0, h));
  const Scene pair = fluid_scene({Vec2(0.0, 0.0), Vec2(dx, 0.0)}, h);
  EXPECT_TRUE(kernels::is_sparse(pair.cloud(), 0, 0.5 * n0, 0.25 * n0, h));
}

TEST(LddKernels, ViscousAccelerationIsExactForAQuadraticVelocity) {
  const double dx = 0.01, h = 2.1 * dx, nu = 1e-3;
  Scene s = fluid_scene(test::lattice<2>(Vec2(0.0, 0.0), Vec2(0.2, 0.2), dx), h);
  std::vector<Vec2> u(static_cast<std::size_t>(s.points.size()));
  for (Index i = 0; i < s.points.size(); ++i) {
    const Vec2& x = s.points.position[i];
    u[i] = Vec2(x.y() * x.y(), 0.5 * x.x() * x.x() + x.x() * x.y());  // ∇²u = (2, 1)
  }
  const Index i = nearest(s.points, Vec2(0.1, 0.1));
  const Vec2 a = kernels::viscous_acceleration<2>(s.cloud(), i, u, nu);
  EXPECT_NEAR(a.x(), 2.0 * nu, 1e-9);
  EXPECT_NEAR(a.y(), 1.0 * nu, 1e-9);
  s.points.type[i] = PointType::inactive;
  EXPECT_EQ(kernels::viscous_acceleration<2>(s.cloud(), i, u, nu), Vec2::Zero());
}

TEST(LddKernels, PredictedAndCorrectedVelocities) {
  const double dx = 0.01;
  Scene s = lattice_on_floor(dx, 2.1 * dx, true);
  const Index fluid = nearest(s.points, Vec2(0.5 + 0.5 * dx, 1.5 * dx));
  const Index node = s.points.size() - 1;
  s.points.velocity[fluid] = Vec2(1.0, 0.0);
  s.points.wall_velocity[node] = Vec2(0.5, 0.0);
  s.points.wall_acceleration[node] = Vec2(0.0, 2.0);
  const Vec2 g(0.0, -10.0), viscous(0.1, 0.2);
  const double dt = 0.01;
  EXPECT_EQ(kernels::predicted_velocity(s.cloud(), fluid, dt, g, viscous),
            Vec2(1.0, 0.0) + dt * (g + viscous));
  EXPECT_EQ(kernels::predicted_velocity(s.cloud(), node, dt, g, viscous),
            Vec2(0.5, 0.0) + dt * (g + viscous - Vec2(0.0, 2.0)));
  const Vec2 grad_p(100.0, 50.0);
  EXPECT_EQ(kernels::corrected_velocity(s.cloud(), fluid, Vec2(1.0, 1.0), grad_p, 1e-5),
            Vec2(1.0, 1.0) - 1e-5 * grad_p);
  EXPECT_EQ(kernels::corrected_velocity(s.cloud(), node, Vec2(1.0, 1.0), grad_p, 1e-5),
            Vec2(0.5, 0.0));
  s.points.type[fluid] = PointType::isolated;  // ballistic
  EXPECT_EQ(kernels::predicted_velocity(s.cloud(), fluid, dt, g, viscous), Vec2(1.0, 0.0) + dt * g);
  EXPECT_EQ(kernels::corrected_velocity(s.cloud(), fluid, Vec2(1.0, 1.0), grad_p, 1e-5),
            Vec2(1.0, 1.0));
}

TEST(LddKernels, SurfacePressureOfAFlatSurfaceIsHalfACellOfHydrostatics) {
  const double dx = 0.01, h = 2.1 * dx, rho = 1000.0;
  const Scene s = lattice_on_floor(dx, h, false);
  const Index top = nearest(s.points, Vec2(0.5 + 0.5 * dx, 0.3 - 0.5 * dx));
  const auto p = kernels::surface_pressure(s.cloud(), top, h, dx, rho, Vec2(0.0, -9.81));
  ASSERT_TRUE(p);
  EXPECT_NEAR(*p, rho * 9.81 * 0.5 * dx, 1e-9);
  // Upside down (gravity away from the fluid): never tension.
  EXPECT_EQ(*kernels::surface_pressure(s.cloud(), top, h, dx, rho, Vec2(0.0, 9.81)), 0.0);
  const Scene alone = fluid_scene({Vec2(0.0, 0.0)}, h);
  EXPECT_FALSE(kernels::surface_pressure(alone.cloud(), 0, h, dx, rho, Vec2(0.0, -9.81)));
}

TEST(LddKernels, SmoothingLeavesAUniformFlowAndIgnoresTheWalls) {
  const double dx = 0.01, h = 2.1 * dx;
  Scene s = lattice_on_floor(dx, h, true);
  for (Index i = 0; i < s.points.size(); ++i)
    s.points.velocity[i] = s.points.kind[i] == PointKind::fluid ? Vec2(0.7, -0.2) : Vec2(9, 9);
  const Index bottom = nearest(s.points, Vec2(0.5 + 0.5 * dx, 0.5 * dx));
  const auto change = kernels::smoothing_change(s.cloud(), bottom, 0.05, h);
  ASSERT_TRUE(change);
  EXPECT_EQ(*change, Vec2::Zero());
  // One neighbour faster by Δu: the change is ε W/ΣW Δu.
  const Index right = nearest(s.points, Vec2(0.5 + 1.5 * dx, 0.5 * dx));
  s.points.velocity[right] += Vec2(1.0, 0.0);
  double total = 0.0;
  for (Index j : s.neighbours.of(bottom))
    if (s.points.kind[j] == PointKind::fluid)
      total += wendland_c2((s.points.position[j] - s.points.position[bottom]).norm() / h);
  const double w = wendland_c2(dx / h);
  EXPECT_NEAR(kernels::smoothing_change(s.cloud(), bottom, 0.05, h)->x(), 0.05 * w / total, 1e-14);
  const Index node = s.points.size() - 1;
  EXPECT_FALSE(kernels::smoothing_change(s.cloud(), node, 0.05, h));
}

// --- The point-loop driver ----------------------------------------------------------------

TEST(LddPointLoop, VisitsEveryOwnedPointOnceAndNoGhost) {
  const Index owned = 10007, ghosts = 13;
  std::vector<int> visits(static_cast<std::size_t>(owned + ghosts), 0);
  for (const auto balance : {LoopBalance::even, LoopBalance::balanced}) {
    std::fill(visits.begin(), visits.end(), 0);
    for_each_point(
        owned, [&](Index i) { ++visits[static_cast<std::size_t>(i)]; }, balance);
    EXPECT_EQ(std::count(visits.begin(), visits.begin() + owned, 1), owned);
    EXPECT_EQ(std::count(visits.begin() + owned, visits.end(), 0), ghosts);
  }
}

TEST(LddPointLoop, ReducesOverTheOwnedPoints) {
  struct Totals {
    long count = 0;
    long sum = 0;
    Index largest = -1;
    void merge(const Totals& o) {
      count += o.count;
      sum += o.sum;
      largest = std::max(largest, o.largest);
    }
  };
  const Index owned = 5001;
  const auto t = reduce_points(owned, Totals{}, [](Index i, Totals& mine) {
    ++mine.count;
    mine.sum += i;
    mine.largest = std::max(mine.largest, i);
  });
  EXPECT_EQ(t.count, owned);
  EXPECT_EQ(t.sum, static_cast<long>(owned) * (owned - 1) / 2);
  EXPECT_EQ(t.largest, owned - 1);
  EXPECT_EQ(reduce_points(0, Totals{}, [](Index, Totals& m) { ++m.count; }).count, 0);
}

}  // namespace
}  // namespace hm::ldd
