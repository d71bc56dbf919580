#pragma once
// hydromodal's own readers of the triangle-surface formats users give walls and bodies in: STL
// (ASCII and binary), Wavefront OBJ and PLY (ASCII, binary little and big endian). Written here
// rather than taken from assimp because assimp 5.2 (Debian 12), on malformed files, aborts the
// process (an ai_assert in its triangulation), loops for ever (a bad PLY header) or leaks — found
// by fuzzing (tests/fuzz) — and reads ASCII coordinates in single precision, which put an STL face
// given at x = 0.2545 m a few 1e-8 m off. These readers keep ASCII numbers in double precision
// (binary STL is single precision by its format), triangulate polygons as fans from their first
// vertex (exact for convex faces, the faces CAD exporters write), and refuse anything malformed
// with an InputError naming the file, the line (or byte offset) and what was expected.
#include <filesystem>
#include <optional>

#include "mesh/types.hpp"

namespace hm::geometry {

/// Triangles as read, vertices not merged (a 3-D SurfaceMesh), and the faces skipped because they
/// have fewer than three vertices (points and lines).
struct SurfaceFile {
  mesh::SurfaceMesh surface;
  mesh::Index skipped = 0;
};

/// Reads `path` when its extension is .stl, .obj or .ply (case-insensitive); std::nullopt for any
/// other extension. InputError on a malformed file.
std::optional<SurfaceFile> read_known_surface_format(const std::filesystem::path& path);

}  // namespace hm::geometry
