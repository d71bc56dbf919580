#include "driver/wall_io.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/errors.hpp"
#include "driver/length_unit.hpp"
#include "io/schema.hpp"
#include "mesh/wall_mesher.hpp"

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

namespace {

Eigen::VectorXd primitive_vector(const io::SceneView& wall, const std::string& key) {
  const Eigen::VectorXd v = wall.vector(key);
  if (v.size() == 0)
    input_error("{}: {} is required for kind = \"{}\"", wall.file().string(), wall.full(key),
                wall.string("kind"));
  return v;
}

}  // namespace

void validate_scene_wall(const io::SceneView& wall, int dim) {
  const std::string kind = wall.string("kind");
  if ((kind == "rectangle" && dim != 2) || (kind == "box" && dim != 3))
    input_error("{}: kind = \"{}\" needs case.dimension = {}", wall.where("kind"), kind,
                kind == "rectangle" ? 2 : 3);
  if (kind == "file") {
    const std::filesystem::path file = wall.file_path("file");
    if (!std::filesystem::exists(file))
      input_error("{}: wall surface file '{}' does not exist", wall.where("file"), file.string());
    (void)file_length_scale(wall, "length_unit", file);
    return;
  }
  if (wall.string("length_unit") != "m")
    input_error(
        "{}: length_unit applies to a surface file (kind = \"file\"); a {} tank is "
        "given in metres",
        wall.where("length_unit"), kind);
  (void)primitive_vector(wall, "origin");
  if ((primitive_vector(wall, "size").array() <= 0).any())
    input_error("{}: every edge length must be > 0 m", wall.where("size"));
}

mesh::SurfaceMesh mesh_scene_wall(const io::SceneView& wall, int dim) {
  validate_scene_wall(wall, dim);
  mesh::WallOptions options;
  options.dim = dim;
  options.size = wall.number("mesh_size");
  options.faces = wall.strings("faces");
  options.flip_normals = wall.boolean("flip_normals");
  const std::string kind = wall.string("kind");
  if (kind == "rectangle")
    return mesh::mesh_rectangle_walls(
        {primitive_vector(wall, "origin"), primitive_vector(wall, "size")}, options);
  if (kind == "box")
    return mesh::mesh_box_walls({primitive_vector(wall, "origin"), primitive_vector(wall, "size")},
                                options);
  const std::filesystem::path file = wall.file_path("file");
  options.length_scale = file_length_scale(wall, "length_unit", file);
  options.length_unit_key = wall.full("length_unit");
  return mesh::mesh_wall_file(file, options);
}

}  // namespace hm::driver
