#pragma once
// Point storage of the LDD solver, structure of arrays: one std::vector per field, all of the
// same length, indexed by the point index. Fluid points move; wall nodes (CHOICE-B of the spec,
// §0.2) are fixed on the wall meshes at their host element and barycentric coordinates and carry
// the wall's normal (into the fluid), velocity and acceleration.
#include <span>
#include <vector>

#include "ldd/common.hpp"

namespace hm::ldd {

/// What a point is made of: fluid, or a boundary node fixed on a wall.
enum class PointKind : std::uint8_t { fluid, wall };

/// The row a point gets in the pressure Poisson equation (§1.9):
///  interior — Laplacian row; surface — Dirichlet p = 0 (free surface, contact line);
///  wall — Neumann row; isolated — too few neighbours, Dirichlet p = 0, ballistic;
///  inactive — a wall node with no fluid neighbour: no row and no pairs.
enum class PointType : std::uint8_t { interior, surface, wall, isolated, inactive };

/// Where a wall node sits: body (index into the caller's list of walls), element of that body,
/// and the barycentric coordinates in it (2 for a segment, 3 for a triangle).
template <int D>
struct WallHost {
  int body = -1;
  Index element = -1;
  Vec<D> barycentric = Vec<D>::Zero();
};

template <int D>
struct PointSet {
  std::vector<Vec<D>> position;  ///< [m]
  std::vector<Vec<D>> velocity;  ///< [m/s]
  std::vector<double> pressure;  ///< gauge [Pa]
  std::vector<PointKind> kind;
  std::vector<PointType> type;
  // Wall nodes only (zero / body −1 for fluid points):
  std::vector<Vec<D>> wall_normal;        ///< unit normal into the fluid
  std::vector<Vec<D>> wall_velocity;      ///< U [m/s]
  std::vector<Vec<D>> wall_acceleration;  ///< A^w [m/s²]
  std::vector<WallHost<D>> host;

  Index size() const { return static_cast<Index>(position.size()); }
  Index add_fluid(const Vec<D>& x, const Vec<D>& u = Vec<D>::Zero());
  Index add_wall_node(const Vec<D>& x, const Vec<D>& normal, const WallHost<D>& where);
  /// Permutes every field: new point k is old point order[k]. `order` is a permutation.
  void reorder(std::span<const Index> order);
  /// Keeps only the points `kept` (ascending indices), in that order.
  void retain(std::span<const Index> kept);
  /// Number of points of a type.
  Index count(PointType t) const;
};

/// Morton (Z-order) of the cells of size `cell` [m] holding the points: a permutation that puts
/// points of nearby cells next to each other in memory. Ties keep the input order.
template <int D>
std::vector<Index> spatial_order(std::span<const Vec<D>> positions, double cell);

/// Sorts the point set by spatial_order(position, cell).
template <int D>
void sort_spatially(PointSet<D>& points, double cell);

}  // namespace hm::ldd
