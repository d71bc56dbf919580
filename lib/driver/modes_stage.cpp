#include "driver/modes_stage.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <numbers>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/errors.hpp"
#include "core/log.hpp"
#include "core/progress.hpp"
#include "driver/structure_io.hpp"
#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"
#include "fem/hyperelastic_body.hpp"
#include "fem/reduced_basis.hpp"
#include "fem/reduced_stvk.hpp"
#include "io/artefact.hpp"
#include "io/atomic_file.hpp"
#include "io/xdmf.hpp"
#include "modal/eigen_solve.hpp"
#include "modal/modes.hpp"

namespace hm::driver {
namespace {

namespace ds = io::ds;

void require_structure(const io::Scene& scene) {
  if (!scene.has("structure"))
    input_error("{}: the scene has no [structure] section: a rigid-only scene needs no modes",
                scene.file().string());
}

modal::ModeRequest mode_request(const io::Scene& scene) {
  modal::ModeRequest request;
  request.count = static_cast<int>(scene.integer("modes.count"));
  if (const double f_max = scene.number("modes.max_frequency_hz"); f_max > 0) {
    request.max_frequency_hz = f_max;
    request.count = 0;
    request.context = "modes.max_frequency_hz";
  } else {
    request.context = "modes.count";
  }
  return request;
}

modal::EigenOptions eigen_options(const io::Scene& scene) {
  modal::EigenOptions options;
  const std::string solver = scene.string("modes.solver");
  options.backend = solver == "spectra" ? modal::EigenBackend::spectra
                    : solver == "dense" ? modal::EigenBackend::dense
                                        : modal::EigenBackend::arpack;
  options.lanczos.tolerance = scene.number("modes.tolerance");
  options.lanczos.max_restarts = static_cast<int>(scene.integer("modes.max_restarts"));
  return options;
}

modal::Damping damping(const io::Scene& scene) {
  modal::Damping d;
  const double zeta = scene.number("modes.damping_ratio");
  const Eigen::VectorXd ratios = scene.vector("modes.damping_ratios");
  const int given =
      (zeta > 0) + (ratios.size() > 0) +
      (scene.number("modes.rayleigh_alpha") > 0 || scene.number("modes.rayleigh_beta") > 0);
  if (given > 1)
    input_error(
        "{}: give one of modes.damping_ratio, modes.damping_ratios or "
        "modes.rayleigh_alpha/beta, not several",
        scene.file().string());
  if (ratios.size() > 0) {
    d.kind = modal::Damping::Kind::per_mode;
    d.ratios.assign(ratios.data(), ratios.data() + ratios.size());
    d.context = "modes.damping_ratios";
    return d;
  }
  const double alpha = scene.number("modes.rayleigh_alpha"),
               beta = scene.number("modes.rayleigh_beta");
  if (alpha > 0 || beta > 0) {
    d.kind = modal::Damping::Kind::rayleigh;
    d.alpha_per_s = alpha;
    d.beta_s = beta;
    d.context = "modes.rayleigh_alpha/beta";
  } else if (zeta > 0) {
    d.kind = modal::Damping::Kind::uniform;
    d.ratio = zeta;
    d.context = "modes.damping_ratio";
  }
  return d;
}

Eigen::Vector3d reference_point(const io::Scene& scene) {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  const Eigen::VectorXd given = scene.vector("modes.reference_point");
  if (given.size() > 0) point.head(given.size()) = given;
  return point;
}

/// [n_modes, n_nodes, dim] row-major from the n_dofs × n_modes shapes (DOF = dim·node + c).
io::MatrixRM stacked_shapes(const Eigen::MatrixXd& shapes) {
  return io::MatrixRM(shapes.transpose());
}

io::MatrixRM surface_shapes(const Eigen::MatrixXd& shapes,
                            const std::vector<mesh::Index>& volume_node, int dim) {
  io::MatrixRM out(shapes.cols(), static_cast<Eigen::Index>(volume_node.size()) * dim);
  for (Eigen::Index m = 0; m < shapes.cols(); ++m)
    for (std::size_t v = 0; v < volume_node.size(); ++v)
      for (int c = 0; c < dim; ++c)
        out(m, static_cast<Eigen::Index>(v) * dim + c) = shapes(volume_node[v] * dim + c, m);
  return out;
}

/// The reduced model of structure.model = "nonlinear_modal" (modes.derivatives): the basis of
/// the modes and their static modal derivatives, its Saint Venant–Kirchhoff tensors and its
/// participation factors.
struct ReducedModel {
  fem::ReducedBasis basis;
  std::optional<fem::ReducedStvk> tensors;
  Eigen::MatrixXd participation_translation, participation_rotation;  ///< VᵀMT, VᵀMR
  double derivatives_seconds = 0.0;  ///< the body, Θ and the orthonormalisation [s]
};

/// modes.derivative_modes as fem::BasisOptions::derivative_modes (−1: every mode); InputError
/// naming the key when the set has fewer modes.
int derivative_modes(const io::Scene& scene, int mode_count) {
  const auto k = static_cast<int>(scene.integer("modes.derivative_modes"));
  if (k > mode_count)
    input_error("{} = {}: the mode set has {} modes; give at most {} (0: every mode)",
                scene.where("modes.derivative_modes"), k, mode_count, mode_count);
  return k == 0 ? -1 : k;
}

/// V = [Φ, Θ] from the computed modes and its tensors with the scene's linear material (the
/// Lamé constants of E and ν) as a Saint Venant–Kirchhoff body.
ReducedModel reduced_model(const io::Scene& scene, const MeshArtefact& mesh,
                           const fem::DofMap& dofs, const fem::SystemMatrices& system,
                           const modal::ModeSet& modes) {
  const auto begin = std::chrono::steady_clock::now();
  const std::string context = scene.where("modes.derivatives");
  const fem::HyperelasticBody body(
      mesh.structure, {elastic_model(scene), fem::MaterialLaw::saint_venant_kirchhoff}, context);
  const fem::BasisOptions options{.modes = modes.count(),
                                  .derivatives = true,
                                  .derivative_modes = derivative_modes(scene, modes.count())};
  ReducedModel out;
  out.basis =
      fem::build_reduced_basis(body, dofs, {modes.shapes, modes.eigenvalues, 0}, options, context);
  out.derivatives_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  out.tensors.emplace(body, out.basis.vectors, context);
  const Eigen::MatrixXd vtm = out.basis.vectors.transpose() * system.mass;
  out.participation_translation = vtm * fem::rigid_translations(mesh.structure);
  out.participation_rotation = vtm * fem::rigid_rotations(mesh.structure, modes.reference_point);
  return out;
}

/// sqrt(K1_ii / M_r,ii) of every basis vector [rad/s].
Eigen::VectorXd basis_omega(const fem::ReducedStvk& tensors) {
  return (tensors.linear_stiffness().diagonal().array() / tensors.mass().diagonal().array())
      .cwiseMax(0.0)
      .sqrt()
      .matrix();
}

void write_modes(io::ArtefactWriter& w, const modal::ModeSet& modes, const MeshArtefact& mesh) {
  const auto n_modes = static_cast<std::uint64_t>(modes.count());
  const auto n_nodes = static_cast<std::uint64_t>(mesh.structure.node_count());
  const auto dim = static_cast<std::uint64_t>(mesh.structure.dim);
  const auto n_surface = static_cast<std::uint64_t>(mesh.surface.volume_node.size());
  w.write_vector(ds::eigenvalues, modes.eigenvalues);
  w.write_vector(ds::omega, modes.omega);
  w.write_vector(ds::frequencies_hz, modes.frequency_hz);
  w.write_vector(ds::damping_ratio, modes.damping_ratio);
  w.write(ds::shapes, stacked_shapes(modes.shapes).data(), {n_modes, n_nodes, dim});
  w.write(ds::surface_shapes,
          surface_shapes(modes.shapes, mesh.surface.volume_node, mesh.structure.dim).data(),
          {n_modes, n_surface, dim});
  w.write_vector(ds::residual, modes.residuals);
  w.write_vector(ds::orthogonality_error, modes.orthogonality_errors);
  w.write(ds::participation_translation, io::MatrixRM(modes.translational_participation));
  w.write(ds::participation_rotation, io::MatrixRM(modes.rotational_participation));
  w.write(ds::effective_mass_translation, io::MatrixRM(modes.translational_effective_mass));
  w.write(ds::effective_mass_rotation, io::MatrixRM(modes.rotational_effective_mass));
  w.write(ds::modes_nodes, io::MatrixRM(mesh.structure.nodes));
  w.write(ds::modes_cells, io::IndexMatrixRM(mesh.structure.cells));
  if (mesh.structure.dim == 3)
    w.write(ds::modes_cells_vtk, io::IndexMatrixRM(cells_in_vtk_order(mesh.structure)));
  w.write(ds::modes_surface_vertices, io::MatrixRM(mesh.surface.surface.vertices));
  w.write(ds::modes_surface_cells, io::IndexMatrixRM(mesh.surface.surface.cells));
  w.write(ds::modes_surface_node, mesh.surface.volume_node);
}

void write_reduced_model(io::ArtefactWriter& w, const ReducedModel& r, const MeshArtefact& mesh) {
  const fem::ReducedStvk& t = *r.tensors;
  const auto n_basis = static_cast<std::uint64_t>(t.size());
  const auto n_nodes = static_cast<std::uint64_t>(mesh.structure.node_count());
  const auto dim = static_cast<std::uint64_t>(mesh.structure.dim);
  const auto n_surface = static_cast<std::uint64_t>(mesh.surface.volume_node.size());
  w.write(ds::basis_vectors, stacked_shapes(t.basis()).data(), {n_basis, n_nodes, dim});
  w.write(ds::basis_surface_vectors,
          surface_shapes(t.basis(), mesh.surface.volume_node, mesh.structure.dim).data(),
          {n_basis, n_surface, dim});
  io::IndexMatrixRM origin(t.size(), 2);
  for (Eigen::Index k = 0; k < t.size(); ++k)
    origin.row(k) << r.basis.origin[static_cast<std::size_t>(k)][0],
        r.basis.origin[static_cast<std::size_t>(k)][1];
  w.write(ds::basis_origin, origin);
  w.write_vector(ds::basis_omega, basis_omega(t));
  w.write(ds::basis_participation_translation, io::MatrixRM(r.participation_translation));
  w.write(ds::basis_participation_rotation, io::MatrixRM(r.participation_rotation));
  w.write(ds::reduced_mass, io::MatrixRM(t.mass()));
  w.write(ds::reduced_linear, io::MatrixRM(t.linear_stiffness()));
  w.write(ds::reduced_quadratic, io::MatrixRM(t.quadratic()));
  w.write(ds::reduced_cubic, io::MatrixRM(t.cubic()));
  w.set_attribute(io::modes_attr::basis_modes, static_cast<std::int64_t>(r.basis.mode_count));
  w.set_attribute(io::modes_attr::basis_derivatives,
                  static_cast<std::int64_t>(r.basis.derivative_count));
  w.set_attribute(io::modes_attr::basis_dropped, static_cast<std::int64_t>(r.basis.dropped));
  w.set_attribute(io::modes_attr::derivatives_seconds, r.derivatives_seconds);
  w.set_attribute(io::modes_attr::tensor_seconds, t.setup_seconds());
}

void write_solver_attributes(io::ArtefactWriter& w, const modal::ModeSet& modes) {
  const modal::SolverInfo& s = modes.solver;
  w.set_attribute("solver_backend", s.backend);
  w.set_attribute("solver_factorisation", s.factorisation);
  w.set_attribute("solver_status", s.status);
  w.set_attribute("modes_requested", static_cast<std::int64_t>(s.requested));
  w.set_attribute("modes_converged", static_cast<std::int64_t>(s.converged));
  w.set_attribute("shift_rad2_s2", s.shift);
  w.set_attribute("lanczos_restarts", static_cast<std::int64_t>(s.iterations));
  w.set_attribute("operator_applications", static_cast<std::int64_t>(s.op_applications));
  w.set_attribute(io::modes_attr::factorisation_seconds, s.factorisation_seconds);
  w.set_attribute(io::modes_attr::lanczos_seconds, s.lanczos_seconds);
  w.set_attribute("max_relative_residual",
                  modes.residuals.size() ? modes.residuals.maxCoeff() : 0.0);
  w.set_attribute("max_orthogonality_error", modes.orthogonality_error);
}

/// "theta_1_2" for the derivative of modes 1 and 2, "mode_3" for mode 3 (1-based).
std::string basis_field_name(const std::array<int, 2>& origin) {
  return origin[1] < 0 ? fmt::format("mode_{}", origin[0] + 1)
                       : fmt::format("theta_{}_{}", origin[0] + 1, origin[1] + 1);
}

void write_modes_xdmf(const std::filesystem::path& h5, const MeshArtefact& mesh,
                      const modal::ModeSet& modes, const ReducedModel* reduced) {
  const auto& m = mesh.structure;
  const auto n_nodes = static_cast<std::uint64_t>(m.node_count());
  io::XdmfGrid grid{.name = "modes",
                    .dim = m.dim,
                    .topology = m.dim == 2 ? "Tri_6" : "Tet_10",
                    .cells_dataset = m.dim == 2 ? ds::modes_cells : ds::modes_cells_vtk,
                    .cells = static_cast<std::uint64_t>(m.cells.rows()),
                    .nodes_per_cell = static_cast<std::uint64_t>(m.nodes_per_cell()),
                    .nodes_dataset = ds::modes_nodes,
                    .nodes = n_nodes,
                    .fields = {}};
  for (int i = 0; i < modes.count(); ++i)
    grid.fields.push_back(
        {fmt::format("mode_{}_{:.4g}Hz", i + 1, modes.frequency_hz[i]),
         true,
         ds::shapes,
         {static_cast<std::uint64_t>(modes.count()), n_nodes, static_cast<std::uint64_t>(m.dim)},
         i});
  if (reduced != nullptr) {
    const auto n_basis = static_cast<std::uint64_t>(reduced->basis.size());
    for (std::size_t k = 0; k < reduced->basis.origin.size(); ++k)
      grid.fields.push_back({"basis_" + basis_field_name(reduced->basis.origin[k]),
                             true,
                             ds::basis_vectors,
                             {n_basis, n_nodes, static_cast<std::uint64_t>(m.dim)},
                             static_cast<int>(k)});
  }
  io::write_xdmf(std::filesystem::path(h5).replace_extension(".xdmf"), h5, {grid});
}

void log_frequency_table(const modal::ModeSet& modes) {
  std::string table =
      "  mode   frequency [Hz]   omega [rad/s]   zeta     residual   orthogonality\n";
  for (int i = 0; i < modes.count(); ++i)
    table += fmt::format("  {:>4}   {:>14.6f}   {:>13.5f}   {:<6.4g}   {:.2e}   {:.2e}\n", i + 1,
                         modes.frequency_hz[i], modes.omega[i], modes.damping_ratio[i],
                         modes.residuals[i], modes.orthogonality_errors[i]);
  spdlog::info("fsi-modes: {} mode(s) ({} backend, {} factorisation, {} operator applications)\n{}",
               modes.count(), modes.solver.backend, modes.solver.factorisation,
               modes.solver.op_applications, table);
}

void log_reduced_model(const ReducedModel& r, const modal::ModeSet& modes) {
  const fem::ReducedStvk& t = *r.tensors;
  const double eigensolver = modes.solver.factorisation_seconds + modes.solver.lanczos_seconds;
  spdlog::info(
      "fsi-modes: reduced basis (nonlinear_modal): {} modes + {} modal derivatives = {} "
      "vectors ({} dropped as dependent); derivatives {:.3f} s, tensors {:.3f} s ({} + {} + {} "
      "coefficients), eigensolver {:.3f} s; basis frequencies sqrt(K1_ii) [Hz]: {:.5g}",
      r.basis.mode_count, r.basis.derivative_count, t.size(), r.basis.dropped,
      r.derivatives_seconds, t.setup_seconds(), t.linear_stiffness().size(), t.quadratic().size(),
      t.cubic().size(), eigensolver, fmt::join(basis_omega(t) / (2 * std::numbers::pi), ", "));
}

/// The canonical parameter lines of fsi-modes without modes.archived (which names the archive
/// and so differs between the run that made a set and the runs that reuse it).
std::vector<std::string> modes_parameter_lines(const std::string& parameters) {
  std::vector<std::string> lines;
  std::istringstream in(parameters);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line.rfind("modes.archived", 0) != 0) lines.push_back(line);
  return lines;
}

/// Whether `line` ("key = value") sets a key the archived set's parameters `was` do not mention
/// to its declared default: a key added to fsi-modes since the set was made (modes.derivatives
/// came with schema version 2), which asks for what the set was computed as.
bool added_since(const std::string& line, const std::vector<std::string>& was) {
  const std::string key = line.substr(0, line.find(" = "));
  if (std::any_of(was.begin(), was.end(),
                  [&](const std::string& w) { return w.rfind(key + " = ", 0) == 0; }))
    return false;
  const auto& keys = io::scene_keys();
  const auto decl =
      std::find_if(keys.begin(), keys.end(), [&](const io::KeyDecl& d) { return d.path == key; });
  return decl != keys.end() && line == key + " = " + decl->default_text;
}

/// modes.archived: checks that the archived set was computed for this scene's fsi-modes keys and
/// for this mesh's nodes, then copies it to `output` (atomically). InputError naming the
/// difference otherwise.
void reuse_archived_modes(const io::Scene& scene, const MeshArtefact& mesh,
                          const std::filesystem::path& output) {
  const std::filesystem::path archived = scene.file_path("modes.archived");
  const std::string where = scene.where("modes.archived");
  if (!std::filesystem::exists(archived))
    input_error("{}: archived mode set '{}' does not exist", where, archived.string());
  const io::ArtefactReader r(archived, io::modes_schema());
  if (scene.boolean("modes.derivatives") && !r.has(ds::reduced_cubic))
    input_error(
        "{}: the archived mode set '{}' has no reduced model (it was computed without "
        "modes.derivatives), which {} = true asks for (structure.model = \"nonlinear_modal\" "
        "runs on it): archive a set computed with modes.derivatives = true, or remove "
        "modes.archived",
        where, archived.string(), scene.where("modes.derivatives"));
  const auto was = modes_parameter_lines(r.provenance().parameters);
  const auto now = modes_parameter_lines(scene.parameters_for("fsi-modes"));
  std::vector<std::string> differences;
  for (const std::string& line : now)
    if (std::find(was.begin(), was.end(), line) == was.end() && !added_since(line, was))
      differences.push_back("scene: " + line);
  for (const std::string& line : was)
    if (std::find(now.begin(), now.end(), line) == now.end())
      differences.push_back("archived: " + line);
  if (!differences.empty())
    input_error(
        "{}: the archived mode set '{}' was computed for other fsi-modes parameters (the "
        "material, formulation or mode request changed); recompute it (remove "
        "modes.archived) or archive a new one:\n  {}",
        where, archived.string(), fmt::join(differences, "\n  "));
  const io::MatrixRM nodes = r.read_matrix(ds::modes_nodes);
  const auto& current = mesh.structure.nodes;
  const double scale = std::max(1.0, current.cwiseAbs().maxCoeff());
  if (nodes.rows() != current.rows() || nodes.cols() != current.cols() ||
      (nodes - current).cwiseAbs().maxCoeff() > 1e-12 * scale)
    input_error(
        "{}: the archived mode set '{}' belongs to another geometry or mesh ({} nodes "
        "there, {} in this mesh{}); recompute it or archive a new one",
        where, archived.string(), nodes.rows(), current.rows(),
        nodes.rows() == current.rows()
            ? fmt::format(", largest node offset {:.3g} m", (nodes - current).cwiseAbs().maxCoeff())
            : std::string());
  io::AtomicOutput copy(output);
  std::filesystem::copy_file(archived, copy.temp_path(),
                             std::filesystem::copy_options::overwrite_existing);
  copy.commit();
  spdlog::info(
      "fsi-modes: reused the archived mode set {} (computed {} by {}): {} matches this "
      "scene's fsi-modes keys and mesh",
      archived.string(), r.provenance().created_utc, r.provenance().tool_version, output.string());
}

/// Wall-clock time of consecutive phases, for the log.
class PhaseClock {
 public:
  /// Ends the present phase under `name`.
  void lap(std::string name) {
    const auto now = std::chrono::steady_clock::now();
    laps_.emplace_back(std::move(name), std::chrono::duration<double>(now - last_).count());
    last_ = now;
  }
  /// "name 1.234, name 0.567, ...".
  std::string text() const {
    std::vector<std::string> parts;
    for (const auto& [name, seconds] : laps_)
      parts.push_back(fmt::format("{} {:.3f}", name, seconds));
    return fmt::format("{}", fmt::join(parts, ", "));
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
  std::vector<std::pair<std::string, double>> laps_;
};

}  // namespace

void validate_modes_scene(const io::Scene& scene) {
  require_structure(scene);
  fem::validate(elastic_model(scene), scene.dimension(), "structure");
  (void)damping(scene);
  const bool derivatives = scene.boolean("modes.derivatives");
  if (scene.string("structure.model") == "nonlinear_modal" && !derivatives)
    input_error(
        "{} = \"nonlinear_modal\" runs on the reduced model of modes.h5 (the modes, their modal "
        "derivatives and its tensors): set {} = true",
        scene.where("structure.model"), "modes.derivatives");
  if (derivatives && scene.number("modes.max_frequency_hz") <= 0)
    (void)derivative_modes(scene, static_cast<int>(scene.integer("modes.count")));
  if (derivatives && clamped_groups(scene).empty())
    input_error(
        "{} = true: modal derivatives need a clamped body (the linear stiffness is singular on a "
        "free one); set structure.clamped",
        scene.where("modes.derivatives"));
}

void run_modes_stage(const io::Scene& scene, const std::filesystem::path& mesh_artefact,
                     const std::filesystem::path& output) {
  validate_modes_scene(scene);
  const io::ArtefactReader reader(mesh_artefact, io::mesh_schema());
  const MeshArtefact mesh = read_structure_mesh(reader);
  if (mesh.structure.dim != scene.dimension())
    input_error("'{}' holds a {}-D mesh but {} says case.dimension = {}; rerun fsi-mesh",
                mesh_artefact.string(), mesh.structure.dim, scene.file().string(),
                scene.dimension());
  if (!scene.string("modes.archived").empty()) {
    reuse_archived_modes(scene, mesh, output);
    return;
  }

  // Phases: assembly, eigensolver, (the reduced model,) checks and output (a bar on a terminal,
  // lines in logs).
  const bool derivatives = scene.boolean("modes.derivatives");
  Progress progress("fsi-modes", derivatives ? 4 : 3, "phases",
                    spdlog::get_level() > spdlog::level::info);
  const auto start = std::chrono::steady_clock::now();
  const auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  PhaseClock phases;
  const fem::SystemMatrices system =
      fem::assemble(mesh.structure, elastic_model(scene), "structure.material");
  phases.lap("assembly");
  const std::vector<std::string> clamped = clamped_groups(scene);
  const fem::DofMap dofs = fem::DofMap::clamp_groups(mesh.structure, clamped, "structure.clamped");
  spdlog::info("fsi-modes: assembled K and M, {} DOFs ({} free, {} clamped), {:.2f} s",
               dofs.full_count(), dofs.free_count(), dofs.clamped_count(), seconds());
  progress.update(1);
  const modal::EigenSolution solution = [&] {  // K and M of the free DOFs live for the solve only
    const modal::SparseMatrix k_free = dofs.reduce(system.stiffness);
    const modal::SparseMatrix m_free = dofs.reduce(system.mass);
    phases.lap("constraints");
    return modal::solve_eigenproblem(k_free, m_free, mode_request(scene), eigen_options(scene));
  }();
  phases.lap("eigensolver");
  spdlog::info("fsi-modes: eigensolver done ({} factorisation {:.2f} s), {:.2f} s",
               modal::to_string(solution.factorisation), solution.factorisation_seconds, seconds());
  progress.update(2);
  const modal::ModeSet modes = modal::build_mode_set(solution, system, dofs, mesh.structure,
                                                     reference_point(scene), damping(scene));
  phases.lap("checks");
  const bool converged = solution.pairs.status == modal::EigenStatus::converged;
  std::optional<ReducedModel> reduced;
  if (derivatives && converged) {
    reduced = reduced_model(scene, mesh, dofs, system, modes);
    phases.lap("reduced model");
    spdlog::info("fsi-modes: reduced model done, {:.2f} s", seconds());
    progress.update(3);
  }

  const std::filesystem::path target =
      converged ? output : std::filesystem::path(output).replace_extension(".failed.h5");
  io::ArtefactWriter writer(
      target, io::modes_schema(), "fsi-modes", scene.parameters_for("fsi-modes"),
      {io::input_record("scene", scene.file()), io::input_record("mesh", mesh_artefact)});
  write_modes(writer, modes, mesh);
  if (reduced) write_reduced_model(writer, *reduced, mesh);
  write_solver_attributes(writer, modes);
  if (!converged)
    writer.set_attribute(
        io::attr::status,
        fmt::format("{}: {} of {} modes converged ({})", modes.solver.status,
                    modes.solver.converged, modes.solver.requested, modes.solver.message));
  writer.commit();
  phases.lap("output");
  if (!converged)
    numerical_error(
        "fsi-modes: the eigensolver did not converge ({}: {} of {} modes; {}); the converged "
        "modes are in '{}', nothing was written at '{}'",
        modes.solver.status, modes.solver.converged, modes.solver.requested, modes.solver.message,
        target.string(), output.string());
  write_modes_xdmf(output, mesh, modes, reduced ? &*reduced : nullptr);
  phases.lap("xdmf");
  progress.finish();
  spdlog::info("fsi-modes: phases [s]: {} (factorisation {:.3f}, Lanczos {:.3f}); {:.2f} s in all",
               phases.text(), modes.solver.factorisation_seconds, modes.solver.lanczos_seconds,
               seconds());
  log_frequency_table(modes);
  if (reduced) log_reduced_model(*reduced, modes);
}

}  // namespace hm::driver
