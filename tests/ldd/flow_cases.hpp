#pragma once
// Flow set-ups shared by the flow tests and benchmarks: a water column in a box tank (at rest or
// as a dam break), 2-D and 3-D, with walls meshed by lib/mesh.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "ldd/flow.hpp"
#include "ldd/probes.hpp"
#include "ldd/seeding.hpp"
#include "tank.hpp"

namespace hm::ldd::test {

/// Water occupying `fluid` in a box tank of inside [0, size] (faces: all but the top), gravity
/// −9.81 along the last axis. `jitter`: uniform random displacement of the lattice, × dx.
template <int D>
FlowSolver<D> water_in_tank(const Vec<D>& size, const Box<D>& fluid, double dx,
                            FlowOptions<D> options = {}, double jitter = 0.0,
                            double wall_element = 0.0) {
  std::vector<std::string> faces =
      D == 2 ? std::vector<std::string>{"xmin", "xmax", "ymin"}
             : std::vector<std::string>{"xmin", "xmax", "ymin", "ymax", "zmin"};
  std::vector<WallMesh<D>> walls;
  walls.push_back(box_tank<D>(size, wall_element > 0 ? wall_element : 4 * dx, faces));
  auto x = seed_box<D>(fluid, dx, walls);
  if (jitter > 0.0) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-jitter * dx, jitter * dx);
    for (auto& p : x)
      for (int a = 0; a < D; ++a) p[a] += u(rng);
  }
  options.dx = dx;
  options.gravity = Vec<D>::Zero();
  options.gravity[D - 1] = -9.81;
  return FlowSolver<D>(std::move(walls), x, {}, options);
}

/// Runs to `end` [s] with the solver's own stable time step; returns the number of steps.
template <int D>
long run_until(FlowSolver<D>& flow, double end, double* max_drift = nullptr) {
  long steps = 0;
  while (flow.time() < end - 1e-12) {
    const double dt = bounded_step(flow.stable_dt(0.0).first, end - flow.time());
    const auto m = flow.step(dt);
    if (max_drift) *max_drift = std::max(*max_drift, std::abs(m.volume_drift));
    ++steps;
  }
  return steps;
}

/// Free-surface height from elevation gauges (probe_elevation) on a grid of spacing 2dx over
/// the tank's inside [0, size] (horizontal axes), 2dx away from the walls: mean and spread
/// (max − min) [m].
template <int D>
std::pair<double, double> surface_height(const PointSet<D>& p, double dx, const Vec<D>& size) {
  std::vector<double> eta;
  Vec<D> x = Vec<D>::Zero();
  const double step = 2 * dx;
  const int nx = static_cast<int>((size[0] - 2 * step) / step) + 1;
  const int ny = D == 3 ? static_cast<int>((size[1] - 2 * step) / step) + 1 : 1;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      x[0] = step + i * step;
      if constexpr (D == 3) x[1] = step + j * step;
      eta.push_back(probe_elevation<D>(p, x, dx));
    }
  double sum = 0;
  for (double e : eta) sum += e;
  const auto [lo, hi] = std::minmax_element(eta.begin(), eta.end());
  return {sum / static_cast<double>(eta.size()), *hi - *lo};
}

}  // namespace hm::ldd::test

namespace hm::ldd::test {

/// Koshizuka & Oka (1996) dam break: a water column L × 2L (L = 0.146 m) at the left wall of a
/// tank 4L long (4L high), dry floor, at resolution dx = L / resolution.
struct KoshizukaOka {
  static constexpr double L = 0.146;  ///< column width [m]
  static FlowSolver<2> flow(int resolution, FlowOptions<2> options = {}) {
    const double dx = L / resolution;
    const Box<2> fluid{Vec<2>::Zero(), Vec<2>(L, 2 * L)};
    return water_in_tank<2>(Vec<2>(4 * L, 4 * L), fluid, dx, options);
  }
  /// T = t√(2g/L)
  static double time_scale() { return std::sqrt(2 * 9.81 / L); }
};

/// Reads a two-column numeric CSV with one header line (reference data).
inline std::vector<std::pair<double, double>> read_xy_csv(const std::string& path) {
  std::vector<std::pair<double, double>> xy;
  std::FILE* f = std::fopen(path.c_str(), "r");
  if (!f) return xy;
  char line[512];
  bool header = true;
  while (std::fgets(line, sizeof line, f)) {
    if (header) {
      header = false;
      continue;
    }
    double a = 0, b = 0;
    if (std::sscanf(line, "%lf,%lf", &a, &b) == 2) xy.emplace_back(a, b);
  }
  std::fclose(f);
  return xy;
}

/// Linear interpolation in a table sorted by x (clamped at the ends).
inline double interpolate(const std::vector<std::pair<double, double>>& xy, double x) {
  if (x <= xy.front().first) return xy.front().second;
  for (std::size_t k = 1; k < xy.size(); ++k)
    if (x <= xy[k].first) {
      const double s = (x - xy[k - 1].first) / (xy[k].first - xy[k - 1].first);
      return xy[k - 1].second + s * (xy[k].second - xy[k - 1].second);
    }
  return xy.back().second;
}

}  // namespace hm::ldd::test
