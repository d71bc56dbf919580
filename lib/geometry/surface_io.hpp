#pragma once
// Triangle surfaces from files (STL, OBJ, PLY read here; the other formats assimp reads) and a
// small ASCII STL writer. Coordinates are taken as metres, as written in the file.
#include <filesystem>
#include <string_view>

#include "mesh/types.hpp"

namespace hm::geometry {

/// Reads a triangle surface: STL, OBJ and PLY with hydromodal's own readers (surface_formats.hpp:
/// ASCII numbers in double precision, malformed files refused), any other format assimp reads
/// with assimp (JoinIdenticalVertices | Triangulate | PreTransformVertices); merges bit-identical
/// vertices and returns one 3-D triangle surface. Points and lines in the file are skipped with
/// a warning. Throws InputError naming the file when it is missing, malformed or holds no
/// triangle.
mesh::SurfaceMesh read_surface_file(const std::filesystem::path& path);

/// Merges vertices with identical coordinates and renumbers the cells (first occurrence wins).
void merge_identical_vertices(mesh::SurfaceMesh& surface);

/// Writes a 3-D triangle surface as ASCII STL (facet normals by the right-hand rule).
void write_stl_ascii(const mesh::SurfaceMesh& surface, const std::filesystem::path& path,
                     std::string_view solid_name = "hydromodal");

}  // namespace hm::geometry
