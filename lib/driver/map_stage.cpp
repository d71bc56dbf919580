#include "driver/map_stage.hpp"

#include <array>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/log.hpp"
#include "driver/length_unit.hpp"
#include "geometry/surface_checks.hpp"
#include "geometry/surface_io.hpp"
#include "io/artefact.hpp"
#include "io/xdmf.hpp"
#include "mesh/wall_mesher.hpp"
#include "rbf/interpolator.hpp"

namespace hm::driver {
namespace {

namespace ds = io::ds;

/// A mode set's reduced basis (modes.derivatives): mapped like the modes, for
/// structure.model = "nonlinear_modal".
struct SourceBasis {
  Eigen::MatrixXd vectors;  ///< n_surface_vertices·dim × n_basis
  io::IndexMatrixRM origin;
  Eigen::VectorXd omega;
  io::MatrixRM participation_translation, participation_rotation;
};

/// What fsi-map takes from a mode artefact.
struct SourceModes {
  mesh::SurfaceMesh surface;
  Eigen::MatrixXd shapes;  ///< n_surface_vertices·dim × n_modes (DOF = dim·vertex + c)
  Eigen::VectorXd frequencies_hz, omega, damping_ratio;
  io::MatrixRM participation_translation, participation_rotation;
  std::optional<SourceBasis> basis;  ///< none in a set without modes.derivatives
};

std::optional<SourceBasis> read_source_basis(const io::ArtefactReader& r) {
  if (!r.has(ds::basis_surface_vectors)) return std::nullopt;
  SourceBasis b;
  b.vectors = r.read_columns(ds::basis_surface_vectors);  // [vector][vertex][c]
  b.origin = r.read_indices(ds::basis_origin);
  b.omega = r.read_vector(ds::basis_omega);
  b.participation_translation = r.read_matrix(ds::basis_participation_translation);
  b.participation_rotation = r.read_matrix(ds::basis_participation_rotation);
  return b;
}

SourceModes read_source_modes(const io::ArtefactReader& r) {
  SourceModes s;
  s.surface.vertices = r.read_matrix(ds::modes_surface_vertices);
  s.surface.dim = static_cast<int>(s.surface.vertices.cols());
  s.surface.cells = r.read_indices(ds::modes_surface_cells);
  s.shapes = r.read_columns(ds::surface_shapes);  // [mode][vertex][c]
  s.frequencies_hz = r.read_vector(ds::frequencies_hz);
  s.omega = r.read_vector(ds::omega);
  s.damping_ratio = r.read_vector(ds::damping_ratio);
  s.participation_translation = r.read_matrix(ds::participation_translation);
  s.participation_rotation = r.read_matrix(ds::participation_rotation);
  s.basis = read_source_basis(r);
  return s;
}

/// map.file: a surface mesh (.stl, .obj, .ply) as read, or a gmsh script (.geo) meshed as a
/// wall at map.mesh_size, its curves (2-D) or surfaces (3-D) oriented with the fluid on their
/// normal side — the wetted outside of the structure only, at the fluid's spacing (a structure
/// mesh fine enough for thin plates has a boundary far finer than the fluid needs).
mesh::SurfaceMesh read_target_file(const io::Scene& scene) {
  const std::filesystem::path file = scene.file_path("map.file");
  const double scale = file_length_scale(scene, "map.length_unit", file);
  if (file.extension() != ".geo") {
    mesh::SurfaceMesh surface = geometry::read_surface_file(file);
    surface.vertices *= scale;
    return surface;
  }
  mesh::WallOptions o;
  o.dim = scene.dimension();
  o.size = scene.number("map.mesh_size");
  if (!(o.size > 0))
    input_error(
        "{}: a .geo target ({}) is meshed at map.mesh_size; give it in metres (> 0), "
        "e.g. half the fluid's dx",
        scene.where("map.mesh_size"), file.string());
  return mesh::mesh_wall_file(file, o);
}

mesh::SurfaceMesh target_surface(const io::Scene& scene, const SourceModes& source) {
  mesh::SurfaceMesh target = source.surface;
  if (scene.string("map.target") == "file") {
    target = read_target_file(scene);
    if (target.dim != source.surface.dim)
      input_error("{}: the target surface is {}-D but the structure is {}-D",
                  scene.where("map.file"), target.dim, source.surface.dim);
  }
  if (const double max_edge = scene.number("map.max_edge"); max_edge > 0)
    target = geometry::refine_uniformly(target, max_edge);
  return target;
}

/// Per-vertex blocks: n_vertices × dim matrix of one field from the DOF-stacked column.
Eigen::MatrixXd vertex_rows(const Eigen::VectorXd& column, int dim) {
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      column.data(), column.size() / dim, dim);
}

/// Consistent map of every mode: each displacement component is a scalar field on the points.
/// Returns [n_modes, n_target, dim] row-major.
io::MatrixRM map_modes(const rbf::RbfInterpolator& map, const Eigen::MatrixXd& shapes, int dim,
                       Eigen::MatrixXd& component_fields) {
  const Eigen::Index n_modes = shapes.cols(), n_source = map.source_count();
  component_fields.resize(n_source, n_modes * dim);  // column m·dim + c
  for (Eigen::Index m = 0; m < n_modes; ++m)
    component_fields.middleCols(m * dim, dim) = vertex_rows(shapes.col(m), dim);
  const Eigen::MatrixXd mapped = map.apply(component_fields);  // n_target × (n_modes·dim)
  io::MatrixRM out(n_modes, map.target_count() * dim);
  for (Eigen::Index m = 0; m < n_modes; ++m)
    for (Eigen::Index t = 0; t < map.target_count(); ++t)
      for (int c = 0; c < dim; ++c) out(m, t * dim + c) = mapped(t, m * dim + c);
  return out;
}

/// Leave-some-out error of each mode: the worst of its components.
Eigen::VectorXd mode_errors(const rbf::QualityReport& q, Eigen::Index n_modes, int dim) {
  Eigen::VectorXd e(n_modes);
  for (Eigen::Index m = 0; m < n_modes; ++m) e[m] = q.field_error.segment(m * dim, dim).maxCoeff();
  return e;
}

/// When every target vertex is a source node (map.target = "surface" without map.max_edge:
/// the map is the identity there), the interpolation error of each mode measured at the targets:
/// max |mapped − source| over the target vertices and components, over max |source|. The RBF
/// interpolant is exact at its nodes, so this is round-off; the leave-some-out estimate (every
/// 10th node left out, 3–8 % on the gate) describes another map. Empty when a target vertex is
/// not a source node.
std::optional<Eigen::VectorXd> errors_at_source_nodes(const mesh::SurfaceMesh& source,
                                                      const mesh::SurfaceMesh& target,
                                                      const Eigen::MatrixXd& source_shapes,
                                                      const io::MatrixRM& mapped, int dim) {
  std::map<std::array<double, 3>, Eigen::Index> node_at;
  auto key = [](const auto& row) {
    std::array<double, 3> k{0.0, 0.0, 0.0};
    for (Eigen::Index c = 0; c < row.size(); ++c) k[static_cast<std::size_t>(c)] = row[c];
    return k;
  };
  for (Eigen::Index v = 0; v < source.vertices.rows(); ++v)
    node_at.emplace(key(source.vertices.row(v)), v);
  std::vector<Eigen::Index> node(static_cast<std::size_t>(target.vertices.rows()));
  for (Eigen::Index t = 0; t < target.vertices.rows(); ++t) {
    const auto it = node_at.find(key(target.vertices.row(t)));
    if (it == node_at.end()) return std::nullopt;
    node[static_cast<std::size_t>(t)] = it->second;
  }
  Eigen::VectorXd errors(source_shapes.cols());
  for (Eigen::Index m = 0; m < source_shapes.cols(); ++m) {
    double worst = 0.0;
    for (Eigen::Index t = 0; t < target.vertices.rows(); ++t)
      for (int c = 0; c < dim; ++c)
        worst = std::max(worst,
                         std::abs(mapped(m, t * dim + c) -
                                  source_shapes(node[static_cast<std::size_t>(t)] * dim + c, m)));
    const double scale = source_shapes.col(m).cwiseAbs().maxCoeff();
    errors[m] = scale > 0.0 ? worst / scale : worst;
  }
  return errors;
}

void check_far_targets(const rbf::QualityReport& q, const mesh::SurfaceMesh& target,
                       const io::Scene& scene) {
  if (q.far_targets == 0) return;
  const auto worst = target.vertices.row(q.worst_target);
  input_error(
      "{}: {} of {} target vertices lie farther than {:.3g} m ({} source spacings) from the "
      "structure's surface nodes; the worst, vertex {} at ({}), is {:.3g} m away. Is the "
      "target surface the structure's wetted surface, in metres?",
      scene.file().string(), q.far_targets, target.vertices.rows(), q.far_tolerance,
      scene.number("map.far_factor"), q.worst_target, fmt::join(worst, ", "),
      q.worst_target_distance);
}

void write_mapped(io::ArtefactWriter& w, const mesh::SurfaceMesh& target,
                  const io::MatrixRM& shapes, const SourceModes& s, const Eigen::VectorXd& errors,
                  const rbf::QualityReport& q) {
  const auto n_modes = static_cast<std::uint64_t>(s.shapes.cols());
  w.write(ds::target_vertices, io::MatrixRM(target.vertices));
  w.write(ds::target_cells, io::IndexMatrixRM(target.cells));
  w.write(ds::mapped_shapes, shapes.data(),
          {n_modes, static_cast<std::uint64_t>(target.vertices.rows()),
           static_cast<std::uint64_t>(target.dim)});
  w.write_vector(ds::frequencies_hz, s.frequencies_hz);
  w.write_vector(ds::omega, s.omega);
  w.write_vector(ds::damping_ratio, s.damping_ratio);
  w.write(ds::participation_translation, s.participation_translation);
  w.write(ds::participation_rotation, s.participation_rotation);
  w.write_vector(ds::mapping_field_error, errors);
  w.set_attribute("support_radius_m", q.support_radius);
  w.set_attribute("source_spacing_m", q.source_spacing);
  w.set_attribute("far_tolerance_m", q.far_tolerance);
  w.set_attribute("worst_target_distance_m", q.worst_target_distance);
  w.set_attribute("condition_estimate", q.condition_estimate);
  w.set_attribute("polynomial_terms", static_cast<std::int64_t>(q.polynomial_terms));
  w.set_attribute("dropped_directions", static_cast<std::int64_t>(q.dropped_directions));
  w.set_attribute("mean_neighbours", q.mean_neighbours);
}

/// The mapped basis and its data beside the mapped modes.
void write_mapped_basis(io::ArtefactWriter& w, const mesh::SurfaceMesh& target,
                        const io::MatrixRM& vectors, const SourceBasis& b,
                        const Eigen::VectorXd& errors) {
  w.write(
      ds::mapped_basis, vectors.data(),
      {static_cast<std::uint64_t>(b.vectors.cols()),
       static_cast<std::uint64_t>(target.vertices.rows()), static_cast<std::uint64_t>(target.dim)});
  w.write(ds::basis_origin, b.origin);
  w.write_vector(ds::basis_omega, b.omega);
  w.write(ds::basis_participation_translation, b.participation_translation);
  w.write(ds::basis_participation_rotation, b.participation_rotation);
  w.write_vector(ds::mapped_basis_field_error, errors);
}

std::vector<io::InputRecord> map_inputs(const io::Scene& scene,
                                        const std::filesystem::path& modes) {
  std::vector<io::InputRecord> inputs{io::input_record("scene", scene.file()),
                                      io::input_record("modes", modes)};
  if (scene.string("map.target") == "file")
    inputs.push_back(io::input_record("target", scene.file_path("map.file")));
  return inputs;
}

void write_mapped_xdmf(const std::filesystem::path& h5, const mesh::SurfaceMesh& target,
                       Eigen::Index n_modes, Eigen::Index n_basis) {
  const auto n = static_cast<std::uint64_t>(target.vertices.rows());
  const auto dim = static_cast<std::uint64_t>(target.dim);
  io::XdmfGrid grid{.name = "mapped_modes",
                    .dim = target.dim,
                    .topology = target.dim == 2 ? "Polyline" : "Triangle",
                    .cells_dataset = ds::target_cells,
                    .cells = static_cast<std::uint64_t>(target.cells.rows()),
                    .nodes_per_cell = dim,
                    .nodes_dataset = ds::target_vertices,
                    .nodes = n,
                    .fields = {}};
  for (Eigen::Index m = 0; m < n_modes; ++m)
    grid.fields.push_back({fmt::format("mode_{}", m + 1),
                           true,
                           ds::mapped_shapes,
                           {static_cast<std::uint64_t>(n_modes), n, dim},
                           m});
  for (Eigen::Index k = 0; k < n_basis; ++k)
    grid.fields.push_back({fmt::format("basis_{}", k + 1),
                           true,
                           ds::mapped_basis,
                           {static_cast<std::uint64_t>(n_basis), n, dim},
                           k});
  io::write_xdmf(std::filesystem::path(h5).replace_extension(".xdmf"), h5, {grid});
}

}  // namespace

rbf::RbfOptions rbf_options(const io::Scene& scene) {
  rbf::RbfOptions o;
  o.support_factor = scene.number("map.support_factor");
  o.support_radius = scene.number("map.support_radius");
  o.far_factor = scene.number("map.far_factor");
  return o;
}

void validate_map_scene(const io::Scene& scene) {
  if (scene.string("map.target") != "file") return;
  if (scene.string("map.file").empty())
    input_error("{}: map.file is required for map.target = \"file\"", scene.file().string());
  if (!std::filesystem::exists(scene.file_path("map.file")))
    input_error("{}: target surface '{}' does not exist", scene.where("map.file"),
                scene.file_path("map.file").string());
}

void run_map_stage(const io::Scene& scene, const std::filesystem::path& modes_artefact,
                   const std::filesystem::path& output) {
  validate_map_scene(scene);
  const io::ArtefactReader reader(modes_artefact, io::modes_schema());
  const SourceModes source = read_source_modes(reader);
  const mesh::SurfaceMesh target = target_surface(scene, source);
  const int dim = source.surface.dim;
  const rbf::RbfInterpolator map(source.surface.vertices, target.vertices, rbf_options(scene));
  Eigen::MatrixXd component_fields;
  const io::MatrixRM shapes = map_modes(map, source.shapes, dim, component_fields);
  const rbf::QualityReport quality = map.quality_report(component_fields);
  check_far_targets(quality, target, scene);
  const std::optional<Eigen::VectorXd> measured =
      errors_at_source_nodes(source.surface, target, source.shapes, shapes, dim);
  const Eigen::VectorXd errors =
      measured ? *measured : mode_errors(quality, source.shapes.cols(), dim);
  const char* error_kind = measured ? "interpolation error measured at the targets (each a "
                                      "structure surface node: the map is the identity)"
                                    : "interpolation error estimate (leave-some-out)";
  // The reduced basis, by the same interpolation (the modes' shapes above stay as they were).
  io::MatrixRM basis;
  Eigen::VectorXd basis_errors;
  if (source.basis) {
    Eigen::MatrixXd basis_fields;
    basis = map_modes(map, source.basis->vectors, dim, basis_fields);
    const auto basis_measured =
        errors_at_source_nodes(source.surface, target, source.basis->vectors, basis, dim);
    basis_errors = basis_measured
                       ? *basis_measured
                       : mode_errors(map.quality_report(basis_fields), basis.rows(), dim);
  }

  io::ArtefactWriter writer(output, io::mapped_modes_schema(), "fsi-map",
                            scene.parameters_for("fsi-map"), map_inputs(scene, modes_artefact));
  write_mapped(writer, target, shapes, source, errors, quality);
  if (source.basis) write_mapped_basis(writer, target, basis, *source.basis, basis_errors);
  writer.commit();
  write_mapped_xdmf(output, target, source.shapes.cols(), basis.rows());
  spdlog::info(
      "fsi-map: {} modes from {} structure surface nodes onto {} target vertices; support "
      "radius {:.3g} m ({:.3g} spacings), condition estimate {:.3g}, {:.1f} neighbours per "
      "row, {} per mode: {:.2e}",
      source.shapes.cols(), source.surface.vertices.rows(), target.vertices.rows(),
      quality.support_radius, quality.support_radius / quality.source_spacing,
      quality.condition_estimate, quality.mean_neighbours, error_kind, fmt::join(errors, ", "));
  if (source.basis)
    spdlog::info(
        "fsi-map: the reduced basis, {} vectors (nonlinear_modal's interface); {} per vector: "
        "{:.2e}",
        basis.rows(), error_kind, fmt::join(basis_errors, ", "));
}

}  // namespace hm::driver
