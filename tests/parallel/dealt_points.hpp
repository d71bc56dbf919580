#pragma once
// Points for the decomposition's tests and benchmark: a water column's lattice, jittered, dealt
// out over the processes by id, each point carrying fields that are known functions of its id.
#include <cmath>
#include <cstdint>

#include "parallel/decomposition.hpp"

namespace hm::parallel::test {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

inline constexpr int kWidth = 3;  // fields per point

/// The fields a point carries: known functions of its id.
inline double field(std::int64_t id, int k) {
  return 1000.0 * static_cast<double>(id) + k;
}

/// A displacement in [−amplitude, amplitude]^D, a fixed function of the id (the same on any
/// process count).
template <int D>
Vec<D> displacement(std::int64_t id, double amplitude) {
  Vec<D> d;
  for (int a = 0; a < D; ++a) {
    const auto h = static_cast<std::uint64_t>(id) * 2654435761u + 97u * static_cast<unsigned>(a);
    d[a] = amplitude * (2.0 * static_cast<double>(h % 10007) / 10006.0 - 1.0);
  }
  return d;
}

/// This process's share of a lattice over the column [0, 0.6] × [0, 0.3] (3-D: 0.15 wide) of
/// spacing dx, jittered by up to dx/4 (as points are after a few steps: no two on one plane),
/// dealt out by id.
template <int D>
PointBlock<D> dealt_lattice(double dx, const Processes& p) {
  Vec<D> size;
  size[0] = 0.6;
  if constexpr (D == 3) size[1] = 0.15;
  size[D - 1] = 0.3;
  Eigen::Matrix<int, D, 1> n;
  for (int a = 0; a < D; ++a) n[a] = static_cast<int>(std::round(size[a] / dx));
  PointBlock<D> block;
  block.width = kWidth;
  const std::int64_t total = n.prod();
  for (std::int64_t id = p.rank; id < total; id += p.count) {
    Vec<D> x;
    std::int64_t rest = id;
    for (int a = 0; a < D; ++a) {
      x[a] = (static_cast<double>(rest % n[a]) + 0.5) * dx;
      rest /= n[a];
    }
    x += displacement<D>(id + total, 0.25 * dx);
    const double f[kWidth] = {field(id, 0), field(id, 1), field(id, 2)};
    block.add(x, id, f);
  }
  return block;
}

}  // namespace hm::parallel::test
