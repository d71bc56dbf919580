#pragma once
// Structured quadratic meshes of rectangles (tri6) and boxes (tet10), for tests and refinement
// studies of the structure solver. Coordinates in metres.
//
// Nodes lie on the lattice of half-cells: (2nx+1)(2ny+1)[(2nz+1)] nodes, numbered x fastest,
// then y, then z. Every quadratic node is the mid-point of its edge (straight-sided elements).
//   rectangle: each of the nx·ny cells is split along its (x0,y0)–(x1,y1) diagonal into 2 tri6.
//   box:       each of the nx·ny·nz cells is split into the 6 Kuhn tetrahedra around its
//              (x0,y0,z0)–(x1,y1,z1) diagonal; identical splits in every cell make the mesh
//              conforming (the face diagonals of neighbouring cells coincide).
// Cells are positively oriented. Boundary facets (line3 in 2-D, tri6 in 3-D) are oriented with
// their normal pointing out of the domain and grouped by side. Node groups and facet groups are
// named xmin, xmax, ymin, ymax (and zmin, zmax in 3-D).
#include <Eigen/Core>

#include "mesh/types.hpp"

namespace hm::mesh {

/// Rectangle [x0, x0+lx] × [y0, y0+ly] meshed with 2·nx·ny tri6. Throws InputError if a length
/// is not positive or a cell count is below 1.
StructureMesh structured_rectangle(double lx, double ly, int nx, int ny,
                                   Eigen::Vector2d origin = Eigen::Vector2d::Zero());

/// Box [x0, x0+lx] × [y0, y0+ly] × [z0, z0+lz] meshed with 6·nx·ny·nz tet10.
StructureMesh structured_box(double lx, double ly, double lz, int nx, int ny, int nz,
                             Eigen::Vector3d origin = Eigen::Vector3d::Zero());

}  // namespace hm::mesh
