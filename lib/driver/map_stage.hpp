#pragma once
// fsi-map: scene + modes.h5 → mapped.h5 (hydromodal.mapped_modes).
#include <filesystem>

#include "io/scene.hpp"
#include "rbf/interpolator.hpp"

namespace hm::driver {

/// The RBF options of the scene's map.* keys (fsi-map's, and fsi-simulate's map of a nonlinear
/// structure's displacement onto the same wall).
rbf::RbfOptions rbf_options(const io::Scene& scene);

/// Checks everything fsi-map needs from the scene (for --validate).
void validate_map_scene(const io::Scene& scene);

/// Interpolates every mode shape from the structure's boundary surface nodes onto the target
/// surface (RBF), reports the mapping quality and writes the artefact atomically. InputError
/// when target vertices lie farther than map.far_factor source spacings from the structure.
void run_map_stage(const io::Scene& scene, const std::filesystem::path& modes_artefact,
                   const std::filesystem::path& output);

}  // namespace hm::driver
