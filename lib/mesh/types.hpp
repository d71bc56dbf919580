#pragma once
// In-memory meshes exchanged between lib/mesh (gmsh), lib/geometry (assimp, CGAL), lib/fem and
// the HDF5 artefacts. Coordinates in metres. Node order of quadratic elements is gmsh's:
//   tri6:  0,1,2 corners; 3:e01 4:e12 5:e20
//   tet10: 0..3 corners; 4:e01 5:e12 6:e20 7:e03 8:e23 9:e13   (VTK swaps 8 and 9)
//   line3: 0,1 ends; 2: mid-edge
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace hm::mesh {

using Index = std::int64_t;
using IndexMatrix = Eigen::Matrix<Index, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using Coordinates = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Volume (3-D) or area (2-D) mesh of an elastic structure, quadratic elements.
struct StructureMesh {
  int dim = 3;         ///< 2: tri6 cells, line3 boundary facets; 3: tet10 cells, tri6 facets
  Coordinates nodes;   ///< n_nodes × dim [m]
  IndexMatrix cells;   ///< n_cells × (6 | 10), 0-based node indices, gmsh order
  IndexMatrix facets;  ///< boundary facets, n_facets × (3 | 6), 0-based node indices
  /// Physical groups of the geometry: name → sorted node indices (every node on the group).
  std::map<std::string, std::vector<Index>> node_groups;
  /// Physical groups of the boundary: name → indices into `facets`.
  std::map<std::string, std::vector<Index>> facet_groups;

  Index node_count() const { return nodes.rows(); }
  int nodes_per_cell() const { return dim == 2 ? 6 : 10; }
  int nodes_per_facet() const { return dim == 2 ? 3 : 6; }
};

/// A wall or wetted surface as the fluid sees it: segments (2-D) or triangles (3-D), linear.
/// Normals: a triangle (a, b, c) has normal (b − a) × (c − a); a 2-D segment (a, b) has normal
/// ẑ × (b − a), i.e. its left side. Fluid walls point into the fluid; the boundary surface of a
/// structure points out of the structure (which is again into the fluid around it).
struct SurfaceMesh {
  int dim = 3;           ///< 2: cells are segments (2 vertices); 3: triangles (3 vertices)
  Coordinates vertices;  ///< n_vertices × dim [m]
  IndexMatrix cells;     ///< n_cells × dim, 0-based vertex indices
};

}  // namespace hm::mesh
