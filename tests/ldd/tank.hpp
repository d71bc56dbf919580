#pragma once
// A water column at rest in a box tank whose walls are a surface mesh (lib/mesh wall mesher):
// fluid lattice dx/2 from the walls, wall nodes on the walls (CHOICE-B), one PPE solve.
// Shared by the tests and the benchmark.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <vector>

#include "ldd/free_surface.hpp"
#include "ldd/ppe.hpp"
#include "ldd/seeding.hpp"
#include "ldd/walls.hpp"
#include "mesh/wall_mesher.hpp"

namespace hm::ldd::test {

template <int D>
WallMesh<D> box_tank(const Vec<D>& size, double element, std::vector<std::string> faces = {}) {
  mesh::WallOptions o;
  o.dim = D;
  o.size = element;
  o.faces = std::move(faces);
  if constexpr (D == 2) {
    return WallMesh<2>(mesh::mesh_rectangle_walls({Eigen::Vector2d::Zero(), size}, o), "tank");
  } else {
    return WallMesh<3>(mesh::mesh_box_walls({Eigen::Vector3d::Zero(), size}, o), "tank");
  }
}

/// Seconds spent in each phase of one PPE set-up and solve.
struct PhaseTimes {
  double neighbours = 0, operators = 0, free_surface = 0, assembly = 0, solve = 0;
};

template <int D>
struct Column {
  std::vector<WallMesh<D>> walls;
  PointSet<D> points;
  Neighbours nb;
  Operators<D> ops;
  PoissonSystem system;
  SolveReport report;
  FreeSurfaceReport surface;
  PhaseTimes times;
  double dx = 0, h = 0, n0 = 0;
};

/// Water of depth `depth` (last axis up) in the tank `tank` whose inside spans [0, size], gravity
/// −9.81 along the last axis. `beyond`: deactivate the wall nodes beyond the fluid (above the
/// surface) rather than make them Dirichlet p = 0.
template <int D>
Column<D> water_column_in(WallMesh<D> tank, const Vec<D>& size, double depth, double dx,
                          Preconditioner pre = Preconditioner::automatic, double jitter = 0.0,
                          bool beyond = true) {
  Column<D> c;
  c.dx = dx;
  c.h = 2.5 * dx;
  c.walls.push_back(std::move(tank));
  Box<D> fluid{Vec<D>::Zero(), size};
  fluid.upper[D - 1] = depth;
  auto x = seed_box<D>(fluid, dx, c.walls);
  if (jitter > 0.0) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-jitter * dx, jitter * dx);
    for (auto& p : x)
      for (int a = 0; a < D; ++a) p[a] += u(rng);
  }
  for (const auto& p : x) c.points.add_fluid(p);
  add_wall_nodes<D>(c.points, c.walls[0], 0, dx);
  sort_spatially<D>(c.points, c.h);
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  auto lap = [&](double& into) {
    const auto t = clock::now();
    into = std::chrono::duration<double>(t - t0).count();
    t0 = t;
  };
  c.nb = find_neighbours<D>(c.points.position, c.h);
  deactivate_dry_wall_nodes<D>(c.points, c.nb);
  c.n0 = lattice_number_density<D>(dx, c.h);
  FreeSurfaceOptions fs;
  fs.reference_density = c.n0;
  if (beyond) deactivate_wall_nodes_beyond_fluid<D>(c.points, c.nb, fs);
  lap(c.times.neighbours);
  c.ops = compute_operators<D>(c.points.position, c.nb);
  lap(c.times.operators);
  c.surface = detect_free_surface<D>(c.points, c.nb, c.ops, fs);
  lap(c.times.free_surface);
  PpeOptions<D> po;
  po.gravity = Vec<D>::Zero();
  po.gravity[D - 1] = -9.81;
  po.dt = 1e-3;
  po.dx = dx;
  po.reference_density = c.n0;
  // At rest: u* = Δt g for fluid points and for wall nodes (U = 0, A^w = 0).
  std::vector<Vec<D>> predicted(c.points.position.size(), po.dt * po.gravity);
  const auto data = ppe_data<D>(c.points, c.nb, c.ops, predicted, {}, po);
  c.system = assemble_poisson<D>(c.points, c.nb, c.ops, data, dx);
  lap(c.times.assembly);
  SolverOptions so;
  so.preconditioner = pre;
  c.report = solve_poisson(c.system, c.points.pressure, so);
  lap(c.times.solve);
  return c;
}

/// Water of depth `depth` (last axis up) in a box tank `size` meshed by lib/mesh.
template <int D>
Column<D> water_column(const Vec<D>& size, double depth, double dx, double wall_element,
                       Preconditioner pre = Preconditioner::automatic, double jitter = 0.0,
                       bool beyond = true) {
  return water_column_in<D>(box_tank<D>(size, wall_element), size, depth, dx, pre, jitter, beyond);
}

/// Max |p − ρg(H − z)| / (ρgH) over fluid points below the top layer, H = height of the top layer.
template <int D>
double hydrostatic_error(const Column<D>& c, double* top_out = nullptr) {
  double top = -1e300;
  for (Index i = 0; i < c.points.size(); ++i)
    if (c.points.kind[i] == PointKind::fluid) top = std::max(top, c.points.position[i][D - 1]);
  const double rho_g = 1000.0 * 9.81;
  double err = 0.0;
  for (Index i = 0; i < c.points.size(); ++i) {
    if (c.points.kind[i] != PointKind::fluid) continue;
    const double z = c.points.position[i][D - 1];
    if (z > top - 0.5 * c.dx) continue;
    err = std::max(err, std::abs(c.points.pressure[i] - rho_g * (top - z)) / (rho_g * top));
  }
  if (top_out) *top_out = top;
  return err;
}

}  // namespace hm::ldd::test
