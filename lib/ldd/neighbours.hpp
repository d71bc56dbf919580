#pragma once
// Neighbour lists of the LDD operators (spec §1.6): N_i = {j : 0 < |r_j − r_i| < h}, found with a
// uniform cell grid of cell size h, stored in CSR form with each list sorted by index. The same
// lists are the sparsity pattern of the pressure Poisson matrix (plus the diagonal).
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "ldd/points.hpp"

namespace hm::ldd {

struct Neighbours {
  double radius = 0.0;  ///< support radius h [m]
  std::vector<std::int64_t>
      offsets;                 ///< size n + 1; list of i is indices[offsets[i], offsets[i+1])
  std::vector<Index> indices;  ///< neighbour point indices, ascending within each list

  Index points() const { return offsets.empty() ? 0 : static_cast<Index>(offsets.size() - 1); }
  std::int64_t pairs() const { return offsets.empty() ? 0 : offsets.back(); }
  Index count(Index i) const { return static_cast<Index>(offsets[i + 1] - offsets[i]); }
  std::span<const Index> of(Index i) const {
    return {indices.data() + offsets[i], static_cast<std::size_t>(count(i))};
  }
};

/// All pairs closer than `radius` (> 0) [m]; OpenMP parallel. Coincident points are not
/// neighbours of each other. Cells are keyed and sorted, so far-flung points (a splash) cost no
/// memory for empty cells.
template <int D>
Neighbours find_neighbours(std::span<const Vec<D>> positions, double radius);

/// Removes every pair (i, j) of the lists for which drop(i, j) is true (the test is called once
/// per directed pair, in parallel: it must be thread-safe).
void remove_pairs(Neighbours& neighbours, const std::function<bool(Index, Index)>& drop);

/// Wall nodes with no fluid neighbour become PointType::inactive and every pair with them is
/// removed (spec §0.2 item 3). An inactive node with a fluid neighbour again becomes
/// PointType::wall. Returns the number of inactive nodes.
template <int D>
Index deactivate_dry_wall_nodes(PointSet<D>& points, Neighbours& neighbours);

}  // namespace hm::ldd
