#pragma once
// The declared length unit of a geometry file (STL, OBJ, PLY, STEP, ...): a file written in
// millimetres is read as metres unless the scene says otherwise.
#include <filesystem>
#include <string>

#include "io/scene.hpp"

namespace hm::driver {

/// The units a length-unit key accepts, as listed in the key reference.
inline const std::vector<std::string> length_units{"m", "cm", "mm", "in", "ft"};

/// Metres per unit of `file`, from the key `unit_key` of `view` (m, cm, mm, in, ft). A .geo script
/// is in metres (its numbers are gmsh's lengths; scale in the script with Dilate): any other unit
/// is refused, naming the key.
double file_length_scale(const io::SceneView& view, const std::string& unit_key,
                         const std::filesystem::path& file);

}  // namespace hm::driver
