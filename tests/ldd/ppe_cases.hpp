#pragma once
// Real PPE systems for the linear-solver tests and benchmarks: the dam break of bench_ppe (a
// column H × 2H, H = 0.3 m, in a tank 4H long; 3-D 0.15 m wide) and the system its own
// projection assembles a few steps after release (FlowSolver::observe_ppe).
#include <cmath>
#include <memory>

#include "flow_cases.hpp"
#include "linsolve/linear_solver.hpp"
#include "tank.hpp"

namespace hm::ldd::test {

/// The dam break at spacing dx [m] with the PPE solver options `ppe`; over the processes of
/// `processes` when given (FlowSolver's constructor).
template <int D>
FlowSolver<D> dam_break(double dx, const SolverOptions& ppe,
                        std::shared_ptr<PointExchange<D>> processes = nullptr) {
  Vec<D> size, column;
  size[0] = 1.2;
  column[0] = 0.6;
  if constexpr (D == 3) {
    size[1] = 0.15;
    column[1] = 0.15;
  }
  size[D - 1] = 0.6;
  column[D - 1] = 0.3;
  const Box<D> fluid{Vec<D>::Zero(), column};
  std::vector<std::string> faces =
      D == 2 ? std::vector<std::string>{"xmin", "xmax", "ymin"}
             : std::vector<std::string>{"xmin", "xmax", "ymin", "ymax", "zmin"};
  std::vector<WallMesh<D>> walls;
  walls.push_back(box_tank<D>(size, 4 * dx, faces));
  FlowOptions<D> o;
  o.dx = dx;
  o.gravity[D - 1] = -9.81;
  o.ppe = ppe;
  auto x = seed_box<D>(fluid, dx, walls);
  return FlowSolver<D>(std::move(walls), x, {}, o, 0.0, std::move(processes));
}

/// The same with the flow's PPE options but for the preconditioner and the reuse policy.
template <int D>
FlowSolver<D> dam_break(double dx, Preconditioner preconditioner,
                        linsolve::ReusePolicy reuse = {}) {
  SolverOptions ppe = FlowOptions<D>{}.ppe;
  ppe.preconditioner = preconditioner;
  ppe.reuse = reuse;
  return dam_break<D>(dx, ppe);
}

/// The spacing that gives the column about `points` fluid points: 0.18 m² / dx² (2-D),
/// 0.027 m³ / dx³ (3-D).
template <int D>
double spacing_for(double points) {
  return D == 2 ? std::sqrt(0.18 / points) : std::cbrt(0.027 / points);
}

/// A PPE system of a real run and the pressure the run warm-started it from.
struct CapturedPpe {
  linsolve::CsrMatrix matrix;  ///< compressed
  Eigen::VectorXd rhs, warm_start;
  Index points = 0;  ///< of the run (fluid points and wall nodes)
};

/// The last PPE system of the dam break at spacing dx after `steps` steps (the run itself on
/// BoomerAMG where PETSc is built in: the fastest way to the state).
template <int D>
CapturedPpe capture_ppe(double dx, int steps = 3) {
  const auto pre = linsolve::is_available(linsolve::Method::boomeramg) ? Preconditioner::boomeramg
                                                                       : Preconditioner::automatic;
  auto flow = dam_break<D>(dx, pre);
  CapturedPpe c;
  flow.observe_ppe([&c](const PoissonSystem& s, std::span<const double> warm, const SolveReport&) {
    c.matrix = s.matrix;
    c.rhs = s.rhs;
    c.warm_start.resize(static_cast<Eigen::Index>(s.point_of.size()));
    for (std::size_t r = 0; r < s.point_of.size(); ++r)
      c.warm_start[static_cast<Eigen::Index>(r)] = warm[static_cast<std::size_t>(s.point_of[r])];
  });
  for (int s = 0; s < steps; ++s) flow.step(flow.stable_dt(0.0).first);
  c.matrix.makeCompressed();
  c.points = flow.points().size();
  return c;
}

}  // namespace hm::ldd::test
