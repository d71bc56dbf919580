#pragma once
// Neighbour lists of the LDD operators (spec §1.6): N_i = {j : 0 < |r_j − r_i| < h}, found with a
// uniform cell grid of cell size h, stored in CSR form with each list sorted by index. The same
// lists are the sparsity pattern of the pressure Poisson matrix (plus the diagonal).
#include <cstdint>
#include <numeric>
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

/// The lists of the fluid points and of the wall nodes within `radius` of one; the other wall
/// nodes (dry: deactivate_dry_wall_nodes makes them inactive and removes their pairs) get
/// empty lists. After deactivate_dry_wall_nodes the lists equal find_neighbours' (a shallow
/// tank's dry walls hold most of its wall nodes: rhee_sloshing 7 900 of 10 900).
template <int D>
Neighbours find_wet_neighbours(const PointSet<D>& points, double radius);

/// Removes every pair (i, j) of the lists for which drop(i, j) is true (the test is called once
/// per directed pair, in parallel: it must be thread-safe). A template, so that the test, called
/// for every pair of every step, is inlined.
template <typename Drop>
void remove_pairs(Neighbours& nb, Drop&& drop) {
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
  if (static_cast<std::size_t>(kept.back()) == nb.indices.size()) return;  // none dropped
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

/// Whether a deactivation removes the pairs of the nodes it made inactive at once, or leaves
/// them to the caller's remove_pairs_with_inactive (over processes: once the ghosts' types have
/// arrived, one pass for the owners' and the ghosts' inactive nodes alike).
enum class InactivePairs : bool { removed, kept };

/// Wall nodes with no fluid neighbour become PointType::inactive and every pair with them is
/// removed (spec §0.2 item 3; with InactivePairs::kept the caller removes them). An inactive
/// node with a fluid neighbour again becomes PointType::wall. Returns the number of inactive
/// nodes. Only the points [0, owned) are decided (all with owned < 0): past them are ghosts
/// (ldd/point_loop.hpp), whose own lists end at the halo's edge; their owners decide, and
/// remove_pairs_with_inactive follows once their types have arrived.
template <int D>
Index deactivate_dry_wall_nodes(PointSet<D>& points, Neighbours& neighbours, Index owned = -1,
                                InactivePairs pairs = InactivePairs::removed);

/// Removes every pair with an inactive point.
template <int D>
void remove_pairs_with_inactive(const PointSet<D>& points, Neighbours& neighbours);

}  // namespace hm::ldd
