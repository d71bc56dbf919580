#include "driver/length_unit.hpp"

#include <algorithm>
#include <cctype>
#include <map>

#include "core/errors.hpp"

namespace hm::driver {

double file_length_scale(const io::SceneView& view, const std::string& unit_key,
                         const std::filesystem::path& file) {
  static const std::map<std::string, double> metres_per{
      {"m", 1.0}, {"cm", 0.01}, {"mm", 0.001}, {"in", 0.0254}, {"ft", 0.3048}};
  const std::string unit = view.string(unit_key);
  const auto it = metres_per.find(unit);
  HM_ASSERT(it != metres_per.end(), "the scene reader checks the length-unit choices");
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".geo" && unit != "m")
    input_error(
        "{}: length_unit = \"{}\" cannot apply to the gmsh script '{}': a .geo script's lengths "
        "are metres. Remove the key, or scale the geometry in the script (Dilate)",
        view.where(unit_key), unit, file.string());
  return it->second;
}

}  // namespace hm::driver
