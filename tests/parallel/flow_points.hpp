#pragma once
// A flow's points over processes, for the tests of lib/parallel with the flow: each process
// takes every count-th point (dealt out by index, its global id) with the fields the phases of
// a step read, and rebuilds a PointSet from owned points and ghosts.
#include <vector>

#include "ldd/points.hpp"
#include "parallel/decomposition.hpp"

namespace hm::ldd::test {

using Vec2 = Vec<2>;

/// The fields a point carries across processes: velocity, kind, type, wall normal, and a wall
/// node's host (wall, element, barycentric coordinates).
inline constexpr int kFields = 10;

inline parallel::PointBlock<2> dealt_points(const PointSet<2>& points,
                                            const parallel::Processes& p) {
  parallel::PointBlock<2> block;
  block.width = kFields;
  for (Index i = p.rank; i < points.size(); i += p.count) {
    const double f[kFields] = {points.velocity[i].x(),
                               points.velocity[i].y(),
                               static_cast<double>(points.kind[i]),
                               static_cast<double>(points.type[i]),
                               points.wall_normal[i].x(),
                               points.wall_normal[i].y(),
                               static_cast<double>(points.host[i].body),
                               static_cast<double>(points.host[i].element),
                               points.host[i].barycentric.x(),
                               points.host[i].barycentric.y()};
    block.add(points.position[i], i, f);
  }
  return block;
}

/// Appends the points of `block` to `points` (their global ids to `ids`).
inline void append(const parallel::PointBlock<2>& block, PointSet<2>& points,
                   std::vector<std::int64_t>& ids) {
  for (std::size_t k = 0; k < block.size(); ++k) {
    const double* f = &block.fields[k * kFields];
    const Vec2 velocity(f[0], f[1]);
    const Index i = static_cast<PointKind>(f[2]) == PointKind::fluid
                        ? points.add_fluid(block.position[k], velocity)
                        : points.add_wall_node(
                              block.position[k], Vec2(f[4], f[5]),
                              {static_cast<int>(f[6]), static_cast<Index>(f[7]), Vec2(f[8], f[9])});
    points.velocity[i] = velocity;
    points.type[i] = static_cast<PointType>(f[3]);
    ids.push_back(block.id[k]);
  }
}

/// Sets the ghosts' (points from `owned` on) types to their owners'.
inline void refresh_types(const parallel::Halo<2>& halo, PointSet<2>& points, Index owned) {
  std::vector<double> owned_types(static_cast<std::size_t>(owned));
  for (Index i = 0; i < owned; ++i) owned_types[i] = static_cast<double>(points.type[i]);
  const auto ghost_types = halo.refresh(owned_types, 1);
  for (std::size_t k = 0; k < ghost_types.size(); ++k)
    points.type[owned + static_cast<Index>(k)] = static_cast<PointType>(ghost_types[k]);
}

}  // namespace hm::ldd::test
