#include "driver/wall_io.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/errors.hpp"
#include "io/schema.hpp"

namespace hm::driver {

namespace ds = io::ds;

std::vector<std::string> wall_names(const io::ArtefactReader& reader) {
  const std::string group(ds::walls);
  return reader.children(group.substr(0, group.size() - 1));
}

mesh::SurfaceMesh read_wall(const io::ArtefactReader& reader, const std::string& name) {
  const std::string prefix = ds::walls + name;
  const std::string vertices = prefix + "/vertices", cells = prefix + "/cells";
  // Look the name up among the children first: H5Lexists fails on a missing intermediate group.
  const auto present = wall_names(reader);
  const bool listed = std::find(present.begin(), present.end(), name) != present.end();
  if (!listed || !reader.has(vertices) || !reader.has(cells)) {
    input_error(
        "'{}': no wall '{}' ({} and {} expected); walls present: {}", reader.path().string(), name,
        vertices, cells,
        present.empty() ? std::string("none") : fmt::format("{}", fmt::join(present, ", ")));
  }
  mesh::SurfaceMesh wall;
  wall.vertices = reader.read_matrix(vertices);
  wall.cells = reader.read_indices(cells);
  wall.dim = static_cast<int>(wall.vertices.cols());
  if (wall.dim != 2 && wall.dim != 3)
    input_error("'{}': {} has {} columns; expected 2 or 3 coordinates", reader.path().string(),
                vertices, wall.dim);
  if (wall.cells.cols() != wall.dim)
    input_error("'{}': {} has {} vertices per cell; a {}-D wall needs {} ({})",
                reader.path().string(), cells, wall.cells.cols(), wall.dim, wall.dim,
                wall.dim == 2 ? "segments" : "triangles");
  if (wall.cells.size() &&
      (wall.cells.minCoeff() < 0 || wall.cells.maxCoeff() >= wall.vertices.rows()))
    input_error("'{}': {} refers to vertices outside [0, {})", reader.path().string(), cells,
                wall.vertices.rows());
  return wall;
}

}  // namespace hm::driver
