// Cost of the two-way coupling (coupling/flexible_body.hpp) on a light body: a piston wall on a
// spring closing a 2-D water layer 0.2 m × 0.1 m (m_a/m_s = 10, wet frequency 10 Hz; the case of
// tests/coupling/test_flexible_body.cpp), dx = H/80 (about 12 800 points). Reported per step:
// the coupling's own share of the wall time (loads, modal forces, CFPI, wall updates; with and
// without the added-mass solves), the pressure solves of the strong scheme's sub-iterations,
// and the step's cost against the same flow with the piston held fixed (one solve a step).
#include <benchmark/benchmark.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "coupling/flexible_body.hpp"
#include "ldd/seeding.hpp"
#include "mesh/wall_mesher.hpp"

namespace hm::coupling {
namespace {

using ldd::Vec;
constexpr double H = 0.1, L = 0.2;

struct Piston {
  std::unique_ptr<ldd::FlowSolver<2>> flow;
  std::vector<FlexibleBody<2>> bodies;
};

Piston piston(double dx) {
  mesh::WallOptions o;
  o.dim = 2;
  o.size = 4 * dx;
  o.faces = {"xmin", "ymin"};
  const auto tank =
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
  walls.back().set_releases_tension(false);
  const double added = 0.5428 * 1000 * H * H, mass = added / 10;  // m_a of a long layer [kg/m]
  ModalSurface<2> modes;
  for (int k = 0; k <= segments; ++k) modes.x0.push_back(wall.vertices.row(k).transpose());
  modes.shapes = Eigen::MatrixXd::Zero(2 * (segments + 1), 1);
  for (int k = 0; k <= segments; ++k) modes.shapes(2 * k, 0) = 1 / std::sqrt(mass);
  modes.omega = Eigen::VectorXd::Constant(1, 2 * std::numbers::pi * 10 * std::sqrt(11.0));
  modes.zeta = Eigen::VectorXd::Zero(1);
  ldd::FlowOptions<2> fo;
  fo.dx = dx;
  fo.gravity = Vec<2>(0, -9.81);
  const auto x = ldd::seed_box<2>({Vec<2>::Zero(), Vec<2>(L, H)}, dx, walls);
  Piston p;
  p.flow = std::make_unique<ldd::FlowSolver<2>>(std::move(walls), x, std::span<const Vec<2>>{}, fo);
  p.bodies.emplace_back("piston", std::move(modes), 1, CouplingOptions{}, p.flow->walls()[1]);
  return p;
}

void BM_StrongCoupling(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  Piston p = piston(H / 80);
  p.bodies[0].start(*p.flow);
  std::vector<CouplingMonitor> monitors;
  const auto step = [&] {
    const double dt = p.flow->stable_dt(p.bodies[0].max_speed()).first;
    return coupled_step<2>(*p.flow, p.bodies, dt, monitors);
  };
  for (int s = 0; s < 20; ++s) step();  // the piston under way
  double coupling = 0, added = 0, solves = 0, wall = 0, fixed = 0;
  long steps = 0;
  for (auto _ : state) {
    for (int s = 0; s < 40; ++s) {
      const auto t0 = std::chrono::steady_clock::now();
      step();
      wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      coupling += monitors[0].seconds;
      added += monitors[0].added_mass_seconds;
      solves += monitors[0].iterations;
      ++steps;
    }
  }
  // The same flow with the piston held where it is: one pressure solve a step.
  for (int s = 0; s < 40; ++s) {
    const double dt = p.flow->stable_dt(0.0).first;
    const auto t0 = std::chrono::steady_clock::now();
    p.flow->step(dt);
    fixed += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  state.counters["points"] = static_cast<double>(p.flow->points().size());
  state.counters["coupling_share"] = (coupling - added) / wall;
  state.counters["with_added_mass_share"] = coupling / wall;
  state.counters["solves_per_step"] = solves / static_cast<double>(steps);
  state.counters["step_vs_fixed_wall"] = (wall / static_cast<double>(steps)) / (fixed / 40.0);
}

BENCHMARK(BM_StrongCoupling)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace
}  // namespace hm::coupling
