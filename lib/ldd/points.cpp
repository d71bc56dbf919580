#include "ldd/points.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/errors.hpp"

namespace hm::ldd {
namespace {

template <typename T>
void permute(std::vector<T>& v, std::span<const Index> order) {
  std::vector<T> out(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) out[k] = v[static_cast<std::size_t>(order[k])];
  v.swap(out);
}

/// Spreads the low 21 bits of x so that two zero bits follow each (3-D Morton).
std::uint64_t spread3(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

/// Spreads the low 32 bits of x so that one zero bit follows each (2-D Morton).
std::uint64_t spread2(std::uint64_t x) {
  x &= 0xffffffffULL;
  x = (x | x << 16) & 0x0000ffff0000ffffULL;
  x = (x | x << 8) & 0x00ff00ff00ff00ffULL;
  x = (x | x << 4) & 0x0f0f0f0f0f0f0f0fULL;
  x = (x | x << 2) & 0x3333333333333333ULL;
  x = (x | x << 1) & 0x5555555555555555ULL;
  return x;
}

}  // namespace

template <int D>
Index PointSet<D>::add_fluid(const Vec<D>& x, const Vec<D>& u) {
  position.push_back(x);
  velocity.push_back(u);
  pressure.push_back(0.0);
  kind.push_back(PointKind::fluid);
  type.push_back(PointType::interior);
  wall_normal.push_back(Vec<D>::Zero());
  wall_velocity.push_back(Vec<D>::Zero());
  wall_acceleration.push_back(Vec<D>::Zero());
  host.push_back({});
  return size() - 1;
}

template <int D>
Index PointSet<D>::add_wall_node(const Vec<D>& x, const Vec<D>& normal, const WallHost<D>& where) {
  const Index i = add_fluid(x);
  kind[i] = PointKind::wall;
  type[i] = PointType::wall;
  wall_normal[i] = normal;
  host[i] = where;
  return i;
}

template <int D>
void PointSet<D>::reorder(std::span<const Index> order) {
  HM_ASSERT(order.size() == position.size(), "reorder: {} indices for {} points", order.size(),
            position.size());
  permute(position, order);
  permute(velocity, order);
  permute(pressure, order);
  permute(kind, order);
  permute(type, order);
  permute(wall_normal, order);
  permute(wall_velocity, order);
  permute(wall_acceleration, order);
  permute(host, order);
}

template <int D>
void PointSet<D>::retain(std::span<const Index> kept) {
  HM_ASSERT(std::is_sorted(kept.begin(), kept.end()), "retain: indices must ascend");
  permute(position, kept);
  permute(velocity, kept);
  permute(pressure, kept);
  permute(kind, kept);
  permute(type, kept);
  permute(wall_normal, kept);
  permute(wall_velocity, kept);
  permute(wall_acceleration, kept);
  permute(host, kept);
}

template <int D>
Index PointSet<D>::count(PointType t) const {
  return static_cast<Index>(std::count(type.begin(), type.end(), t));
}

template <int D>
std::vector<Index> spatial_order(std::span<const Vec<D>> positions, double cell) {
  HM_ASSERT(cell > 0.0, "spatial_order: cell size {} must be > 0", cell);
  const std::size_t n = positions.size();
  std::vector<Index> order(n);
  std::iota(order.begin(), order.end(), 0);
  if (n == 0) return order;
  Vec<D> lo = positions[0];
  for (const auto& x : positions) lo = lo.cwiseMin(x);
  std::vector<std::uint64_t> code(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t c = 0;
    for (int a = 0; a < D; ++a) {
      const auto k = static_cast<std::uint64_t>(std::floor((positions[i][a] - lo[a]) / cell));
      c |= (D == 3 ? spread3(k) : spread2(k)) << a;
    }
    code[i] = c;
  }
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) {
    return code[static_cast<std::size_t>(a)] < code[static_cast<std::size_t>(b)];
  });
  return order;
}

template <int D>
void sort_spatially(PointSet<D>& points, double cell) {
  const auto order = spatial_order<D>(points.position, cell);
  points.reorder(order);
}

template struct PointSet<2>;
template struct PointSet<3>;
template std::vector<Index> spatial_order<2>(std::span<const Vec<2>>, double);
template std::vector<Index> spatial_order<3>(std::span<const Vec<3>>, double);
template void sort_spatially<2>(PointSet<2>&, double);
template void sort_spatially<3>(PointSet<3>&, double);

}  // namespace hm::ldd
