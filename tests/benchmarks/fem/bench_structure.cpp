// The nonlinear structure models on the 3-D baffle of pipelines/sloshing_baffle: the full
// total-Lagrangian tet10 body against the reduced (modal) model of its lowest modes and their
// modal derivatives, at a stated accuracy against the full one. Measured, never asserted. Run
// from a release build:
//   build/release/tests/benchmarks/fem/bench_structure --benchmark_counters_tabular=true
// Model: the baffle, 5 mm (x) × 120 mm (y) × 150 mm (z), E = 38.4 MPa, ν = 0.3, ρ = 4096 kg/m³,
// Saint Venant–Kirchhoff, clamped at its foot (zmin); a structured tet10 mesh of nx × ny × nz
// cells (6 tets each): 1 × 24 × 30 (5 mm cells, 27 k DOFs) and 2 × 48 × 60 (2.5 mm, the
// pipeline's mesh size, 176 k DOFs). Load: a sideways acceleration of 10 m/s² along x switched
// on at t = 0 (the tank's sway as a step), which swings the top by about 0.45 of the height
// (a large rotation); the energy-conserving scheme (the coupled runs' default), Δt = 5 ms.
// Counters: dofs, basis size r, seconds a step, Newton iterations a step, the basis and tensor
// set-up [s] and the top's displacement error against the full model after `steps` steps.
// BM_TangentLu: one numeric factorisation of the energy-conserving Newton matrix (unsymmetric)
// by Eigen's SparseLU (COLAMD) and by UMFPACK, and of the symmetric one by CHOLMOD, on the 2-D
// gate strip (tri6, 2 × 32 cells, 664 DOFs) and the two baffles: the rule of fem::TangentSolver.
#include <benchmark/benchmark.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseLU>
#include <Eigen/UmfPackSupport>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fem/dof_map.hpp"
#include "fem/hyperelastic_body.hpp"
#include "fem/nonlinear_dynamics.hpp"
#include "fem/reduced_basis.hpp"
#include "fem/reduced_dynamics.hpp"
#include "fem/reduced_stvk.hpp"
#include "mesh/structured.hpp"

namespace {

using namespace hm;

constexpr double kThickness = 0.005, kWidth = 0.12, kHeight = 0.15;  // m
constexpr double kDt = 0.005;                                        // s
const Eigen::Vector3d kSway(10.0, 0.0, 0.0);                         // m/s²

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Baffle {
  mesh::StructureMesh mesh;
  fem::HyperelasticBody body;
  fem::DofMap dofs;
  Eigen::VectorXd load;  ///< the sway's body force [N]
  Eigen::Index top = 0;  ///< the node at the middle of the top edge

  Baffle(int nx, int ny, int nz)
      : mesh(mesh::structured_box(kThickness, kWidth, kHeight, nx, ny, nz)),
        body(mesh,
             {{{38.4e6, 0.3, 4096.0}, fem::PlaneAssumption::plane_strain, 1.0},
              fem::MaterialLaw::saint_venant_kirchhoff},
             "bench"),
        dofs(fem::DofMap::clamp_groups(mesh, std::vector<std::string>{"zmin"}, "bench")),
        load(body.body_force(kSway)) {
    const Eigen::RowVector3d point(0.0, 0.5 * kWidth, kHeight);
    (mesh.nodes.rowwise() - point).rowwise().squaredNorm().minCoeff(&top);
  }
};

const Baffle& baffle(int nx, int ny, int nz) {
  static std::map<std::array<int, 3>, std::unique_ptr<Baffle>> cache;
  auto& b = cache[{nx, ny, nz}];
  if (!b) b = std::make_unique<Baffle>(nx, ny, nz);
  return *b;
}

fem::DynamicsOptions options() {
  fem::DynamicsOptions o;
  o.scheme = fem::TimeScheme::energy_conserving;
  return o;
}

/// The top's displacement along x after `steps` steps of the full model (memoised per mesh).
double full_top_displacement(const Baffle& b, int steps, double* step_seconds = nullptr,
                             double* iterations = nullptr) {
  static std::map<std::pair<const Baffle*, int>, std::array<double, 3>> cache;
  auto [it, inserted] = cache.try_emplace({&b, steps});
  if (inserted) {
    fem::NonlinearDynamics full(b.body, b.dofs, options());
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(b.body.dof_count());
    full.start(0.0, zero, zero, b.load);
    int newton = 0;
    const auto begin = std::chrono::steady_clock::now();
    for (int n = 0; n < steps; ++n) {
      const fem::NewtonReport& r = full.solve_step(kDt, b.load);
      if (!r.converged) throw std::runtime_error("full model: " + r.failure);
      newton += r.iterations;
      full.commit();
    }
    it->second = {full.state().u[3 * b.top], seconds_since(begin) / steps,
                  static_cast<double>(newton) / steps};
  }
  if (step_seconds != nullptr) *step_seconds = it->second[1];
  if (iterations != nullptr) *iterations = it->second[2];
  return it->second[0];
}

/// args: nx, ny, nz, steps.
void BM_FullModel(benchmark::State& state) {
  const Baffle& b = baffle(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                           static_cast<int>(state.range(2)));
  const int steps = static_cast<int>(state.range(3));
  for (auto _ : state) {
    double step = 0.0, iterations = 0.0;
    const double top = full_top_displacement(b, steps, &step, &iterations);
    state.counters["dofs"] = static_cast<double>(b.dofs.free_count());
    state.counters["step_s"] = step;
    state.counters["newton_per_step"] = iterations;
    state.counters["top_ux_mm"] = 1e3 * top;
    state.counters["top_over_height"] = top / kHeight;
  }
}

/// args: nx, ny, nz, steps, linear modes (with the derivatives of all of them).
void BM_ReducedModel(benchmark::State& state) {
  const Baffle& b = baffle(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                           static_cast<int>(state.range(2)));
  const int steps = static_cast<int>(state.range(3));
  const int modes = static_cast<int>(state.range(4));
  for (auto _ : state) {
    auto begin = std::chrono::steady_clock::now();
    const fem::ReducedBasis basis =
        fem::build_reduced_basis(b.body, b.dofs, {modes, true, -1, 1e-6}, "bench");
    const double basis_seconds = seconds_since(begin);
    const fem::ReducedStvk model(b.body, basis.vectors, "bench");
    fem::ReducedDynamics reduced(model, options());
    const Eigen::VectorXd load = model.project(b.load);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.size());
    reduced.start(0.0, zero, zero, load);
    int newton = 0;
    begin = std::chrono::steady_clock::now();
    for (int n = 0; n < steps; ++n) {
      const fem::NewtonReport& r = reduced.solve_step(kDt, load);
      if (!r.converged) throw std::runtime_error("reduced model: " + r.failure);
      newton += r.iterations;
      reduced.commit();
    }
    const double step = seconds_since(begin) / steps;
    const double top = model.displacement(reduced.state().q)[3 * b.top];
    double full_step = 0.0;
    const double full = full_top_displacement(b, steps, &full_step);
    state.counters["dofs"] = static_cast<double>(b.dofs.free_count());
    state.counters["r"] = static_cast<double>(model.size());
    state.counters["basis_s"] = basis_seconds;
    state.counters["tensors_s"] = model.setup_seconds();
    state.counters["step_s"] = step;
    state.counters["newton_per_step"] = static_cast<double>(newton) / steps;
    state.counters["speedup"] = full_step / step;
    state.counters["top_error"] = std::abs(top / full - 1.0);
  }
}

/// The Newton matrix of an energy-conserving step of Δt = 5 ms from rest at u₀ = 0 to u (the
/// linear static response to the sway), free DOFs; symmetric: the generalised-α one instead.
Eigen::SparseMatrix<double> newton_matrix(const fem::HyperelasticBody& body,
                                          const fem::DofMap& dofs, const Eigen::VectorXd& load,
                                          bool symmetric) {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> k0(
      dofs.reduce(body.linear_stiffness()));
  const Eigen::VectorXd u = dofs.full_values(k0.solve(dofs.free_values(load)));
  const Eigen::VectorXd u0 = Eigen::VectorXd::Zero(u.size());
  fem::EvaluationRequest request;
  request.tangent = true;
  request.mass_weight = 2.0 / (kDt * kDt);
  if (!symmetric) request.start = &u0;
  return dofs.reduce(body.evaluate(u, request).tangent);
}

/// args: 2 (the gate strip) or 3 (a baffle: nx, ny, nz), solver 0 SparseLU, 1 UMFPACK,
/// 2 CHOLMOD (symmetric matrix).
void BM_TangentLu(benchmark::State& state) {
  const int solver = static_cast<int>(state.range(4));
  std::unique_ptr<fem::HyperelasticBody> strip;
  std::unique_ptr<fem::DofMap> strip_dofs;
  const fem::HyperelasticBody* body = nullptr;
  const fem::DofMap* dofs = nullptr;
  Eigen::VectorXd load;
  if (state.range(0) == 2) {
    const mesh::StructureMesh m = mesh::structured_rectangle(0.005, 0.079, 2, 32);
    strip = std::make_unique<fem::HyperelasticBody>(
        m,
        fem::HyperelasticModel{{{12e6, 0.4, 1100.0}, fem::PlaneAssumption::plane_strain, 1.0},
                               fem::MaterialLaw::saint_venant_kirchhoff},
        "bench");
    strip_dofs = std::make_unique<fem::DofMap>(
        fem::DofMap::clamp_groups(m, std::vector<std::string>{"ymax"}, "bench"));
    body = strip.get();
    dofs = strip_dofs.get();
    load = body->body_force(Eigen::Vector2d(1000.0, 0.0));
  } else {
    const Baffle& b = baffle(static_cast<int>(state.range(1)), static_cast<int>(state.range(2)),
                             static_cast<int>(state.range(3)));
    body = &b.body;
    dofs = &b.dofs;
    load = b.load;
  }
  const Eigen::SparseMatrix<double> a = newton_matrix(*body, *dofs, load, solver == 2);
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(a.rows());
  double analyse = 0.0, factorise = 0.0, residual = 0.0;
  const auto run = [&](auto& lu) {
    auto begin = std::chrono::steady_clock::now();
    lu.analyzePattern(a);
    analyse = seconds_since(begin);
    begin = std::chrono::steady_clock::now();
    lu.factorize(a);
    factorise = seconds_since(begin);
    if (lu.info() != Eigen::Success) throw std::runtime_error("factorisation failed");
    residual = (a * lu.solve(rhs) - rhs).norm() / rhs.norm();
  };
  for (auto _ : state) {
    if (solver == 0) {
      Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
      run(lu);
    } else if (solver == 1) {
      Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu;
      run(lu);
    } else {
      Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
      run(llt);
    }
  }
  state.SetLabel(solver == 0 ? "SparseLU" : solver == 1 ? "UMFPACK" : "CHOLMOD (symmetric)");
  state.counters["dofs"] = static_cast<double>(a.rows());
  state.counters["analyse_s"] = analyse;
  state.counters["factorise_s"] = factorise;
  state.counters["residual"] = residual;
}

BENCHMARK(BM_TangentLu)
    ->ArgsProduct({{2}, {0}, {0}, {0}, {0, 1, 2}})
    ->ArgsProduct({{3}, {1}, {24}, {30}, {0, 1, 2}})
    ->ArgsProduct({{3}, {2}, {48}, {60}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();

// The coarse baffle over 30 steps (0.15 s, half the dry first period): the accuracy of the
// reduced model as its basis grows. The pipeline's mesh over 4 steps: the cost of a step.
BENCHMARK(BM_FullModel)
    ->Args({1, 24, 30, 30})
    ->Args({2, 48, 60, 4})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK(BM_ReducedModel)
    ->Args({1, 24, 30, 30, 1})
    ->Args({1, 24, 30, 30, 2})
    ->Args({1, 24, 30, 30, 3})
    ->Args({1, 24, 30, 30, 5})
    ->Args({2, 48, 60, 4, 5})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace
