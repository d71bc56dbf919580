#pragma once
// Walls in artefacts: fsi-mesh writes each [[wall]] of the scene to hydromodal.mesh as
// /walls/<name>/vertices (n × dim, m) and /walls/<name>/cells (segments in 2-D, triangles in
// 3-D, normals into the fluid). The flow stages read them back here.
#include <string>
#include <vector>

#include "io/artefact.hpp"
#include "io/scene.hpp"
#include "mesh/types.hpp"

namespace hm::driver {

/// Names of the walls in a mesh artefact, sorted.
std::vector<std::string> wall_names(const io::ArtefactReader& mesh_artefact);

/// Reads wall `name` of a hydromodal.mesh artefact. InputError naming the file and the wall when
/// the wall is absent (listing the walls present) or its datasets are inconsistent (columns ≠
/// dimension, cells referring to vertices that do not exist).
mesh::SurfaceMesh read_wall(const io::ArtefactReader& mesh_artefact, const std::string& name);

/// Checks one [[wall]] of a scene without meshing it (what mesh_scene_wall refuses before gmsh).
void validate_scene_wall(const io::SceneView& wall, int dim);

/// Meshes one [[wall]] of a scene (`dim` = case.dimension): a rectangle or box tank, or a surface
/// file in its declared length_unit. InputError naming the key for a primitive without origin or
/// size, a kind that does not match the dimension, a missing file or a length_unit on a
/// primitive.
mesh::SurfaceMesh mesh_scene_wall(const io::SceneView& wall, int dim);

}  // namespace hm::driver
