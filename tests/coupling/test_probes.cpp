// Probes fixed to a wall (moves_with) follow the wall's rigid motion exactly: a sensor on a
// swaying, rolling tank stays at the same place on the tank.
#include <gtest/gtest.h>

#include <cmath>

#include "coupling/probes.hpp"
#include "mesh/wall_mesher.hpp"

namespace hm::coupling {
namespace {

template <int D>
ldd::WallMesh<D> tank() {
  mesh::WallOptions o;
  o.dim = D;
  o.size = 0.1;
  if constexpr (D == 2) {
    o.faces = {"xmin", "xmax", "ymin"};
    return ldd::WallMesh<2>(mesh::mesh_rectangle_walls({{0.0, 0.0}, {1.0, 0.6}}, o), "tank");
  } else {
    o.faces = {"xmin", "xmax", "ymin", "ymax", "zmin"};
    return ldd::WallMesh<3>(
        mesh::mesh_box_walls({Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 0.5, 0.6)}, o), "tank");
  }
}

/// Rotation by θ in the (x, up) plane (about z in 2-D, about y in 3-D), then a shift [m].
template <int D>
ldd::Vec<D> rigid(const ldd::Vec<D>& x, double theta, const ldd::Vec<D>& shift) {
  ldd::Vec<D> y = x;
  const int a = 0, b = D - 1;  // rotate in the (x, up) plane
  y[a] = std::cos(theta) * x[a] - std::sin(theta) * x[b];
  y[b] = std::sin(theta) * x[a] + std::cos(theta) * x[b];
  return y + shift;
}

template <int D>
void follows_rigid_motion() {
  auto wall = tank<D>();
  std::vector<Probe<D>> probes(3);
  probes[0].position.setConstant(0.3);  // inside the water, off the walls
  probes[1].position.setConstant(0.2);
  probes[1].position[0] = 0.0;  // on the xmin wall
  probes[2].position.setConstant(0.25);
  probes[2].position[D - 1] = 0.0;  // on the floor
  for (auto& p : probes) attach_probe<D>(p, wall, 0);
  const double theta = 0.3;
  ldd::Vec<D> shift = ldd::Vec<D>::Constant(0.05);
  std::vector<ldd::Vec<D>> moved;
  for (const auto& x : wall.vertices()) moved.push_back(rigid<D>(x, theta, shift));
  wall.move(moved);
  for (const auto& p : probes) {
    const ldd::Vec<D> now = probe_position<D>(p, std::span<const ldd::WallMesh<D>>(&wall, 1));
    const ldd::Vec<D> exact = rigid<D>(p.position, theta, shift);
    EXPECT_LT((now - exact).norm(), 1e-12) << D << "-D probe at " << p.position.transpose();
  }
}

TEST(Probes, FixedToAWallFollowItsRigidMotion2D) {
  follows_rigid_motion<2>();
}
TEST(Probes, FixedToAWallFollowItsRigidMotion3D) {
  follows_rigid_motion<3>();
}

}  // namespace
}  // namespace hm::coupling
