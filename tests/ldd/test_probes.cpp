// Probes on a hydrostatic water column (the PPE's own pressure field, hydrostatic to < 0.5 % of
// ρgH): pressure at a point (wet/dry, thin walls), elevation gauges, surge front, and the
// consistent wall loads (exact for a constant pressure; floor and side-wall forces of the column).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>

#include "ldd/probes.hpp"
#include "tank.hpp"

namespace hm::ldd {
namespace {

constexpr double rho_g = 1000.0 * 9.81;

/// Height of the top fluid layer: the column's pressure is ρg(top − z) (Dirichlet p = 0 there).
template <int D>
double top_layer(const PointSet<D>& points) {
  double top = -1e300;
  for (Index i = 0; i < points.size(); ++i)
    if (points.kind[i] == PointKind::fluid) top = std::max(top, points.position[i][D - 1]);
  return top;
}

// ---- pressure
// -------------------------------------------------------------------------------------

TEST(LddProbes, PressureInTheColumnAtAWallAndAboveTheSurface2D) {
  // 0.5 × 0.4 tank, 0.3 m of water, dx = 1 cm: 30 layers, top layer at 0.295 m.
  const auto c = test::water_column<2>(Vec<2>(0.5, 0.4), 0.3, 0.01, 0.05);
  ASSERT_TRUE(c.report.converged);
  const double top = top_layer(c.points), radius = c.h;
  std::span<const WallMesh<2>> walls(c.walls);
  auto relative_error = [&](const Vec<2>& x, bool& wet) {
    const double p = probe_pressure<2>(c.points, walls, x, radius, c.dx, &wet);
    return std::abs(p - rho_g * (top - x.y())) / (rho_g * (top - x.y()));
  };
  bool wet = false;
  const double mid = relative_error(Vec<2>(0.25, 0.15), wet);
  EXPECT_TRUE(wet);
  bool wet_wall = false;  // on the side wall: half a sphere of fluid plus the wall nodes
  const double wall = relative_error(Vec<2>(0.0, 0.15), wet_wall);
  EXPECT_TRUE(wet_wall);
  bool wet_deep = false;  // a quarter depth, off the wall by half a spacing
  const double deep = relative_error(Vec<2>(0.005, 0.075), wet_deep);
  std::printf("2-D probe error of rho g (H - z): mid-depth %.2e, side wall %.2e, near wall %.2e\n",
              mid, wall, deep);
  EXPECT_LT(mid, 0.01);
  EXPECT_LT(wall, 0.01);
  EXPECT_LT(deep, 0.01);
  // Dry: above the surface by more than the radius (nothing), and at 0.8 radius above the top
  // layer (a thin cap of the sphere).
  for (const double above : {1.5, 0.8}) {
    bool w = true;
    EXPECT_EQ(
        probe_pressure<2>(c.points, walls, Vec<2>(0.25, top + above * radius), radius, c.dx, &w),
        0.0);
    EXPECT_FALSE(w) << above;
  }
}

std::span<const WallMesh<2>> tank_only(const std::vector<WallMesh<2>>& walls) {
  return std::span<const WallMesh<2>>(walls).first(1);
}

TEST(LddProbes, PressureProbeDoesNotSeeThroughAThinWall2D) {
  // Tank 0.5 × 0.4, thin wall at x = 0.25 over the full height. Left of it p = 1, right p = 2
  // (fluid points and the wall nodes on each side).
  std::vector<WallMesh<2>> walls;
  walls.push_back(test::box_tank<2>(Vec<2>(0.5, 0.4), 0.05));
  mesh::SurfaceMesh baffle;
  baffle.dim = 2;
  baffle.vertices.resize(2, 2);
  baffle.vertices << 0.25, 0.0, 0.25, 0.4;
  baffle.cells.resize(1, 2);
  baffle.cells << 0, 1;
  walls.emplace_back(baffle, "baffle", true);
  const double dx = 0.01;
  PointSet<2> pts;
  // Seeded against the tank only (seed_box keeps the fluid side of every wall, one side of a
  // thin one); the lattice is dx/2 from the baffle on both sides.
  for (const auto& x : seed_box<2>({Vec<2>::Zero(), Vec<2>(0.5, 0.3)}, dx, tank_only(walls)))
    pts.add_fluid(x);
  for (int b = 0; b < 2; ++b) add_wall_nodes<2>(pts, walls[b], b, dx);
  for (Index i = 0; i < pts.size(); ++i) {
    const double x = pts.position[i].x();
    const bool left = x < 0.25 - 1e-12 || (x < 0.25 + 1e-12 && pts.wall_normal[i].x() < 0.0);
    pts.pressure[i] = left ? 1.0 : 2.0;
  }
  std::span<const WallMesh<2>> all(walls);
  const double radius = 2.5 * dx;
  for (const double offset : {0.002, 0.02}) {
    bool wet = false;
    EXPECT_EQ(probe_pressure<2>(pts, all, Vec<2>(0.25 - offset, 0.15), radius, dx, &wet), 1.0);
    EXPECT_TRUE(wet);
    EXPECT_EQ(probe_pressure<2>(pts, all, Vec<2>(0.25 + offset, 0.15), radius, dx, &wet), 2.0);
    EXPECT_TRUE(wet);
  }
  // Without the thin wall the same probe mixes the two sides.
  const double mixed = probe_pressure<2>(pts, all.first(1), Vec<2>(0.248, 0.15), radius, dx);
  std::printf("thin wall left out: probe 2 mm left of it reads %.3f (1 = its side only)\n", mixed);
  EXPECT_GT(mixed, 1.2);
  EXPECT_LT(mixed, 1.8);
}

TEST(LddProbes, PressureInTheColumn3D) {
  // 0.15 × 0.125 × 0.3 tank, 10 layers of dx = 1.25 cm (top layer 0.11875 m).
  const auto c = test::water_column<3>(Vec<3>(0.15, 0.125, 0.3), 0.125, 0.0125, 0.1);
  ASSERT_TRUE(c.report.converged);
  const double top = top_layer(c.points);
  std::span<const WallMesh<3>> walls(c.walls);
  for (const Vec<3>& x : {Vec<3>(0.075, 0.0625, 0.0625), Vec<3>(0.0, 0.0625, 0.0625)}) {
    bool wet = false;
    const double p = probe_pressure<3>(c.points, walls, x, c.h, c.dx, &wet);
    const double err = std::abs(p - rho_g * (top - x.z())) / (rho_g * (top - x.z()));
    std::printf("3-D probe at (%.4g, %.4g, %.4g): error %.2e of rho g (H - z)\n", x.x(), x.y(),
                x.z(), err);
    EXPECT_TRUE(wet);
    EXPECT_LT(err, 0.01);
  }
  bool wet = true;
  EXPECT_EQ(
      probe_pressure<3>(c.points, walls, Vec<3>(0.075, 0.0625, top + 1.5 * c.h), c.h, c.dx, &wet),
      0.0);
  EXPECT_FALSE(wet);
}

// ---- elevation and front -----------------------------------------------------------------------

TEST(LddProbes, ElevationGaugeOnALattice) {
  // 30 layers at (k + ½)dx: the gauge reads the depth 0.3 m, between columns and on one.
  PointSet<2> pts;
  const double dx = 0.01;
  std::vector<WallMesh<2>> walls;
  walls.push_back(test::box_tank<2>(Vec<2>(0.5, 0.4), 0.05));
  for (const auto& x : seed_box<2>({Vec<2>::Zero(), Vec<2>(0.5, 0.3)}, dx, walls)) pts.add_fluid(x);
  add_wall_nodes<2>(pts, walls[0], 0, dx);
  for (const double x : {0.25, 0.255, 0.1234, 0.0}) {
    bool wet = false;
    EXPECT_NEAR(probe_elevation<2>(pts, Vec<2>(x, 0.9), dx, &wet), 0.3, 1e-12) << x;
    EXPECT_TRUE(wet);
  }
  bool wet = true;
  EXPECT_EQ(probe_elevation<2>(pts, Vec<2>(0.6, 0.1), dx, &wet), 0.0);  // outside the tank
  EXPECT_FALSE(wet);
  // A drop 1.5 dx above the column top counts as the column; spray more than 2 dx up does not,
  // nor an isolated point.
  const Index drop = pts.add_fluid(Vec<2>(0.255, 0.295 + 1.5 * dx));
  EXPECT_NEAR(probe_elevation<2>(pts, Vec<2>(0.255, 0.0), dx), 0.315, 1e-12);
  pts.position[drop].y() = 0.295 + 2.5 * dx;
  EXPECT_NEAR(probe_elevation<2>(pts, Vec<2>(0.255, 0.0), dx), 0.3, 1e-12);
  pts.position[drop].y() = 0.295 + 1.0 * dx;
  pts.type[drop] = PointType::isolated;
  EXPECT_NEAR(probe_elevation<2>(pts, Vec<2>(0.255, 0.0), dx), 0.3, 1e-12);
}

TEST(LddProbes, ElevationGauge3D) {
  PointSet<3> pts;
  const double dx = 0.0125;
  std::vector<WallMesh<3>> walls;
  walls.push_back(test::box_tank<3>(Vec<3>(0.15, 0.125, 0.3), 0.1));
  // A sloping surface: columns of 8 layers for x < 0.075, 10 layers beyond.
  for (const auto& x : seed_box<3>({Vec<3>::Zero(), Vec<3>(0.15, 0.125, 0.125)}, dx, walls))
    if (x.x() > 0.075 || x.z() < 0.1) pts.add_fluid(x);
  EXPECT_NEAR(probe_elevation<3>(pts, Vec<3>(0.03125, 0.05625, 0.0), dx), 0.1, 1e-12);
  EXPECT_NEAR(probe_elevation<3>(pts, Vec<3>(0.1, 0.06, 0.5), dx), 0.125, 1e-12);
}

TEST(LddProbes, SurgeFront) {
  // A dam-break block 0.2 × 0.3 of dx = 1 cm in a 0.5 m tank.
  PointSet<2> pts;
  const double dx = 0.01;
  std::vector<WallMesh<2>> walls;
  walls.push_back(test::box_tank<2>(Vec<2>(0.5, 0.4), 0.05));
  for (const auto& x : seed_box<2>({Vec<2>::Zero(), Vec<2>(0.2, 0.3)}, dx, walls)) pts.add_fluid(x);
  add_wall_nodes<2>(pts, walls[0], 0, dx);  // wall nodes never count
  EXPECT_NEAR(probe_front<2>(pts, Vec<2>(1, 0), 0.0, 0.05, dx), 0.2, 1e-12);
  EXPECT_NEAR(probe_front<2>(pts, Vec<2>(3, 0), 0.0, 0.05, dx), 0.2, 1e-12);  // normalised
  // A point ahead of the block above the band does not count; one in the band does.
  const Index ahead = pts.add_fluid(Vec<2>(0.4, 0.2));
  EXPECT_NEAR(probe_front<2>(pts, Vec<2>(1, 0), 0.0, 0.05, dx), 0.2, 1e-12);
  pts.position[ahead] = Vec<2>(0.3, 0.02);
  EXPECT_NEAR(probe_front<2>(pts, Vec<2>(1, 0), 0.0, 0.05, dx), 0.305, 1e-12);
  pts.type[ahead] = PointType::isolated;
  EXPECT_NEAR(probe_front<2>(pts, Vec<2>(1, 0), 0.0, 0.05, dx), 0.2, 1e-12);
  bool found = true;
  EXPECT_EQ(probe_front<2>(pts, Vec<2>(1, 0), 0.35, 0.4, dx, &found), 0.0);
  EXPECT_FALSE(found);
  // 3-D, along the diagonal of the floor: max of (x + y)/√2 over the block, + dx/2.
  PointSet<3> p3;
  std::vector<WallMesh<3>> w3;
  w3.push_back(test::box_tank<3>(Vec<3>(0.5, 0.5, 0.4), 0.1));
  for (const auto& x : seed_box<3>({Vec<3>::Zero(), Vec<3>(0.2, 0.1, 0.1)}, dx, w3))
    p3.add_fluid(x);
  EXPECT_NEAR(probe_front<3>(p3, Vec<3>(1, 1, 0), 0.0, 0.1, dx),
              (0.195 + 0.095) / std::sqrt(2.0) + 0.005, 1e-12);
}

// ---- wall loads
// ------------------------------------------------------------------------------------

TEST(LddProbes, WallLoadsOfAConstantPressureAreExact3D) {
  // Closed box, every wall node at p0: each element carries −p0 A n, each vertex −p0 Σ A/3 n
  // over its triangles (consistent linear shape functions), and the total vanishes.
  const auto box = test::box_tank<3>(Vec<3>(0.3, 0.2, 0.1), 0.05);
  PointSet<3> pts;
  add_wall_nodes<3>(pts, box, 0, 0.02);
  const double p0 = 1234.5;
  std::fill(pts.pressure.begin(), pts.pressure.end(), p0);
  const auto loads = wall_pressure_loads<3>(pts, box, 0, 0.02);
  std::vector<Vec<3>> expected(box.vertices().size(), Vec<3>::Zero());
  double area = 0.0;
  for (Index e = 0; e < box.element_count(); ++e) {
    const auto& t = box.element(e);
    const auto& x = box.vertices();
    const double a = 0.5 * (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm();
    const Vec<3> n = box.normal_at(e, Vec<3>::Constant(1.0 / 3.0));
    area += a;
    EXPECT_TRUE(loads.element_force[e].isApprox(-p0 * a * n, 1e-12)) << e;
    for (int k = 0; k < 3; ++k) expected[t[k]] -= p0 * a / 3.0 * n;
  }
  for (std::size_t v = 0; v < expected.size(); ++v)
    EXPECT_LT((loads.vertex_force[v] - expected[v]).norm(), 1e-12 * p0 * area) << v;
  EXPECT_LT(loads.total.norm(), 1e-12 * p0 * area);
  EXPECT_NEAR(loads.wetted, 2 * (0.3 * 0.2 + 0.3 * 0.1 + 0.2 * 0.1), 1e-12);
  // Nodes of another body are not this wall's.
  const auto none = wall_pressure_loads<3>(pts, box, 1, 0.02);
  EXPECT_EQ(none.total.norm(), 0.0);
  EXPECT_EQ(none.wetted, 0.0);
}

TEST(LddProbes, ThinWallLoadIsThePressureJump2D) {
  // A free-standing thin plate from (0, 0) to (0, 0.2); normal ẑ × (b − a) = −x. Nodes on the
  // −x side at p = 300, on the +x side at p = 100: net force (−300 + 100)·(−x)·0.2 = +40 N/m in x.
  mesh::SurfaceMesh plate;
  plate.dim = 2;
  plate.vertices.resize(3, 2);
  plate.vertices << 0.0, 0.0, 0.0, 0.1, 0.0, 0.2;
  plate.cells.resize(2, 2);
  plate.cells << 0, 1, 1, 2;
  const WallMesh<2> wall(plate, "plate", true);
  PointSet<2> pts;
  add_wall_nodes<2>(pts, wall, 3, 0.01);
  for (Index i = 0; i < pts.size(); ++i) pts.pressure[i] = pts.wall_normal[i].x() < 0 ? 300 : 100;
  const auto loads = wall_pressure_loads<2>(pts, wall, 3, 0.01);
  EXPECT_NEAR(loads.total.x(), 40.0, 1e-11);
  EXPECT_NEAR(loads.total.y(), 0.0, 1e-11);
  EXPECT_NEAR(loads.wetted, 0.4, 1e-12);  // both sides
  // Consistent forces of a uniform load on two segments of 0.1 m: 10, 20, 10 N/m.
  EXPECT_NEAR(loads.vertex_force[0].x(), 10.0, 1e-11);
  EXPECT_NEAR(loads.vertex_force[1].x(), 20.0, 1e-11);
  EXPECT_NEAR(loads.vertex_force[2].x(), 10.0, 1e-11);
  // Dry on the +x side (inactive nodes): only the −x side pushes, 300 · 0.2 = 60 N/m.
  for (Index i = 0; i < pts.size(); ++i)
    if (pts.wall_normal[i].x() > 0) pts.type[i] = PointType::inactive;
  const auto one_side = wall_pressure_loads<2>(pts, wall, 3, 0.01);
  EXPECT_NEAR(one_side.total.x(), 60.0, 1e-11);
  EXPECT_NEAR(one_side.wetted, 0.2, 1e-12);
}

/// Force on the elements whose normal is `n` (one face of the tank).
template <int D>
Vec<D> face_force(const WallMesh<D>& wall, const WallLoads<D>& loads, const Vec<D>& n) {
  Vec<D> f = Vec<D>::Zero();
  for (Index e = 0; e < wall.element_count(); ++e)
    if (wall.normal_at(e, Vec<D>::Constant(1.0 / D)).dot(n) > 0.999) f += loads.element_force[e];
  return f;
}

// Wall shear (wall_viscous_loads) on the floor of the column under an imposed velocity field:
// a linear profile u = (γy, 0) gives μγ per metre of floor exactly (the one-sided difference is
// exact for it); a curved one u = (γy + b y², 0) is first order in dx: the error μ·b·d̄ halves
// with dx. The side walls see only the normal component and carry no shear.
TEST(LddProbes, WallShearOfAShearFlowOnTheFloor2D) {
  const double mu = 1e-3, gamma = 2.0, b = 50.0, length = 0.5;
  double previous = 0.0;
  for (const double dx : {0.02, 0.01}) {
    auto c = test::water_column<2>(Vec<2>(length, 0.4), 0.3, dx, 0.05);
    for (const double curve : {0.0, b}) {
      for (Index i = 0; i < c.points.size(); ++i)
        if (c.points.kind[i] == PointKind::fluid) {
          const double y = c.points.position[i].y();
          c.points.velocity[i] = Vec<2>(gamma * y + curve * y * y, 0.0);
        }
      const auto loads = wall_viscous_loads<2>(c.points, c.walls[0], dx, mu);
      const Vec<2> floor = face_force<2>(c.walls[0], loads, Vec<2>(0, 1));
      const double exact = mu * gamma * length, error = std::abs(floor.x() / exact - 1);
      std::printf("wall shear, dx = %.3g m, b = %g: floor %.6g N/m (exact %.6g, error %.2e)\n", dx,
                  curve, floor.x(), exact, error);
      EXPECT_LT((loads.total - floor).norm(), 1e-14);  // no shear on the side walls
      if (curve == 0.0) {
        EXPECT_LT(error, 1e-12);
      } else {
        if (previous > 0.0) {
          EXPECT_NEAR(previous / error, 2.0, 0.3);  // first order
        }
        previous = error;
      }
    }
  }
}

TEST(LddProbes, HydrostaticWallLoads2D) {
  // Column of 30 layers (dx = 1 cm) in a 0.5 m wide tank; p = ρg(H − y) with H = 0.295 m, the
  // top layer. Floor: ρgH·0.5 per metre; each side wall: ½ρgH².
  const auto c = test::water_column<2>(Vec<2>(0.5, 0.4), 0.3, 0.01, 0.05);
  ASSERT_TRUE(c.report.converged);
  const double H = top_layer(c.points);
  const auto& tank = c.walls[0];
  const auto loads = wall_pressure_loads<2>(c.points, tank, 0, c.dx);
  const Vec<2> floor = face_force<2>(tank, loads, Vec<2>(0, 1));
  const Vec<2> left = face_force<2>(tank, loads, Vec<2>(1, 0));
  const Vec<2> right = face_force<2>(tank, loads, Vec<2>(-1, 0));
  const double floor_exact = rho_g * H * 0.5, side_exact = 0.5 * rho_g * H * H;
  std::printf(
      "2-D loads: floor %.6g N/m (exact %.6g, error %.2e), left wall %.6g (exact %.6g, error "
      "%.2e), right %.6g, wetted %.4g m\n",
      -floor.y(), floor_exact, std::abs(-floor.y() / floor_exact - 1), -left.x(), side_exact,
      std::abs(-left.x() / side_exact - 1), right.x(), loads.wetted);
  EXPECT_NEAR(-floor.y(), floor_exact, 0.01 * floor_exact);
  EXPECT_NEAR(floor.x(), 0.0, 1e-9 * floor_exact);
  // Side walls: the wetted band ends within about a spacing of the top layer, where p is
  // O(ρg dx): an error of order ρg dx² against ½ρgH², bounded by 2(dx/H)² (2.3e-3 here).
  const double side_tolerance = 2.0 * std::pow(c.dx / H, 2);
  EXPECT_NEAR(-left.x(), side_exact, side_tolerance * side_exact);
  EXPECT_NEAR(right.x(), side_exact, side_tolerance * side_exact);
  // Nodal forces sum to the total and to the element forces.
  Vec<2> sum_elements = Vec<2>::Zero(), sum_vertices = Vec<2>::Zero();
  for (const auto& f : loads.element_force) sum_elements += f;
  for (const auto& f : loads.vertex_force) sum_vertices += f;
  EXPECT_EQ(sum_vertices, loads.total);
  EXPECT_LT((sum_elements - loads.total).norm(), 1e-12 * floor_exact);
  // The tank as a whole: the side forces cancel, the vertical force is the water's weight.
  EXPECT_NEAR(loads.total.x(), 0.0, 1e-3 * side_exact);
}

TEST(LddProbes, HydrostaticFloorLoad3D) {
  const auto c = test::water_column<3>(Vec<3>(0.15, 0.125, 0.3), 0.125, 0.0125, 0.1);
  ASSERT_TRUE(c.report.converged);
  const double H = top_layer(c.points);
  const auto& tank = c.walls[0];
  const auto loads = wall_pressure_loads<3>(c.points, tank, 0, c.dx);
  const Vec<3> floor = face_force<3>(tank, loads, Vec<3>(0, 0, 1));
  const Vec<3> side = face_force<3>(tank, loads, Vec<3>(1, 0, 0));
  const double floor_exact = rho_g * H * 0.15 * 0.125, side_exact = 0.5 * rho_g * H * H * 0.125;
  std::printf(
      "3-D loads: floor %.6g N (exact %.6g, error %.2e), x = 0 wall %.6g N (exact %.6g, error "
      "%.2e)\n",
      -floor.z(), floor_exact, std::abs(-floor.z() / floor_exact - 1), -side.x(), side_exact,
      std::abs(-side.x() / side_exact - 1));
  EXPECT_NEAR(-floor.z(), floor_exact, 0.01 * floor_exact);
  // As in 2-D, bounded by 2(dx/H)² (2.2e-2 with 10 layers).
  EXPECT_NEAR(-side.x(), side_exact, 2.0 * std::pow(c.dx / H, 2) * side_exact);
  Vec<3> sum_elements = Vec<3>::Zero();
  for (const auto& f : loads.element_force) sum_elements += f;
  EXPECT_LT((sum_elements - loads.total).norm(), 1e-12 * floor_exact);
}

}  // namespace
}  // namespace hm::ldd
