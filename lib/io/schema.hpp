#pragma once
// The artefact schemas of hydromodal: every dataset each artefact kind holds, with its shape,
// type, unit and meaning. This header and schema.cpp are the single place where dataset and
// attribute names are spelled; `fsi-inspect --print-schemas` prints this as the reference.
//
// Shapes are lists of symbolic extents ("n_nodes", "dim") or literal numbers ("3"). A reader
// checks that every required dataset exists and that a symbol means the same extent in every
// dataset of one file.
#include <string>
#include <string_view>
#include <vector>

namespace hm::io {

enum class DType { f64, i64, str };
std::string_view dtype_name(DType type);

struct DatasetSpec {
  std::string path;  ///< absolute HDF5 path; a final "*" matches any child name
  DType type = DType::f64;
  std::vector<std::string> shape;  ///< symbolic extents, outermost first
  std::string unit;                ///< SI unit, "1" for dimensionless, "" for indices/labels
  std::string doc;
  bool required = true;
  /// NaN marks a missing value (a probe with no fluid at a sample); other non-finite values are
  /// still refused. Off: every value must be finite.
  bool missing_values = false;
};

struct SchemaSpec {
  std::string name;  ///< e.g. "hydromodal.modes"
  int version = 1;   ///< what the writer stamps
  std::string doc;
  std::vector<DatasetSpec> datasets;
  /// The oldest version a reader still accepts (0: `version` only). Versions in between may lack
  /// datasets added since (declared optional), never change the meaning of one.
  int oldest_readable = 0;

  const DatasetSpec* find(std::string_view dataset_path) const;
  /// Whether a file of `file_version` is read by this schema.
  bool reads(int file_version) const;
  /// "version 2" or "versions 1 to 2", for messages.
  std::string readable_versions() const;
};

/// Root attribute names every artefact carries (provenance).
namespace attr {
inline constexpr const char* schema = "schema";
inline constexpr const char* schema_version = "schema_version";
inline constexpr const char* stage = "stage";
inline constexpr const char* tool_version = "tool_version";
inline constexpr const char* created_utc = "created_utc";
inline constexpr const char* parameters = "parameters";                ///< canonical TOML text
inline constexpr const char* parameters_sha256 = "parameters_sha256";  ///< of `parameters`
inline constexpr const char* input_prefix =
    "input:";                                    ///< "input:<role>:path", "input:<role>:sha256"
inline constexpr const char* status = "status";  ///< "ok" or a failure description
inline constexpr const char* unit = "unit";      ///< on every dataset
inline constexpr const char* description = "description";  ///< on every dataset
}  // namespace attr

/// Schema names and the datasets of each artefact kind.
namespace schema {
inline constexpr const char* mesh = "hydromodal.mesh";
inline constexpr const char* modes = "hydromodal.modes";
inline constexpr const char* mapped_modes = "hydromodal.mapped_modes";
inline constexpr const char* results = "hydromodal.results";
inline constexpr const char* checkpoint = "hydromodal.checkpoint";
inline constexpr const char* report = "hydromodal.report";
}  // namespace schema

namespace ds {
// hydromodal.mesh
inline constexpr const char* structure_nodes = "/structure/nodes";
inline constexpr const char* structure_cells = "/structure/cells";
inline constexpr const char* structure_cells_vtk = "/structure/cells_vtk";
inline constexpr const char* structure_facets = "/structure/facets";
inline constexpr const char* structure_node_groups = "/structure/node_groups/";    // + name
inline constexpr const char* structure_facet_groups = "/structure/facet_groups/";  // + name
inline constexpr const char* structure_surface_vertices = "/structure/surface/vertices";
inline constexpr const char* structure_surface_cells = "/structure/surface/cells";
inline constexpr const char* structure_surface_node = "/structure/surface/volume_node";
inline constexpr const char* structure_quality = "/structure/quality";
inline constexpr const char* walls = "/walls/";  // + name + "/vertices" | "/cells"
// hydromodal.modes
inline constexpr const char* eigenvalues = "/modes/eigenvalues";
inline constexpr const char* omega = "/modes/omega";
inline constexpr const char* frequencies_hz = "/modes/frequencies_hz";
inline constexpr const char* damping_ratio = "/modes/damping_ratio";
inline constexpr const char* shapes = "/modes/shapes";
inline constexpr const char* residual = "/modes/relative_residual";
inline constexpr const char* orthogonality_error = "/modes/orthogonality_error";
inline constexpr const char* participation_translation = "/modes/participation_translation";
inline constexpr const char* participation_rotation = "/modes/participation_rotation";
inline constexpr const char* effective_mass_translation = "/modes/effective_mass_translation";
inline constexpr const char* effective_mass_rotation = "/modes/effective_mass_rotation";
inline constexpr const char* surface_shapes = "/modes/surface_shapes";
inline constexpr const char* modes_nodes = "/mesh/nodes";
inline constexpr const char* modes_cells = "/mesh/cells";
inline constexpr const char* modes_cells_vtk = "/mesh/cells_vtk";
inline constexpr const char* modes_surface_vertices = "/mesh/surface/vertices";
inline constexpr const char* modes_surface_cells = "/mesh/surface/cells";
inline constexpr const char* modes_surface_node = "/mesh/surface/volume_node";
// hydromodal.modes (version 2, with modes.derivatives): the reduced basis V = [Φ, Θ] of the
// nonlinear modal model and its Saint Venant–Kirchhoff tensors (fem/reduced_stvk.hpp).
inline constexpr const char* basis_vectors = "/basis/vectors";
inline constexpr const char* basis_surface_vectors = "/basis/surface_vectors";
inline constexpr const char* basis_origin = "/basis/origin";
inline constexpr const char* basis_omega = "/basis/omega";
inline constexpr const char* basis_participation_translation = "/basis/participation_translation";
inline constexpr const char* basis_participation_rotation = "/basis/participation_rotation";
inline constexpr const char* reduced_mass = "/reduced/mass";
inline constexpr const char* reduced_linear = "/reduced/linear";
inline constexpr const char* reduced_quadratic = "/reduced/quadratic";
inline constexpr const char* reduced_cubic = "/reduced/cubic";
// hydromodal.mapped_modes
inline constexpr const char* target_vertices = "/target/vertices";
inline constexpr const char* target_cells = "/target/cells";
inline constexpr const char* mapped_shapes = "/modes/shapes";  // on the target vertices
inline constexpr const char* mapping_field_error = "/quality/field_error";
// hydromodal.mapped_modes (version 2): the reduced basis on the target vertices (besides
// basis_origin, basis_omega and the basis' participation factors, spelled as in modes.h5).
inline constexpr const char* mapped_basis = "/basis/shapes";
inline constexpr const char* mapped_basis_field_error = "/basis/field_error";
// hydromodal.results (groups: /probes, /monitors, /run; issue 7 adds /modal, /bodies)
inline constexpr const char* probe_time = "/probes/time";
inline constexpr const char* probe_values = "/probes/values";
inline constexpr const char* monitor_step = "/monitors/step";
inline constexpr const char* monitor_time = "/monitors/time";
inline constexpr const char* monitor_dt = "/monitors/dt";
inline constexpr const char* monitor_dt_limit = "/monitors/dt_limit";
inline constexpr const char* monitor_ppe_iterations = "/monitors/ppe_iterations";
inline constexpr const char* monitor_ppe_passes = "/monitors/ppe_passes";
inline constexpr const char* monitor_ppe_residual = "/monitors/ppe_residual";
inline constexpr const char* monitor_ppe_converged = "/monitors/ppe_converged";
inline constexpr const char* monitor_max_divergence = "/monitors/max_divergence";
inline constexpr const char* monitor_volume_drift = "/monitors/volume_drift";
inline constexpr const char* monitor_max_speed = "/monitors/max_speed";
inline constexpr const char* monitor_escaped = "/monitors/escaped";
inline constexpr const char* monitor_fluid = "/monitors/fluid";
inline constexpr const char* monitor_surface = "/monitors/surface";
inline constexpr const char* monitor_isolated = "/monitors/isolated";
inline constexpr const char* monitor_wall_active = "/monitors/wall_active";
inline constexpr const char* run_phase_seconds = "/run/phase_seconds";
inline constexpr const char* modal_time = "/modal/time";
inline constexpr const char* modal_coordinates = "/modal/coordinates";
inline constexpr const char* modal_velocities = "/modal/velocities";
inline constexpr const char* modal_forces = "/modal/forces";
inline constexpr const char* modal_added_mass = "/modal/added_mass";
inline constexpr const char* modal_added_mass_initial = "/modal/added_mass_initial";
inline constexpr const char* monitor_coupling_iterations = "/monitors/coupling_iterations";
inline constexpr const char* monitor_interface_residual = "/monitors/interface_residual";
inline constexpr const char* monitor_structure_stretch = "/monitors/structure_stretch";
inline constexpr const char* monitor_coupling_seconds = "/monitors/coupling_seconds";
inline constexpr const char* monitor_structure_seconds = "/monitors/structure_seconds";
inline constexpr const char* monitor_structure_deformation = "/monitors/structure_deformation";
inline constexpr const char* monitor_structure_peak_pressure = "/monitors/structure_peak_pressure";
/// The structure's energy balance per step, [n_steps, 5]: kinetic, strain, work of the loads,
/// damping, numerical dissipation [J] (StructureEnergy).
inline constexpr const char* monitor_structure_energy = "/monitors/structure_energy";
inline constexpr const char* monitor_structure_solver_iterations =
    "/monitors/structure_solver_iterations";
inline constexpr const char* body_position = "/body/position";
inline constexpr const char* body_velocity = "/body/velocity";
}  // namespace ds

/// Root attributes of hydromodal.modes read by other stages (besides the provenance ones).
namespace modes_attr {
inline constexpr const char* factorisation_seconds = "factorisation_seconds";  ///< [s]
inline constexpr const char* lanczos_seconds = "lanczos_seconds";              ///< [s]
/// With modes.derivatives: the reduced basis' make-up and cost.
inline constexpr const char* basis_modes = "basis_modes";              ///< linear modes in V
inline constexpr const char* basis_derivatives = "basis_derivatives";  ///< derivatives in V
inline constexpr const char* basis_dropped = "basis_dropped";  ///< candidates dropped (dependent)
inline constexpr const char* derivatives_seconds = "derivatives_seconds";  ///< Θ and V [s]
inline constexpr const char* tensor_seconds = "tensor_seconds";            ///< K1, K2, K3, M_r [s]
}  // namespace modes_attr

/// Root attributes of hydromodal.results (besides the provenance ones).
namespace results_attr {
inline constexpr const char* run_status = "run_status";  ///< "completed" or "diverged"
inline constexpr const char* divergence_report = "divergence_report";  ///< "" when completed
inline constexpr const char* wall_seconds = "wall_seconds";            ///< run time [s]
inline constexpr const char* steps = "steps";                          ///< time steps taken
inline constexpr const char* points = "points";                ///< fluid points at the start
inline constexpr const char* end_time = "end_time";            ///< physical time reached [s]
inline constexpr const char* snapshots = "snapshots";          ///< snapshots written
inline constexpr const char* probe_columns = "probe_columns";  ///< CSV names, comma-separated
/// The probes that saw no fluid at any sample of the run (their values all missing; a force
/// probe's all 0), comma-separated; "" when every probe saw fluid.
inline constexpr const char* probes_without_fluid = "probes_without_fluid";
inline constexpr const char* dt_limit_names = "dt_limit_names";  ///< code → name, comma-separated
inline constexpr const char* phase_names = "phase_names";        ///< /run/phase_seconds entries
inline constexpr const char* dx = "dx";                          ///< [m]
inline constexpr const char* support = "support";                ///< h [m]
inline constexpr const char* coupling_scheme = "coupling_scheme";  ///< explicit | strong
/// The structure model (structure.model: linear_modal | nonlinear_fe | nonlinear_modal; its law
/// and scheme are in the parameters).
inline constexpr const char* structure_model = "structure_model";
/// The energy columns of /monitors/structure_energy, comma-separated.
inline constexpr const char* energy_columns = "energy_columns";
/// Largest max|Σ Φ y| / body size of the run: above 0.05 the linear modes stretch visibly.
inline constexpr const char* max_structure_stretch = "max_structure_stretch";
/// Coupling wall-clock totals [s]: loads, CFPI, wall updates, added-mass solves (not the PPE
/// re-solves of the sub-iterations), and the added-mass part alone.
inline constexpr const char* coupling_seconds = "coupling_seconds";
inline constexpr const char* added_mass_seconds = "added_mass_seconds";
inline constexpr const char* structure_seconds = "structure_seconds";
/// Largest elastic displacement of the run [m] (the rigid translation of a free body excluded).
inline constexpr const char* max_structure_deformation = "max_structure_deformation";
/// Largest wall-node pressure on the structure over the run [Pa].
inline constexpr const char* max_structure_pressure = "max_structure_pressure";
/// A body in free translation: its mass [kg] and its axis (x, y or z).
inline constexpr const char* body_mass = "body_mass";
inline constexpr const char* free_axis = "free_axis";
}  // namespace results_attr

const SchemaSpec& mesh_schema();
const SchemaSpec& checkpoint_schema();
const SchemaSpec& modes_schema();
const SchemaSpec& mapped_modes_schema();
const SchemaSpec& results_schema();
const SchemaSpec& report_schema();
/// Every schema hydromodal writes (for fsi-inspect and the generated reference).
std::vector<const SchemaSpec*> all_schemas();
const SchemaSpec* find_schema(std::string_view name);

/// The schema reference as Markdown (generated; README links to it).
std::string schema_reference_markdown();

}  // namespace hm::io
