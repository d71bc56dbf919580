#pragma once
// A dry three-vertex plate above a 5 cm water layer in a 0.4 m wide open tank (dx = 1 cm): the
// rig of the tests of bodies in prescribed or free motion (tests/coupling), where the fluid must
// not touch the body. Its one-mode set: the rigid translation along x, Φ = e_x/√m (Γ = √m e_x),
// on a spring of ω.
#include <cmath>
#include <memory>

#include "coupling/flexible_body.hpp"
#include "ldd/seeding.hpp"
#include "mesh/wall_mesher.hpp"

namespace hm::coupling::test {

struct PlateRig {
  mesh::SurfaceMesh tank, plate;
  std::unique_ptr<ldd::FlowSolver<2>> flow;  ///< walls: 0 the tank, 1 the plate
};

/// The plate through (x, y) of `vertices` (3 × 2, [m]) in a tank `height` [m] high.
inline PlateRig plate_rig(const Eigen::Matrix<double, 3, 2>& vertices, double height) {
  const double dx = 0.01;
  PlateRig rig;
  mesh::WallOptions wo;
  wo.dim = 2;
  wo.size = 4 * dx;
  wo.faces = {"xmin", "xmax", "ymin"};
  rig.tank =
      mesh::mesh_rectangle_walls({Eigen::Vector2d::Zero(), Eigen::Vector2d(0.4, height)}, wo);
  rig.plate.dim = 2;
  rig.plate.vertices = vertices;
  rig.plate.cells.resize(2, 2);
  rig.plate.cells << 0, 1, 1, 2;
  std::vector<ldd::WallMesh<2>> walls;
  walls.emplace_back(rig.tank, "tank");
  walls.emplace_back(rig.plate, "plate");
  ldd::FlowOptions<2> fo;
  fo.dx = dx;
  fo.gravity = ldd::Vec<2>(0, -9.81);
  const auto x = ldd::seed_box<2>({ldd::Vec<2>::Zero(), ldd::Vec<2>(0.4, 0.05)}, dx, walls);
  rig.flow =
      std::make_unique<ldd::FlowSolver<2>>(std::move(walls), x, std::span<const ldd::Vec<2>>{}, fo);
  return rig;
}

/// The vertical plate x = 0.2 m, y ∈ [0.15, 0.25] (centre (0.2, 0.2)) in a tank 0.3 m high.
inline PlateRig vertical_plate_rig() {
  Eigen::Matrix<double, 3, 2> vertical;
  vertical << 0.2, 0.15, 0.2, 0.2, 0.2, 0.25;
  return plate_rig(vertical, 0.3);
}

/// The plate's one mode: the translation along x of a mass `mass` [kg] on a spring of `omega`
/// [rad/s].
inline ModalSurface<2> sliding_mode(const mesh::SurfaceMesh& plate, double mass, double omega) {
  ModalSurface<2> modes;
  for (int k = 0; k < 3; ++k) modes.x0.push_back(plate.vertices.row(k).transpose());
  modes.shapes = Eigen::MatrixXd::Zero(6, 1);
  for (int k = 0; k < 3; ++k) modes.shapes(2 * k, 0) = 1 / std::sqrt(mass);
  modes.omega = Eigen::VectorXd::Constant(1, omega);
  modes.zeta = Eigen::VectorXd::Zero(1);
  modes.participation = Eigen::MatrixXd::Zero(1, 2);
  modes.participation(0, 0) = std::sqrt(mass);
  return modes;
}

}  // namespace hm::coupling::test
