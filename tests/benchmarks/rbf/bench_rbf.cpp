// RBF mapping at production size: 20 000 structure surface nodes → 200 000 fluid wall vertices on
// a sphere of radius 0.5 m, 20 fields (modes). Measures the build of H (neighbour search, sparse
// Cholesky of the Wendland matrix, target kernel matrix) and one application to 20 fields, plus
// the transpose (forces). Run from a release build:
//   build/<release>/tests/benchmarks/rbf/bench_rbf --benchmark_min_time=1
#include <memory>

#include <benchmark/benchmark.h>

#include "point_sets.hpp"
#include "rbf/interpolator.hpp"

namespace {

using hm::rbf::Points;
using hm::rbf::RbfInterpolator;

constexpr Eigen::Index kSources = 20000, kTargets = 200000, kFields = 20;

const Points& sources() {
  static const Points p = hm::rbf::test::fibonacci_sphere(kSources, 0.5);
  return p;
}
const Points& targets() {
  static const Points p = hm::rbf::test::fibonacci_sphere(kTargets, 0.5 * (1 + 1e-4), 0.37);
  return p;
}

void BM_RbfBuild(benchmark::State& state) {
  for (auto _ : state) {
    RbfInterpolator H(sources(), targets());
    benchmark::DoNotOptimize(H.support_radius());
  }
}
BENCHMARK(BM_RbfBuild)->Unit(benchmark::kMillisecond)->Iterations(2);

void BM_RbfApply20Fields(benchmark::State& state) {
  static const RbfInterpolator H(sources(), targets());
  const Eigen::MatrixXd modes = Eigen::MatrixXd::Random(kSources, kFields);
  for (auto _ : state) benchmark::DoNotOptimize(H.apply(modes).data());
}
BENCHMARK(BM_RbfApply20Fields)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_RbfTranspose20Fields(benchmark::State& state) {
  static const RbfInterpolator H(sources(), targets());
  const Eigen::MatrixXd forces = Eigen::MatrixXd::Random(kTargets, kFields);
  for (auto _ : state) benchmark::DoNotOptimize(H.apply_transpose(forces).data());
}
BENCHMARK(BM_RbfTranspose20Fields)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
