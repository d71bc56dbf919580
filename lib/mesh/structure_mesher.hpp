#pragma once
// Quadratic structure meshes made by gmsh 4.8: tri6 cells + line3 boundary facets in 2-D, tet10
// cells + tri6 boundary facets in 3-D, in gmsh node order (types.hpp). Cells are positively
// oriented; `facets` are all boundary facets, oriented outward (boundary.hpp).
//
// Named groups (node_groups / facet_groups) come from
//   * physical groups of a .geo script, by name (an unnamed one by its number);
//   * box groups of the options, for every source (this is how CAD and STL sources are named);
//   * the face names xmin, xmax, ymin, ymax (zmin, zmax) of the rectangle and box primitives.
// A group of dimension dim−1 also fills facet_groups (its boundary facets). Every name in
// options.required_groups must exist and be non-empty, else an InputError lists the groups.
// Each call logs the extent (so a mm/m mix-up shows) and the quality, warning on slivers.
#include <filesystem>
#include <string_view>

#include "mesh/options.hpp"
#include "mesh/types.hpp"

namespace hm::mesh {

/// 2-D rectangle (OpenCASCADE kernel), options.dim must be 2.
StructureMesh mesh_rectangle(const RectangleShape& rectangle, const MeshOptions& options);

/// 3-D box / plate (OpenCASCADE kernel), options.dim must be 3.
StructureMesh mesh_box(const BoxShape& box, const MeshOptions& options);

/// A gmsh .geo script; its physical groups become named groups. options.size may be 0 to keep
/// the script's own sizes; a positive size caps them (Mesh.MeshSizeMax).
StructureMesh mesh_geo_file(const std::filesystem::path& path, const MeshOptions& options);

/// STEP, BREP or IGES through OpenCASCADE; name groups with options.box_groups.
StructureMesh mesh_cad_file(const std::filesystem::path& path, const MeshOptions& options);

/// A closed triangle surface (STL, OBJ, PLY; read with assimp), checked and oriented by
/// geometry::check_closed_surface, then filled with tet10 by gmsh (classifySurfaces at 40°,
/// createGeometry, surface loop, volume). 3-D only.
StructureMesh mesh_surface_file(const std::filesystem::path& path, const MeshOptions& options);

/// As mesh_surface_file, for a surface already in memory (`source` names it in messages).
StructureMesh mesh_closed_surface(SurfaceMesh surface, const MeshOptions& options,
                                  std::string_view source);

/// Dispatches on the file extension (case-insensitive): .geo; .step .stp .brep .brp .iges .igs;
/// .stl .obj .ply. InputError for anything else.
StructureMesh mesh_geometry_file(const std::filesystem::path& path, const MeshOptions& options);

}  // namespace hm::mesh
