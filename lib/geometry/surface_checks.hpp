#pragma once
// Checks of a triangle surface that is to bound a solid (before gmsh turns it into a volume):
// no degenerate triangle, every edge shared by exactly two triangles, one consistent orientation,
// no self-intersection; then the orientation is made outward. A failure is an InputError with the
// counts and the coordinates of the first offending elements.
#include <string_view>

#include "geometry/bounding_box.hpp"
#include "mesh/types.hpp"

namespace hm::geometry {

struct SurfaceCheckReport {
  mesh::Index vertices = 0;
  mesh::Index triangles = 0;
  mesh::Index components = 0;               ///< connected components (shells)
  mesh::Index flipped_for_consistency = 0;  ///< triangles flipped to agree with their neighbours
  mesh::Index flipped_outward = 0;  ///< triangles flipped so that the surface bounds a volume
  double enclosed_volume = 0.0;     ///< [m³], by the divergence theorem, after orientation
  BoundingBox box;
};

/// A triangle is degenerate when two of its vertices coincide or when
/// |(b−a)×(c−a)| ≤ degenerate_tolerance · (longest edge)² (collinear vertices, needles, caps).
inline constexpr double degenerate_tolerance = 1e-10;

/// Checks `surface` (named `source` in messages) and orients it in place so that it bounds a
/// volume with outward normals. Inconsistently oriented triangles of a closed surface are flipped
/// to agree with the first triangle of their shell (a warning gives the count); a shell oriented
/// inward as a whole is reversed (info). Throws InputError for degenerate triangles, open
/// (border) edges, edges shared by more than two triangles, a non-orientable shell, and
/// self-intersections.
SurfaceCheckReport check_closed_surface(mesh::SurfaceMesh& surface, std::string_view source);

/// Number of edges used by exactly one triangle (0 for a closed surface).
mesh::Index count_border_edges(const mesh::SurfaceMesh& surface);

/// Splits every triangle into four (edge midpoints shared between neighbours), or every 2-D
/// segment into two, until the longest edge is ≤ max_edge [m]; the geometry and the orientation
/// are unchanged, and the original vertices keep their indices (new ones are appended).
mesh::SurfaceMesh refine_uniformly(const mesh::SurfaceMesh& surface, double max_edge);

/// The cell count refine_uniformly(surface, max_edge) would give, without refining: each
/// halving of the longest edge multiplies the triangles by 4 (segments by 2).
double refined_cell_count(const mesh::SurfaceMesh& surface, double max_edge);

/// Reverses every cell (the normal of each triangle or segment flips).
void reverse_cells(mesh::SurfaceMesh& surface);

/// Signed volume enclosed by a closed 3-D triangle surface [m³]: Σ a·(b×c)/6 (positive when
/// the normals point outward).
double enclosed_volume(const mesh::SurfaceMesh& surface);

}  // namespace hm::geometry
