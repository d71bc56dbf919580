// Walls as surface meshes: closest point, signed distance, barycentrics, refit, wall nodes,
// thin-wall cuts, fluid seeding and its error messages.
#include <gtest/gtest.h>

#include "clouds.hpp"
#include "core/errors.hpp"
#include "tank.hpp"

namespace hm::ldd {
namespace {

template <typename F>
std::string input_error_text(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no InputError";
}

TEST(LddWalls, ClosestAndSignedDistance2D) {
  const auto w = test::box_tank<2>(Vec<2>(0.5, 0.4), 0.05);
  const auto in = w.closest(Vec<2>(0.2, 0.1));
  EXPECT_NEAR(in.signed_distance, 0.1, 1e-14);
  EXPECT_TRUE(in.point.isApprox(Vec<2>(0.2, 0.0), 1e-14));
  EXPECT_TRUE(w.point_at(in.element, in.barycentric).isApprox(in.point, 1e-14));
  EXPECT_NEAR(w.closest(Vec<2>(-0.1, 0.2)).signed_distance, -0.1, 1e-14);
  // Outside, nearest to the corner vertex: the vertex pseudo-normal gives the sign.
  EXPECT_NEAR(w.closest(Vec<2>(-0.1, -0.1)).signed_distance, -std::sqrt(0.02), 1e-14);
  EXPECT_NEAR(w.closest(Vec<2>(0.01, 0.01)).signed_distance, 0.01, 1e-14);
}

TEST(LddWalls, ClosestSignedDistanceAndRefit3D) {
  auto w = test::box_tank<3>(Vec<3>(0.4, 0.3, 0.2), 0.05);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-0.1, 0.5);
  for (int k = 0; k < 200; ++k) {
    const Vec<3> x(u(rng), u(rng), u(rng));
    // Exact signed distance to the box [0,0.4]×[0,0.3]×[0,0.2], positive inside.
    const Vec<3> hi(0.4, 0.3, 0.2);
    const Vec<3> q = (x - hi / 2).cwiseAbs() - hi / 2;
    const double outside = q.cwiseMax(0.0).norm(), inside = std::min(q.maxCoeff(), 0.0);
    const auto c = w.closest(x);
    ASSERT_NEAR(c.signed_distance, -(outside + inside), 1e-12) << x.transpose();
    ASSERT_TRUE(w.point_at(c.element, c.barycentric).isApprox(c.point, 1e-12));
  }
  // Move the tank by (0.3, 0, 0) with velocity (1, 2, 3) m/s: the refitted tree follows.
  std::vector<Vec<3>> moved = w.vertices();
  for (auto& v : moved) v += Vec<3>(0.3, 0.0, 0.0);
  const std::vector<Vec<3>> vel(moved.size(), Vec<3>(1, 2, 3));
  w.move(moved, vel);
  const auto c = w.closest(Vec<3>(0.5, 0.15, 0.05));
  EXPECT_NEAR(c.signed_distance, 0.05, 1e-12);
  EXPECT_TRUE(w.velocity_at(c.element, c.barycentric).isApprox(Vec<3>(1, 2, 3), 1e-12));
}

TEST(LddWalls, WallNodesFollowTheMesh) {
  auto w = test::box_tank<3>(Vec<3>(0.2, 0.2, 0.2), 0.1);
  PointSet<3> pts;
  const Index n = add_wall_nodes<3>(pts, w, 0, 0.02);
  EXPECT_GT(n, 6 * 10 * 10 - 100);
  for (Index i = 0; i < n; ++i) {
    ASSERT_NEAR(w.closest(pts.position[i]).signed_distance, 0.0, 1e-12);
    ASSERT_NEAR(pts.wall_normal[i].norm(), 1.0, 1e-12);
    // Normals into the box: towards its centre.
    ASSERT_GT(pts.wall_normal[i].dot(Vec<3>(0.1, 0.1, 0.1) - pts.position[i]), 0.0);
  }
  // No two nodes closer than a third of dx (vertices and shared edges sampled once).
  const auto nb = find_neighbours<3>(pts.position, 0.02 / 3);
  EXPECT_EQ(nb.pairs(), 0);
  std::vector<Vec<3>> moved = w.vertices(), acc(moved.size(), Vec<3>(0, 0, -2));
  for (auto& v : moved) v += Vec<3>(0.0, 0.0, 0.01);
  w.move(moved, {}, acc);
  std::vector<WallMesh<3>> walls;
  walls.push_back(std::move(w));
  const auto before = pts.position;
  update_wall_nodes<3>(pts, walls);
  for (Index i = 0; i < n; ++i) {
    ASSERT_TRUE(pts.position[i].isApprox(before[i] + Vec<3>(0, 0, 0.01), 1e-12));
    ASSERT_TRUE(pts.wall_acceleration[i].isApprox(Vec<3>(0, 0, -2), 1e-12));
  }
}

TEST(LddWalls, ThinBaffleCutsPairs2D) {
  // Tank 0.5 × 0.4 with a thin baffle at x = 0.25 from the floor to y = 0.3.
  std::vector<WallMesh<2>> walls;
  walls.push_back(test::box_tank<2>(Vec<2>(0.5, 0.4), 0.05));
  mesh::SurfaceMesh baffle;
  baffle.dim = 2;
  baffle.vertices.resize(3, 2);
  baffle.vertices << 0.25, 0.0, 0.25, 0.15, 0.25, 0.3;
  baffle.cells.resize(2, 2);
  baffle.cells << 0, 1, 1, 2;
  walls.emplace_back(baffle, "baffle", true);
  const double dx = 0.01;
  PointSet<2> pts;
  for (const auto& x : seed_box<2>({Vec<2>::Zero(), Vec<2>(0.5, 0.4)}, dx, walls)) pts.add_fluid(x);
  for (int b = 0; b < 2; ++b) add_wall_nodes<2>(pts, walls[b], b, dx);
  auto nb = find_neighbours<2>(pts.position, 2.5 * dx);
  const auto cut = cut_pairs_through_thin_walls<2>(nb, pts, walls);
  EXPECT_GT(cut, 0);
  Index kept_across_top = 0;
  for (Index i = 0; i < pts.size(); ++i)
    for (Index j : nb.of(i)) {
      const auto &a = pts.position[i], &b = pts.position[j];
      const bool across = (a.x() - 0.25) * (b.x() - 0.25) < 0.0;
      const double y = a.y() + (b.y() - a.y()) * (0.25 - a.x()) / (b.x() - a.x());
      ASSERT_FALSE(across && y < 0.3) << a.transpose() << " | " << b.transpose();
      kept_across_top += across && y > 0.3 + 1e-9;
    }
  EXPECT_GT(kept_across_top, 0);  // above the baffle the two sides still talk
}

// A solid body thinner than the support (the 5 mm elastic gate at h = 6.25 mm): the fluid on
// one face must not see the other face's wall nodes nor the fluid beyond. Before solid walls cut
// pairs, the left fluid coupled to the right face's nodes (normals pointing away from it) and to
// the fluid leaking past the gate.
TEST(LddWalls, SolidBodyThinnerThanTheSupportCutsPairs2D) {
  const double dx = 0.0025, t = 0.005, x0 = 0.1;
  std::vector<WallMesh<2>> walls;
  walls.push_back(test::box_tank<2>(Vec<2>(0.2, 0.1), 4 * dx));
  mesh::SurfaceMesh gate;  // closed outline of [x0, x0 + t] × [0, 0.05], normals outwards
  gate.dim = 2;
  gate.vertices.resize(4, 2);
  gate.vertices << x0, 0.0, x0, 0.05, x0 + t, 0.05, x0 + t, 0.0;
  gate.cells.resize(4, 2);
  gate.cells << 0, 1, 1, 2, 2, 3, 3, 0;
  walls.emplace_back(gate, "gate");
  walls.back().set_solid(true);
  PointSet<2> pts;
  for (const auto& x : seed_box<2>({Vec<2>::Zero(), Vec<2>(0.2, 0.04)}, dx, walls))
    pts.add_fluid(x);
  for (int b = 0; b < 2; ++b) add_wall_nodes<2>(pts, walls[b], b, dx);
  auto nb = find_neighbours<2>(pts.position, 2.5 * dx);
  const auto cut = cut_pairs_through_thin_walls<2>(nb, pts, walls);
  EXPECT_GT(cut, 0);
  const auto side = [&](Index i) {  // −1 left of the gate, +1 right, 0 on it
    const double x = pts.position[i].x();
    return x < x0 - 1e-12 ? -1 : x > x0 + t + 1e-12 ? 1 : 0;
  };
  for (Index i = 0; i < pts.size(); ++i) {
    if (pts.kind[i] != PointKind::fluid) continue;
    for (Index j : nb.of(i)) {
      if (pts.kind[j] == PointKind::fluid) {
        ASSERT_EQ(side(i), side(j))
            << pts.position[i].transpose() << " | " << pts.position[j].transpose();
      } else if (pts.host[j].body == 1) {  // a gate node: only those facing the point
        ASSERT_GE((pts.position[i] - pts.position[j]).dot(pts.wall_normal[j]), 0.0)
            << pts.position[i].transpose() << " sees the node at " << pts.position[j].transpose();
      }
    }
  }
}

TEST(LddSeeding, FillsBoxAndClosedSurface) {
  const auto w = test::box_tank<3>(Vec<3>(0.2, 0.1, 0.1), 0.05);
  const auto x = seed_inside<3>(w, 0.01);
  EXPECT_EQ(x.size(), 20u * 10u * 10u);
  for (const auto& p : x) ASSERT_GE(w.closest(p).signed_distance, 0.005 * (1 - 1e-6));
  std::vector<WallMesh<3>> walls;
  walls.push_back(test::box_tank<3>(Vec<3>(0.2, 0.1, 0.1), 0.05));
  EXPECT_EQ(seed_box<3>({Vec<3>::Zero(), Vec<3>(0.2, 0.1, 0.05)}, 0.01, walls).size(), 1000u);
}

TEST(LddSeeding, BadInputMessages) {
  std::vector<WallMesh<3>> walls;
  walls.push_back(
      test::box_tank<3>(Vec<3>(0.2, 0.1, 0.1), 0.05, {"xmin", "xmax", "ymin", "ymax", "zmin"}));
  // An open tank (no lid) cannot bound a fluid seeded "inside" it.
  auto m = input_error_text([&] { seed_inside<3>(walls[0], 0.01); });
  EXPECT_NE(m.find("wall 'tank' must be a closed surface for seeding the fluid inside it"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("open edges"), std::string::npos) << m;
  // Fluid outside the tank.
  m = input_error_text([&] {
    seed_box<3>({Vec<3>(0.1, 0.0, 0.0), Vec<3>(0.3, 0.1, 0.05)}, 0.01, walls);
  });
  EXPECT_NE(m.find("fluid box (0.1, 0, 0)–(0.3, 0.1, 0.05) is not inside the tank: the walls "
                   "span (0, 0, 0)–(0.2, 0.1, 0.1)"),
            std::string::npos)
      << m;
  // dx larger than the domain.
  m = input_error_text([&] { seed_box<3>({Vec<3>::Zero(), Vec<3>(0.2, 0.1, 0.05)}, 0.08, walls); });
  EXPECT_NE(m.find("fluid spacing dx = 0.08 m is too large for the fluid box"), std::string::npos)
      << m;
  EXPECT_NE(m.find("smallest side 0.05 m holds fewer than 4 points; choose dx ≤ 0.0125 m"),
            std::string::npos)
      << m;
  // 2-D: an open polyline.
  const auto open2 = test::box_tank<2>(Vec<2>(0.5, 0.4), 0.05, {"xmin", "ymin", "xmax"});
  m = input_error_text([&] { seed_inside<2>(open2, 0.01); });
  EXPECT_NE(m.find("must be a closed curve"), std::string::npos) << m;
  EXPECT_NE(m.find("2 open ends"), std::string::npos) << m;
}

}  // namespace
}  // namespace hm::ldd
