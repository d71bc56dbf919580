#pragma once
// The boundary of a quadratic structure mesh: its facets, oriented with the outward normal of the
// structure, and the linear surface the fluid side sees, linked to the volume nodes.
#include <span>
#include <string>
#include <vector>

#include "mesh/types.hpp"

namespace hm::mesh {

/// Reorders every cell with a negative (corner) Jacobian so that all cells are positively
/// oriented (counter-clockwise tri6 in 2-D, right-handed tet10 in 3-D). Returns how many.
Index orient_cells_positively(StructureMesh& mesh);

/// Fills `mesh.facets` with the facets that belong to exactly one cell (line3 in 2-D, tri6 in
/// 3-D), in gmsh node order and oriented outward: 3-D normal (b−a)×(c−a) of the corners points
/// out of the structure; a 2-D line3 (a, b, mid) has the structure on its left. Requires
/// positively oriented cells. Clears facet_groups (their indices would be stale).
void build_boundary_facets(StructureMesh& mesh);

/// Key of a facet: its sorted corner node indices (2 in 2-D, 3 in 3-D; the last is -1 in 2-D).
std::array<Index, 3> facet_key(std::span<const Index> facet_nodes, int dim);

enum class SurfaceSplit {
  corners,  ///< one triangle (segment) per facet, through its corner nodes
  refined,  ///< all nodes used: tri6 → 4 triangles, line3 → 2 segments
};

/// A linear surface extracted from the structure's boundary. Surface vertex i is volume node
/// volume_node[i]. Cells follow the SurfaceMesh normal convention (types.hpp, options.hpp) with
/// normals pointing OUT of the structure — into the surrounding fluid.
struct BoundarySurface {
  SurfaceMesh surface;
  std::vector<Index> volume_node;
};

/// The surface of the given facets (indices into mesh.facets; empty span = all facets).
BoundarySurface extract_boundary_surface(const StructureMesh& mesh, SurfaceSplit split,
                                         std::span<const Index> facets = {});

/// The surface of a named facet group; InputError listing the facet groups if it is missing.
BoundarySurface extract_boundary_surface(const StructureMesh& mesh, SurfaceSplit split,
                                         const std::string& facet_group);

}  // namespace hm::mesh
