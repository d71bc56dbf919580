#pragma once
// fsi-mesh: scene → mesh.h5 (hydromodal.mesh) + mesh.xdmf.
#include <filesystem>

#include "io/scene.hpp"
#include "mesh/options.hpp"

namespace hm::driver {

/// The meshing options the scene asks for (InputError naming the key when inconsistent).
mesh::MeshOptions mesh_options_from_scene(const io::Scene& scene);

/// Checks everything fsi-mesh needs from the scene without meshing (for --validate).
void validate_mesh_scene(const io::Scene& scene);

/// Meshes the structure of the scene and writes the artefact atomically.
void run_mesh_stage(const io::Scene& scene, const std::filesystem::path& output);

}  // namespace hm::driver
