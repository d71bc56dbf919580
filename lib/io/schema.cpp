#include "io/schema.hpp"

#include <fmt/format.h>

namespace hm::io {

std::string_view dtype_name(DType type) {
  switch (type) {
    case DType::f64:
      return "float64";
    case DType::i64:
      return "int64";
    case DType::str:
      return "string";
  }
  return "?";
}

static bool path_matches(std::string_view pattern, std::string_view path) {
  // Component-wise match; a component "*" matches any single name.
  while (!pattern.empty() || !path.empty()) {
    const auto cut = [](std::string_view& s) {
      const auto slash = s.find('/', 1);
      std::string_view head = s.substr(0, slash);
      s = slash == std::string_view::npos ? std::string_view{} : s.substr(slash);
      return head;
    };
    const std::string_view p = cut(pattern), q = cut(path);
    if (p != "/*" && p != q) return false;
    if (p == "/*" && q.size() < 2) return false;
  }
  return true;
}

const DatasetSpec* SchemaSpec::find(std::string_view dataset_path) const {
  for (const auto& spec : datasets)
    if (path_matches(spec.path, dataset_path)) return &spec;
  return nullptr;
}

bool SchemaSpec::reads(int file_version) const {
  return file_version <= version &&
         file_version >= (oldest_readable > 0 ? oldest_readable : version);
}

std::string SchemaSpec::readable_versions() const {
  if (oldest_readable <= 0 || oldest_readable == version) return fmt::format("version {}", version);
  return fmt::format("versions {} to {}", oldest_readable, version);
}

static DatasetSpec optional(DatasetSpec spec) {
  spec.required = false;
  return spec;
}

/// A dataset whose NaNs are missing values (DatasetSpec::missing_values).
static DatasetSpec with_missing_values(DatasetSpec spec) {
  spec.missing_values = true;
  return spec;
}

const SchemaSpec& mesh_schema() {
  static const SchemaSpec spec{
      schema::mesh,
      1,
      "Structure mesh (quadratic: tri6 in 2-D, tet10 in 3-D; gmsh node order) with named groups, "
      "its linear boundary surface, and fluid wall surfaces. Written by fsi-mesh.",
      {
          {ds::structure_nodes, DType::f64, {"n_nodes", "dim"}, "m", "node coordinates"},
          {ds::structure_cells,
           DType::i64,
           {"n_cells", "nodes_per_cell"},
           "",
           "0-based node indices of each cell (tri6: 6, tet10: 10; gmsh order)"},
          optional({ds::structure_cells_vtk,
                    DType::i64,
                    {"n_cells", "nodes_per_cell"},
                    "",
                    "3-D only: the cells in VTK/XDMF node order (tet10 nodes 8, 9 swapped)"}),
          {ds::structure_facets,
           DType::i64,
           {"n_facets", "nodes_per_facet"},
           "",
           "boundary facets (line3 in 2-D, tri6 in 3-D), 0-based node indices"},
          optional({std::string(ds::structure_node_groups) + "*",
                    DType::i64,
                    {"*"},
                    "",
                    "physical group: sorted 0-based indices of its nodes"}),
          optional({std::string(ds::structure_facet_groups) + "*",
                    DType::i64,
                    {"*"},
                    "",
                    "physical group: indices into /structure/facets"}),
          {ds::structure_surface_vertices,
           DType::f64,
           {"n_surface_vertices", "dim"},
           "m",
           "linear boundary surface: vertices"},
          {ds::structure_surface_cells,
           DType::i64,
           {"n_surface_cells", "dim"},
           "",
           "linear boundary surface: segments (2-D) or triangles (3-D)"},
          {ds::structure_surface_node,
           DType::i64,
           {"n_surface_vertices"},
           "",
           "volume node index of each surface vertex"},
          {ds::structure_quality,
           DType::f64,
           {"n_cells"},
           "1",
           "element shape quality in [0, 1] (1: equilateral)"},
          optional({std::string(ds::walls) + "*/vertices",
                    DType::f64,
                    {"*", "dim"},
                    "m",
                    "fluid wall surface: vertices"}),
          optional(
              {std::string(ds::walls) + "*/cells",
               DType::i64,
               {"*", "dim"},
               "",
               "fluid wall surface: segments (2-D) or triangles (3-D); normals into the fluid"}),
      }};
  return spec;
}

const SchemaSpec& modes_schema() {
  static const SchemaSpec spec{
      schema::modes,
      2,
      "Natural frequencies and mass-normalised mode shapes (Phi^T M Phi = I) of one structure, "
      "with invariant checks and participation factors. Written by fsi-modes. With "
      "modes.derivatives (version 2) also the reduced basis V = [Phi, Theta] of the nonlinear "
      "modal model (structure.model = \"nonlinear_modal\") and its Saint Venant-Kirchhoff "
      "force, exactly cubic in the reduced coordinates q (u = V q): f_r,i(q) = sum_j K1_ij q_j + "
      "sum_{j<=k} K2_i,jk q_j q_k + sum_{j<=k<=l} K3_i,jkl q_j q_k q_l, the pairs (j, k) and "
      "triples (j, k, l) in lexicographic order ((0,0), (0,1), ..., (0,r-1), (1,1), ...), each "
      "coefficient the Taylor coefficient of its monomial (the derivative of f_r,i by q_j, q_k "
      "(, q_l) divided by 2 when two indices are equal, by 6 when three are); the strain energy "
      "is W = q.f1/2 + q.f2/3 + q.f3/4 of the parts of degree 1, 2, 3. Root attributes then: "
      "basis_modes, basis_derivatives, basis_dropped, derivatives_seconds, tensor_seconds.",
      {
          {ds::eigenvalues, DType::f64, {"n_modes"}, "rad^2/s^2", "eigenvalues lambda = omega^2"},
          {ds::omega, DType::f64, {"n_modes"}, "rad/s", "angular natural frequencies"},
          {ds::frequencies_hz, DType::f64, {"n_modes"}, "Hz", "natural frequencies"},
          {ds::damping_ratio, DType::f64, {"n_modes"}, "1", "modal damping ratio zeta"},
          {ds::shapes,
           DType::f64,
           {"n_modes", "n_nodes", "dim"},
           "1/sqrt(kg)",
           "mass-normalised mode shapes on every node"},
          {ds::residual, DType::f64, {"n_modes"}, "1", "||K phi - lambda M phi|| / ||K phi||"},
          {ds::orthogonality_error,
           DType::f64,
           {"n_modes"},
           "1",
           "max_j |(Phi^T M Phi - I)_ij| for mode i"},
          {ds::participation_translation,
           DType::f64,
           {"n_modes", "dim"},
           "sqrt(kg)",
           "Phi^T M T for unit translations along x, y (, z)"},
          {ds::participation_rotation,
           DType::f64,
           {"n_modes", "n_rotations"},
           "sqrt(kg)*m",
           "Phi^T M R for unit rotations about the reference point (z in 2-D; x, y, z in 3-D)"},
          {ds::effective_mass_translation,
           DType::f64,
           {"n_modes", "dim"},
           "kg",
           "effective modal masses (participation squared)"},
          {ds::effective_mass_rotation,
           DType::f64,
           {"n_modes", "n_rotations"},
           "kg*m^2",
           "effective modal moments of inertia about the reference point"},
          {ds::surface_shapes,
           DType::f64,
           {"n_modes", "n_surface_vertices", "dim"},
           "1/sqrt(kg)",
           "mode shapes on the linear boundary surface vertices"},
          {ds::modes_nodes, DType::f64, {"n_nodes", "dim"}, "m", "copy of the structure nodes"},
          {ds::modes_cells, DType::i64, {"n_cells", "nodes_per_cell"}, "", "copy of the cells"},
          optional({ds::modes_cells_vtk,
                    DType::i64,
                    {"n_cells", "nodes_per_cell"},
                    "",
                    "3-D only: the cells in VTK/XDMF node order"}),
          {ds::modes_surface_vertices,
           DType::f64,
           {"n_surface_vertices", "dim"},
           "m",
           "copy of the boundary surface vertices"},
          {ds::modes_surface_cells,
           DType::i64,
           {"n_surface_cells", "dim"},
           "",
           "copy of the boundary surface cells"},
          {ds::modes_surface_node,
           DType::i64,
           {"n_surface_vertices"},
           "",
           "volume node of each surface vertex"},
          optional({ds::basis_vectors,
                    DType::f64,
                    {"n_basis", "n_nodes", "dim"},
                    "1/sqrt(kg)",
                    "the reduced basis V on every node: the modes, then the static modal "
                    "derivatives theta_ij = -K0^-1 d2f[phi_i, phi_j] (i <= j), M-orthonormalised "
                    "(V^T M V = I, Gram-Schmidt in that order, dependent candidates dropped); "
                    "zero at clamped nodes"}),
          optional({ds::basis_surface_vectors,
                    DType::f64,
                    {"n_basis", "n_surface_vertices", "dim"},
                    "1/sqrt(kg)",
                    "the reduced basis on the linear boundary surface vertices"}),
          optional({ds::basis_origin,
                    DType::i64,
                    {"n_basis", "2"},
                    "",
                    "what each basis vector came from: (i, -1) mode i, (i, j) the derivative "
                    "theta_ij (0-based mode indices)"}),
          optional({ds::basis_omega,
                    DType::f64,
                    {"n_basis"},
                    "rad/s",
                    "sqrt(K1_ii / M_r,ii) of each basis vector: omega of a mode, the Rayleigh "
                    "quotient's frequency of a derivative"}),
          optional({ds::basis_participation_translation,
                    DType::f64,
                    {"n_basis", "dim"},
                    "sqrt(kg)",
                    "V^T M T for unit translations along x, y (, z)"}),
          optional({ds::basis_participation_rotation,
                    DType::f64,
                    {"n_basis", "n_rotations"},
                    "sqrt(kg)*m",
                    "V^T M R for unit rotations about the reference point"}),
          optional({ds::reduced_mass,
                    DType::f64,
                    {"n_basis", "n_basis"},
                    "1",
                    "M_r = V^T M V (the identity to round-off)"}),
          optional({ds::reduced_linear,
                    DType::f64,
                    {"n_basis", "n_basis"},
                    "1/s^2",
                    "K1 = V^T K0 V: the linear part of f_r (the Lame constants of E and nu, "
                    "Saint Venant-Kirchhoff)"}),
          optional({ds::reduced_quadratic,
                    DType::f64,
                    {"n_basis", "n_pairs"},
                    "1/(s^2*m*sqrt(kg))",
                    "K2: column (j, k), j <= k, lexicographic, r(r+1)/2 of them: the coefficient "
                    "of q_j q_k in f_r"}),
          optional({ds::reduced_cubic,
                    DType::f64,
                    {"n_basis", "n_triples"},
                    "1/(s^2*m^2*kg)",
                    "K3: column (j, k, l), j <= k <= l, lexicographic, r(r+1)(r+2)/6 of them: the "
                    "coefficient of q_j q_k q_l in f_r"}),
      },
      1};
  return spec;
}

const SchemaSpec& mapped_modes_schema() {
  static const SchemaSpec spec{
      schema::mapped_modes,
      2,
      "Mode shapes interpolated from the structure's boundary surface onto the surface the fluid "
      "sees (RBF: Wendland C2 + linear polynomial; consistent for shapes, its transpose "
      "conservative for forces), with the modal data fsi-simulate needs. Written by fsi-map. A "
      "mode set with a reduced basis (modes.derivatives, version 2) has its basis mapped by the "
      "same interpolation, the modes' shapes unchanged: the interface of structure.model = "
      "\"nonlinear_modal\".",
      {
          {ds::target_vertices, DType::f64, {"n_target", "dim"}, "m", "target surface vertices"},
          {ds::target_cells,
           DType::i64,
           {"n_target_cells", "dim"},
           "",
           "target surface segments (2-D) or triangles (3-D)"},
          {ds::mapped_shapes,
           DType::f64,
           {"n_modes", "n_target", "dim"},
           "1/sqrt(kg)",
           "mass-normalised mode shapes at the target vertices"},
          {ds::frequencies_hz, DType::f64, {"n_modes"}, "Hz", "natural frequencies"},
          {ds::omega, DType::f64, {"n_modes"}, "rad/s", "angular natural frequencies"},
          {ds::damping_ratio, DType::f64, {"n_modes"}, "1", "modal damping ratio zeta"},
          {ds::participation_translation,
           DType::f64,
           {"n_modes", "dim"},
           "sqrt(kg)",
           "Phi^T M T (base excitation of a moving tank)"},
          {ds::participation_rotation,
           DType::f64,
           {"n_modes", "n_rotations"},
           "sqrt(kg)*m",
           "Phi^T M R about the reference point of fsi-modes"},
          {ds::mapping_field_error,
           DType::f64,
           {"n_modes"},
           "1",
           "interpolation error of each mode, max |error| / max |mode|: measured at the targets "
           "when every target vertex is a structure surface node (the identity map: round-off), "
           "else the leave-some-out estimate (every 10th node left out)"},
          optional({ds::mapped_basis,
                    DType::f64,
                    {"n_basis", "n_target", "dim"},
                    "1/sqrt(kg)",
                    "the reduced basis V (modes.h5 /basis) at the target vertices"}),
          optional({ds::basis_origin,
                    DType::i64,
                    {"n_basis", "2"},
                    "",
                    "(i, -1) mode i, (i, j) the derivative theta_ij (as in modes.h5)"}),
          optional({ds::basis_omega,
                    DType::f64,
                    {"n_basis"},
                    "rad/s",
                    "sqrt(K1_ii / M_r,ii) of each basis vector (as in modes.h5)"}),
          optional({ds::basis_participation_translation,
                    DType::f64,
                    {"n_basis", "dim"},
                    "sqrt(kg)",
                    "V^T M T (the body's weight and a moving tank's base excitation)"}),
          optional({ds::basis_participation_rotation,
                    DType::f64,
                    {"n_basis", "n_rotations"},
                    "sqrt(kg)*m",
                    "V^T M R about the reference point of fsi-modes"}),
          optional({ds::mapped_basis_field_error,
                    DType::f64,
                    {"n_basis"},
                    "1",
                    "interpolation error of each basis vector, as /quality/field_error"}),
      },
      1};
  return spec;
}

const SchemaSpec& results_schema() {
  static const SchemaSpec spec{
      schema::results,
      1,
      "A simulation run of fsi-simulate: the probe series (also in probes.csv), the monitors of "
      "every time step and the run's totals. Root attributes: run_status (completed | diverged), "
      "divergence_report (the report text of a diverged run, else empty), wall_seconds, steps, "
      "points (fluid points at the start), end_time [s], snapshots, dx [m], support (h) [m], "
      "probe_columns (the names of the columns of /probes/values as in the CSV header, "
      "comma-separated; a sample with no fluid in a probe's support is NaN, a missing value), "
      "probes_without_fluid (the probes that saw no fluid at any sample, comma-separated; empty "
      "when every probe did), dt_limit_names (the names of the /monitors/dt_limit codes in code "
      "order: "
      "cfl, viscous, acceleration, maximum, output) and phase_names (the entries of "
      "/run/phase_seconds); a coupled run also coupling_scheme, max_structure_stretch, "
      "max_structure_deformation [m], max_structure_pressure [Pa], coupling_seconds, "
      "added_mass_seconds and structure_seconds (the structure model's part of the coupling), "
      "and with a body "
      "in free translation body_mass [kg] and free_axis. A "
      "diverged run has status \"diverged: ...\" (so --if-stale reruns "
      "it). A flow run has the /monitors and /run datasets; a structure-only run (no fluid) the "
      "/modal ones instead; a coupled run (fluid and structure) both.",
      {
          optional({ds::probe_time, DType::f64, {"n_probe_rows"}, "s", "times of the probe rows"}),
          with_missing_values(
              optional({ds::probe_values,
                        DType::f64,
                        {"n_probe_rows", "n_probe_columns"},
                        "column",
                        "probe values, one row per probe time, one column per name of the "
                        "probe_columns attribute (its unit in brackets: Pa, m or N); NaN: no "
                        "fluid at the probe (a missing value)"})),
          optional({ds::monitor_step, DType::i64, {"n_steps"}, "", "step number, from 1"}),
          optional({ds::monitor_time, DType::f64, {"n_steps"}, "s", "time at the end of the step"}),
          optional({ds::monitor_dt, DType::f64, {"n_steps"}, "s", "time step"}),
          optional(
              {ds::monitor_dt_limit,
               DType::i64,
               {"n_steps"},
               "",
               "what set the step: 0 cfl, 1 viscous, 2 acceleration, 3 maximum (dt_max), 4 output "
               "(a snapshot, probe or end time)"}),
          optional(
              {ds::monitor_ppe_iterations, DType::i64, {"n_steps"}, "", "PPE solver iterations"}),
          optional({ds::monitor_ppe_passes,
                    DType::i64,
                    {"n_steps"},
                    "",
                    "PPE solves (1 + re-solves after releasing wall tension)"}),
          optional({ds::monitor_ppe_residual,
                    DType::f64,
                    {"n_steps"},
                    "1",
                    "relative residual of the last PPE solve"}),
          optional(
              {ds::monitor_ppe_converged, DType::i64, {"n_steps"}, "", "1 if the PPE converged"}),
          optional({ds::monitor_max_divergence,
                    DType::f64,
                    {"n_steps"},
                    "1/s",
                    "max |div u| over interior fluid points after the step"}),
          optional({ds::monitor_volume_drift,
                    DType::f64,
                    {"n_steps"},
                    "1",
                    "V/V0 - 1 of the volume the fluid fills (half-density region of its kernel "
                    "density), V0 scaled by the share of points not escaped"}),
          optional(
              {ds::monitor_max_speed, DType::f64, {"n_steps"}, "m/s", "max |u| of fluid points"}),
          optional({ds::monitor_escaped,
                    DType::i64,
                    {"n_steps"},
                    "",
                    "fluid points removed so far (left the walls' bounding box)"}),
          optional({ds::monitor_fluid, DType::i64, {"n_steps"}, "", "fluid points"}),
          optional({ds::monitor_surface, DType::i64, {"n_steps"}, "", "free-surface fluid points"}),
          optional(
              {ds::monitor_isolated, DType::i64, {"n_steps"}, "", "isolated (ballistic) points"}),
          optional({ds::monitor_wall_active, DType::i64, {"n_steps"}, "", "active wall nodes"}),
          optional(
              {ds::run_phase_seconds,
               DType::f64,
               {"n_phases"},
               "s",
               "wall-clock time per phase of the step summed over the run (names: phase_names)"}),
          optional({ds::modal_time,
                    DType::f64,
                    {"n_modal_rows"},
                    "s",
                    "structure-only and coupled runs: the start and the end of every step"}),
          optional({ds::modal_coordinates,
                    DType::f64,
                    {"n_modal_rows", "n_modes"},
                    "m*sqrt(kg)",
                    "modal coordinates y (mass-normalised modes): the structure model's interface "
                    "coordinates (nonlinear_fe: Phi^T M u; nonlinear_modal: the coordinates q of "
                    "its basis V, n_modes = n_basis)"}),
          optional({ds::modal_velocities,
                    DType::f64,
                    {"n_modal_rows", "n_modes"},
                    "m*sqrt(kg)/s",
                    "modal velocities dy/dt"}),
          optional({ds::modal_forces,
                    DType::f64,
                    {"n_modal_rows", "n_modes"},
                    "N/sqrt(kg)",
                    "modal forces F = Phi^T f"}),
          optional({ds::modal_added_mass,
                    DType::f64,
                    {"n_modes", "n_modes"},
                    "1",
                    "coupled runs (strong scheme): the last measured modal added-mass matrix of "
                    "the fluid (in units of the modal mass)"}),
          optional({ds::modal_added_mass_initial,
                    DType::f64,
                    {"n_modes", "n_modes"},
                    "1",
                    "coupled runs (strong scheme): the modal added-mass matrix at the start"}),
          optional({ds::monitor_coupling_iterations,
                    DType::i64,
                    {"n_steps"},
                    "",
                    "coupled runs: PPE solves of the step (the coupling sub-iterations)"}),
          optional({ds::monitor_interface_residual,
                    DType::f64,
                    {"n_steps"},
                    "1",
                    "coupled runs: relative mismatch between the modal acceleration the fluid "
                    "saw and the structure's answer to the fluid's load, after the last solve"}),
          optional({ds::monitor_structure_stretch,
                    DType::f64,
                    {"n_steps"},
                    "1",
                    "coupled runs: max |sum Phi y| over the structure's surface / its size "
                    "(linear modes stretch visibly above 0.05)"}),
          optional({ds::monitor_coupling_seconds,
                    DType::f64,
                    {"n_steps"},
                    "s",
                    "coupled runs: wall-clock time of the coupling in the step (loads, CFPI, "
                    "wall updates, added-mass solves; not the PPE re-solves)"}),
          optional({ds::monitor_structure_seconds,
                    DType::f64,
                    {"n_steps"},
                    "s",
                    "coupled runs: the part of coupling_seconds spent in the structure model "
                    "(its predictor and corrector, e.g. the Newton solves of a nonlinear body, "
                    "and the walls it places)"}),
          optional({ds::monitor_structure_deformation,
                    DType::f64,
                    {"n_steps"},
                    "m",
                    "coupled runs: max |sum Phi y| of the elastic modes over the structure's "
                    "surface (a free body's rigid translation excluded)"}),
          optional({ds::monitor_structure_peak_pressure,
                    DType::f64,
                    {"n_steps"},
                    "Pa",
                    "coupled runs: the largest pressure of the structure's wall nodes at the "
                    "step's end"}),
          optional({ds::monitor_structure_energy,
                    DType::f64,
                    {"n_steps", "5"},
                    "J",
                    "coupled runs: the structure's energy at the step's end (2-D: per its "
                    "thickness), columns energy_columns: kinetic, strain, the work of the "
                    "fluid's loads and the body's weight since the start, the energy taken by "
                    "the structural damping, and the numerical dissipation (work − damping − "
                    "change of kinetic + strain; CFPI: the error of the trapezoidal work sum)"}),
          optional({ds::monitor_structure_solver_iterations,
                    DType::i64,
                    {"n_steps"},
                    "",
                    "coupled runs with a nonlinear structure model: Newton iterations of the "
                    "structure in the step (predictor and corrector)"}),
          optional({ds::body_position,
                    DType::f64,
                    {"n_modal_rows"},
                    "m",
                    "a body in free translation: its displacement along free_axis"}),
          optional({ds::body_velocity,
                    DType::f64,
                    {"n_modal_rows"},
                    "m/s",
                    "a body in free translation: its velocity along free_axis"}),
      }};
  return spec;
}

const SchemaSpec& report_schema() {
  static const SchemaSpec spec{
      schema::report,
      1,
      "The report of a finished run (fsi-report): per [[report.compare]] entry the error "
      "metrics of a probe column against a reference curve. Root attribute comparison_labels "
      "(`<column> vs <label>`, separated by newlines). The plots (PNG), metrics.json and "
      "metrics.md are written beside it.",
      {
          optional({"/comparisons/metrics",
                    DType::f64,
                    {"n_comparisons", "n_metrics"},
                    "column",
                    "per comparison (none: a report of plots only): computed peak, its time [s], "
                    "reference peak, its time [s], relative peak error, time-of-peak error [s], "
                    "RMS difference, RMS / |reference peak|, window start [s], window end [s] "
                    "(peaks are the values of largest magnitude; units of the probe column)"}),
      }};
  return spec;
}

const SchemaSpec& checkpoint_schema() {
  auto f64 = [](const char* path, std::vector<std::string> shape, const char* unit, const char* doc,
                bool required = true) {
    return DatasetSpec{path, DType::f64, std::move(shape), unit, doc, required};
  };
  auto i64 = [](const char* path, std::vector<std::string> shape, const char* doc) {
    return DatasetSpec{path, DType::i64, std::move(shape), "", doc, true};
  };
  static const SchemaSpec spec{
      schema::checkpoint,
      1,
      "The state of an fsi-simulate run at a checkpoint time (time.checkpoint_interval), from "
      "which `fsi-simulate --restart` continues exactly (a run over processes, or a restart on "
      "another number of them: to the PPE tolerance): every point with its fields and id, the last "
      "neighbour lists, the walls' vertex kinematics, the flexible bodies' modal state and the "
      "run so far (monitors, probe rows, modal histories). Root attributes: time [s], step, "
      "start_time [s], escaped, initial_fluid, initial_volume, last_volume_drift, "
      "last_max_wall_speed, last_max_speed, neighbour_radius [m], snapshots, wall_seconds. "
      "Written for one scene: a restart checks its parameters.",
      {
          f64("/points/position", {"n_points", "dim"}, "m", "point positions"),
          f64("/points/velocity", {"n_points", "dim"}, "m/s", "point velocities"),
          f64("/points/pressure", {"n_points"}, "Pa", "gauge pressure"),
          i64("/points/kind", {"n_points"}, "0 fluid, 1 wall node"),
          i64("/points/type", {"n_points"},
              "0 interior, 1 surface, 2 wall, 3 isolated, 4 inactive"),
          f64("/points/wall_normal", {"n_points", "dim"}, "1", "wall nodes: unit normal"),
          f64("/points/wall_velocity", {"n_points", "dim"}, "m/s", "wall nodes: velocity"),
          f64("/points/wall_acceleration", {"n_points", "dim"}, "m/s^2",
              "wall nodes: acceleration"),
          i64("/points/host_body", {"n_points"}, "wall nodes: wall index (-1 for fluid points)"),
          i64("/points/host_element", {"n_points"}, "wall nodes: element of the wall"),
          f64("/points/host_barycentric", {"n_points", "dim"}, "1", "wall nodes: barycentrics"),
          f64("/points/velocity_gradient", {"n_points", "dim2"}, "1/s", "grad u, row-major"),
          f64("/points/wall_distance", {"n_points"}, "m", "lower bound of the wall clearance"),
          f64("/points/acceleration", {"n_points"}, "m/s^2", "|du/dt| of the last step"),
          optional(i64("/points/id", {"n_points"},
                       "each point's id over the run (checkpoints before it: the points' order)")),
          i64("/neighbours/offsets", {"n_offsets"},
              "list of i: indices[offsets[i], offsets[i+1]); a distributed run's checkpoint "
              "holds none (offsets {0}): the restart rebuilds them"),
          i64("/neighbours/indices", {"n_pairs"}, "neighbour point indices"),
          i64("/walls/offsets", {"n_wall_offsets"}, "vertices of wall w: rows offsets[w] ... "),
          f64("/walls/x", {"n_wall_vertices", "dim"}, "m", "wall vertex positions"),
          f64("/walls/v", {"n_wall_vertices", "dim"}, "m/s", "wall vertex velocities"),
          f64("/walls/a", {"n_wall_vertices", "dim"}, "m/s^2", "wall vertex accelerations"),
          f64("/bodies/y", {"n_bodies", "n_modes"}, "m*sqrt(kg)", "modal coordinates", false),
          f64("/bodies/v", {"n_bodies", "n_modes"}, "m*sqrt(kg)/s", "modal velocities", false),
          f64("/bodies/a", {"n_bodies", "n_modes"}, "m*sqrt(kg)/s^2", "modal accelerations", false),
          f64("/bodies/F", {"n_bodies", "n_modes"}, "N/sqrt(kg)", "modal forces", false),
          f64("/bodies/added_mass", {"n_bodies", "n_modes", "n_modes"}, "1", "M hat", false),
          f64("/bodies/model/*", {"*"}, "SI",
              "the structure model's own state beyond its interface coordinates (a nonlinear "
              "body: nodal u [m], v [m/s], a [m/s^2], load [N]; energy_balance [J]: its start, "
              "the work, the damping)",
              false),
          f64("/bodies/added_mass_initial", {"n_bodies", "n_modes", "n_modes"}, "1",
              "M hat at the start", false),
          f64("/run/monitors", {"n_steps", "n_monitor_fields"}, "column",
              "the StepMonitor of every step so far, packed (driver/checkpoint_io.cpp)", false),
          f64("/run/coupling", {"n_steps", "n_coupling_fields"}, "column",
              "the CouplingMonitors of every step so far, packed", false),
          f64("/run/phase_totals", {"n_phases"}, "s", "phase seconds so far"),
          f64("/run/probe_time", {"n_probe_rows"}, "s", "probe times so far", false),
          with_missing_values(f64("/run/probe_values", {"n_probe_rows", "n_probe_columns"},
                                  "column", "probe rows so far (NaN: a missing value)", false)),
          f64("/run/modal", {"n_bodies", "n_modal_rows", "n_modal_fields"}, "column",
              "per body and modal row: t, y, v, F", false),
      }};
  return spec;
}

std::vector<const SchemaSpec*> all_schemas() {
  return {&mesh_schema(),    &modes_schema(),      &mapped_modes_schema(),
          &results_schema(), &checkpoint_schema(), &report_schema()};
}

const SchemaSpec* find_schema(std::string_view name) {
  for (const SchemaSpec* spec : all_schemas())
    if (spec->name == name) return spec;
  return nullptr;
}

std::string schema_reference_markdown() {
  std::string out =
      "# Artefact schemas\n\nGenerated by `fsi-inspect --print-schemas`. Every artefact carries "
      "the "
      "root attributes `schema`, `schema_version`, `stage`, `tool_version`, `created_utc`, "
      "`parameters` (canonical TOML), `parameters_sha256`, `status`, and for every input "
      "`input:<role>:path` and `input:<role>:sha256`. Every dataset carries `unit` and "
      "`description` attributes.\n";
  for (const SchemaSpec* spec : all_schemas()) {
    out += fmt::format(
        "\n## `{}` version {}\n\n{}{}\n\n| dataset | type | shape | unit | meaning |\n"
        "|---|---|---|---|---|\n",
        spec->name, spec->version, spec->doc,
        spec->reads(spec->version - 1)
            ? fmt::format(" (Readers accept {}.)", spec->readable_versions())
            : std::string());
    for (const auto& d : spec->datasets) {
      std::string shape;
      for (const auto& s : d.shape) shape += (shape.empty() ? "" : " × ") + s;
      out +=
          fmt::format("| `{}`{} | {} | {} | {} | {} |\n", d.path, d.required ? "" : " (optional)",
                      dtype_name(d.type), shape, d.unit.empty() ? "—" : d.unit, d.doc);
    }
  }
  return out;
}

}  // namespace hm::io
