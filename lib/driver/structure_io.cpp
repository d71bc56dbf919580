#include "driver/structure_io.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/errors.hpp"
#include "io/xdmf.hpp"

namespace hm::driver {

namespace ds = io::ds;

mesh::IndexMatrix cells_in_vtk_order(const mesh::StructureMesh& mesh) {
  mesh::IndexMatrix cells = mesh.cells;
  if (mesh.dim == 3) cells.col(8).swap(cells.col(9));
  return cells;
}

void write_structure_mesh(io::ArtefactWriter& writer, const mesh::StructureMesh& mesh,
                          const mesh::BoundarySurface& surface, const Eigen::VectorXd& quality) {
  writer.write(ds::structure_nodes, io::MatrixRM(mesh.nodes));
  writer.write(ds::structure_cells, io::IndexMatrixRM(mesh.cells));
  if (mesh.dim == 3)
    writer.write(ds::structure_cells_vtk, io::IndexMatrixRM(cells_in_vtk_order(mesh)));
  writer.write(ds::structure_facets, io::IndexMatrixRM(mesh.facets));
  for (const auto& [name, nodes] : mesh.node_groups)
    writer.write(ds::structure_node_groups + name, nodes);
  for (const auto& [name, facets] : mesh.facet_groups)
    writer.write(ds::structure_facet_groups + name, facets);
  writer.write(ds::structure_surface_vertices, io::MatrixRM(surface.surface.vertices));
  writer.write(ds::structure_surface_cells, io::IndexMatrixRM(surface.surface.cells));
  writer.write(ds::structure_surface_node, surface.volume_node);
  writer.write_vector(ds::structure_quality, quality);
}

MeshArtefact read_structure_mesh(const io::ArtefactReader& reader) {
  MeshArtefact out;
  mesh::StructureMesh& m = out.structure;
  m.nodes = reader.read_matrix(ds::structure_nodes);
  m.dim = static_cast<int>(m.nodes.cols());
  m.cells = reader.read_indices(ds::structure_cells);
  m.facets = reader.read_indices(ds::structure_facets);
  if (m.dim != 2 && m.dim != 3)
    input_error("'{}': {} has {} columns; expected 2 or 3 coordinates", reader.path().string(),
                ds::structure_nodes, m.dim);
  if (m.cells.cols() != m.nodes_per_cell())
    input_error("'{}': {} has {} nodes per cell; a {}-D structure needs {} ({})",
                reader.path().string(), ds::structure_cells, m.cells.cols(), m.dim,
                m.nodes_per_cell(), m.dim == 2 ? "tri6" : "tet10");
  if (m.cells.size() && (m.cells.minCoeff() < 0 || m.cells.maxCoeff() >= m.node_count()))
    input_error("'{}': {} refers to nodes outside [0, {})", reader.path().string(),
                ds::structure_cells, m.node_count());
  const std::string node_groups(ds::structure_node_groups),
      facet_groups(ds::structure_facet_groups);
  for (const auto& name : reader.children(node_groups.substr(0, node_groups.size() - 1)))
    m.node_groups[name] = reader.read_index_values(node_groups + name);
  for (const auto& name : reader.children(facet_groups.substr(0, facet_groups.size() - 1)))
    m.facet_groups[name] = reader.read_index_values(facet_groups + name);
  out.surface.surface.dim = m.dim;
  out.surface.surface.vertices = reader.read_matrix(ds::structure_surface_vertices);
  out.surface.surface.cells = reader.read_indices(ds::structure_surface_cells);
  out.surface.volume_node = reader.read_index_values(ds::structure_surface_node);
  return out;
}

void write_mesh_xdmf(const std::filesystem::path& h5_path, const mesh::StructureMesh& mesh,
                     const std::map<std::string, mesh::SurfaceMesh>& walls) {
  const auto cells = static_cast<std::uint64_t>(mesh.cells.rows());
  io::XdmfGrid grid{.name = "structure",
                    .dim = mesh.dim,
                    .topology = mesh.dim == 2 ? "Tri_6" : "Tet_10",
                    .cells_dataset = mesh.dim == 2 ? ds::structure_cells : ds::structure_cells_vtk,
                    .cells = cells,
                    .nodes_per_cell = static_cast<std::uint64_t>(mesh.nodes_per_cell()),
                    .nodes_dataset = ds::structure_nodes,
                    .nodes = static_cast<std::uint64_t>(mesh.node_count()),
                    .fields = {{"quality", false, ds::structure_quality, {cells}, -1}}};
  std::vector<io::XdmfGrid> grids{grid};
  for (const auto& [name, wall] : walls) {
    const std::string prefix = io::ds::walls + name;
    grids.push_back({.name = "wall_" + name,
                     .dim = wall.dim,
                     .topology = wall.dim == 2 ? "Polyline" : "Triangle",
                     .cells_dataset = prefix + "/cells",
                     .cells = static_cast<std::uint64_t>(wall.cells.rows()),
                     .nodes_per_cell = static_cast<std::uint64_t>(wall.dim),
                     .nodes_dataset = prefix + "/vertices",
                     .nodes = static_cast<std::uint64_t>(wall.vertices.rows()),
                     .fields = {}});
  }
  io::write_xdmf(std::filesystem::path(h5_path).replace_extension(".xdmf"), h5_path, grids);
}

modal::ModeSet read_mode_set(const io::ArtefactReader& reader) {
  namespace ds = io::ds;
  modal::ModeSet m;
  m.eigenvalues = reader.read_vector(ds::eigenvalues);
  m.omega = reader.read_vector(ds::omega);
  m.frequency_hz = reader.read_vector(ds::frequencies_hz);
  m.damping_ratio = reader.read_vector(ds::damping_ratio);
  const io::Dims dims = reader.dims(ds::shapes);  // n_modes × n_nodes × dim
  HM_ASSERT(dims.size() == 3, "{}: {} has rank {}", reader.path().string(), ds::shapes,
            dims.size());
  m.dim = static_cast<int>(dims[2]);
  m.shapes = reader.read_columns(ds::shapes);
  return m;
}

std::optional<fem::ReducedStvk> read_reduced_model(const io::ArtefactReader& reader) {
  const std::vector<const char*> parts{ds::basis_vectors, ds::reduced_mass, ds::reduced_linear,
                                       ds::reduced_quadratic, ds::reduced_cubic};
  const auto present = std::count_if(parts.begin(), parts.end(),
                                     [&](const char* dataset) { return reader.has(dataset); });
  if (present == 0) return std::nullopt;
  if (present < static_cast<std::ptrdiff_t>(parts.size()))
    input_error("'{}' holds part of a reduced model ({} of the datasets {}): rerun fsi-modes",
                reader.path().string(), present, fmt::join(parts, ", "));
  const auto matrix = [&](const char* dataset) {
    return Eigen::MatrixXd(reader.read_matrix(dataset));
  };
  return fem::ReducedStvk(reader.read_columns(ds::basis_vectors), matrix(ds::reduced_mass),
                          matrix(ds::reduced_linear), matrix(ds::reduced_quadratic),
                          matrix(ds::reduced_cubic), reader.path().string());
}

fem::ElasticModel elastic_model(const io::Scene& scene) {
  fem::ElasticModel model;
  model.material = {scene.number("structure.material.youngs_modulus"),
                    scene.number("structure.material.poisson_ratio"),
                    scene.number("structure.material.density")};
  model.plane = scene.string("structure.formulation") == "plane_stress"
                    ? fem::PlaneAssumption::plane_stress
                    : fem::PlaneAssumption::plane_strain;
  model.thickness_m = scene.number("structure.thickness");
  return model;
}

std::vector<std::string> clamped_groups(const io::Scene& scene) {
  const std::string clamped = scene.string("structure.clamped");
  return clamped.empty() ? std::vector<std::string>{} : std::vector<std::string>{clamped};
}

}  // namespace hm::driver
