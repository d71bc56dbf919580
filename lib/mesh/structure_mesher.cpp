#include "mesh/structure_mesher.hpp"

#include <algorithm>
#include <cctype>
#include <functional>
#include <set>

#include <gmsh.h>
#include <spdlog/spdlog.h>

#include "core/errors.hpp"
#include "core/text.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/surface_checks.hpp"
#include "geometry/surface_io.hpp"
#include "mesh/boundary.hpp"
#include "mesh/gmsh_model.hpp"
#include "mesh/gmsh_session.hpp"
#include "mesh/groups.hpp"
#include "mesh/quality.hpp"
#include "mesh/size_estimate.hpp"

namespace hm::mesh {
namespace {

using gmsh_model::DimTag;

/// What differs between the sources once a gmsh model exists.
struct Source {
  std::string name;                   ///< for messages: the file, or "rectangle" / "box"
  std::function<void()> build_model;  ///< fills the gmsh model (inside the session)
  std::vector<BoxGroup> primitive_groups;
  bool size_required = true;
  bool straight_second_order = false;  ///< mid-edge nodes on straight edges (discrete surfaces)
  /// The solid's area (2-D) / volume (3-D) [m^dim] once the model is built, for the element
  /// estimate; empty: no estimate.
  std::function<double()> measure;
  bool from_file = false;  ///< a geometry file (whose length unit may be wrong)
};

void validate(const MeshOptions& o, const Source& s) {
  if (o.dim != 2 && o.dim != 3) input_error("{}: mesh dimension {} is not 2 or 3", s.name, o.dim);
  if (o.order != 2)
    input_error("{}: element order {} is not supported; structure meshes are quadratic (order 2)",
                s.name, o.order);
  if (!(o.size > 0.0) && (s.size_required || o.size != 0.0))
    input_error("{}: mesh size {} m is not positive", s.name, o.size);
  if (o.threads < 1) input_error("{}: gmsh threads {} must be ≥ 1", s.name, o.threads);
  for (const auto& [group, size] : o.group_sizes)
    if (!(size > 0.0))
      input_error("{}: mesh size {} m of group '{}' is not positive", s.name, size, group);
}

Eigen::Vector3d model_extent() {
  double x0, y0, z0, x1, y1, z1;
  gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
  return {x1 - x0, y1 - y0, z1 - z0};
}

double model_diagonal() {
  return model_extent().norm();
}

/// The bounding box's area (2-D) / volume (3-D): an upper bound of the solid's measure, for
/// models whose kernel cannot tell it (a .geo script of the built-in kernel).
double bounding_measure(int dim) {
  const Eigen::Vector3d extent = model_extent();
  return dim == 2 ? extent.x() * extent.y() : extent.prod();
}

/// OpenCASCADE's area (2-D) / volume (3-D) of the model's top-dimension entities.
double occ_measure(int dim) {
  gmsh::vectorpair entities;
  gmsh::model::getEntities(entities, dim);
  double sum = 0.0;
  for (const auto& [d, tag] : entities) {
    double mass = 0.0;
    gmsh::model::occ::getMass(d, tag, mass);
    sum += std::abs(mass);
  }
  return sum;
}

/// Refuses, before gmsh meshes, a mesh whose element estimate would not fit fsi-modes here.
void check_estimate(const MeshOptions& o, const Source& s) {
  if (!(o.size > 0.0) || !s.measure) return;
  check_structure_estimate(o.dim, s.measure(), o.size, model_extent(), s.from_file, s.name);
}

/// Geometry entities (of dimension < dim) a group name refers to, before meshing.
std::vector<DimTag> group_entities(const std::string& name, const std::vector<BoxGroup>& boxes,
                                   int dim, const std::string& source) {
  const auto physical = gmsh_model::physical_groups();
  std::vector<DimTag> entities;
  if (const auto it = physical.find(name); it != physical.end()) {
    for (const auto& [d, tag] : it->second) {
      std::vector<int> tags;
      gmsh::model::getEntitiesForPhysicalGroup(d, tag, tags);
      for (int t : tags) entities.emplace_back(d, t);
    }
    return entities;
  }
  const auto box =
      std::find_if(boxes.begin(), boxes.end(), [&](const BoxGroup& b) { return b.name == name; });
  if (box == boxes.end()) {
    std::vector<std::string> names;
    for (const auto& [n, dt] : physical) names.push_back(n);
    for (const auto& b : boxes) names.push_back(b.name);
    input_error(
        "{}: a mesh size is given for group '{}', which is neither a physical group nor a "
        "box group; groups: [{}]",
        source, name, join(names, ", "));
  }
  const double min[3] = {box->min.x(), box->min.y(), dim == 2 ? 0.0 : box->min.z()};
  const double max[3] = {box->max.x(), box->max.y(), dim == 2 ? 0.0 : box->max.z()};
  const double tolerance = box_group_tolerance * model_diagonal() + 1e-6;
  return gmsh_model::entities_in_box(min, max, tolerance, dim);
}

void apply_sizes(const MeshOptions& o, const std::vector<BoxGroup>& boxes, const Source& s) {
  if (o.size > 0.0) gmsh::option::setNumber("Mesh.MeshSizeMax", o.size);
  for (const auto& [group, size] : o.group_sizes) {
    if (o.size > 0.0 && size > o.size)
      spdlog::warn(
          "{}: mesh size {} m of group '{}' exceeds the global size {} m and has no effect", s.name,
          size, group, o.size);
    const auto points = gmsh_model::points_of(group_entities(group, boxes, o.dim, s.name));
    if (points.empty())
      input_error("{}: group '{}' (given a mesh size) holds no geometry point", s.name, group);
    gmsh::model::mesh::setSize(points, size);
  }
}

void check_model_dimension(int wanted, const std::string& source) {
  const int found = gmsh::model::getDimension();
  if (found != wanted)
    input_error(
        "{}: the geometry is {}-D (highest entity dimension {}), but a {}-D structure mesh "
        "was asked for",
        source, std::max(found, 0), found, wanted);
}

void generate(const MeshOptions& o, const Source& s) {
  gmsh::option::setNumber("Mesh.ElementOrder", 2);
  gmsh::option::setNumber("Mesh.SecondOrderLinear", s.straight_second_order ? 1 : 0);
  gmsh::model::mesh::generate(o.dim);
}

IndexMatrix to_matrix(const std::vector<std::size_t>& flat, int columns,
                      const gmsh_model::Numbering& numbering) {
  IndexMatrix m(static_cast<Index>(flat.size()) / columns, columns);
  for (std::size_t i = 0; i < flat.size(); ++i)
    m(static_cast<Index>(i) / columns, static_cast<Index>(i) % columns) =
        numbering.index.at(flat[i]);
  return m;
}

void reject_off_plane(const Coordinates& xyz, const std::string& source) {
  const double diagonal = geometry::bounding_box(xyz).diagonal();
  for (Index i = 0; i < xyz.rows(); ++i)
    if (std::abs(xyz(i, 2)) > 1e-12 * diagonal)
      input_error("{}: a 2-D structure must lie in the plane z = 0, but node ({}, {}, {}) does not",
                  source, xyz(i, 0), xyz(i, 1), xyz(i, 2));
}

StructureMesh read_cells(int dim, const std::string& source) {
  const int type = dim == 2 ? gmsh_model::tri6 : gmsh_model::tet10;
  const auto flat = gmsh_model::element_nodes(type);
  if (flat.empty())
    input_error("{}: gmsh produced no {} element; does the geometry hold a {}?", source,
                dim == 2 ? "tri6" : "tet10", dim == 2 ? "surface" : "closed volume");
  const auto numbering = gmsh_model::number_nodes(flat);
  StructureMesh m;
  m.dim = dim;
  m.cells = to_matrix(flat, m.nodes_per_cell(), numbering);
  const Coordinates xyz = gmsh_model::node_coordinates(numbering.tags, 3);
  if (dim == 2) reject_off_plane(xyz, source);
  m.nodes = xyz.leftCols(dim);
  return m;
}

/// Maps gmsh's facet elements of one entity onto our boundary facets (by corner key).
void add_facets_of_entity(int entity, const std::map<std::array<Index, 3>, Index>& facet_of_key,
                          const gmsh_model::Numbering& numbering, int dim,
                          std::vector<Index>& out) {
  const int type = dim == 2 ? gmsh_model::line3 : gmsh_model::tri6;
  const int per = dim == 2 ? 3 : 6;
  const auto flat = gmsh_model::element_nodes(type, entity);
  for (std::size_t e = 0; e + per <= flat.size(); e += per) {
    std::array<Index, 3> corners{};
    bool known = true;
    for (int k = 0; k < dim; ++k) {
      const auto it = numbering.index.find(flat[e + k]);
      known = known && it != numbering.index.end();
      if (known) corners[k] = it->second;
    }
    if (!known) continue;
    const auto it = facet_of_key.find(facet_key(corners, dim));
    if (it != facet_of_key.end()) out.push_back(it->second);  // interior surfaces are skipped
  }
}

void read_physical_groups(StructureMesh& m, const gmsh_model::Numbering& numbering) {
  std::map<std::array<Index, 3>, Index> facet_of_key;
  for (Index f = 0; f < m.facets.rows(); ++f)
    facet_of_key.emplace(
        facet_key({m.facets.row(f).data(), static_cast<std::size_t>(m.dim)}, m.dim), f);
  for (const auto& [name, dim_tags] : gmsh_model::physical_groups()) {
    std::set<Index> nodes;
    std::vector<Index> facets;
    for (const auto& [d, tag] : dim_tags) {
      std::vector<std::size_t> tags;
      std::vector<double> xyz;
      gmsh::model::mesh::getNodesForPhysicalGroup(d, tag, tags, xyz);
      for (std::size_t t : tags)
        if (const auto it = numbering.index.find(t); it != numbering.index.end())
          nodes.insert(it->second);
      if (d != m.dim - 1) continue;
      std::vector<int> entities;
      gmsh::model::getEntitiesForPhysicalGroup(d, tag, entities);
      for (int e : entities) add_facets_of_entity(e, facet_of_key, numbering, m.dim, facets);
    }
    m.node_groups[name].assign(nodes.begin(), nodes.end());
    if (!facets.empty()) {
      std::sort(facets.begin(), facets.end());
      facets.erase(std::unique(facets.begin(), facets.end()), facets.end());
      m.facet_groups[name] = std::move(facets);
    }
  }
}

StructureMesh read_structure(int dim, const std::string& source) {
  StructureMesh m = read_cells(dim, source);
  if (const Index flipped = orient_cells_positively(m); flipped > 0)
    spdlog::debug("{}: reordered {} negatively oriented cells", source, flipped);
  build_boundary_facets(m);
  // The node numbering of read_cells is first appearance in the cell list: rebuild it to map
  // gmsh tags of the physical groups.
  const int type = dim == 2 ? gmsh_model::tri6 : gmsh_model::tet10;
  read_physical_groups(m, gmsh_model::number_nodes(gmsh_model::element_nodes(type)));
  return m;
}

StructureMesh run(const Source& source, const MeshOptions& options) {
  validate(options, source);
  std::vector<BoxGroup> boxes = source.primitive_groups;
  boxes.insert(boxes.end(), options.box_groups.begin(), options.box_groups.end());
  StructureMesh mesh;
  {
    GmshSession session({options.threads, options.verbose});
    gmsh_call(source.name, [&] {
      source.build_model();
      check_model_dimension(options.dim, source.name);
      check_estimate(options, source);
      apply_sizes(options, boxes, source);
      generate(options, source);
      mesh = read_structure(options.dim, source.name);
    });
  }
  apply_box_groups(mesh, boxes, source.name);
  require_groups(mesh, options.required_groups, source.name);
  const MeshQuality quality = assess_quality(mesh, options.sliver_threshold);
  report_quality(quality, source.name);
  return mesh;
}

void require_file(const std::filesystem::path& path, std::string_view kind) {
  if (!std::filesystem::is_regular_file(path))
    input_error("{} file '{}' does not exist (or is not a regular file)", kind, path.string());
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void check_shape(const Eigen::VectorXd& size, std::string_view what) {
  if (!(size.array() > 0.0).all())
    input_error("{}: every side length must be positive, got ({})", what,
                fmt::join(size.data(), size.data() + size.size(), ", "));
}

/// Builds a gmsh model of one closed surface: a discrete surface entity with our triangles,
/// classified into patches (40° feature angle), reparametrised, and closed into a volume.
void build_volume_from_surface(const SurfaceMesh& surface) {
  const int entity = gmsh::model::addDiscreteEntity(2);
  std::vector<std::size_t> tags(static_cast<std::size_t>(surface.vertices.rows()));
  std::vector<double> xyz;
  for (Index v = 0; v < surface.vertices.rows(); ++v) {
    tags[static_cast<std::size_t>(v)] = static_cast<std::size_t>(v + 1);
    for (int k = 0; k < 3; ++k) xyz.push_back(surface.vertices(v, k));
  }
  gmsh::model::mesh::addNodes(2, entity, tags, xyz);
  std::vector<std::size_t> triangles;
  for (Index c = 0; c < surface.cells.rows(); ++c)
    for (int k = 0; k < 3; ++k)
      triangles.push_back(static_cast<std::size_t>(surface.cells(c, k) + 1));
  gmsh::model::mesh::addElementsByType(entity, gmsh_model::tri3, {}, triangles);
  constexpr double feature_angle = 40.0 * 3.14159265358979323846 / 180.0;
  gmsh::model::mesh::classifySurfaces(feature_angle, true, false, 3.14159265358979323846);
  gmsh::model::mesh::createGeometry();
  gmsh::vectorpair surfaces;
  gmsh::model::getEntities(surfaces, 2);
  std::vector<int> surface_tags;
  for (const auto& s : surfaces) surface_tags.push_back(s.second);
  const int loop = gmsh::model::geo::addSurfaceLoop(surface_tags);
  gmsh::model::geo::addVolume({loop});
  gmsh::model::geo::synchronize();
}

}  // namespace

StructureMesh mesh_rectangle(const RectangleShape& r, const MeshOptions& options) {
  check_shape(r.size, "rectangle");
  Source s{"rectangle",
           [&] {
             gmsh::model::occ::addRectangle(r.origin.x(), r.origin.y(), 0.0, r.size.x(),
                                            r.size.y());
             gmsh::model::occ::synchronize();
           },
           primitive_face_groups(r)};
  s.measure = [&] { return r.size.prod(); };
  return run(s, options);
}

StructureMesh mesh_box(const BoxShape& b, const MeshOptions& options) {
  check_shape(b.size, "box");
  Source s{"box",
           [&] {
             gmsh::model::occ::addBox(b.origin.x(), b.origin.y(), b.origin.z(), b.size.x(),
                                      b.size.y(), b.size.z());
             gmsh::model::occ::synchronize();
           },
           primitive_face_groups(b)};
  s.measure = [&] { return b.size.prod(); };
  return run(s, options);
}

StructureMesh mesh_geo_file(const std::filesystem::path& path, const MeshOptions& options) {
  require_file(path, "gmsh script");
  if (options.length_scale != 1.0)
    input_error(
        "gmsh script '{}': its lengths are metres; a length scale of {} cannot apply "
        "(scale the geometry in the script with Dilate)",
        path.string(), options.length_scale);
  Source s{path.string(), [&] { gmsh::open(path.string()); }, {}, false};
  s.measure = [&] { return bounding_measure(options.dim); };
  s.from_file = true;
  return run(s, options);
}

StructureMesh mesh_cad_file(const std::filesystem::path& path, const MeshOptions& options) {
  require_file(path, "CAD");
  Source s{path.string(),
           [&] {
             gmsh::vectorpair shapes;
             gmsh::option::setNumber("Geometry.OCCScaling", options.length_scale);
             gmsh::model::occ::importShapes(path.string(), shapes);
             gmsh::model::occ::synchronize();
             if (shapes.empty()) input_error("CAD file '{}' holds no shape", path.string());
           },
           {}};
  s.measure = [&] { return occ_measure(options.dim); };
  s.from_file = true;
  return run(s, options);
}

StructureMesh mesh_closed_surface(SurfaceMesh surface, const MeshOptions& options,
                                  std::string_view source) {
  if (options.dim != 3)
    input_error("{}: a closed triangle surface bounds a 3-D solid; mesh dimension {} was asked",
                source, options.dim);
  const geometry::SurfaceCheckReport report = geometry::check_closed_surface(surface, source);
  Source s{std::string(source), [&] { build_volume_from_surface(surface); }, {}, true, true};
  s.measure = [&] { return report.enclosed_volume; };
  s.from_file = true;
  return run(s, options);
}

StructureMesh mesh_surface_file(const std::filesystem::path& path, const MeshOptions& options) {
  SurfaceMesh surface = geometry::read_surface_file(path);
  surface.vertices *= options.length_scale;
  return mesh_closed_surface(std::move(surface), options, path.string());
}

StructureMesh mesh_geometry_file(const std::filesystem::path& path, const MeshOptions& options) {
  const std::string ext = lower_extension(path);
  if (ext == ".geo") return mesh_geo_file(path, options);
  if (ext == ".step" || ext == ".stp" || ext == ".brep" || ext == ".brp" || ext == ".iges" ||
      ext == ".igs")
    return mesh_cad_file(path, options);
  if (ext == ".stl" || ext == ".obj" || ext == ".ply") return mesh_surface_file(path, options);
  input_error(
      "geometry file '{}': extension '{}' is not supported; accepted: .geo, .step, .stp, "
      ".brep, .brp, .iges, .igs, .stl, .obj, .ply",
      path.string(), ext);
}

}  // namespace hm::mesh
