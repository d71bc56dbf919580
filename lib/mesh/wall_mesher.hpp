#pragma once
// Fluid walls that are only surfaces (a tank): linear SurfaceMesh (triangles in 3-D, segments in
// 2-D) with normals pointing into the fluid. Normal convention (types.hpp / options.hpp):
// triangle (a,b,c): (b−a)×(c−a); segment (a,b): ẑ×(b−a), i.e. its left side.
#include <filesystem>

#include "mesh/options.hpp"
#include "mesh/types.hpp"

namespace hm::mesh {

/// Walls of a rectangle (options.dim 2): its edges xmin, xmax, ymin, ymax (options.faces, empty =
/// all), segments of length ≤ options.size, normals into the rectangle (the fluid inside).
SurfaceMesh mesh_rectangle_walls(const RectangleShape& rectangle, const WallOptions& options);

/// Walls of a box (options.dim 3): its faces xmin … zmax (options.faces, empty = all),
/// triangles of size ≈ options.size from gmsh, normals into the box.
SurfaceMesh mesh_box_walls(const BoxShape& box, const WallOptions& options);

/// Walls from a file:
///  * .geo: gmsh meshes the surfaces (curves in 2-D) of the physical groups named in
///    options.faces (empty: all); cells keep the orientation of each surface in the script.
///  * .stl/.obj/.ply (3-D): the triangles as read (assimp), split 1:4 until every edge is
///    ≤ options.size. A closed surface is checked (geometry::check_closed_surface) and oriented
///    inward (the fluid is inside); an open one keeps the file's orientation.
/// options.flip_normals reverses the result in both cases.
SurfaceMesh mesh_wall_file(const std::filesystem::path& path, const WallOptions& options);

}  // namespace hm::mesh
