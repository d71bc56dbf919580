#pragma once
// Fluid seeding (spec §0.2 item 1): lattice points at spacing dx, cell-centred in the region,
// keeping only points at least dx/2 from every wall and on the wall's fluid side.
#include <span>
#include <vector>

#include "ldd/walls.hpp"

namespace hm::ldd {

template <int D>
struct Box {
  Vec<D> lower = Vec<D>::Zero();  ///< [m]
  Vec<D> upper = Vec<D>::Zero();  ///< [m]
};

/// Lattice points lower + (k + ½)dx inside `fluid`. Throws InputError if dx ≤ 0, if fewer than 4
/// points fit across the box's smallest side (dx too large for the region), if the box is not
/// inside the bounding box of the walls (a fluid region outside the tank), or if no point is left.
template <int D>
std::vector<Vec<D>> seed_box(const Box<D>& fluid, double dx, std::span<const WallMesh<D>> walls);

/// Lattice points inside the closed wall `container` (a tank given as a closed surface), at
/// least dx/2 from it. Throws InputError if the wall is not closed, for a bad dx as seed_box.
template <int D>
std::vector<Vec<D>> seed_inside(const WallMesh<D>& container, double dx);

}  // namespace hm::ldd
