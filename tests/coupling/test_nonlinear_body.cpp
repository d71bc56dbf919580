// The structure-model seam with the total-Lagrangian FE body: a cantilever plate standing on the
// floor of a tank, water on its left, coupled two-way (strong). At small deflection the
// nonlinear body must give the linear modes' answer; the FE body's own checks (objectivity,
// the elastica, CSM1–3, energy) are in tests/fem.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "coupling/flexible_body.hpp"
#include "coupling/linear_modal_model.hpp"
#include "coupling/nonlinear_fe_model.hpp"
#include "fem/assembly.hpp"
#include "ldd/seeding.hpp"
#include "mesh/boundary.hpp"
#include "mesh/structured.hpp"
#include "mesh/wall_mesher.hpp"
#include "modal/eigen_solve.hpp"

namespace hm::coupling {
namespace {

using ldd::Vec;

constexpr double kDx = 0.005;                    // fluid spacing [m]
constexpr double kDepth = 0.1, kLeft = 0.2;      // water depth, plate position [m]
constexpr double kThick = 0.01, kHeight = 0.15;  // plate [m]
const fem::Material kPlate{1e8, 0.3, 1200.0};    // E [Pa], ν, ρ [kg/m³]

/// The plate (clamped on the floor, ymin), its boundary as the fluid's wall and its modes.
struct PlateStructure {
  mesh::StructureMesh mesh =
      mesh::structured_rectangle(kThick, kHeight, 2, 30, Eigen::Vector2d(kLeft, 0.0));
  mesh::BoundarySurface boundary;
  fem::ElasticModel elastic{kPlate, fem::PlaneAssumption::plane_strain, 1.0};
  fem::DofMap dofs = fem::DofMap::clamp_groups(mesh, std::vector<std::string>{"ymin"}, "plate");
  Eigen::MatrixXd modes;  ///< full DOFs, mass-normalised
  Eigen::VectorXd omega;

  explicit PlateStructure(int count) {
    boundary = mesh::extract_boundary_surface(mesh, mesh::SurfaceSplit::refined);
    const fem::SystemMatrices k_m = fem::assemble(mesh, elastic, "plate");
    modal::ModeRequest request;
    request.count = count;
    const modal::EigenSolution s =
        modal::solve_eigenproblem(dofs.reduce(k_m.stiffness), dofs.reduce(k_m.mass), request);
    modes = dofs.expand(s.pairs.vectors);
    omega = s.pairs.values.cwiseMax(0.0).cwiseSqrt();
  }

  std::shared_ptr<const ModalSurface<2>> interface() const {
    ModalSurface<2> m;
    const auto n = static_cast<Eigen::Index>(boundary.volume_node.size());
    m.shapes.resize(2 * n, modes.cols());
    for (Eigen::Index v = 0; v < n; ++v) {
      m.x0.push_back(boundary.surface.vertices.row(v).transpose());
      m.shapes.middleRows(2 * v, 2) = modes.middleRows(2 * boundary.volume_node[v], 2);
    }
    m.omega = omega;
    m.zeta = Eigen::VectorXd::Zero(omega.size());
    Eigen::MatrixXd translation = Eigen::MatrixXd::Zero(modes.rows(), 2);
    for (Eigen::Index node = 0; node < mesh.node_count(); ++node)
      translation.block<2, 2>(2 * node, 0).setIdentity();
    m.participation =
        modes.transpose() * (fem::assemble(mesh, elastic, "plate").mass * translation);
    return std::make_shared<const ModalSurface<2>>(std::move(m));
  }

  std::unique_ptr<StructureModel<2>> nonlinear(std::shared_ptr<const ModalSurface<2>> i) const {
    NonlinearFeParts parts;
    parts.body = std::make_unique<fem::HyperelasticBody>(
        mesh, fem::HyperelasticModel{elastic, fem::MaterialLaw::saint_venant_kirchhoff}, "plate");
    parts.dofs = std::make_unique<fem::DofMap>(dofs);
    parts.wall_map = std::make_unique<FeWallMap>(boundary.surface.vertices, boundary.volume_node,
                                                 mesh.node_count(), boundary.surface.vertices,
                                                 rbf::RbfOptions{});
    parts.modes = modes;
    parts.dynamics.newton.tolerance = 1e-10;
    parts.dynamics.scheme = fem::TimeScheme::energy_conserving;
    parts.context = "structure 'plate'";
    return std::make_unique<NonlinearFeModel<2>>(std::move(i), std::move(parts));
  }
};

struct TipHistory {
  std::vector<double> time, ux;
  double mean_iterations = 0.0;  ///< PPE solves a step
  double energy_error = 0.0;     ///< |numerical dissipation| / work at the end
};

/// The tip's horizontal displacement over `end` seconds, the body on `model`.
TipHistory run(const PlateStructure& plate, bool nonlinear, double end) {
  mesh::WallOptions o;
  o.dim = 2;
  o.size = 4 * kDx;
  o.faces = {"xmin", "ymin", "xmax"};
  const mesh::SurfaceMesh tank =
      mesh::mesh_rectangle_walls({Eigen::Vector2d::Zero(), Eigen::Vector2d(0.4, 0.2)}, o);
  std::vector<ldd::WallMesh<2>> walls;
  walls.emplace_back(tank, "tank");
  walls.emplace_back(plate.boundary.surface, "structure");
  ldd::FlowOptions<2> fo;
  fo.dx = kDx;
  fo.gravity = Vec<2>(0, -9.81);
  const auto x = ldd::seed_box<2>({Vec<2>::Zero(), Vec<2>(kLeft, kDepth)}, kDx, walls);
  ldd::FlowSolver<2> flow(std::move(walls), x, std::span<const Vec<2>>{}, fo);
  auto interface = plate.interface();
  auto model =
      nonlinear
          ? plate.nonlinear(interface)
          : std::unique_ptr<StructureModel<2>>(std::make_unique<LinearModalModel<2>>(interface));
  CouplingOptions co;
  co.scheme = CouplingScheme::strong;
  std::vector<FlexibleBody<2>> bodies;
  bodies.emplace_back("plate", interface, std::move(model), 1, co, flow.walls()[1]);
  Eigen::Index tip = 0;
  for (std::size_t v = 0; v < interface->x0.size(); ++v)
    if ((interface->x0[v] - Vec<2>(kLeft + kThick / 2, kHeight)).norm() <
        (interface->x0[tip] - Vec<2>(kLeft + kThick / 2, kHeight)).norm())
      tip = static_cast<Eigen::Index>(v);
  bodies.front().start(flow);
  TipHistory h;
  std::vector<CouplingMonitor> monitors;
  // One fixed step for both models (the stable step depends on the body's speed).
  const double dt = std::min(0.5 * flow.stable_dt(0.0).first, 2e-4);
  while (flow.time() < end - 0.5 * dt) {
    coupled_step<2>(flow, bodies, dt, monitors);
    h.time.push_back(flow.time());
    h.ux.push_back(bodies.front().displacement(tip).x());
    h.mean_iterations += monitors.front().iterations;
  }
  h.mean_iterations /= static_cast<double>(h.time.size());
  const StructureEnergy e = bodies.front().model().energy();
  h.energy_error = std::abs(e.numerical_dissipation) / std::max(std::abs(e.external_work), 1e-300);
  return h;
}

/// Both integrate without numerical dissipation (CFPI; the energy-conserving midpoint rule), so
/// what differs is the 12 modes against the full body and the geometric nonlinearity at a
/// stretch below 1 %. Measured: 0.73 % of the peak (generalised-α at ρ∞ = 0.8: 1.65 %, the
/// damping of the upper modes).
TEST(NonlinearFeBody, SmallDeflectionInWaterMatchesTheLinearModes) {
  const PlateStructure plate(12);
  const double end = 0.03;  // past the first peak
  const TipHistory linear = run(plate, false, end), fe = run(plate, true, end);
  ASSERT_EQ(linear.time.size(), fe.time.size());
  double peak = 0.0, difference = 0.0;
  for (std::size_t k = 0; k < linear.time.size(); ++k) {
    peak = std::max(peak, std::abs(linear.ux[k]));
    difference = std::max(difference, std::abs(fe.ux[k] - linear.ux[k]));
  }
  std::printf(
      "[ plate in water ] tip peak %.4g mm (linear modes), max |FE − linear| %.3g mm "
      "(%.2f %%), stretch %.2g %%; PPE solves a step %.2f (linear) / %.2f (FE); FE "
      "energy balance residual %.2g of the work\n",
      1e3 * peak, 1e3 * difference, 100 * difference / peak, 100 * peak / kHeight,
      linear.mean_iterations, fe.mean_iterations, fe.energy_error);
  EXPECT_GT(peak, 1e-4);               // the water really bends it
  EXPECT_LT(peak / kHeight, 0.01);     // and it stays in the linear range
  EXPECT_LT(difference, 0.02 * peak);  // the same answer
  // The modal Jacobian serves the FE body too: at most one more PPE solve a step on average
  // (measured 3.65 against 2.83: the FE wall's acceleration beyond the modal subspace is held at
  // the predictor's during the iterations).
  EXPECT_LT(fe.mean_iterations, linear.mean_iterations + 1.0);
  EXPECT_LT(fe.energy_error, 1e-9);  // the midpoint rule's balance is exact
}

}  // namespace
}  // namespace hm::coupling
