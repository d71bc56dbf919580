#include "mesh/wall_mesher.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <functional>

#include <gmsh.h>
#include <spdlog/spdlog.h>

#include "core/errors.hpp"
#include "core/text.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/surface_checks.hpp"
#include "geometry/surface_io.hpp"
#include "mesh/gmsh_model.hpp"
#include "mesh/gmsh_session.hpp"
#include "mesh/groups.hpp"
#include "mesh/size_estimate.hpp"

namespace hm::mesh {
namespace {

using gmsh_model::DimTag;

void validate(const WallOptions& o, const std::string& source) {
  if (o.dim != 2 && o.dim != 3) input_error("{}: wall dimension {} is not 2 or 3", source, o.dim);
  if (!(o.size > 0.0)) input_error("{}: wall mesh size {} m is not positive", source, o.size);
  if (o.threads < 1) input_error("{}: gmsh threads {} must be ≥ 1", source, o.threads);
}

/// Reads the linear wall cells gmsh made on `entities`, numbering the nodes compactly.
SurfaceMesh read_walls(const std::vector<DimTag>& entities, int dim) {
  const int type = dim == 2 ? gmsh_model::line2 : gmsh_model::tri3;
  std::vector<std::size_t> flat;
  for (const auto& e : entities) {
    const auto nodes = gmsh_model::element_nodes(type, e.second);
    flat.insert(flat.end(), nodes.begin(), nodes.end());
  }
  const auto numbering = gmsh_model::number_nodes(flat);
  SurfaceMesh s;
  s.dim = dim;
  s.vertices = gmsh_model::node_coordinates(numbering.tags, dim);
  s.cells.resize(static_cast<Index>(flat.size()) / dim, dim);
  for (std::size_t i = 0; i < flat.size(); ++i)
    s.cells(static_cast<Index>(i) / dim, static_cast<Index>(i) % dim) = numbering.index.at(flat[i]);
  return s;
}

Eigen::Vector3d point(const SurfaceMesh& s, Index v) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  p.head(s.dim) = s.vertices.row(v).transpose();
  return p;
}

/// Orients every cell so that its normal points towards `inside` (a convex primitive's centre).
void orient_towards(SurfaceMesh& s, const Eigen::Vector3d& inside) {
  for (Index c = 0; c < s.cells.rows(); ++c) {
    const Eigen::Vector3d a = point(s, s.cells(c, 0)), b = point(s, s.cells(c, 1));
    Eigen::Vector3d normal, centroid;
    if (s.dim == 2) {
      normal = Eigen::Vector3d::UnitZ().cross(b - a);
      centroid = 0.5 * (a + b);
    } else {
      const Eigen::Vector3d d = point(s, s.cells(c, 2));
      normal = (b - a).cross(d - a);
      centroid = (a + b + d) / 3.0;
    }
    if (normal.dot(inside - centroid) < 0.0) std::swap(s.cells(c, 0), s.cells(c, 1));
  }
}

std::vector<BoxGroup> selected_faces(const std::vector<BoxGroup>& all, const WallOptions& o,
                                     const std::string& source) {
  if (o.faces.empty()) return all;
  std::vector<BoxGroup> chosen;
  std::vector<std::string> names;
  for (const auto& g : all) names.push_back(g.name);
  for (const auto& face : o.faces) {
    const auto it =
        std::find_if(all.begin(), all.end(), [&](const BoxGroup& g) { return g.name == face; });
    if (it == all.end())
      input_error("{}: wall face '{}' does not exist; faces: [{}]", source, face,
                  join(names, ", "));
    chosen.push_back(*it);
  }
  return chosen;
}

SurfaceMesh primitive_walls(const std::string& source, const WallOptions& o,
                            const std::function<void()>& build, const std::vector<BoxGroup>& faces,
                            const Eigen::Vector3d& centre, double diagonal) {
  validate(o, source);
  const auto chosen = selected_faces(faces, o, source);
  SurfaceMesh walls;
  {
    GmshSession session({o.threads, o.verbose});
    gmsh_call(source, [&] {
      build();
      gmsh::option::setNumber("Mesh.MeshSizeMax", o.size);
      gmsh::option::setNumber("Mesh.ElementOrder", 1);
      gmsh::model::mesh::generate(o.dim - 1);
      std::vector<DimTag> entities;
      const double tolerance = box_group_tolerance * diagonal + 1e-6;
      for (const auto& f : chosen) {
        const double min[3] = {f.min.x(), f.min.y(), f.min.z()};
        const double max[3] = {f.max.x(), f.max.y(), f.max.z()};
        for (const auto& e : gmsh_model::entities_in_box(min, max, tolerance, o.dim))
          if (e.first == o.dim - 1) entities.push_back(e);
      }
      walls = read_walls(entities, o.dim);
    });
  }
  orient_towards(walls, centre);
  if (o.flip_normals) geometry::reverse_cells(walls);
  return walls;
}

std::vector<DimTag> wall_entities_of_script(const WallOptions& o, const std::string& source) {
  gmsh::vectorpair all;
  gmsh::model::getEntities(all, o.dim - 1);
  if (o.faces.empty()) return all;
  const auto groups = gmsh_model::physical_groups();
  std::vector<DimTag> entities;
  for (const auto& name : o.faces) {
    const auto it = groups.find(name);
    std::vector<int> tags;
    if (it != groups.end())
      for (const auto& [d, tag] : it->second)
        if (d == o.dim - 1) {
          gmsh::model::getEntitiesForPhysicalGroup(d, tag, tags);
          for (int t : tags) entities.emplace_back(d, t);
        }
    if (it == groups.end() || tags.empty()) {
      std::vector<std::string> names;
      for (const auto& [n, dt] : groups) names.push_back(n);
      input_error(
          "{}: wall group '{}' is not a physical group of dimension {}; physical groups: [{}]",
          source, name, o.dim - 1, join(names, ", "));
    }
  }
  return entities;
}

SurfaceMesh script_walls(const std::filesystem::path& path, const WallOptions& o) {
  const std::string source = path.string();
  SurfaceMesh walls;
  GmshSession session({o.threads, o.verbose});
  gmsh_call(source, [&] {
    gmsh::open(source);
    gmsh::option::setNumber("Mesh.MeshSizeMax", o.size);
    gmsh::option::setNumber("Mesh.ElementOrder", 1);
    gmsh::model::mesh::generate(o.dim - 1);
    walls = read_walls(wall_entities_of_script(o, source), o.dim);
  });
  if (walls.cells.rows() == 0)
    input_error("{}: the script holds no {} to make walls of", source,
                o.dim == 3 ? "surface" : "curve");
  return walls;
}

SurfaceMesh triangle_file_walls(const std::filesystem::path& path, const WallOptions& o) {
  if (o.dim != 3)
    input_error("wall file '{}': triangle files give 3-D walls; dimension {} was asked",
                path.string(), o.dim);
  SurfaceMesh walls = geometry::read_surface_file(path);
  walls.vertices *= o.length_scale;
  check_wall_estimate(o.dim, geometry::refined_cell_count(walls, o.size), o.size,
                      geometry::bounding_box(walls.vertices).extent(), o.length_unit_key,
                      path.string());
  if (geometry::count_border_edges(walls) == 0) {
    geometry::check_closed_surface(walls, path.string());  // now outward
    geometry::reverse_cells(walls);                        // the fluid is inside
  }
  return geometry::refine_uniformly(walls, o.size);
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

SurfaceMesh mesh_rectangle_walls(const RectangleShape& r, const WallOptions& options) {
  if (options.dim != 2) input_error("rectangle walls: dimension {} is not 2", options.dim);
  const Eigen::Vector3d centre(r.origin.x() + 0.5 * r.size.x(), r.origin.y() + 0.5 * r.size.y(),
                               0.0);
  return primitive_walls(
      "rectangle walls", options,
      [&] {
        gmsh::model::occ::addRectangle(r.origin.x(), r.origin.y(), 0.0, r.size.x(), r.size.y());
        gmsh::model::occ::synchronize();
      },
      primitive_face_groups(r), centre, r.size.norm());
}

SurfaceMesh mesh_box_walls(const BoxShape& b, const WallOptions& options) {
  if (options.dim != 3) input_error("box walls: dimension {} is not 3", options.dim);
  return primitive_walls(
      "box walls", options,
      [&] {
        gmsh::model::occ::addBox(b.origin.x(), b.origin.y(), b.origin.z(), b.size.x(), b.size.y(),
                                 b.size.z());
        gmsh::model::occ::synchronize();
      },
      primitive_face_groups(b), b.origin + 0.5 * b.size, b.size.norm());
}

SurfaceMesh mesh_wall_file(const std::filesystem::path& path, const WallOptions& options) {
  validate(options, path.string());
  if (!std::filesystem::is_regular_file(path))
    input_error("wall geometry file '{}' does not exist (or is not a regular file)", path.string());
  const std::string ext = lower_extension(path);
  SurfaceMesh walls;
  if (ext == ".geo" && options.length_scale != 1.0)
    input_error(
        "gmsh script '{}': its lengths are metres; a length scale of {} cannot apply "
        "(scale the geometry in the script with Dilate)",
        path.string(), options.length_scale);
  if (ext == ".geo")
    walls = script_walls(path, options);
  else if (ext == ".stl" || ext == ".obj" || ext == ".ply")
    walls = triangle_file_walls(path, options);
  else
    input_error(
        "wall geometry file '{}': extension '{}' is not supported; accepted: .geo, .stl, "
        ".obj, .ply",
        path.string(), ext);
  if (options.flip_normals) geometry::reverse_cells(walls);
  geometry::report_extent(geometry::bounding_box(walls.vertices), path.string());
  return walls;
}

}  // namespace hm::mesh
