#pragma once
// The rig of the structure-model tests in water (tests/coupling): a cantilever plate (tri6,
// E = 100 MPa, ρ = 1200 kg/m³, 10 mm × 150 mm, plane strain) standing on the floor of a 0.4 m
// tank at x = 0.2 m, a 0.1 m layer of water on its left (dx = 5 mm), coupled two-way (strong).
// Its linear modes come from the eigensolver; the models on them: linear modes (CFPI), the
// total-Lagrangian FE body (interface: the modes) and the reduced Saint Venant–Kirchhoff model
// on the modes and their modal derivatives (interface: that basis).
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "coupling/flexible_body.hpp"
#include "coupling/linear_modal_model.hpp"
#include "coupling/nonlinear_fe_model.hpp"
#include "coupling/nonlinear_modal_model.hpp"
#include "fem/assembly.hpp"
#include "fem/reduced_basis.hpp"
#include "fem/reduced_stvk.hpp"
#include "ldd/seeding.hpp"
#include "mesh/boundary.hpp"
#include "mesh/structured.hpp"
#include "mesh/wall_mesher.hpp"
#include "modal/eigen_solve.hpp"

namespace hm::coupling::test {

constexpr double kDx = 0.005;                         // fluid spacing [m]
constexpr double kDepth = 0.1, kLeft = 0.2;           // water depth, plate position [m]
constexpr double kThick = 0.01, kHeight = 0.15;       // plate [m]
inline const fem::Material kPlate{1e8, 0.3, 1200.0};  // E [Pa], ν, ρ [kg/m³]

/// The plate (clamped on the floor, ymin), its boundary as the fluid's wall and its modes.
struct PlateStructure {
  mesh::StructureMesh mesh =
      mesh::structured_rectangle(kThick, kHeight, 2, 30, Eigen::Vector2d(kLeft, 0.0));
  mesh::BoundarySurface boundary;
  fem::ElasticModel elastic;
  fem::DofMap dofs = fem::DofMap::clamp_groups(mesh, std::vector<std::string>{"ymin"}, "plate");
  Eigen::MatrixXd modes;  ///< full DOFs, mass-normalised
  Eigen::VectorXd omega;

  explicit PlateStructure(int count, const fem::Material& material = kPlate)
      : elastic{material, fem::PlaneAssumption::plane_strain, 1.0} {
    boundary = mesh::extract_boundary_surface(mesh, mesh::SurfaceSplit::refined);
    const fem::SystemMatrices k_m = fem::assemble(mesh, elastic, "plate");
    modal::ModeRequest request;
    request.count = count;
    const modal::EigenSolution s =
        modal::solve_eigenproblem(dofs.reduce(k_m.stiffness), dofs.reduce(k_m.mass), request);
    modes = dofs.expand(s.pairs.vectors);
    omega = s.pairs.values.cwiseMax(0.0).cwiseSqrt();
  }

  fem::HyperelasticBody body() const {
    return {mesh, fem::HyperelasticModel{elastic, fem::MaterialLaw::saint_venant_kirchhoff},
            "plate"};
  }

  /// Full-DOF vectors (columns) on the boundary vertices, with their frequencies and ΓᵀM T.
  std::shared_ptr<const ModalSurface<2>> surface_of(const Eigen::MatrixXd& vectors,
                                                    const Eigen::VectorXd& frequencies) const {
    ModalSurface<2> m;
    const auto n = static_cast<Eigen::Index>(boundary.volume_node.size());
    m.shapes.resize(2 * n, vectors.cols());
    for (Eigen::Index v = 0; v < n; ++v) {
      m.x0.push_back(boundary.surface.vertices.row(v).transpose());
      m.shapes.middleRows(2 * v, 2) = vectors.middleRows(2 * boundary.volume_node[v], 2);
    }
    m.omega = frequencies;
    m.zeta = Eigen::VectorXd::Zero(frequencies.size());
    Eigen::MatrixXd translation = Eigen::MatrixXd::Zero(vectors.rows(), 2);
    for (Eigen::Index node = 0; node < mesh.node_count(); ++node)
      translation.block<2, 2>(2 * node, 0).setIdentity();
    m.participation =
        vectors.transpose() * (fem::assemble(mesh, elastic, "plate").mass * translation);
    return std::make_shared<const ModalSurface<2>>(std::move(m));
  }

  /// The interface of the linear modes and of the FE body.
  std::shared_ptr<const ModalSurface<2>> interface() const { return surface_of(modes, omega); }

  std::unique_ptr<StructureModel<2>> nonlinear(std::shared_ptr<const ModalSurface<2>> i) const {
    NonlinearFeParts parts;
    parts.body = std::make_unique<fem::HyperelasticBody>(body());
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

  /// The reduced model on the lowest `count` modes and the derivatives of the lowest
  /// `derivative_modes`, and its interface (the basis on the wall).
  struct Reduced {
    std::shared_ptr<const ModalSurface<2>> interface;
    std::unique_ptr<StructureModel<2>> model;
  };
  Reduced reduced(int count, int derivative_modes) const {
    const fem::HyperelasticBody b = body();
    const fem::ReducedBasis basis = fem::build_reduced_basis(
        b, dofs, {modes, omega.array().square().matrix(), 0},
        {.modes = count, .derivatives = true, .derivative_modes = derivative_modes}, "plate");
    NonlinearModalParts parts;
    parts.tensors = std::make_unique<fem::ReducedStvk>(b, basis.vectors, "plate");
    const Eigen::VectorXd frequencies =
        parts.tensors->linear_stiffness().diagonal().cwiseMax(0.0).cwiseSqrt();
    parts.dynamics.newton.tolerance = 1e-10;
    parts.dynamics.scheme = fem::TimeScheme::energy_conserving;
    parts.context = "structure 'plate'";
    Reduced out;
    out.interface = surface_of(basis.vectors, frequencies);
    out.model = std::make_unique<NonlinearModalModel<2>>(out.interface, std::move(parts));
    return out;
  }
};

struct TipHistory {
  std::vector<double> time, ux, uy;
  double mean_iterations = 0.0;  ///< PPE solves a step
  double energy_error = 0.0;     ///< |numerical dissipation| / work at the end
  double seconds = 0.0;          ///< wall-clock time of the run [s]
};

/// The tip's displacement over `end` seconds, the body on `model` (its interface `interface`).
inline TipHistory run_in_water(const PlateStructure& plate,
                               std::shared_ptr<const ModalSurface<2>> interface,
                               std::unique_ptr<StructureModel<2>> model, double end,
                               double dt_max = 2e-4) {
  const auto begin = std::chrono::steady_clock::now();
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
  fo.gravity = ldd::Vec<2>(0, -9.81);
  const auto x = ldd::seed_box<2>({ldd::Vec<2>::Zero(), ldd::Vec<2>(kLeft, kDepth)}, kDx, walls);
  ldd::FlowSolver<2> flow(std::move(walls), x, std::span<const ldd::Vec<2>>{}, fo);
  CouplingOptions co;
  co.scheme = CouplingScheme::strong;
  std::vector<FlexibleBody<2>> bodies;
  bodies.emplace_back("plate", interface, std::move(model), 1, co, flow.walls()[1]);
  const ldd::Vec<2> top(kLeft + kThick / 2, kHeight);
  Eigen::Index tip = 0;
  for (std::size_t v = 0; v < interface->x0.size(); ++v)
    if ((interface->x0[v] - top).norm() < (interface->x0[tip] - top).norm())
      tip = static_cast<Eigen::Index>(v);
  bodies.front().start(flow);
  TipHistory h;
  std::vector<CouplingMonitor> monitors;
  // One fixed step for every model (the stable step depends on the body's speed).
  const double dt = std::min(0.5 * flow.stable_dt(0.0).first, dt_max);
  while (flow.time() < end - 0.5 * dt) {
    coupled_step<2>(flow, bodies, dt, monitors);
    h.time.push_back(flow.time());
    h.ux.push_back(bodies.front().displacement(tip).x());
    h.uy.push_back(bodies.front().displacement(tip).y());
    h.mean_iterations += monitors.front().iterations;
  }
  h.mean_iterations /= static_cast<double>(h.time.size());
  const StructureEnergy e = bodies.front().model().energy();
  h.energy_error = std::abs(e.numerical_dissipation) / std::max(std::abs(e.external_work), 1e-300);
  h.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return h;
}

/// The linear modes' run.
inline TipHistory run_linear(const PlateStructure& plate, double end) {
  auto interface = plate.interface();
  return run_in_water(plate, interface, std::make_unique<LinearModalModel<2>>(interface), end);
}

/// The FE body's run.
inline TipHistory run_fe(const PlateStructure& plate, double end) {
  auto interface = plate.interface();
  return run_in_water(plate, interface, plate.nonlinear(interface), end);
}

/// max_k |a_k − b_k| of two histories of equal steps.
inline double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double largest = 0.0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k)
    largest = std::max(largest, std::abs(a[k] - b[k]));
  return largest;
}

/// max_k |a_k|.
inline double largest(const std::vector<double>& a) {
  double out = 0.0;
  for (double x : a) out = std::max(out, std::abs(x));
  return out;
}

}  // namespace hm::coupling::test
