#include "driver/mesh_stage.hpp"

#include <ranges>
#include <set>

#include "core/errors.hpp"
#include "core/log.hpp"
#include "driver/length_unit.hpp"
#include "driver/structure_io.hpp"
#include "driver/wall_io.hpp"
#include "io/artefact.hpp"
#include "mesh/boundary.hpp"
#include "mesh/quality.hpp"
#include "mesh/structure_mesher.hpp"
#include "mesh/wall_mesher.hpp"

namespace hm::driver {
namespace {

void require_structure(const io::Scene& scene) {
  if (!scene.has("structure"))
    input_error(
        "{}: the scene has no [structure] section, so there is nothing for fsi-mesh to "
        "mesh (a rigid-only scene skips the structure stages)",
        scene.file().string());
}

Eigen::VectorXd primitive_vector(const io::Scene& scene, const std::string& key) {
  const Eigen::VectorXd v = scene.vector(key);
  if (v.size() == 0)
    input_error("{}: {} is required for structure.geometry.kind = \"{}\" ({} values in m)",
                scene.file().string(), key, scene.string("structure.geometry.kind"),
                scene.dimension());
  return v;
}

void check_kind_matches_dimension(const io::Scene& scene) {
  const std::string kind = scene.string("structure.geometry.kind");
  const int dim = scene.dimension();
  if ((kind == "rectangle" && dim != 2) || (kind == "box" && dim != 3))
    input_error("{}: structure.geometry.kind = \"{}\" needs case.dimension = {}, the scene has {}",
                scene.where("structure.geometry.kind"), kind, kind == "rectangle" ? 2 : 3, dim);
  if (kind == "file" && scene.string("structure.geometry.file").empty())
    input_error("{}: structure.geometry.file is required for structure.geometry.kind = \"file\"",
                scene.file().string());
  if (kind == "file" && !std::filesystem::exists(scene.file_path("structure.geometry.file")))
    input_error("{}: geometry file '{}' does not exist", scene.where("structure.geometry.file"),
                scene.file_path("structure.geometry.file").string());
}

/// Metres per unit of the structure's geometry file; a primitive is in metres.
double structure_length_scale(const io::Scene& scene) {
  const std::string kind = scene.string("structure.geometry.kind");
  if (kind == "file")
    return file_length_scale(scene, "structure.geometry.length_unit",
                             scene.file_path("structure.geometry.file"));
  if (scene.string("structure.geometry.length_unit") != "m")
    input_error(
        "{}: length_unit applies to a geometry file (kind = \"file\"); a {} is given in "
        "metres",
        scene.where("structure.geometry.length_unit"), kind);
  return 1.0;
}

mesh::StructureMesh mesh_structure(const io::Scene& scene, const mesh::MeshOptions& options) {
  const std::string kind = scene.string("structure.geometry.kind");
  if (kind == "rectangle") {
    mesh::RectangleShape rectangle{primitive_vector(scene, "structure.geometry.origin"),
                                   primitive_vector(scene, "structure.geometry.size")};
    return mesh::mesh_rectangle(rectangle, options);
  }
  if (kind == "box") {
    mesh::BoxShape box{primitive_vector(scene, "structure.geometry.origin"),
                       primitive_vector(scene, "structure.geometry.size")};
    return mesh::mesh_box(box, options);
  }
  return mesh::mesh_geometry_file(scene.file_path("structure.geometry.file"), options);
}

Eigen::VectorXd cell_qualities(const mesh::StructureMesh& m) {
  Eigen::VectorXd q(m.cells.rows());
  for (Eigen::Index c = 0; c < m.cells.rows(); ++c) q[c] = mesh::cell_quality(m, c);
  return q;
}

std::vector<io::InputRecord> mesh_inputs(const io::Scene& scene) {
  std::vector<io::InputRecord> inputs{io::input_record("scene", scene.file())};
  if (scene.string("structure.geometry.kind") == "file")
    inputs.push_back(io::input_record("geometry", scene.file_path("structure.geometry.file")));
  for (const auto& wall : scene.array("wall"))
    if (wall.string("kind") == "file")
      inputs.push_back(io::input_record("wall:" + wall.string("name"), wall.file_path("file")));
  return inputs;
}

std::map<std::string, mesh::SurfaceMesh> write_walls(io::ArtefactWriter& writer,
                                                     const io::Scene& scene) {
  std::map<std::string, mesh::SurfaceMesh> walls;
  for (const auto& wall : scene.array("wall")) {
    const mesh::SurfaceMesh& surface = walls[wall.string("name")] =
        mesh_scene_wall(wall, scene.dimension());
    const std::string prefix = io::ds::walls + wall.string("name");
    writer.write(prefix + "/vertices", io::MatrixRM(surface.vertices));
    writer.write(prefix + "/cells", io::IndexMatrixRM(surface.cells));
    spdlog::info("fsi-mesh: wall '{}': {} vertices, {} {}", wall.string("name"),
                 surface.vertices.rows(), surface.cells.rows(),
                 surface.dim == 2 ? "segments" : "triangles");
  }
  return walls;
}

}  // namespace

mesh::MeshOptions mesh_options_from_scene(const io::Scene& scene) {
  require_structure(scene);
  mesh::MeshOptions options;
  options.dim = scene.dimension();
  options.size = scene.number("structure.mesh.size");
  options.sliver_threshold = scene.number("structure.mesh.min_quality");
  options.length_scale = structure_length_scale(scene);
  for (const auto& group : scene.array("structure.group")) {
    mesh::BoxGroup box{group.string("name"), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    box.min.head(options.dim) = group.vector("min");
    box.max.head(options.dim) = group.vector("max");
    if ((box.max.array() < box.min.array()).any())
      input_error("{}: the group box has max < min in some coordinate", group.where("max"));
    options.box_groups.push_back(box);
  }
  for (const auto& refine : scene.array("structure.refine"))
    options.group_sizes[refine.string("group")] = refine.number("size");
  if (const std::string clamped = scene.string("structure.clamped"); !clamped.empty())
    options.required_groups.push_back(clamped);
  return options;
}

void validate_mesh_scene(const io::Scene& scene) {
  (void)mesh_options_from_scene(scene);
  std::set<std::string> wall_names;
  for (const auto& wall : scene.array("wall")) {
    validate_scene_wall(wall, scene.dimension());
    if (!wall_names.insert(wall.string("name")).second)
      input_error("{}: a wall named '{}' is already declared", wall.where("name"),
                  wall.string("name"));
  }
  check_kind_matches_dimension(scene);
  const std::string kind = scene.string("structure.geometry.kind");
  if (kind != "file") {
    primitive_vector(scene, "structure.geometry.origin");
    const Eigen::VectorXd size = primitive_vector(scene, "structure.geometry.size");
    if ((size.array() <= 0).any())
      input_error("{}: every edge length must be > 0 m", scene.where("structure.geometry.size"));
  }
}

void run_mesh_stage(const io::Scene& scene, const std::filesystem::path& output) {
  validate_mesh_scene(scene);
  const mesh::MeshOptions options = mesh_options_from_scene(scene);
  const std::vector<io::InputRecord> inputs = mesh_inputs(scene);
  const mesh::StructureMesh structure = mesh_structure(scene, options);
  const mesh::BoundarySurface surface =
      mesh::extract_boundary_surface(structure, mesh::SurfaceSplit::refined);
  const Eigen::VectorXd quality = cell_qualities(structure);
  io::ArtefactWriter writer(output, io::mesh_schema(), "fsi-mesh", scene.parameters_for("fsi-mesh"),
                            inputs);
  write_structure_mesh(writer, structure, surface, quality);
  const auto walls = write_walls(writer, scene);
  writer.set_attribute("quality_min", quality.size() ? quality.minCoeff() : 0.0);
  writer.set_attribute("quality_mean", quality.size() ? quality.mean() : 0.0);
  writer.commit();
  write_mesh_xdmf(output, structure, walls);
  spdlog::info("fsi-mesh: wrote {} ({} nodes, {} {} cells, {} boundary facets, groups: {})",
               output.string(), structure.node_count(), structure.cells.rows(),
               structure.dim == 2 ? "tri6" : "tet10", structure.facets.rows(),
               fmt::join(std::views::keys(structure.node_groups), ", "));
}

}  // namespace hm::driver
