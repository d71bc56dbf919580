#pragma once
// The CGAL part of the surface checks, in its own library (hm::geometry_cgal) because CGAL adds
// -frounding-math to whatever compiles it and costs ~15 s per translation unit.
// Kernel: Exact_predicates_inexact_constructions_kernel (exact predicates, so a self-intersection
// verdict is robust).
#include <utility>
#include <vector>

#include "mesh/types.hpp"

namespace hm::geometry::cgal {

/// Pairs of triangles (indices into `surface.cells`) that intersect other than through a shared
/// edge or vertex. Precondition: a consistently oriented, edge-manifold triangle surface.
std::vector<std::pair<mesh::Index, mesh::Index>> self_intersecting_faces(
    const mesh::SurfaceMesh& surface);

/// CGAL::Polygon_mesh_processing::is_outward_oriented for a closed surface.
bool is_outward_oriented(const mesh::SurfaceMesh& surface);

/// Flips whole connected components so that the surface bounds a volume (outer shells with
/// outward normals, cavities inward) — CGAL orient_to_bound_a_volume. Preconditions: closed,
/// consistently oriented, no self-intersection. Returns the number of triangles flipped.
mesh::Index orient_to_bound_a_volume(mesh::SurfaceMesh& surface);

}  // namespace hm::geometry::cgal
