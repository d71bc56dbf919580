#include "ldd/neighbours.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "core/errors.hpp"

namespace hm::ldd {
namespace {

/// Points keyed by their cell (x fastest) and sorted by key: a cell's points are a contiguous
/// run of `order`, found by binary search in `keys`.
template <int D>
struct CellIndex {
  Vec<D> lo;
  double cell = 0.0;
  std::array<std::int64_t, D> dims{};
  std::vector<std::uint64_t> keys;  // sorted
  std::vector<Index> order;         // point of each sorted key

  std::array<std::int64_t, D> cell_of(const Vec<D>& x) const {
    std::array<std::int64_t, D> c{};
    for (int a = 0; a < D; ++a) c[a] = static_cast<std::int64_t>(std::floor((x[a] - lo[a]) / cell));
    return c;
  }
  std::uint64_t key(const std::array<std::int64_t, D>& c) const {
    std::uint64_t k = 0;
    for (int a = D - 1; a >= 0; --a) k = k * static_cast<std::uint64_t>(dims[a]) + c[a];
    return k;
  }
};

template <int D>
CellIndex<D> build_cells(std::span<const Vec<D>> x, double cell) {
  CellIndex<D> g;
  g.cell = cell;
  g.lo = x[0];
  Vec<D> hi = x[0];
  for (const auto& p : x) {
    g.lo = g.lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  for (int a = 0; a < D; ++a) {
    g.dims[a] = static_cast<std::int64_t>(std::floor((hi[a] - g.lo[a]) / cell)) + 1;
    if (g.dims[a] > (std::int64_t{1} << (62 / D)))
      numerical_error(
          "neighbour search: the points span {} m along axis {}, {} cells of h = {} m; "
          "points have left the domain (a run diverged?)",
          hi[a] - g.lo[a], a, g.dims[a], cell);
  }
  const std::size_t n = x.size();
  std::vector<std::uint64_t> k(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) k[i] = g.key(g.cell_of(x[i]));
  g.order.resize(n);
  std::iota(g.order.begin(), g.order.end(), 0);
  std::sort(g.order.begin(), g.order.end(), [&](Index a, Index b) {
    return k[static_cast<std::size_t>(a)] < k[static_cast<std::size_t>(b)] ||
           (k[static_cast<std::size_t>(a)] == k[static_cast<std::size_t>(b)] && a < b);
  });
  g.keys.resize(n);
  for (std::size_t s = 0; s < n; ++s) g.keys[s] = k[static_cast<std::size_t>(g.order[s])];
  return g;
}

/// Calls f(j) for every j ≠ i with 0 < |x_j − x_i| < radius.
template <int D, typename F>
void for_each_within(const CellIndex<D>& g, std::span<const Vec<D>> x, Index i, double radius,
                     F&& f) {
  const Vec<D>& xi = x[static_cast<std::size_t>(i)];
  const auto c = g.cell_of(xi);
  const double r2 = radius * radius;
  const std::int64_t x0 = std::max<std::int64_t>(c[0] - 1, 0);
  const std::int64_t x1 = std::min<std::int64_t>(c[0] + 1, g.dims[0] - 1);
  constexpr int rows = D == 2 ? 3 : 9;  // runs of three cells along x
  for (int r = 0; r < rows; ++r) {
    std::array<std::int64_t, D> lo = c, hi = c;
    bool inside = true;
    for (int a = 1, rem = r; a < D; ++a, rem /= 3) {
      lo[a] = hi[a] = c[a] + rem % 3 - 1;
      inside = inside && lo[a] >= 0 && lo[a] < g.dims[a];
    }
    if (!inside) continue;
    lo[0] = x0;
    hi[0] = x1;
    const auto first = std::lower_bound(g.keys.begin(), g.keys.end(), g.key(lo));
    const auto last = std::upper_bound(first, g.keys.end(), g.key(hi));
    for (auto s = first; s != last; ++s) {
      const Index j = g.order[static_cast<std::size_t>(s - g.keys.begin())];
      const double d2 = (x[static_cast<std::size_t>(j)] - xi).squaredNorm();
      if (d2 < r2 && d2 > 0.0) f(j);
    }
  }
}

}  // namespace

template <int D>
Neighbours find_neighbours(std::span<const Vec<D>> x, double radius) {
  HM_ASSERT(radius > 0.0, "find_neighbours: radius {} must be > 0", radius);
  Neighbours nb;
  nb.radius = radius;
  const auto n = static_cast<Index>(x.size());
  nb.offsets.assign(static_cast<std::size_t>(n) + 1, 0);
  if (n == 0) return nb;
  const auto g = build_cells<D>(x, radius);
#pragma omp parallel for schedule(dynamic, 256)
  for (Index i = 0; i < n; ++i) {
    std::int64_t c = 0;
    for_each_within<D>(g, x, i, radius, [&](Index) { ++c; });
    nb.offsets[static_cast<std::size_t>(i) + 1] = c;
  }
  std::partial_sum(nb.offsets.begin(), nb.offsets.end(), nb.offsets.begin());
  nb.indices.resize(static_cast<std::size_t>(nb.offsets.back()));
#pragma omp parallel for schedule(dynamic, 256)
  for (Index i = 0; i < n; ++i) {
    Index* out = nb.indices.data() + nb.offsets[i];
    Index* const begin = out;
    for_each_within<D>(g, x, i, radius, [&](Index j) { *out++ = j; });
    std::sort(begin, out);
  }
  return nb;
}

void remove_pairs(Neighbours& nb, const std::function<bool(Index, Index)>& drop) {
  const Index n = nb.points();
  std::vector<std::uint8_t> keep(nb.indices.size());
  std::vector<std::int64_t> kept(static_cast<std::size_t>(n) + 1, 0);
#pragma omp parallel for schedule(dynamic, 256)
  for (Index i = 0; i < n; ++i) {
    std::int64_t c = 0;
    for (auto s = nb.offsets[i]; s < nb.offsets[i + 1]; ++s) {
      keep[static_cast<std::size_t>(s)] = drop(i, nb.indices[static_cast<std::size_t>(s)]) ? 0 : 1;
      c += keep[static_cast<std::size_t>(s)];
    }
    kept[static_cast<std::size_t>(i) + 1] = c;
  }
  std::partial_sum(kept.begin(), kept.end(), kept.begin());
  std::vector<Index> out(static_cast<std::size_t>(kept.back()));
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    auto o = kept[static_cast<std::size_t>(i)];
    for (auto s = nb.offsets[i]; s < nb.offsets[i + 1]; ++s)
      if (keep[static_cast<std::size_t>(s)]) out[static_cast<std::size_t>(o++)] = nb.indices[s];
  }
  nb.offsets.swap(kept);
  nb.indices.swap(out);
}

template <int D>
Index deactivate_dry_wall_nodes(PointSet<D>& points, Neighbours& nb) {
  const Index n = points.size();
  HM_ASSERT(nb.points() == n, "neighbour lists of {} points for {} points", nb.points(), n);
  Index inactive = 0;
#pragma omp parallel for reduction(+ : inactive)
  for (Index i = 0; i < n; ++i) {
    if (points.kind[i] != PointKind::wall) continue;
    bool wet = false;
    for (Index j : nb.of(i)) wet = wet || points.kind[j] == PointKind::fluid;
    if (!wet) {
      points.type[i] = PointType::inactive;
      ++inactive;
    } else if (points.type[i] == PointType::inactive) {
      points.type[i] = PointType::wall;
    }
  }
  if (inactive > 0)
    remove_pairs(nb, [&](Index i, Index j) {
      return points.type[i] == PointType::inactive || points.type[j] == PointType::inactive;
    });
  return inactive;
}

template Neighbours find_neighbours<2>(std::span<const Vec<2>>, double);
template Neighbours find_neighbours<3>(std::span<const Vec<3>>, double);
template Index deactivate_dry_wall_nodes<2>(PointSet<2>&, Neighbours&);
template Index deactivate_dry_wall_nodes<3>(PointSet<3>&, Neighbours&);

}  // namespace hm::ldd
