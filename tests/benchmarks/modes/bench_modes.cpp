// The 10 lowest modes of a clamped tet10 box with ≥ 100 000 DOFs: wall time of assembly,
// factorisation of K − σM (LDLᵀ and CHOLMOD supernodal LLᵀ), and shift-invert Lanczos with
// ARPACK and Spectra on the same operator. Measured, never asserted. Run from a release build:
//   build/<release>/tests/benchmarks/modes/bench_modes --benchmark_counters_tabular=true
// Model: a steel cantilever plate 2.1 × 2.1 × 0.1 m, 42 × 42 × 2 cells of 0.05 m (21 168 tet10),
// 85 × 85 × 5 = 36 125 nodes, 108 375 DOFs, clamped at x = 0 (425 nodes): 107 100 free DOFs.
// A 30 × 30 × 2 plate (55 815 DOFs) shows the scaling. The shift is the default one (σ < 0).
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <string>

#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"
#include "mesh/structured.hpp"
#include "modal/eigen_backends.hpp"
#include "modal/eigen_operator.hpp"
#include "modal/eigen_solve.hpp"

namespace {

using namespace hm;

struct Model {
  mesh::StructureMesh mesh;
  fem::SystemMatrices system;
  std::unique_ptr<fem::DofMap> dofs;
  modal::SparseMatrix k, m;
};

const fem::ElasticModel kSteel{{2.1e11, 0.3, 7850.0}};

Model build(int nx, int ny, int nz) {
  Model model;
  model.mesh = mesh::structured_box(0.05 * nx, 0.05 * ny, 0.05 * nz, nx, ny, nz);
  model.system = fem::assemble(model.mesh, kSteel, "bench");
  model.dofs = std::make_unique<fem::DofMap>(
      fem::DofMap::clamp_groups(model.mesh, std::vector<std::string>{"xmin"}, "bench"));
  model.k = model.dofs->reduce(model.system.stiffness);
  model.m = model.dofs->reduce(model.system.mass);
  return model;
}

const Model& model(int nx, int ny, int nz) {
  static std::map<std::array<int, 3>, Model> cache;
  auto [it, inserted] = cache.try_emplace({nx, ny, nz});
  if (inserted) it->second = build(nx, ny, nz);
  return it->second;
}

const modal::SparseShiftInvert& shift_invert(const Model& mdl, modal::Factorisation f) {
  static std::map<std::pair<const Model*, modal::Factorisation>,
                  std::unique_ptr<modal::SparseShiftInvert>>
      cache;
  auto& op = cache[{&mdl, f}];
  if (!op)
    op = std::make_unique<modal::SparseShiftInvert>(mdl.k, mdl.m,
                                                    modal::default_shift(mdl.k, mdl.m), f);
  return *op;
}

void BM_Assemble(benchmark::State& state) {
  const auto mesh =
      mesh::structured_box(0.05 * state.range(0), 0.05 * state.range(1), 0.05 * state.range(2),
                           static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                           static_cast<int>(state.range(2)));
  for (auto _ : state) {
    fem::SystemMatrices s = fem::assemble(mesh, kSteel, "bench");
    benchmark::DoNotOptimize(s.stiffness.nonZeros());
    state.counters["dofs"] = static_cast<double>(s.dof_count());
    state.counters["nnz"] = static_cast<double>(s.stiffness.nonZeros());
  }
}

void BM_Factorise(benchmark::State& state) {
  const Model& mdl = model(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                           static_cast<int>(state.range(2)));
  const auto f = static_cast<modal::Factorisation>(state.range(3));
  state.SetLabel(modal::to_string(f));
  for (auto _ : state) {
    modal::SparseShiftInvert op(mdl.k, mdl.m, modal::default_shift(mdl.k, mdl.m), f);
    state.counters["ok"] = op.ok();
    state.counters["seconds"] = op.factorisation_seconds();
    state.counters["free_dofs"] = static_cast<double>(mdl.k.rows());
  }
}

void BM_Lanczos(benchmark::State& state) {
  const Model& mdl = model(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                           static_cast<int>(state.range(2)));
  const bool arpack = state.range(3) == 0;
  const auto f = static_cast<modal::Factorisation>(state.range(4));
  const auto& op = shift_invert(mdl, f);
  state.SetLabel(std::string(arpack ? "arpack" : "spectra") + " on " + modal::to_string(f));
  for (auto _ : state) {
    const modal::EigenPairs p =
        arpack ? modal::arpack_shift_invert(op, 10) : modal::spectra_shift_invert(op, 10);
    state.counters["converged"] = p.converged;
    state.counters["op_applications"] = p.op_applications;
    state.counters["restarts"] = p.iterations;
    state.counters["f1_hz"] = std::sqrt(p.values(0)) / (2 * std::numbers::pi);
    state.counters["f10_hz"] = std::sqrt(p.values(9)) / (2 * std::numbers::pi);
    double residual = 0.0;
    for (int i = 0; i < p.converged; ++i) {
      const Eigen::VectorXd kphi = mdl.k * p.vectors.col(i);
      residual = std::max(residual,
                          (kphi - p.values(i) * (mdl.m * p.vectors.col(i))).norm() / kphi.norm());
    }
    state.counters["max_residual"] = residual;
  }
}

#define MODEL_ARGS ->Args({42, 42, 2})->Args({30, 30, 2})

BENCHMARK(BM_Assemble) MODEL_ARGS->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_Factorise)
    ->ArgsProduct({{42}, {42}, {2}, {1, 2}})
    ->Args({30, 30, 2, 1})
    ->Args({30, 30, 2, 2})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK(BM_Lanczos)
    ->ArgsProduct({{42}, {42}, {2}, {0, 1}, {1, 2}})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace
