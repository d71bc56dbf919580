#pragma once
// A vertical piston wall on a spring closing a 2-D water layer (depth H, length L, rigid floor
// and far wall, free surface), its one mode the rigid translation Φ = e_x/√m_s: the analytic
// case of tests/coupling/test_flexible_body.cpp, also timed by bench_coupling.
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "coupling/flexible_body.hpp"
#include "ldd/seeding.hpp"
#include "mesh/wall_mesher.hpp"

namespace hm::coupling::test {

using ldd::Vec;
inline constexpr double rho = 1000.0, g = 9.81;  // [kg/m³], [m/s²]
inline constexpr double H = 0.1, L = 0.2;        // water depth and layer length [m]

/// m_a of the piston [kg/m]: (16 ρ H²/π³) Σ coth((2n−1)πL/(2H))/(2n−1)³.
inline double piston_added_mass() {
  double sum = 0.0;
  for (int n = 1; n < 200; ++n) {
    const double k = (2 * n - 1) * std::numbers::pi / (2 * H);
    sum += 1.0 / std::tanh(k * L) / std::pow(2 * n - 1, 3);
  }
  return 16 * rho * H * H / std::pow(std::numbers::pi, 3) * sum;
}

struct Piston {
  std::unique_ptr<ldd::FlowSolver<2>> flow;
  std::vector<FlexibleBody<2>> bodies;
  double mass = 0.0;  ///< m_s [kg/m]
};

/// The piston at x = L (normal −x into the fluid) from the floor to 1.5 H; the tank's floor runs
/// on under it so that it slides on the floor.
inline Piston piston(double dx, double mass_ratio, double wet_frequency_hz, CouplingScheme scheme,
                     bool release_wall_tension = true, long added_mass_interval = 20) {
  mesh::WallOptions o;
  o.dim = 2;
  o.size = 4 * dx;
  o.faces = {"xmin", "ymin"};
  const mesh::SurfaceMesh tank =
      mesh::mesh_rectangle_walls({Eigen::Vector2d::Zero(), Eigen::Vector2d(L + 0.05, 2 * H)}, o);
  const int segments = static_cast<int>(std::ceil(1.5 * H / (2 * dx)));
  mesh::SurfaceMesh wall;
  wall.dim = 2;
  wall.vertices.resize(segments + 1, 2);
  wall.cells.resize(segments, 2);
  for (int k = 0; k <= segments; ++k) wall.vertices.row(k) << L, 1.5 * H * k / segments;
  for (int k = 0; k < segments; ++k) wall.cells.row(k) << k, k + 1;
  std::vector<ldd::WallMesh<2>> walls;
  walls.emplace_back(tank, "tank");
  walls.emplace_back(wall, "piston");

  Piston p;
  p.mass = piston_added_mass() / mass_ratio;
  ModalSurface<2> modes;
  for (int k = 0; k <= segments; ++k) modes.x0.push_back(wall.vertices.row(k).transpose());
  modes.shapes = Eigen::MatrixXd::Zero(2 * (segments + 1), 1);
  for (int k = 0; k <= segments; ++k) modes.shapes(2 * k, 0) = 1.0 / std::sqrt(p.mass);
  const double wet = 2 * std::numbers::pi * wet_frequency_hz;
  modes.omega = Eigen::VectorXd::Constant(1, wet * std::sqrt(1 + mass_ratio));
  modes.zeta = Eigen::VectorXd::Zero(1);
  CouplingOptions co;
  co.scheme = scheme;
  co.tolerance = 1e-4;
  co.added_mass_interval = added_mass_interval;

  ldd::FlowOptions<2> fo;
  fo.dx = dx;
  fo.gravity = Vec<2>(0, -g);
  fo.viscosity = 0.0;
  fo.release_wall_tension = release_wall_tension;
  const auto x = ldd::seed_box<2>({Vec<2>::Zero(), Vec<2>(L, H)}, dx, walls);
  p.flow = std::make_unique<ldd::FlowSolver<2>>(std::move(walls), x, std::span<const Vec<2>>{}, fo);
  p.bodies.emplace_back("piston", std::move(modes), 1, co, p.flow->walls()[1]);
  return p;
}

}  // namespace hm::coupling::test
