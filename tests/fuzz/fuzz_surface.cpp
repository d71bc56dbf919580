// libFuzzer harness: the surface-mesh readers (geometry::read_surface_file through assimp: STL
// ASCII and binary, OBJ, PLY) and the checks every file wall goes through (closedness, bounding
// box). The first byte chooses the extension, the rest is the file. A bad file must end in an
// InputError naming the file; anything else is a defect.
#include <array>

#include "core/errors.hpp"
#include "fuzz_input.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/surface_checks.hpp"
#include "geometry/surface_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static constexpr std::array<const char*, 3> names{"surface.stl", "surface.obj", "surface.ply"};
  const auto path = hm::fuzz::input_file(hm::fuzz::as_text(data + 1, size - 1),
                                         names[static_cast<std::size_t>(data[0] % 3)]);
  try {
    hm::mesh::SurfaceMesh surface = hm::geometry::read_surface_file(path);
    (void)hm::geometry::bounding_box(surface.vertices);
    if (hm::geometry::count_border_edges(surface) == 0)
      hm::geometry::check_closed_surface(surface, path.string());
  } catch (const hm::InputError&) {
  }
  return 0;
}
