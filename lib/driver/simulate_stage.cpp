#include "driver/simulate_stage.hpp"

#include <array>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/errors.hpp"
#include "core/log.hpp"
#include "core/progress.hpp"
#include "core/text.hpp"
#include "coupling/free_motion.hpp"
#include "coupling/linear_modal_model.hpp"
#include "coupling/nonlinear_fe_model.hpp"
#include "coupling/nonlinear_modal_model.hpp"
#include "coupling/probes.hpp"
#include "coupling/run.hpp"
#include "coupling/structure_run.hpp"
#include "driver/checkpoint_io.hpp"
#include "driver/flow_processes.hpp"
#include "driver/flow_setup.hpp"
#include "driver/map_stage.hpp"
#include "driver/structure_io.hpp"
#include "fem/hyperelastic.hpp"
#include "fem/static_solve.hpp"
#include "io/artefact.hpp"
#include "io/hash.hpp"
#include "io/probe_csv.hpp"
#include "ldd/snapshots.hpp"
#include "motion/time_table.hpp"

namespace hm::driver {
namespace {

namespace ds = io::ds;
namespace ra = io::results_attr;
constexpr const char* stage_name = "fsi-simulate";

std::vector<io::InputRecord> provenance_inputs(const io::Scene& scene, const SimulateInputs& inputs,
                                               const std::vector<std::filesystem::path>& tables) {
  std::vector<io::InputRecord> records{io::input_record("scene", scene.file())};
  if (!inputs.mesh.empty()) records.push_back(io::input_record("mesh", inputs.mesh));
  if (!inputs.mapped.empty()) records.push_back(io::input_record("mapped", inputs.mapped));
  if (!inputs.modes.empty()) records.push_back(io::input_record("modes", inputs.modes));
  for (std::size_t k = 0; k < tables.size(); ++k)
    records.push_back(io::input_record(fmt::format("motion_table_{}", k), tables[k]));
  return records;
}

/// One field of every per-step record, as a dataset column.
template <typename T, typename S, typename F>
std::vector<T> column(const std::vector<S>& steps, F field) {
  std::vector<T> out;
  out.reserve(steps.size());
  for (const auto& s : steps) out.push_back(static_cast<T>(field(s)));
  return out;
}

void write_monitors(io::ArtefactWriter& w, const std::vector<ldd::StepMonitor>& m) {
  using M = ldd::StepMonitor;
  w.write(ds::monitor_step, column<std::int64_t>(m, [](const M& s) { return s.step; }));
  w.write(ds::monitor_time, column<double>(m, [](const M& s) { return s.time; }));
  w.write(ds::monitor_dt, column<double>(m, [](const M& s) { return s.dt; }));
  w.write(ds::monitor_dt_limit,
          column<std::int64_t>(m, [](const M& s) { return static_cast<int>(s.limit); }));
  w.write(ds::monitor_ppe_iterations,
          column<std::int64_t>(m, [](const M& s) { return s.ppe_iterations; }));
  w.write(ds::monitor_ppe_passes, column<std::int64_t>(m, [](const M& s) { return s.ppe_passes; }));
  w.write(ds::monitor_ppe_residual, column<double>(m, [](const M& s) { return s.ppe_residual; }));
  w.write(ds::monitor_ppe_converged,
          column<std::int64_t>(m, [](const M& s) { return s.ppe_converged ? 1 : 0; }));
  w.write(ds::monitor_max_divergence,
          column<double>(m, [](const M& s) { return s.max_divergence; }));
  w.write(ds::monitor_volume_drift, column<double>(m, [](const M& s) { return s.volume_drift; }));
  w.write(ds::monitor_max_speed, column<double>(m, [](const M& s) { return s.max_speed; }));
  w.write(ds::monitor_escaped, column<std::int64_t>(m, [](const M& s) { return s.escaped; }));
  w.write(ds::monitor_fluid, column<std::int64_t>(m, [](const M& s) { return s.fluid; }));
  w.write(ds::monitor_surface, column<std::int64_t>(m, [](const M& s) { return s.surface; }));
  w.write(ds::monitor_isolated, column<std::int64_t>(m, [](const M& s) { return s.isolated; }));
  w.write(ds::monitor_wall_active,
          column<std::int64_t>(m, [](const M& s) { return s.wall_active; }));
}

void write_phase_totals(io::ArtefactWriter& w, const ldd::PhaseSeconds& s) {
  const auto values = s.values();
  w.write(ds::run_phase_seconds, std::vector<double>(values.begin(), values.end()));
  w.set_attribute(ra::phase_names, std::string(ldd::PhaseSeconds::names));
}

void write_probes(io::ArtefactWriter& w, const coupling::ProbeSeries& series,
                  const std::vector<std::string>& columns) {
  w.set_attribute(ra::probe_columns, join(columns, ","));
  if (columns.empty()) return;
  io::MatrixRM values(static_cast<Eigen::Index>(series.time.size()),
                      static_cast<Eigen::Index>(columns.size()));
  for (std::size_t r = 0; r < series.rows.size(); ++r)
    for (std::size_t c = 0; c < columns.size(); ++c)
      values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = series.rows[r][c];
  w.write(ds::probe_time, series.time);
  w.write(ds::probe_values, values);
}

std::string first_line(const std::string& text) {
  return text.substr(0, text.find('\n'));
}

template <int D>
std::string describe_walls(const FlowSetup<D>& setup, const io::Scene& scene) {
  std::vector<std::string> lines;
  const auto views = scene.array("wall");
  for (std::size_t w = 0; w < setup.walls.size(); ++w) {
    const std::string motion = static_cast<int>(w) == setup.structure_wall
                                   ? std::string("modal")
                                   : views[w].string("motion");
    lines.push_back(fmt::format("{} ({} vertices, {} elements, motion {}{})", setup.wall_names[w],
                                setup.walls[w].vertices().size(), setup.walls[w].element_count(),
                                motion, setup.walls[w].thin() ? ", thin" : ""));
  }
  return join(lines, "; ");
}

// ---- coupled runs ---------------------------------------------------------------------------

/// The flexible body of a coupled scene: mapped.h5's target surface, its modes and, from a mode
/// set with modes.derivatives, its reduced basis (the interface of nonlinear_modal; its ζ and
/// its rotation reference are set by reduced_interface).
template <int D>
struct MappedBody {
  mesh::SurfaceMesh surface;
  coupling::ModalSurface<D> modes;
  std::optional<coupling::ModalSurface<D>> basis;
};

template <int D>
MappedBody<D> read_mapped_body(const std::filesystem::path& file) {
  const io::ArtefactReader r(file, io::mapped_modes_schema());
  MappedBody<D> body;
  body.surface.vertices = r.read_matrix(ds::target_vertices);
  body.surface.dim = static_cast<int>(body.surface.vertices.cols());
  body.surface.cells = r.read_indices(ds::target_cells);
  if (body.surface.dim != D)
    input_error("{}: the mapped surface is {}-D, the case is {}-D", file.string(), body.surface.dim,
                D);
  body.modes.shapes = r.read_columns(ds::mapped_shapes);  // [mode][vertex][c]
  for (Eigen::Index v = 0; v < body.surface.vertices.rows(); ++v)
    body.modes.x0.push_back(body.surface.vertices.row(v).transpose());
  body.modes.omega = r.read_vector(ds::omega);
  body.modes.zeta = r.read_vector(ds::damping_ratio);
  body.modes.participation = r.read_matrix(ds::participation_translation);
  body.modes.rotation_participation = r.read_matrix(ds::participation_rotation);
  if (r.has(ds::mapped_basis)) {
    coupling::ModalSurface<D>& basis = body.basis.emplace();
    basis.x0 = body.modes.x0;
    basis.shapes = r.read_columns(ds::mapped_basis);  // [vector][vertex][c]
    basis.omega = r.read_vector(ds::basis_omega);
    basis.zeta = Eigen::VectorXd::Zero(basis.omega.size());
    basis.participation = r.read_matrix(ds::basis_participation_translation);
    basis.rotation_participation = r.read_matrix(ds::basis_participation_rotation);
  }
  return body;
}

coupling::CouplingOptions coupling_options(const io::Scene& scene) {
  const io::SceneView c = scene.section("coupling");
  coupling::CouplingOptions o;
  o.scheme = c.string("scheme") == "explicit" ? coupling::CouplingScheme::explicit_staggered
                                              : coupling::CouplingScheme::strong;
  o.tolerance = c.number("tolerance");
  o.max_iterations = static_cast<int>(c.number("max_iterations"));
  o.added_mass_interval = static_cast<long>(c.number("added_mass_interval"));
  o.load_scale = scene.dimension() == 2 ? scene.number("structure.thickness") : 1.0;
  o.static_start = scene.boolean("structure.static_start");
  o.viscous_traction = c.boolean("viscous_traction");
  return o;
}

/// Refuses what a nonlinear structure model cannot do, naming the key.
void check_nonlinear_scene(const io::Scene& scene) {
  const std::string model = scene.string("structure.model");
  if (model == "linear_modal") return;
  if (!scene.string("structure.free_translation").empty())
    input_error(
        "{} = \"{}\" with {} = \"{}\": a body in free translation runs on linear modes only "
        "(its rigid-body motion is a mode of the set); use structure.model = \"linear_modal\"",
        scene.where("structure.free_translation"), scene.string("structure.free_translation"),
        scene.where("structure.model"), model);
}

/// The scene keys of a structure model, checked without artefacts (--validate).
void validate_structure_model(const io::Scene& scene) {
  check_nonlinear_scene(scene);
  const std::string model = scene.string("structure.model");
  if (model == "linear_modal") return;
  const fem::HyperelasticModel material{
      elastic_model(scene), fem::material_law_from(scene.string("structure.material.law"),
                                                   scene.where("structure.material.law"))};
  fem::validate(material, scene.dimension(), scene.where("structure.material.poisson_ratio"));
  if (model == "nonlinear_modal" && material.law != fem::MaterialLaw::saint_venant_kirchhoff)
    input_error(
        "{} = \"{}\" with {} = \"nonlinear_modal\": the reduced model's cubic force is exact "
        "for saint_venant_kirchhoff only (its tensors come from the Lamé constants of E and nu); "
        "use law = \"saint_venant_kirchhoff\", or structure.model = \"nonlinear_fe\" for "
        "neo_hookean",
        scene.where("structure.material.law"), scene.string("structure.material.law"),
        scene.where("structure.model"));
}

/// The dynamics options of a nonlinear structure model: scheme, ρ∞, Newton's tolerance and
/// iterations, and the Rayleigh damping of the modes' ζ (fitted at the two lowest frequencies)
/// plus the scene's own Rayleigh α and β.
fem::DynamicsOptions dynamics_options(const io::Scene& scene, const Eigen::VectorXd& omega) {
  fem::DynamicsOptions o;
  o.scheme = fem::time_scheme_from(scene.string("structure.time_scheme"),
                                   scene.where("structure.time_scheme"));
  o.rho_infinity = scene.number("structure.rho_infinity");
  o.newton.tolerance = scene.number("structure.newton_tolerance");
  o.newton.max_iterations = static_cast<int>(scene.integer("structure.newton_max_iterations"));
  const Eigen::VectorXd ratios = scene.vector("modes.damping_ratios");
  const double zeta = ratios.size() > 0 ? ratios[0] : scene.number("modes.damping_ratio");
  const coupling::RayleighFit fit = coupling::rayleigh_for(zeta, omega.size() > 0 ? omega[0] : 0.0,
                                                           omega.size() > 1 ? omega[1] : 0.0);
  o.rayleigh_alpha = scene.number("modes.rayleigh_alpha") + fit.alpha;
  o.rayleigh_beta = scene.number("modes.rayleigh_beta") + fit.beta;
  return o;
}

/// The total-Lagrangian body of structure.model = "nonlinear_fe" on the scene's structure
/// (mesh.h5), its clamped group, material and law, its linear modes (modes.h5: the interface's
/// shapes before mapping) and the map of its displacement onto the wall of mapped.h5.
template <int D>
std::unique_ptr<coupling::StructureModel<D>> nonlinear_fe_model(
    const io::Scene& scene, const SimulateInputs& inputs,
    std::shared_ptr<const coupling::ModalSurface<D>> interface, const mesh::SurfaceMesh& wall) {
  if (inputs.mesh.empty() || inputs.modes.empty())
    throw UsageError(fmt::format(
        "{}: {} = \"nonlinear_fe\" needs --mesh mesh.h5 (the structure's elements) and --modes "
        "modes.h5 (its linear modes, the coupling's interface)",
        stage_name, scene.where("structure.model")));
  MeshArtefact mesh = read_structure_mesh(io::ArtefactReader(inputs.mesh, io::mesh_schema()));
  const modal::ModeSet modes = read_mode_set(io::ArtefactReader(inputs.modes, io::modes_schema()));
  if (modes.shapes.cols() != interface->modes() ||
      modes.shapes.rows() != mesh.structure.dim * mesh.structure.node_count())
    input_error(
        "{}: {} modes of {} DOFs; the mapped set {} has {} modes and {} the structure {} "
        "DOFs: the mode set is not this mesh's or mapped.h5's",
        inputs.modes.string(), modes.shapes.cols(), modes.shapes.rows(), inputs.mapped.string(),
        interface->modes(), inputs.mesh.string(), mesh.structure.dim * mesh.structure.node_count());
  const std::string context = fmt::format("structure '{}'", structure_wall_name);
  coupling::NonlinearFeParts parts;
  fem::HyperelasticModel material{elastic_model(scene),
                                  fem::material_law_from(scene.string("structure.material.law"),
                                                         scene.where("structure.material.law"))};
  fem::validate(material, mesh.structure.dim, scene.where("structure.material"));
  parts.dofs = std::make_unique<fem::DofMap>(
      fem::DofMap::clamp_groups(mesh.structure, clamped_groups(scene), "structure.clamped"));
  parts.wall_map = std::make_unique<coupling::FeWallMap>(
      mesh.surface.surface.vertices, mesh.surface.volume_node, mesh.structure.node_count(),
      wall.vertices, rbf_options(scene));
  parts.body =
      std::make_unique<fem::HyperelasticBody>(std::move(mesh.structure), material, context);
  parts.modes = modes.shapes;
  parts.dynamics = dynamics_options(scene, modes.omega);
  parts.context = context;
  spdlog::info(
      "{}: structure model nonlinear_fe: {} DOFs ({} free), {} law, {} (rho_inf {}), "
      "Rayleigh alpha {:.4g} 1/s, beta {:.4g} s; wall {} the structure's boundary",
      stage_name, parts.body->dof_count(), parts.dofs->free_count(),
      scene.string("structure.material.law"), scene.string("structure.time_scheme"),
      parts.dynamics.rho_infinity, parts.dynamics.rayleigh_alpha, parts.dynamics.rayleigh_beta,
      parts.wall_map->identity() ? "is" : "is RBF-mapped from");
  if (parts.dynamics.scheme == fem::TimeScheme::generalized_alpha &&
      parts.dynamics.rho_infinity < 1.0)
    spdlog::warn(
        "{}: {} = \"generalized_alpha\" at rho_infinity {}: the fluid's load enters with the "
        "weight 1 - alpha_f, the inertia with 1 - alpha_m, which misstates a strong added mass "
        "(a light body in water moves too far); energy_conserving treats both alike",
        stage_name, scene.where("structure.time_scheme"), parts.dynamics.rho_infinity);
  return std::make_unique<coupling::NonlinearFeModel<D>>(std::move(interface), std::move(parts));
}

/// The interface of structure.model = "nonlinear_modal": mapped.h5's basis, with the modal
/// damping's Rayleigh ratio ζ_i = α/(2ω_i) + βω_i/2 of each vector (informative: the model
/// damps by α M_r + β K1). InputError naming the file and what to do when modes.h5 has no
/// reduced model or mapped.h5 no basis, or when mapped.h5 was mapped from another mode set.
template <int D>
coupling::ModalSurface<D> reduced_interface(const io::Scene& scene, const SimulateInputs& inputs,
                                            const MappedBody<D>& mapped) {
  if (inputs.modes.empty())
    throw UsageError(fmt::format(
        "{}: {} = \"nonlinear_modal\" needs --modes modes.h5 (the reduced model's tensors)",
        stage_name, scene.where("structure.model")));
  const io::ArtefactReader modes(inputs.modes, io::modes_schema());
  if (!modes.has(ds::reduced_cubic)) {
    const std::string archived = scene.string("modes.archived");
    input_error(
        "{}: the mode set{} has no reduced model (basis and tensors), which {} = "
        "\"nonlinear_modal\" runs on: set modes.derivatives = true and rerun fsi-modes and "
        "fsi-map{}",
        inputs.modes.string(),
        archived.empty()
            ? std::string()
            : fmt::format(" (the archived set {})", scene.file_path("modes.archived").string()),
        scene.where("structure.model"),
        archived.empty() ? std::string() : " (with an archived set computed so)");
  }
  if (!mapped.basis)
    input_error(
        "{}: mapped from a mode set without the reduced basis; {} has one: rerun fsi-map on it",
        inputs.mapped.string(), inputs.modes.string());
  const io::Provenance p = io::read_artefact_provenance(inputs.mapped);
  const auto source = std::find_if(p.inputs.begin(), p.inputs.end(),
                                   [](const io::InputRecord& r) { return r.role == "modes"; });
  if (source != p.inputs.end() && source->sha256 != io::sha256_file(inputs.modes))
    input_error(
        "{}: mapped from another mode set ({}) than {}: their bases would not match; rerun "
        "fsi-map on {}",
        inputs.mapped.string(), source->path, inputs.modes.string(), inputs.modes.string());
  coupling::ModalSurface<D> basis = *mapped.basis;
  const fem::DynamicsOptions d = dynamics_options(scene, mapped.modes.omega);
  for (Eigen::Index k = 0; k < basis.modes(); ++k) {
    const double w = basis.omega[k];
    basis.zeta[k] = w > 0.0 ? d.rayleigh_alpha / (2 * w) + d.rayleigh_beta * w / 2 : 0.0;
  }
  return basis;
}

/// The reduced model of structure.model = "nonlinear_modal" on its interface (the mapped basis):
/// modes.h5's tensors, integrated as structure.time_scheme says.
template <int D>
std::unique_ptr<coupling::StructureModel<D>> nonlinear_modal_model(
    const io::Scene& scene, const SimulateInputs& inputs,
    std::shared_ptr<const coupling::ModalSurface<D>> interface) {
  const io::ArtefactReader reader(inputs.modes, io::modes_schema());
  std::optional<fem::ReducedStvk> tensors = read_reduced_model(reader);
  HM_ASSERT(tensors.has_value(), "{} lost its reduced model", inputs.modes.string());
  const Eigen::MatrixXi origin = reader.read_indices(ds::basis_origin).cast<int>();
  coupling::NonlinearModalParts parts;
  parts.tensors = std::make_unique<fem::ReducedStvk>(std::move(*tensors));
  parts.dynamics = dynamics_options(scene, reader.read_vector(ds::omega));
  parts.context = fmt::format("structure '{}'", structure_wall_name);
  const auto derivatives = (origin.col(1).array() >= 0).count();
  spdlog::info(
      "{}: structure model nonlinear_modal: {} basis vectors ({} modes, {} modal derivatives), "
      "{} (rho_inf {}), Rayleigh alpha {:.4g} 1/s, beta {:.4g} s; {} PPE solves per added-mass "
      "measurement",
      stage_name, parts.tensors->size(), parts.tensors->size() - derivatives, derivatives,
      scene.string("structure.time_scheme"), parts.dynamics.rho_infinity,
      parts.dynamics.rayleigh_alpha, parts.dynamics.rayleigh_beta, parts.tensors->size());
  if (parts.dynamics.scheme == fem::TimeScheme::generalized_alpha &&
      parts.dynamics.rho_infinity < 1.0)
    spdlog::warn(
        "{}: {} = \"generalized_alpha\" at rho_infinity {}: the fluid's load enters with the "
        "weight 1 - alpha_f, the inertia with 1 - alpha_m, which misstates a strong added mass; "
        "energy_conserving treats both alike",
        stage_name, scene.where("structure.time_scheme"), parts.dynamics.rho_infinity);
  return std::make_unique<coupling::NonlinearModalModel<D>>(std::move(interface), std::move(parts));
}

/// The structure model of structure.model on the mapped interface.
template <int D>
std::unique_ptr<coupling::StructureModel<D>> structure_model(
    const io::Scene& scene, const SimulateInputs& inputs,
    std::shared_ptr<const coupling::ModalSurface<D>> interface, const mesh::SurfaceMesh& wall) {
  check_nonlinear_scene(scene);
  const std::string model = scene.string("structure.model");
  if (model == "nonlinear_fe")
    return nonlinear_fe_model<D>(scene, inputs, std::move(interface), wall);
  if (model == "nonlinear_modal")
    return nonlinear_modal_model<D>(scene, inputs, std::move(interface));
  return std::make_unique<coupling::LinearModalModel<D>>(std::move(interface));
}

/// A displacement probe of a coupled run: the vertex of the structure's wall nearest to it.
struct SurfaceProbe {
  std::string name;
  Eigen::Index vertex = 0;
};

template <int D>
std::vector<SurfaceProbe> surface_probes(const io::Scene& scene,
                                         const coupling::ModalSurface<D>& modes) {
  std::vector<SurfaceProbe> probes;
  for (const io::SceneView& view : scene.array("probe")) {
    if (view.string("kind") != "displacement") continue;
    const Eigen::VectorXd x = view.vector("position");
    if (x.size() != D)
      input_error("{}: a displacement probe needs position, {} values (m)", view.where("kind"), D);
    Eigen::Index best = 0;
    double distance = std::numeric_limits<double>::infinity();
    for (std::size_t v = 0; v < modes.x0.size(); ++v) {
      const double d = (modes.x0[v] - x).norm();
      if (d < distance) {
        distance = d;
        best = static_cast<Eigen::Index>(v);
      }
    }
    spdlog::info("{}: probe {}: structure surface vertex {} at [{}] m, {:.3g} m from the position",
                 stage_name, view.string("name"), best, fmt::join(modes.x0[best], ", "), distance);
    probes.push_back({view.string("name"), best});
  }
  return probes;
}

/// One field of the first body's coupling monitor of every step.
template <typename T, typename F>
std::vector<T> coupling_column(const std::vector<std::vector<coupling::CouplingMonitor>>& steps,
                               F field) {
  return column<T>(
      steps, [&](const auto& s) { return s.empty() ? T{} : static_cast<T>(field(s.front())); });
}
/// The body's free translation (structure.free_translation), if the scene asks for one: its
/// rigid-body modes become the one translation (coupling/free_motion.hpp).
template <int D>
std::optional<coupling::FreeTranslation> free_translation(const io::Scene& scene,
                                                          coupling::ModalSurface<D>& modes) {
  const std::string axis = scene.string("structure.free_translation");
  if (axis.empty()) return std::nullopt;
  const int a = axis == "x" ? 0 : axis == "y" ? 1 : 2;
  if (a >= D)
    input_error("{} = \"{}\": a {}-D case moves along x or y",
                scene.where("structure.free_translation"), axis, D);
  const double velocity = scene.number("structure.initial_velocity");
  const coupling::FreeTranslation free = coupling::make_free_translation<D>(
      modes, a, velocity, scene.where("structure.free_translation"));
  spdlog::info(
      "{}: the structure moves freely along {}: mass {:.6g} kg, {} rigid-body modes replaced by "
      "the translation (mode {}), {} elastic modes, initial velocity {} m/s",
      stage_name, axis, free.mass, free.rigid_dropped, free.mode, free.mode, velocity);
  return free;
}

/// The free body's position and velocity along its axis from the translation's modal
/// coordinate (y = √M·X), one row per modal row.
void write_free_translation(io::ArtefactWriter& w, const coupling::ModalHistory& h,
                            const coupling::FreeTranslation& free) {
  const double root = std::sqrt(free.mass);
  std::vector<double> position, velocity;
  for (std::size_t k = 0; k < h.time.size(); ++k) {
    position.push_back(h.y[k][free.mode] / root);
    velocity.push_back(h.v[k][free.mode] / root);
  }
  w.write(ds::body_position, position);
  w.write(ds::body_velocity, velocity);
  w.set_attribute(ra::body_mass, free.mass);
  w.set_attribute(ra::free_axis, std::string(1, "xyz"[free.axis]));
}

/// Writes a per-step monitor and its run maximum (0 for no steps) as `attribute`; returns it.
double write_with_maximum(io::ArtefactWriter& w, const char* dataset, const char* attribute,
                          const std::vector<double>& column) {
  w.write(dataset, column);
  const double largest = column.empty() ? 0.0 : *std::max_element(column.begin(), column.end());
  w.set_attribute(attribute, largest);
  return largest;
}

/// The structure's model, its energy balance per step and its Newton iterations.
template <int D>
void write_structure_energy(io::ArtefactWriter& w, const coupling::RunResult& r,
                            const coupling::FlexibleBody<D>& body) {
  using C = coupling::CouplingMonitor;
  const std::string model = body.model().kind();
  w.set_attribute(ra::structure_model, model);
  io::MatrixRM energy(static_cast<Eigen::Index>(r.coupling.size()), 5);
  for (std::size_t k = 0; k < r.coupling.size(); ++k) {
    const coupling::StructureEnergy e =
        r.coupling[k].empty() ? coupling::StructureEnergy{} : r.coupling[k].front().energy;
    energy.row(static_cast<Eigen::Index>(k)) << e.kinetic, e.strain, e.external_work, e.damping,
        e.numerical_dissipation;
  }
  w.write(ds::monitor_structure_energy, energy);
  w.set_attribute(ra::energy_columns,
                  std::string("kinetic,strain,external_work,damping,numerical_dissipation"));
  if (model == "linear_modal") return;
  const auto iterations =
      coupling_column<std::int64_t>(r.coupling, [](const C& c) { return c.solver_iterations; });
  w.write(ds::monitor_structure_solver_iterations, iterations);
  const double total = std::accumulate(iterations.begin(), iterations.end(), 0.0);
  spdlog::info("{}: the {} structure took {:.0f} Newton iterations, {:.2f} a step", stage_name,
               model, total, total / std::max<double>(1.0, static_cast<double>(iterations.size())));
}

template <int D>
void write_coupling(io::ArtefactWriter& w, const coupling::RunResult& r,
                    const coupling::FlexibleBody<D>& body,
                    const std::optional<coupling::FreeTranslation>& free) {
  using C = coupling::CouplingMonitor;
  const coupling::ModalHistory& h = r.modal.front();
  const auto rows = static_cast<Eigen::Index>(h.time.size());
  const Eigen::Index m = body.modes().modes();
  Eigen::MatrixXd y(rows, m), v(rows, m), F(rows, m);
  for (Eigen::Index k = 0; k < rows; ++k) {
    y.row(k) = h.y[static_cast<std::size_t>(k)].transpose();
    v.row(k) = h.v[static_cast<std::size_t>(k)].transpose();
    F.row(k) = h.F[static_cast<std::size_t>(k)].transpose();
  }
  w.write(ds::modal_time, h.time);
  w.write(ds::modal_coordinates, io::MatrixRM(y));
  w.write(ds::modal_velocities, io::MatrixRM(v));
  w.write(ds::modal_forces, io::MatrixRM(F));
  if (body.added_mass().size() > 0) {
    w.write(ds::modal_added_mass, io::MatrixRM(body.added_mass()));
    w.write(ds::modal_added_mass_initial, io::MatrixRM(body.initial_added_mass()));
  }
  w.write(ds::monitor_coupling_iterations,
          coupling_column<std::int64_t>(r.coupling, [](const C& c) { return c.iterations; }));
  w.write(ds::monitor_interface_residual,
          coupling_column<double>(r.coupling, [](const C& c) { return c.residual; }));
  const auto seconds = coupling_column<double>(r.coupling, [](const C& c) { return c.seconds; });
  const auto added =
      coupling_column<double>(r.coupling, [](const C& c) { return c.added_mass_seconds; });
  const auto structure =
      coupling_column<double>(r.coupling, [](const C& c) { return c.structure_seconds; });
  w.write(ds::monitor_coupling_seconds, seconds);
  w.write(ds::monitor_structure_seconds, structure);
  const double total = std::accumulate(seconds.begin(), seconds.end(), 0.0);
  const double added_total = std::accumulate(added.begin(), added.end(), 0.0);
  const double structure_total = std::accumulate(structure.begin(), structure.end(), 0.0);
  w.set_attribute(ra::coupling_seconds, total);
  w.set_attribute(ra::added_mass_seconds, added_total);
  w.set_attribute(ra::structure_seconds, structure_total);
  const auto percent = [&](double s) { return 100 * s / std::max(r.wall_seconds, 1e-12); };
  spdlog::info(
      "{}: coupling {:.3g} s of {:.3g} s ({:.1f} %), of which added-mass solves {:.3g} s "
      "({:.1f} %) and the structure model {:.3g} s ({:.1f} %)",
      stage_name, total, r.wall_seconds, percent(total), added_total, percent(added_total),
      structure_total, percent(structure_total));
  w.set_attribute(ra::coupling_scheme, std::string(coupling::to_string(body.options().scheme)));
  write_structure_energy<D>(w, r, body);
  const double largest =
      write_with_maximum(w, ds::monitor_structure_stretch, ra::max_structure_stretch,
                         coupling_column<double>(r.coupling, [](const C& c) { return c.stretch; }));
  const double deformation = write_with_maximum(
      w, ds::monitor_structure_deformation, ra::max_structure_deformation,
      coupling_column<double>(r.coupling, [](const C& c) { return c.deformation; }));
  const double peak = write_with_maximum(
      w, ds::monitor_structure_peak_pressure, ra::max_structure_pressure,
      coupling_column<double>(r.coupling, [](const C& c) { return c.peak_pressure; }));
  spdlog::info(
      "{}: the structure's largest wall pressure {:.6g} Pa, its largest elastic "
      "displacement {:.4g} m",
      stage_name, peak, deformation);
  if (free) write_free_translation(w, h, *free);
  const bool linear = std::string_view(body.model().kind()) == "linear_modal";
  if (largest > 0.05 && linear)
    spdlog::warn(
        "{}: the structure's displacement reached {:.1f} % of its size: linear modes stretch "
        "the body visibly beyond 5 % (rotations are not rigid); read the response with care, "
        "or run the geometrically nonlinear body: structure.model = \"nonlinear_fe\"",
        stage_name, 100 * largest);
}

/// Snapshot fields of the flexible bodies' walls: the displacement Σ Φ y and the pressure of
/// the wall node at each vertex (no fields for the other walls; none at all without bodies).
/// `points`: the flow's points to write (FlowSolver::output_points).
template <int D>
std::vector<ldd::WallFields<D>> body_fields(const ldd::FlowSolver<D>& flow,
                                            const ldd::PointSet<D>& points,
                                            std::span<const coupling::FlexibleBody<D>> bodies) {
  std::vector<ldd::WallFields<D>> fields;
  if (bodies.empty()) return fields;
  fields.resize(flow.walls().size());
  for (const auto& body : bodies) {
    const auto& wall = flow.walls()[static_cast<std::size_t>(body.wall())];
    auto& f = fields[static_cast<std::size_t>(body.wall())];
    const auto n = static_cast<Eigen::Index>(wall.vertices().size());
    for (Eigen::Index v = 0; v < n; ++v) f.displacement.push_back(body.displacement(v));
    f.pressure.assign(static_cast<std::size_t>(n), 0.0);
    for (ldd::Index i = 0; i < points.size(); ++i) {
      const auto& h = points.host[i];
      if (points.kind[i] != ldd::PointKind::wall || h.body != body.wall()) continue;
      for (int k = 0; k < D; ++k)
        if (h.barycentric[k] == 1.0)
          f.pressure[static_cast<std::size_t>(wall.element(h.element)[k])] = points.pressure[i];
    }
  }
  return fields;
}

template <int D>
std::string simulate_flow(const io::Scene& scene, const SimulateInputs& inputs,
                          const std::filesystem::path& output, FlowSetup<D> setup,
                          std::optional<MappedBody<D>> mapped,
                          const std::vector<std::filesystem::path>& wall_files,
                          std::shared_ptr<ldd::PointExchange<D>> processes);

template <int D>
void run_flow(const io::Scene& scene, const SimulateInputs& inputs,
              const std::filesystem::path& output) {
  std::vector<std::filesystem::path> wall_files;
  const bool coupled = scene.has("structure");
  if (coupled && inputs.mapped.empty())
    throw UsageError(fmt::format(
        "{}: {} couples the flow with a [structure]: give --mapped mapped.h5 (fsi-map's modes "
        "on the structure's surface)",
        stage_name, scene.file().string()));
  std::optional<MappedBody<D>> mapped;
  if (coupled) mapped = read_mapped_body<D>(inputs.mapped);
  const mesh::SurfaceMesh* structure = mapped ? &mapped->surface : nullptr;
  FlowSetup<D> setup;
  if (inputs.mesh.empty()) {
    spdlog::info("{}: no --mesh: meshing the walls from the scene's [[wall]] keys", stage_name);
    setup = flow_setup<D>(scene, scene_wall_surfaces(scene, &wall_files), structure);
  } else {
    setup = flow_setup<D>(scene, io::ArtefactReader(inputs.mesh, io::mesh_schema()), structure);
  }
  const auto processes = flow_processes<D>();
  std::string diverged;  // how the flow diverged, if it did
  try {
    diverged = simulate_flow<D>(scene, inputs, output, std::move(setup), std::move(mapped),
                                wall_files, processes);
  } catch (const std::exception& e) {
    // A failure that one process alone may meet (its output files, its part of a step) would
    // leave the others waiting in their next collective call: every process ends, with this
    // one's message and exit code. A diverged flow is none: every process sees it (its
    // criteria are reduced over them) and ends below, process 0 having written the results.
    if (processes) abort_processes(e);
    throw;
  }
  if (!diverged.empty()) numerical_error("{}", diverged);
}

/// The flow of run_flow from its set-up on (over `processes`, or one process when null): the
/// run and its output. Returns "" or, when the flow diverged, the message to end with.
template <int D>
std::string simulate_flow(const io::Scene& scene, const SimulateInputs& inputs,
                          const std::filesystem::path& output, FlowSetup<D> setup,
                          std::optional<MappedBody<D>> mapped,
                          const std::vector<std::filesystem::path>& wall_files,
                          std::shared_ptr<ldd::PointExchange<D>> processes) {
  const auto& o = setup.options;
  const bool writes = writes_output(processes.get());
  if (!writes) spdlog::set_level(spdlog::level::warn);  // one log: process 0's
  spdlog::info(
      "{}: {}-D flow: {} fluid points, dx = {} m, h = {} m, ρ = {} kg/m³, ν = {} m²/s, "
      "g = [{}] m/s², to t = {} s; walls: {}; {} probe(s)",
      stage_name, D, setup.fluid.size(), o.dx, o.support_factor * o.dx, o.density, o.viscosity,
      fmt::join(o.gravity, ", "), setup.time.end, describe_walls(setup, scene),
      setup.probes.size());
  auto records = provenance_inputs(scene, inputs, setup.motion_tables);
  for (std::size_t k = 0; k < wall_files.size(); ++k)
    records.push_back(io::input_record(fmt::format("wall_file_{}", k), wall_files[k]));
  const std::vector<std::string> wall_names = setup.wall_names;
  const ldd::Index fluid_points = static_cast<ldd::Index>(setup.fluid.size());
  ldd::FlowSolver<D> solver(std::move(setup.walls), setup.fluid, setup.velocity, o, 0.0, processes);
  if (processes)
    spdlog::info("{}: over {} processes (each its region of the points, ghosts within h)",
                 stage_name, processes->processes());
  else
    spdlog::info("{}: {} wall nodes; initial pressure solved", stage_name,
                 solver.points().size() - fluid_points);

  std::vector<coupling::FlexibleBody<D>> bodies;
  std::vector<SurfaceProbe> displacement;
  std::optional<coupling::FreeTranslation> free;
  if (mapped) {
    if (scene.string("structure.model") == "nonlinear_modal")
      mapped->modes = reduced_interface<D>(scene, inputs, *mapped);
    displacement = surface_probes<D>(scene, mapped->modes);
    free = free_translation<D>(scene, mapped->modes);
    // The rotational participation factors are about the mode stage's reference point.
    const Eigen::VectorXd reference = scene.vector("modes.reference_point");
    mapped->modes.rotation_reference.head(reference.size()) = reference;
    auto interface = std::make_shared<const coupling::ModalSurface<D>>(std::move(mapped->modes));
    auto model = structure_model<D>(scene, inputs, interface, mapped->surface);
    bodies.emplace_back(structure_wall_name, std::move(interface), std::move(model),
                        setup.structure_wall, coupling_options(scene),
                        solver.walls()[static_cast<std::size_t>(setup.structure_wall)]);
    if (const std::string host = scene.string("coupling.moves_with"); !host.empty()) {
      if (free)
        input_error(
            "{} = \"{}\" and structure.free_translation: a body either moves with a "
            "tank or freely, not both",
            scene.where("coupling.moves_with"), host);
      const auto w = static_cast<std::size_t>(
          std::find(setup.wall_names.begin(), setup.wall_names.end(), host) -
          setup.wall_names.begin());
      if (w >= setup.wall_names.size() || !setup.motions[w].motion)
        input_error("{} = \"{}\" must name a [[wall]] in motion (walls: {})",
                    scene.where("coupling.moves_with"), host, fmt::join(setup.wall_names, ", "));
      bodies.front().set_carrier(*setup.motions[w].motion);
    }
    const auto& body = bodies.front();
    const Eigen::VectorXd hz = body.modes().omega / (2 * std::numbers::pi);
    // The reduced basis's derivative vectors are no modes: their √K_ii are no frequencies.
    const std::string interface_text =
        body.model().kind() == std::string_view("nonlinear_modal")
            ? fmt::format("{} interface vectors (the reduced basis)", body.modes().modes())
            : fmt::format("{} interface modes ({} Hz)", body.modes().modes(), fmt::join(hz, ", "));
    spdlog::info("{}: flexible body '{}': {} structure, {}, {} coupling", stage_name,
                 structure_wall_name, body.model().kind(), interface_text,
                 coupling::to_string(body.options().scheme));
  }

  std::optional<Checkpoint<D>> checkpoint;
  const std::string parameters = simulate_parameters(scene, inputs.mesh.empty());
  if (!inputs.restart.empty()) {
    checkpoint = read_checkpoint<D>(inputs.restart, parameters, bodies.size());
    solver.restore(std::move(checkpoint->flow));
    for (std::size_t b = 0; b < bodies.size(); ++b) bodies[b].restore(checkpoint->bodies[b]);
    records.push_back(io::input_record("restart", inputs.restart));
    spdlog::info("{}: restarting from {} at t = {} s (step {})", stage_name,
                 inputs.restart.string(), solver.time(), solver.step_count());
  }

  const std::filesystem::path folder = output.parent_path().empty() ? "." : output.parent_path();
  std::vector<std::string> columns = coupling::probe_columns<D>(setup.probes);
  for (const SurfaceProbe& p : displacement) {
    static constexpr std::array<const char*, 3> axes{".ux [m]", ".uy [m]", ".uz [m]"};
    for (int a = 0; a < D; ++a) columns.push_back(p.name + axes[static_cast<std::size_t>(a)]);
  }
  std::optional<io::ProbeCsvWriter> csv;
  if (writes && !columns.empty())
    csv.emplace(folder / "probes.csv", columns);
  else if (writes)
    std::filesystem::remove(folder / "probes.csv");
  if (csv && checkpoint)  // the rows up to the checkpoint, as the interrupted run wrote them
    for (std::size_t k = 0; k < checkpoint->run.probes.time.size(); ++k)
      csv->write_row(checkpoint->run.probes.time[k], checkpoint->run.probes.rows[k]);
  std::optional<ldd::SnapshotWriter<D>> snapshots;
  if (writes) snapshots.emplace(folder / "snapshots", "flow");
  if (checkpoint) {
    std::optional<ldd::PointSet<D>> gathered;
    if (processes) gathered = solver.output_points();  // collective
    if (snapshots)
      snapshots->resume(static_cast<std::size_t>(checkpoint->run.snapshots), solver.walls(),
                        wall_names,
                        body_fields<D>(solver, gathered ? *gathered : solver.points(), bodies));
  }
  std::optional<ldd::SnapshotWriter<D>> failed;
  Progress progress(stage_name, setup.time.end, "s", spdlog::get_level() > spdlog::level::info);

  coupling::RunSinks<D> sinks;
  if (!columns.empty()) {
    sinks.evaluate_probes = [&](const ldd::FlowSolver<D>& s) {
      std::vector<double> row;
      if (processes) {  // from the points gathered on process 0, which writes them
        const auto points = s.output_points();
        if (!writes) return std::vector<double>(columns.size(), coupling::probe_missing_value);
        row = coupling::evaluate_probes<D>(points, s.walls(), s.dx(), setup.probes);
      } else {
        row = coupling::evaluate_probes<D>(s, setup.probes);
      }
      // The structure is whole on every process.
      for (const SurfaceProbe& p : displacement) {
        const ldd::Vec<D> u = bodies.front().displacement(p.vertex);
        row.insert(row.end(), u.data(), u.data() + D);
      }
      return row;
    };
    sinks.probe_row = [&](double t, std::span<const double> v) {
      if (csv) csv->write_row(t, v);
    };
  }
  sinks.snapshot = [&](const ldd::FlowSolver<D>& s, coupling::SnapshotKind kind) {
    std::optional<ldd::PointSet<D>> gathered;
    if (processes) gathered = s.output_points();
    if (!writes) return;
    if (kind == coupling::SnapshotKind::diverged && !failed)
      failed.emplace(folder / "snapshots", "diverged");
    auto& writer = kind == coupling::SnapshotKind::regular ? *snapshots : *failed;
    const ldd::PointSet<D>& points = gathered ? *gathered : s.points();
    writer.write(s.time(), points, s.walls(), wall_names, body_fields<D>(s, points, bodies));
  };
  sinks.progress = [&](const ldd::StepMonitor& m) { progress.update(m.time); };
  sinks.checkpoint = [&](const ldd::FlowSolver<D>& s,
                         std::span<const coupling::FlexibleBody<D>> flexible,
                         const coupling::RunResult& so_far) {
    const auto path = checkpoint_path(folder, s.time());
    const ldd::FlowState<D> state = s.state();  // distributed: gathered on process 0
    if (!writes) return;
    write_checkpoint<D>(path, parameters, records, state, flexible, so_far);
    spdlog::info("{}: checkpoint at t = {} s: {}", stage_name, s.time(), path.string());
  };

  const coupling::RunResult r =
      coupling::run<D>(solver, setup.motions, setup.time, sinks, std::span(bodies),
                       checkpoint ? &checkpoint->run : nullptr);
  if (csv) csv->finish();
  const bool completed = r.status == coupling::RunStatus::completed;
  if (completed) progress.finish();
  if (!writes)  // process 0 writes the results and reports
    return completed ? ""
                     : fmt::format("{}: the flow diverged at t = {} s", stage_name, r.end_time);

  io::ArtefactWriter w(output, io::results_schema(), stage_name,
                       simulate_parameters(scene, inputs.mesh.empty()), records);
  write_monitors(w, r.monitors);
  write_phase_totals(w, r.phase_totals);
  write_probes(w, r.probes, columns);
  const std::vector<std::string> dry = coupling::probes_without_fluid<D>(
      setup.probes, std::span<const std::vector<double>>(r.probes.rows));
  w.set_attribute(ra::probes_without_fluid, join(dry, ","));
  if (!bodies.empty()) write_coupling<D>(w, r, bodies.front(), free);
  if (!completed) w.set_attribute(io::attr::status, "diverged: " + first_line(r.divergence_report));
  w.set_attribute(ra::run_status, std::string(coupling::to_string(r.status)));
  w.set_attribute(ra::divergence_report, r.divergence_report);
  w.set_attribute(ra::wall_seconds, r.wall_seconds);
  w.set_attribute(ra::steps, static_cast<std::int64_t>(r.monitors.size()));
  w.set_attribute(ra::points, static_cast<std::int64_t>(fluid_points));
  w.set_attribute(ra::end_time, r.end_time);
  w.set_attribute(ra::snapshots, static_cast<std::int64_t>(r.snapshots));
  w.set_attribute(ra::dt_limit_names, std::string("cfl,viscous,acceleration,maximum,output"));
  w.set_attribute(ra::dx, o.dx);
  w.set_attribute(ra::support, o.support_factor * o.dx);
  w.commit();

  const double steps = static_cast<double>(r.monitors.size());
  spdlog::info(
      "{}: {} at t = {} s: {} steps in {:.2f} s ({:.3g} particle-steps/s); wrote {}, {} "
      "snapshot(s) in {}",
      stage_name, coupling::to_string(r.status), r.end_time, r.monitors.size(), r.wall_seconds,
      steps * fluid_points / std::max(r.wall_seconds, 1e-9), output.string(), r.snapshots,
      (folder / "snapshots").string());
  if (!dry.empty())
    spdlog::warn(
        "{}: probe(s) {} saw no fluid at any sample of the run: their columns hold missing "
        "values (nan) only (a force probe: 0 N); is the probe where the fluid goes?",
        stage_name, join(dry, ", "));
  if (completed) return "";
  return fmt::format(
      "{}: the flow diverged at t = {} s; {} keeps the run up to then (status diverged), {} the "
      "failed state.\n{}",
      stage_name, r.end_time, output.string(), (folder / "snapshots" / "diverged.xdmf").string(),
      r.divergence_report);
}

// ---- structure-only runs ------------------------------------------------------------------

std::vector<std::string> group_names(const mesh::StructureMesh& mesh) {
  std::vector<std::string> names;
  for (const auto& [name, nodes] : mesh.node_groups) names.push_back(name);
  return names;
}

coupling::LoadHistory load_history(const io::SceneView& load,
                                   std::vector<std::filesystem::path>& tables) {
  coupling::LoadHistory h;
  const std::string kind = load.string("history");
  if (kind == "ramp") {
    h.kind = coupling::LoadHistory::Kind::ramp;
    h.ramp_time = load.number("ramp_time");
    if (!(h.ramp_time > 0.0))
      input_error("{}: history = \"ramp\" needs ramp_time > 0 (s)", load.where("history"));
  } else if (kind == "harmonic") {
    h.kind = coupling::LoadHistory::Kind::harmonic;
    h.frequency = load.number("frequency");
    h.phase = load.number("phase");
    if (!(h.frequency > 0.0))
      input_error("{}: history = \"harmonic\" needs frequency > 0 (Hz)", load.where("history"));
  } else if (kind == "table") {
    h.kind = coupling::LoadHistory::Kind::table;
    if (load.string("table").empty())
      input_error("{}: history = \"table\" needs table, a CSV file (t [s], factor [1])",
                  load.where("history"));
    const std::filesystem::path file = load.file_path("table");
    const motion::TimeTable table = motion::read_time_table(file, {"factor [1]"});
    h.table_file = file.string();
    h.table_time = table.time;
    h.table_factor = table.values.front();
    tables.push_back(file);
  }
  return h;
}

std::vector<coupling::StructureLoad> scene_loads(const io::Scene& scene,
                                                 const mesh::StructureMesh& mesh,
                                                 std::vector<std::filesystem::path>& tables) {
  std::vector<coupling::StructureLoad> loads;
  for (const io::SceneView& view : scene.array("load")) {
    coupling::StructureLoad load;
    load.name = view.string("name");
    const std::string group = view.string("group");
    if (!mesh.node_groups.contains(group)) {
      const auto names = group_names(mesh);
      const std::string guess = closest_match(group, names);
      input_error("{} = \"{}\" is not a node group of the structure mesh: expected one of {}{}",
                  view.where("group"), group, fmt::join(names, ", "),
                  guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess));
    }
    const Eigen::VectorXd force = view.vector("force");
    if (force.size() != mesh.dim)
      input_error("{} has {} values; a {}-D structure needs {}", view.where("force"), force.size(),
                  mesh.dim, mesh.dim);
    load.force = fem::nodal_force(mesh, group, force);
    load.history = load_history(view, tables);
    loads.push_back(std::move(load));
  }
  return loads;
}

std::vector<coupling::DisplacementProbe> displacement_probes(const io::Scene& scene,
                                                             const mesh::StructureMesh& mesh) {
  std::vector<coupling::DisplacementProbe> probes;
  for (const io::SceneView& view : scene.array("probe")) {
    if (view.string("kind") != "displacement")
      input_error("{} = \"{}\": a structure-only run (no [fluid]) has displacement probes only",
                  view.where("kind"), view.string("kind"));
    const Eigen::VectorXd x = view.vector("position");
    if (x.size() != mesh.dim)
      input_error("{}: a displacement probe needs position, {} values (m)", view.where("kind"),
                  mesh.dim);
    Eigen::Index node = 0;
    (mesh.nodes.rowwise() - x.transpose()).rowwise().squaredNorm().minCoeff(&node);
    const double distance = (mesh.nodes.row(node).transpose() - x).norm();
    spdlog::info("fsi-simulate: probe {}: node {} at [{}] m, {:.3g} m from the position",
                 view.string("name"), node, fmt::join(mesh.nodes.row(node), ", "), distance);
    probes.push_back({view.string("name"), node});
  }
  return probes;
}

void write_structure_run(io::ArtefactWriter& w, const coupling::StructureRun& run,
                         const std::vector<std::string>& columns) {
  w.write(ds::modal_time, run.time);
  w.write(ds::modal_coordinates, io::MatrixRM(run.y));
  w.write(ds::modal_velocities, io::MatrixRM(run.v));
  w.write(ds::modal_forces, io::MatrixRM(run.F));
  write_probes(w, run.probes, columns);
  w.set_attribute(ra::run_status, std::string("completed"));
  w.set_attribute(ra::divergence_report, std::string());
  w.set_attribute(ra::wall_seconds, run.wall_seconds);
  w.set_attribute(ra::steps, static_cast<std::int64_t>(run.steps));
  w.set_attribute(ra::points, static_cast<std::int64_t>(0));
  w.set_attribute(ra::end_time, run.time.back());
  w.set_attribute(ra::snapshots, static_cast<std::int64_t>(0));
}

void run_structure_only(const io::Scene& scene, const SimulateInputs& inputs,
                        const std::filesystem::path& output) {
  if (inputs.mesh.empty() || inputs.modes.empty())
    throw UsageError(fmt::format(
        "{}: {} is a structure-only scene (no [fluid]): give --mesh mesh.h5 (the node groups) "
        "and --modes modes.h5",
        stage_name, scene.file().string()));
  const auto mesh = read_structure_mesh(io::ArtefactReader(inputs.mesh, io::mesh_schema()));
  const modal::ModeSet modes = read_mode_set(io::ArtefactReader(inputs.modes, io::modes_schema()));
  if (modes.shapes.rows() != mesh.structure.dim * mesh.structure.node_count())
    input_error("{}: the modes have {} DOFs, the mesh {} has {} nodes × {}: not the same mesh",
                inputs.modes.string(), modes.shapes.rows(), inputs.mesh.string(),
                mesh.structure.node_count(), mesh.structure.dim);
  std::vector<std::filesystem::path> tables;
  const auto loads = scene_loads(scene, mesh.structure, tables);
  const auto probes = displacement_probes(scene, mesh.structure);
  const io::SceneView time = scene.section("time");
  const coupling::TimeControl control{.end = time.number("end"),
                                      .probe_interval = time.number("probe_interval")};
  const double dt = time.number("dt_max");
  const bool static_start = scene.section("structure").boolean("static_start");
  spdlog::info("{}: structure only: {} modes, {} load(s), {} probe(s), Δt = {} s to t = {} s{}",
               stage_name, modes.count(), loads.size(), probes.size(), dt, control.end,
               static_start ? ", from the static solution" : "");

  const std::filesystem::path folder = output.parent_path().empty() ? "." : output.parent_path();
  const auto columns = coupling::displacement_columns(probes, mesh.structure.dim);
  std::optional<io::ProbeCsvWriter> csv;
  if (!columns.empty())
    csv.emplace(folder / "probes.csv", columns);
  else
    std::filesystem::remove(folder / "probes.csv");
  const auto run = coupling::run_structure(
      modes, loads, probes, control, dt, static_start,
      [&](double t, std::span<const double> row) { csv->write_row(t, row); });
  if (csv) csv->finish();

  std::vector<io::InputRecord> records{io::input_record("scene", scene.file()),
                                       io::input_record("mesh", inputs.mesh),
                                       io::input_record("modes", inputs.modes)};
  for (std::size_t k = 0; k < tables.size(); ++k)
    records.push_back(io::input_record(fmt::format("load_table_{}", k), tables[k]));
  io::ArtefactWriter w(output, io::results_schema(), stage_name, scene.parameters_for(stage_name),
                       records);
  write_structure_run(w, run, columns);
  w.commit();
  spdlog::info("{}: completed at t = {} s: {} steps in {:.3f} s; wrote {}", stage_name,
               run.time.back(), run.steps, run.wall_seconds, output.string());
}

}  // namespace

std::string simulate_parameters(const io::Scene& scene, bool walls_from_scene) {
  std::string text = scene.parameters_for(stage_name);
  if (!walls_from_scene) return text;
  const std::string mesh = scene.parameters_for("fsi-mesh");
  for (std::size_t start = 0; start < mesh.size();) {
    const std::size_t end = mesh.find('\n', start);
    const std::string line = mesh.substr(start, end - start);
    if (line.rfind("wall[", 0) == 0) text += line + "\n";
    start = end == std::string::npos ? mesh.size() : end + 1;
  }
  return text;
}

void validate_simulate_scene(const io::Scene& scene) {
  if (!is_flow_scene(scene) && !scene.has("structure"))
    input_error(
        "{}: nothing to simulate: the scene has neither a [fluid] nor a [structure] "
        "section",
        scene.file().string());
  validate_flow_scene(scene);
  if (is_flow_scene(scene) && scene.has("structure")) validate_structure_model(scene);
  if (is_flow_scene(scene)) {
    if (!scene.array("load").empty())
      input_error(
          "{}: [[load]]s act on a structure-only run (no [fluid]); a flow loads the "
          "structure itself",
          scene.array("load").front().where("group"));
    return;
  }
  std::vector<std::filesystem::path> tables;
  for (const io::SceneView& load : scene.array("load")) load_history(load, tables);
  for (const io::SceneView& probe : scene.array("probe"))
    if (probe.string("kind") != "displacement")
      input_error("{} = \"{}\": a structure-only run (no [fluid]) has displacement probes only",
                  probe.where("kind"), probe.string("kind"));
}

void run_simulate_stage(const io::Scene& scene, const SimulateInputs& inputs,
                        const std::filesystem::path& output) {
  validate_simulate_scene(scene);
  if (!is_flow_scene(scene)) {
    run_structure_only(scene, inputs, output);
    return;
  }
  if (scene.dimension() == 2)
    run_flow<2>(scene, inputs, output);
  else
    run_flow<3>(scene, inputs, output);
}

}  // namespace hm::driver
