#include "ldd/volume.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

namespace hm::ldd {

template <int D>
double bulk_kernel_density(double dx, double h) {
  // ∫_0^1 W(q) q^{D−1} dq for W = (1 − q)⁴(1 + 4q): 1/14 (D = 2), 1/42 (D = 3); times the
  // measure of the unit sphere, 2π or 4π.
  const double radial = D == 2 ? 1.0 / 14.0 : 1.0 / 42.0;
  const double sphere = D == 2 ? 2.0 * std::numbers::pi : 4.0 * std::numbers::pi;
  return sphere * radial * std::pow(h / dx, D);
}

namespace {

/// The lowest and highest coordinates of `fluid` (not empty).
template <int D>
std::pair<Vec<D>, Vec<D>> bounds(std::span<const Vec<D>> fluid) {
  Vec<D> lower = fluid[0], upper = fluid[0];
  for (const auto& x : fluid) {
    lower = lower.cwiseMin(x);
    upper = upper.cwiseMax(x);
  }
  return {lower, upper};
}

/// The nodes of the grid of spacing dx/2 from `lower` to `upper` where the kernel density of
/// `fluid` reaches half its bulk value (and `counted`, when given, holds).
template <int D>
long nodes_inside(std::span<const Vec<D>> fluid, double dx, double h, const Vec<D>& lower,
                  const Vec<D>& upper, const std::function<bool(const Vec<D>&)>* counted) {
  using Cell = Eigen::Matrix<long, D, 1>;
  // Points binned in cells of size h (counting sort on the linear cell index).
  Cell cells;
  for (int a = 0; a < D; ++a)
    cells[a] = std::max(1L, static_cast<long>(std::ceil((upper[a] - lower[a]) / h)));
  auto linear = [&](const Cell& c) {
    long k = 0;
    for (int a = D - 1; a >= 0; --a) k = k * cells[a] + c[a];
    return k;
  };
  auto cell_of = [&](const Vec<D>& x) {
    Cell c;
    for (int a = 0; a < D; ++a)
      c[a] = std::clamp(static_cast<long>((x[a] - lower[a]) / h), 0L, cells[a] - 1);
    return c;
  };
  const long total_cells = cells.prod();
  std::vector<long> start(static_cast<std::size_t>(total_cells) + 1, 0);
  for (const auto& x : fluid) ++start[linear(cell_of(x)) + 1];
  for (long k = 0; k < total_cells; ++k) start[k + 1] += start[k];
  std::vector<Vec<D>> sorted(fluid.size());
  {
    std::vector<long> fill(start.begin(), start.end() - 1);
    for (const auto& x : fluid) sorted[fill[linear(cell_of(x))]++] = x;
  }
  // Grid nodes at spacing dx/2; each cell of size h is scanned only if a point lies within one
  // cell of it.
  const double s = 0.5 * dx, threshold = 0.5 * bulk_kernel_density<D>(dx, h);
  long inside = 0;
  // `counted` (a process's region: Zoltan's point assignment) is not known to be thread-safe.
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : inside) if (counted == nullptr)
  for (long k = 0; k < total_cells; ++k) {
    Cell c;
    long rest = k;
    for (int a = 0; a < D; ++a) {
      c[a] = rest % cells[a];
      rest /= cells[a];
    }
    // The points of the 3^D cells around c, those of c first (a node's density mostly comes
    // from its own cell, and the sum below stops once it reaches the threshold).
    thread_local std::vector<const Vec<D>*> near;
    near.clear();
    const long own = linear(c);
    for (long j = start[own]; j < start[own + 1]; ++j) near.push_back(&sorted[j]);
    Cell o = Cell::Constant(-1);
    while (true) {
      Cell q = c + o;
      bool valid = !o.isZero();
      for (int a = 0; a < D; ++a) valid = valid && q[a] >= 0 && q[a] < cells[a];
      if (valid) {
        const long l = linear(q);
        for (long j = start[l]; j < start[l + 1]; ++j) near.push_back(&sorted[j]);
      }
      int a = 0;
      while (a < D && ++o[a] > 1) o[a++] = -1;
      if (a == D) break;
    }
    if (near.empty()) continue;
    // The grid nodes whose centre lies in cell c: node index m covers [lower + m s, + s).
    Eigen::Matrix<long, D, 1> first, last;
    for (int a = 0; a < D; ++a) {
      first[a] = static_cast<long>(std::ceil(c[a] * h / s - 0.5));
      last[a] = std::min(static_cast<long>(std::ceil((c[a] + 1) * h / s - 0.5)),
                         static_cast<long>(std::ceil((upper[a] - lower[a]) / s)));
    }
    Eigen::Matrix<long, D, 1> m = first;
    while (true) {
      bool empty = false;
      for (int a = 0; a < D; ++a) empty = empty || m[a] >= last[a];
      if (!empty) {
        Vec<D> x;
        for (int a = 0; a < D; ++a) x[a] = lower[a] + (m[a] + 0.5) * s;
        double density = 0.0;
        for (const Vec<D>* p : near) {
          const double r2 = (*p - x).squaredNorm();
          if (r2 >= h * h) continue;
          density += wendland_c2(std::sqrt(r2) / h);
          if (density >= threshold) break;
        }
        inside += density >= threshold && (counted == nullptr || (*counted)(x));
      }
      int a = 0;
      while (a < D && ++m[a] >= last[a]) m[a] = first[a], ++a;
      if (a == D) break;
    }
  }
  return inside;
}

}  // namespace

template <int D>
double fluid_volume(std::span<const Vec<D>> fluid, double dx, double h) {
  if (fluid.empty()) return 0.0;
  auto [lower, upper] = bounds(fluid);
  lower.array() -= h;
  upper.array() += h;
  const double inside = static_cast<double>(nodes_inside<D>(fluid, dx, h, lower, upper, nullptr));
  return inside * std::pow(0.5 * dx, D);
}

template <int D>
double fluid_volume_share(std::span<const Vec<D>> fluid, double dx, double h, const Vec<D>& origin,
                          const std::function<bool(const Vec<D>&)>& counted) {
  if (fluid.empty()) return 0.0;
  auto [lower, upper] = bounds(fluid);
  const double s = 0.5 * dx;
  for (int a = 0; a < D; ++a)  // on the grid from `origin`
    lower[a] = origin[a] + std::floor((lower[a] - h - origin[a]) / s) * s;
  upper.array() += h;
  const double inside = static_cast<double>(nodes_inside<D>(fluid, dx, h, lower, upper, &counted));
  return inside * std::pow(s, D);
}

template double fluid_volume<2>(std::span<const Vec<2>>, double, double);
template double fluid_volume<3>(std::span<const Vec<3>>, double, double);
template double fluid_volume_share<2>(std::span<const Vec<2>>, double, double, const Vec<2>&,
                                      const std::function<bool(const Vec<2>&)>&);
template double fluid_volume_share<3>(std::span<const Vec<3>>, double, double, const Vec<3>&,
                                      const std::function<bool(const Vec<3>&)>&);
template double bulk_kernel_density<2>(double, double);
template double bulk_kernel_density<3>(double, double);

}  // namespace hm::ldd
