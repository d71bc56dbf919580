// Every scene key of hydromodal, declared once: type, default, unit, range, meaning, and the
// stages whose artefacts depend on it (so a change reruns exactly those stages). The generated
// reference (`--print-config-reference`) and all validation come from this table.
#include "io/scene.hpp"

namespace hm::io {
namespace {

constexpr double inf = 1e300;
const std::vector<std::string> mesh_stage{"fsi-mesh"};
const std::vector<std::string> modes_stage{"fsi-modes"};
const std::vector<std::string> map_stage{"fsi-map"};
const std::vector<std::string> simulate_stage{"fsi-simulate"};
const std::vector<std::string> report_stage{"fsi-report"};

KeyDecl number(std::string path, std::string def, std::string unit, double min, double max,
               std::string doc, std::vector<std::string> stages, bool min_excl = false,
               bool max_excl = false) {
  KeyDecl d;
  d.path = std::move(path);
  d.type = KeyType::number;
  d.default_text = std::move(def);
  d.unit = std::move(unit);
  d.min = min;
  d.max = max;
  d.min_exclusive = min_excl;
  d.max_exclusive = max_excl;
  d.doc = std::move(doc);
  d.stages = std::move(stages);
  return d;
}

KeyDecl integer(std::string path, std::string def, double min, double max, std::string doc,
                std::vector<std::string> stages) {
  KeyDecl d =
      number(std::move(path), std::move(def), "1", min, max, std::move(doc), std::move(stages));
  d.type = KeyType::integer;
  return d;
}

KeyDecl text(std::string path, std::string def, std::vector<std::string> choices, std::string doc,
             std::vector<std::string> stages) {
  KeyDecl d;
  d.path = std::move(path);
  d.type = KeyType::string;
  d.default_text = std::move(def);
  d.choices = std::move(choices);
  d.doc = std::move(doc);
  d.stages = std::move(stages);
  return d;
}

KeyDecl vector(std::string path, std::string def, std::string unit, int size, std::string doc,
               std::vector<std::string> stages, double min = -inf, double max = inf) {
  KeyDecl d = number(std::move(path), std::move(def), std::move(unit), min, max, std::move(doc),
                     std::move(stages));
  d.type = KeyType::vector;
  d.vector_size = size;
  return d;
}

KeyDecl string_list(std::string path, std::string def, std::vector<std::string> choices,
                    std::string doc, std::vector<std::string> stages) {
  KeyDecl d =
      text(std::move(path), std::move(def), std::move(choices), std::move(doc), std::move(stages));
  d.type = KeyType::string_list;
  return d;
}

KeyDecl boolean(std::string path, std::string def, std::string doc,
                std::vector<std::string> stages) {
  KeyDecl d = text(std::move(path), std::move(def), {}, std::move(doc), std::move(stages));
  d.type = KeyType::boolean;
  return d;
}

}  // namespace

const std::vector<SectionDecl>& scene_sections() {
  static const std::vector<SectionDecl> sections{
      {"case", true, "What the case is."},
      {"structure", false,
       "The elastic structure (omit for rigid-only scenes: the structure stages are skipped)."},
      {"structure.geometry", true, "Where the structure's shape comes from."},
      {"structure.mesh", true, "Finite-element mesh of the structure (quadratic elements)."},
      {"structure.group[]", false,
       "Named boundary groups selected by an axis-aligned box (e.g. `clamped`, `wetted`); every "
       "boundary node/facet inside the box belongs to the group. Primitives also have the groups "
       "xmin, xmax, ymin, ymax (, zmin, zmax); .geo files bring their own physical groups."},
      {"structure.refine[]", false,
       "Smaller mesh sizes near named groups (a primitive's face, a .geo physical group or a box "
       "group); gmsh grades the size away from them."},
      {"structure.material", true,
       "Isotropic elastic material: linear, or hyperelastic (law) for the nonlinear models."},
      {"wall[]", false,
       "Rigid fluid walls as surface meshes (segments in 2-D, triangles in 3-D, normals into the "
       "fluid), meshed by fsi-mesh into mesh.h5 under /walls/<name>."},
      {"fluid", false,
       "The fluid (LDD meshless flow, fsi-simulate). Its presence makes the scene a flow scene: "
       "[time] and at least one [[fluid.region]] are then required."},
      {"fluid.region[]", false,
       "Boxes initially filled with fluid (lattice points at spacing fluid.dx, at least dx/2 from "
       "every wall); points of overlapping regions are kept once."},
      {"time", false,
       "Time stepping and output times of fsi-simulate (required for a flow scene)."},
      {"solver", false, "Numerical parameters of the LDD flow solver (LDD-SPEC §1)."},
      {"probe[]", false,
       "Measurements written every probe interval to probes.csv (first column `t [s]`, then "
       "`<name>.<quantity> [unit]`) and to results.h5: pressure → `.p [Pa]`, elevation → "
       "`.eta [m]`, front → `.front [m]`, force → `.fx [N]`, `.fy [N]` (, `.fz [N]`)."},
      {"load[]", false,
       "Prescribed loads on the structure for a structure-only run of fsi-simulate (a scene with "
       "a [structure] and no [fluid]): a total force spread equally over the nodes of a node "
       "group, times a history g(t)."},
      {"coupling", false,
       "Two-way coupling of the flow with the structure (a scene with [fluid] and [structure]): "
       "the structure's mapped surface (mapped.h5, fsi-map) becomes the wall named "
       "\"structure\", moved by the modes and loaded by the fluid's pressure."},
      {"modes", false, "Mode extraction (fsi-modes)."},
      {"map", false, "Mapping of the mode shapes onto the surface the fluid sees (fsi-map)."},
      {"report", false, "The report of a finished run (fsi-report): plots and error metrics."},
      {"report.compare[]", false,
       "A probe column against one reference curve (CSV with a header line): plotted together, "
       "with the peak error, the time-of-peak error and the RMS difference."},
  };
  return sections;
}

const std::vector<KeyDecl>& scene_keys() {
  static const std::vector<KeyDecl> keys{
      // [case]
      text("case.name", "", {}, "case name, used in reports", {}),
      integer("case.dimension", "", 2, 3, "2 for plane (x, y) cases, 3 for spatial ones",
              {"fsi-mesh", "fsi-modes"}),
      text("case.description", "\"\"", {}, "free text for reports", {}),

      // [structure.geometry]
      text("structure.geometry.kind", "", {"rectangle", "box", "file"},
           "rectangle (2-D) or box (3-D) primitive given by origin and size, or a geometry file",
           mesh_stage),
      text("structure.geometry.file", "\"\"", {},
           "geometry file for kind = \"file\", relative to the scene: .geo (gmsh script), "
           ".step/.stp/.brep/.iges/.igs (CAD), .stl/.obj/.ply (closed surface mesh)",
           mesh_stage),
      text("structure.geometry.length_unit", "\"m\"", {"m", "cm", "mm", "in", "ft"},
           "unit of the lengths in structure.geometry.file (CAD and surface files; a .geo script "
           "is in metres). A file written in millimetres needs \"mm\": read as metres it is a "
           "structure 1000 times too large, which fsi-mesh refuses by its element estimate",
           mesh_stage),
      vector("structure.geometry.origin", "[]", "m", 0,
             "lowest corner of the rectangle/box primitive (required for those kinds)", mesh_stage),
      vector("structure.geometry.size", "[]", "m", 0,
             "edge lengths of the rectangle/box primitive (required for those kinds)", mesh_stage,
             0.0),

      // [structure.mesh]
      number("structure.mesh.size", "", "m", 0, inf,
             "target element edge length (gmsh Mesh.MeshSizeMax). For a .geo script it is an "
             "upper bound: the script's own point sizes (characteristic lengths), where smaller, "
             "win. fsi-mesh refuses, before meshing, a size whose element estimate "
             "would not fit this machine's memory in fsi-modes",
             mesh_stage, true),
      number("structure.mesh.min_quality", "0.1", "1", 0, 1,
             "elements below this shape quality are reported as slivers", mesh_stage),

      // [[structure.refine]]
      text("structure.refine[].group", "", {}, "name of the group to refine near", mesh_stage),
      number("structure.refine[].size", "", "m", 0, inf,
             "target element size at the group (below structure.mesh.size)", mesh_stage, true),

      // [[structure.group]]
      text("structure.group[].name", "", {}, "group name (referenced by other keys)", mesh_stage),
      vector("structure.group[].min", "", "m", 0, "lower corner of the selection box", mesh_stage),
      vector("structure.group[].max", "", "m", 0, "upper corner of the selection box", mesh_stage),

      // [[wall]]
      text("wall[].name", "", {}, "wall name (a dataset group /walls/<name> of mesh.h5)",
           mesh_stage),
      text("wall[].kind", "", {"rectangle", "box", "file"},
           "the inside of a rectangle (2-D) or box (3-D) tank given by origin and size, or a "
           "surface file (.stl, .obj, .ply; or .geo curves/surfaces)",
           mesh_stage),
      vector("wall[].origin", "[]", "m", 0, "lowest corner of the tank primitive", mesh_stage),
      vector("wall[].size", "[]", "m", 0, "edge lengths of the tank primitive", mesh_stage, 0.0),
      string_list("wall[].faces", "[]", {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"},
                  "faces of the primitive to keep (empty: all; an open-top tank omits ymax/zmax)",
                  mesh_stage),
      text("wall[].file", "\"\"", {}, "surface file for kind = \"file\", relative to the scene",
           mesh_stage),
      text("wall[].length_unit", "\"m\"", {"m", "cm", "mm", "in", "ft"},
           "unit of the lengths in wall[].file (STL, OBJ, PLY; a .geo script is in metres)",
           mesh_stage),
      number("wall[].mesh_size", "", "m", 0, inf, "target edge length of the wall mesh", mesh_stage,
             true),
      boolean("wall[].flip_normals", "false",
              "reverse the normals of a file wall whose fluid side is the other one. A closed "
              "surface file is a container (the fluid inside) as read; true makes it an obstacle "
              "(the fluid around it). A fluid region outside a container or inside an obstacle "
              "is an error",
              mesh_stage),
      boolean("wall[].thin", "false",
              "the wall is wetted on both sides (a baffle or gate): pairs through it are cut and "
              "wall nodes are sampled on both sides",
              simulate_stage),
      text("wall[].motion", "\"none\"", {"none", "sway", "roll", "table"},
           "prescribed rigid motion: none (fixed), sway A·sin(2πt/T), roll θ0·sin(2πft) about "
           "roll_pivot, or a CSV time table (motion_table)",
           simulate_stage),
      number("wall[].sway_amplitude", "0.0", "m", 0, inf,
             "sway amplitude A (required for motion = \"sway\"; 0 = not given)", simulate_stage,
             true),
      number("wall[].sway_period", "0.0", "s", 0, inf,
             "sway period T (required for motion = \"sway\"; 0 = not given)", simulate_stage, true),
      vector("wall[].sway_direction", "[]", "1", 0,
             "direction of the sway, normalised (default: +x)", simulate_stage),
      number("wall[].roll_amplitude", "0.0", "rad", 0, 3.141592653589793,
             "roll amplitude θ0 (required for motion = \"roll\"; 0 = not given)", simulate_stage,
             true),
      number("wall[].roll_frequency", "0.0", "Hz", 0, inf,
             "roll frequency f (required for motion = \"roll\"; 0 = not given)", simulate_stage,
             true),
      vector("wall[].roll_pivot", "[]", "m", 0,
             "point the roll axis passes through (required for motion = \"roll\" and for a "
             "motion_table with a theta column)",
             simulate_stage),
      vector("wall[].roll_axis", "[]", "1", 3,
             "3-D only: roll axis direction, normalised (default: z; 2-D always rolls about z)",
             simulate_stage),
      number("wall[].motion_ramp", "0.0", "s", 0, inf,
             "C² start-up ramp of sway and roll over this time (0: none)", simulate_stage),
      text("wall[].motion_table", "\"\"", {},
           "CSV time table for motion = \"table\", relative to the scene: `t [s]` then any of "
           "`x [m]`, `y [m]`, `z [m]`, `theta [rad]` or `theta [deg]` (cubic splines)",
           simulate_stage),

      // [structure]
      text("structure.formulation", "\"plane_strain\"", {"plane_strain", "plane_stress"},
           "2-D only: plane strain (thick in z) or plane stress (thin plate in its plane)",
           modes_stage),
      number("structure.thickness", "1.0", "m", 0, inf,
             "2-D only: out-of-plane thickness the 2-D mass and stiffness are multiplied by",
             modes_stage, true),
      text("structure.clamped", "\"\"", {},
           "name of the group whose nodes are fixed (all displacement components); empty: the "
           "structure is free-free",
           modes_stage),

      // [structure.material]
      number("structure.material.youngs_modulus", "", "Pa", 0, inf, "Young's modulus E",
             modes_stage, true),
      number("structure.material.poisson_ratio", "", "1", -1, 0.5, "Poisson's ratio nu",
             modes_stage, true, true),
      number("structure.material.density", "", "kg/m^3", 0, inf, "mass density rho", modes_stage,
             true),

      // [fluid]
      number("fluid.density", "1000.0", "kg/m^3", 0, inf, "fluid density ρ", simulate_stage, true),
      number("fluid.viscosity", "1e-6", "m^2/s", 0, inf,
             "kinematic viscosity ν (0: inviscid; water at 20 °C: 1.0e-6)", simulate_stage),
      vector("fluid.gravity", "[]", "m/s^2", 0,
             "gravitational acceleration (default: −9.81 along the last axis, y in 2-D, z in 3-D)",
             simulate_stage),
      number("fluid.dx", "", "m", 0, inf, "initial point spacing of the fluid", simulate_stage,
             true),

      // [[fluid.region]]
      vector("fluid.region[].origin", "", "m", 0, "lowest corner of the fluid box", simulate_stage),
      vector("fluid.region[].size", "", "m", 0, "edge lengths of the fluid box", simulate_stage,
             0.0),
      vector("fluid.region[].velocity", "[]", "m/s", 0, "initial velocity (default: at rest)",
             simulate_stage),

      // [time]
      number("time.end", "", "s", 0, inf, "simulated end time", simulate_stage, true),
      number("time.dt_max", "1e-2", "s", 0, inf,
             "largest time step (structure-only runs: the step, shortened to meet output times)",
             simulate_stage, true),
      number("time.snapshot_interval", "0.0", "s", 0, inf,
             "physical time between snapshots of points and walls (0: first and last only)",
             simulate_stage),
      number("time.probe_interval", "0.0", "s", 0, inf,
             "physical time between probe rows (0: every step); the end time always gets a row",
             simulate_stage),
      number("time.checkpoint_interval", "0.0", "s", 0, inf,
             "physical time between checkpoints (checkpoints/t_<time>.h5 next to results.h5, "
             "for fsi-simulate --restart; 0: none); checkpoint times bound the steps like the "
             "other output times",
             simulate_stage),
      number("time.cfl", "0.3", "1", 0, 1, "Courant number C_u: Δt ≤ C_u·dx/max|u|", simulate_stage,
             true),
      number("time.acceleration_number", "0.25", "1", 0, 1, "C_a: Δt ≤ C_a·sqrt(dx/max|a|)",
             simulate_stage, true),
      number("time.viscous_number", "0.1", "1", 0, 1,
             "C_ν: Δt ≤ C_ν·dx²/ν (explicit viscosity only)", simulate_stage, true),

      // [solver]
      text("solver.viscosity", "\"explicit\"", {"explicit", "implicit"},
           "viscous term of the predictor: explicit Euler (adds the viscous Δt limit) or implicit "
           "Euler (one sparse solve per component)",
           simulate_stage),
      number("solver.support_factor", "2.5", "1", 1.5, 5,
             "support radius h of the LDD operators in units of dx", simulate_stage),
      number("solver.wall_node_spacing", "1.0", "1", 0.0625, 1,
             "largest spacing of the wall nodes along every wall (tank, obstacle and "
             "structure), in units of dx: edges longer than it are subdivided; nodes also sit at "
             "every vertex of a wall mesh, so a mesh finer than this gives denser nodes. The "
             "coupled answer on thin bodies depends on it (pipelines/elastic_gate/README.md); "
             "below dx/16 the wall rows of the PPE degrade (the gate's added mass +86 % at dx/32)",
             simulate_stage),
      boolean("solver.wall_node_weights", "false",
              "wall nodes enter the LDD operators with the wall length (area) they stand for "
              "instead of weight 1, so that the answer does not depend on how densely a wall is "
              "sampled (solver.wall_node_spacing, or a wall mesh finer than dx); off: every "
              "point weighs 1, as in the paper",
              simulate_stage),
      integer("solver.pbd_iterations", "4", 0, 100,
              "Jacobi iterations of the position-based regularisation (0 disables it)",
              simulate_stage),
      number("solver.pbd_relaxation", "1.5", "1", 0, 2, "relaxation ω of the PBD iteration",
             simulate_stage, true),
      number("solver.pbd_distance", "0.95", "1", 0, 1,
             "PBD minimum pair distance d0 in units of dx (fluid–wall: d0/2)", simulate_stage,
             true),
      number("solver.shifting", "2", "1", 0, 100,
             "coefficient A of the Fickian shifting after PBD, δr = −A dx |u| Δt ∇(n/n0) (0 "
             "disables)",
             simulate_stage),
      number("solver.smoothing", "0.5", "1", 0, 1,
             "XSPH velocity smoothing ε over fluid neighbours (0 disables)", simulate_stage),
      number("solver.volume_relaxation", "0.05", "1", 0, 1,
             "relaxation α of the volume (number-density) source of the PPE (0 disables)",
             simulate_stage),
      boolean("solver.release_wall_tension", "true",
              "wall nodes with negative pressure become p = 0 and the PPE is solved again",
              simulate_stage),
      number("solver.ppe_tolerance", "1e-6", "1", 0, 1,
             "relative residual at which the PPE iteration stops", simulate_stage, true),
      integer("solver.ppe_max_iterations", "1000", 1, 1000000,
              "iterations of the PPE solver before the step counts as not converged",
              simulate_stage),
      text("solver.preconditioner", "\"automatic\"",
           {"automatic", "jacobi", "ilu", "boomeramg", "gamg"},
           "PPE solver: BiCGSTAB preconditioned by automatic (in builds with PETSc, for systems "
           "of 2000 unknowns or more in 2-D and 5000 in 3-D: BoomerAMG or Jacobi, whichever "
           "cost fewer Jacobi-equivalent iterations on the last matrix it solved, the other "
           "tried again now and then; otherwise Jacobi first and ILU when it stalls; the rule "
           "is measured, see the README), jacobi, ilu, or algebraic multigrid from PETSc: "
           "boomeramg (hypre) or gamg (smoothed aggregation); the PETSc ones only in "
           "builds with PETSc (fsi-simulate --version lists them)",
           simulate_stage),
      number("solver.amg_drop", "0.05", "1", 0, 0.5,
             "algebraic multigrid (boomeramg, gamg): its hierarchy is built on the PPE matrix "
             "without the entries smaller than amg_drop × their row's largest, lumped onto the "
             "diagonal (0: on the whole matrix); the iteration still solves the whole matrix to "
             "ppe_tolerance, so only the cost changes",
             simulate_stage),

      // [[probe]]
      text("probe[].name", "", {},
           "probe name, unique, letters, digits and _ (the CSV column prefix)", simulate_stage),
      text("probe[].kind", "", {"pressure", "elevation", "front", "force", "displacement"},
           "pressure at a point, free-surface elevation at a gauge, surge front, force on a "
           "wall, or displacement of the structure node nearest to position (`.ux [m]`, `.uy "
           "[m]` (, `.uz [m]`); structure-only runs)",
           simulate_stage),
      vector("probe[].position", "[]", "m", 0,
             "pressure: the point; elevation: the gauge (its vertical line); required for those "
             "kinds and inside the walls' bounding box",
             simulate_stage),
      number("probe[].radius", "0.0", "m", 0, inf,
             "pressure: radius of the averaging sphere (0: h = support_factor·dx)", simulate_stage),
      text("probe[].wall", "\"\"", {}, "force: name of the [[wall]] the pressure is integrated on",
           simulate_stage),
      text("probe[].moves_with", "\"\"", {},
           "pressure, elevation: name of a [[wall]] the probe is fixed to (it follows the wall's "
           "motion, e.g. a sensor on a swaying tank); empty: fixed in space",
           simulate_stage),
      vector("probe[].direction", "[]", "1", 0,
             "front: direction the front advances in, normalised (default: +x)", simulate_stage),
      vector("probe[].band", "[]", "m", 2,
             "front: [low, high] height band above the floor (the lowest wall point) where the "
             "front point is sought (default: [0, 2·dx])",
             simulate_stage),

      // [[load]]
      text("load[].name", "", {}, "load name (for messages and reports)", simulate_stage),
      text("load[].group", "", {}, "node group of the structure mesh the force is spread over",
           simulate_stage),
      vector("load[].force", "", "N", 0,
             "total force at g = 1, case.dimension values (2-D: per structure.thickness)",
             simulate_stage),
      text("load[].history", "\"constant\"", {"constant", "ramp", "harmonic", "table"},
           "g(t): constant 1 (a step at t = 0), ramp min(t/ramp_time, 1), harmonic "
           "sin(2π·frequency·t + phase), or table (CSV `t [s]`, `factor [1]`, linear between "
           "rows)",
           simulate_stage),
      number("load[].ramp_time", "0.0", "s", 0, inf, "ramp: time to reach the full force",
             simulate_stage),
      number("load[].frequency", "0.0", "Hz", 0, inf, "harmonic: frequency", simulate_stage),
      number("load[].phase", "0.0", "rad", -inf, inf, "harmonic: phase", simulate_stage),
      text("load[].table", "\"\"", {}, "table: CSV file, relative to the scene", simulate_stage),
      // [coupling]
      text("coupling.scheme", "\"strong\"", {"strong", "explicit"},
           "fluid–structure coupling of a scene with [fluid] and [structure]: strong "
           "(sub-iterations of the PPE per step with the measured added mass as the Jacobian; "
           "stable for light structures) or explicit (the paper's staggered scheme, one PPE per "
           "step; unstable when the fluid's added mass exceeds the structure's)",
           simulate_stage),
      number("coupling.tolerance", "1e-3", "1", 0, 1,
             "strong: interface residual (relative modal-acceleration mismatch) that ends the "
             "sub-iterations",
             simulate_stage, true),
      integer("coupling.max_iterations", "20", 1, 1000,
              "strong: PPE solves per step at most (a step that ends above the tolerance is "
              "recorded in /monitors/interface_residual)",
              simulate_stage),
      boolean("coupling.release_tension", "false",
              "release the structure's wall nodes in tension (p < 0 → p = 0, as on rigid walls "
              "with solver.release_wall_tension): the flow separates from the structure's edges "
              "and free ends. The strong scheme releases afresh in the first four PPE solves of a "
              "step and keeps that set in the later ones, so that its sub-iterations converge. "
              "Off, the fluid holds on to the structure, and its suction at a sharp edge follows "
              "how densely the wall is sampled (pipelines/dambreak_elastic_plate/README.md)",
              simulate_stage),
      text("coupling.moves_with", "\"\"", {},
           "name of the [[wall]] in motion (sway, roll or a table) the structure is clamped to: "
           "it moves with it, its modes relative to it, loaded by the base excitation "
           "Γ·Rᵀ(g − Ẍ) and, in a rotating tank, the Euler term −Γ_rot·α about the pivot "
           "(centrifugal and Coriolis terms left out); empty: fixed in space",
           simulate_stage),
      boolean("coupling.viscous_traction", "false",
              "add the fluid's wall shear μ ∂u_t/∂n (μ = ρν, one-sided from the fluid points in "
              "front of the wall) to the pressure loads on the structure; off: pressure only "
              "(the force probes are pressure forces either way)",
              simulate_stage),
      integer("coupling.added_mass_interval", "20", 1, 1000000,
              "strong: steps between measurements of the modal added-mass matrix (one PPE per "
              "mode)",
              simulate_stage),
      boolean("structure.static_start", "false",
              "start every mode at its static solution y = F(0)/ω² instead of at rest: under "
              "the [[load]]s at t = 0 (structure-only runs) or the fluid's load at rest "
              "(coupled runs: a tank filled with the structure in place)",
              simulate_stage),
      text("structure.model", "\"linear_modal\"",
           {"linear_modal", "nonlinear_fe", "nonlinear_modal"},
           "coupled runs: the structure's model. linear_modal: the mapped modes integrated "
           "exactly (CFPI), fast, valid while structure_stretch stays below ~5 % (linear modes "
           "cannot rotate: a bending gate stretches instead of lifting its tip); nonlinear_fe: "
           "the total-Lagrangian finite-element body (tri6/tet10, structure.material.law), "
           "exact for large rotations, one Newton solve per coupling step and its predictor "
           "(fsi-simulate needs --modes modes.h5 for its interface modes); nonlinear_modal: "
           "the reduced Saint Venant-Kirchhoff model on the modes and their static modal "
           "derivatives (needs modes.derivatives = true; the mapped basis is the coupling's "
           "interface, so the added mass costs one pressure solve per basis vector), exact "
           "within its basis, which represents moderate rotations (the error grows with the "
           "rotation and shrinks with more modes)",
           simulate_stage),
      text("structure.material.law", "\"saint_venant_kirchhoff\"",
           {"saint_venant_kirchhoff", "neo_hookean"},
           "nonlinear models: the hyperelastic law with the Lamé constants of E and nu. "
           "saint_venant_kirchhoff: exact for small strain with large rotation; neo_hookean "
           "(compressible): physical in compression, for rubber (nu < 0.5 strictly; <= 0.49 "
           "advised), nonlinear_fe only (nonlinear_modal's cubic reduced force is exact for "
           "saint_venant_kirchhoff alone)",
           simulate_stage),
      text("structure.time_scheme", "\"energy_conserving\"",
           {"energy_conserving", "generalized_alpha"},
           "nonlinear models: implicit time integration. energy_conserving: the midpoint rule "
           "with the discrete-gradient force (no numerical dissipation at any step; the fluid's "
           "load enters like its inertia, as with CFPI); generalized_alpha (Chung & Hulbert "
           "1993): damps unresolved frequencies as rho_infinity says, but weights the fluid's "
           "load (1 - alpha_f) against the inertia's (1 - alpha_m), which misstates a strong "
           "added mass: the gate's tip moves 31 % / 68 % too far in its first 0.02 s at "
           "rho_infinity 0.8 / 0.5 (README)",
           simulate_stage),
      number("structure.rho_infinity", "0.8", "1", 0, 1,
             "generalized_alpha: spectral radius at infinite step (1: no numerical dissipation, "
             "not energy-stable for a nonlinear body; 0: the strongest)",
             simulate_stage),
      number("structure.newton_tolerance", "1e-8", "1", 0, 1e-2,
             "nonlinear models: Newton's residual relative to the largest force term of the "
             "step's equations",
             simulate_stage, true),
      integer("structure.newton_max_iterations", "30", 1, 1000,
              "nonlinear models: Newton iterations of a step before it is retried in halves (up "
              "to 6 times); a step that still fails ends the run (exit 3) with the last good "
              "snapshot",
              simulate_stage),
      text("structure.free_translation", "\"\"", {"", "x", "y", "z"},
           "coupled runs: the axis along which the body moves freely under gravity and the "
           "fluid's force (a wedge dropped on a guided rig); needs a free-free mode set "
           "(structure.clamped = \"\") whose rigid-body modes it replaces by this translation; "
           "empty: the body stays where its modes put it",
           simulate_stage),
      number("structure.initial_velocity", "0.0", "m/s", -inf, inf,
             "with free_translation: the body's velocity along the axis at t = 0 (negative: "
             "towards lower coordinates, e.g. falling)",
             simulate_stage),

      // [modes]
      text("modes.archived", "\"\"", {},
           "an archived mode set (a modes.h5 kept by `make archive`), relative to the scene: "
           "fsi-modes reuses it instead of solving, after checking that it was computed for "
           "this scene's fsi-modes keys (material, formulation, count, ...) and for this mesh's "
           "nodes; a mismatch is an error naming the difference",
           modes_stage),
      integer("modes.count", "10", 1, 100000,
              "number of lowest modes to extract (with max_frequency_hz: the most to return)",
              modes_stage),
      number("modes.max_frequency_hz", "0.0", "Hz", 0, inf,
             "when > 0, extract every mode below this frequency (up to modes.count)", modes_stage),
      number("modes.damping_ratio", "0.0", "1", 0, inf,
             "modal damping ratio zeta added to every mode", modes_stage),
      vector("modes.damping_ratios", "[]", "1", -1,
             "damping ratio of each mode, lowest first (instead of modes.damping_ratio; as many "
             "values as modes are extracted)",
             modes_stage, 0.0),
      number("modes.rayleigh_alpha", "0.0", "1/s", 0, inf,
             "Rayleigh mass-proportional damping: zeta_i += alpha / (2 omega_i)", modes_stage),
      number("modes.rayleigh_beta", "0.0", "s", 0, inf,
             "Rayleigh stiffness-proportional damping: zeta_i += beta omega_i / 2", modes_stage),
      vector("modes.reference_point", "[]", "m", 0,
             "point the rotational participation factors refer to (default: the origin)",
             modes_stage),
      text("modes.solver", "\"arpack\"", {"arpack", "spectra", "dense"},
           "eigensolver: ARPACK shift-invert Lanczos; Spectra (same operator); dense LAPACK-style "
           "(small models only)",
           modes_stage),
      number("modes.tolerance", "1e-12", "1", 0, 1e-3,
             "relative convergence tolerance of the Lanczos iteration", modes_stage, true),
      integer("modes.max_restarts", "1000", 1, 1000000,
              "implicit restarts of the Lanczos iteration before it gives up (exit code 3)",
              modes_stage),
      boolean("modes.derivatives", "false",
              "also compute the reduced model of structure.model = \"nonlinear_modal\": the "
              "static modal derivatives of the modes (a clamped body), the basis of modes and "
              "derivatives and its Saint Venant-Kirchhoff tensors (the Lamé constants of E and "
              "nu), stored in modes.h5 (/basis, /reduced); the basis has n + k(k+1)/2 vectors "
              "for n modes and k = derivative_modes",
              modes_stage),
      integer("modes.derivative_modes", "0", 0, 100000,
              "with derivatives: the derivatives of the lowest this many modes (0: of every "
              "mode); fewer keep the basis and the coupling's added-mass solves small",
              modes_stage),

      // [report], [[report.compare]]
      vector("report.window", "[]", "s", 2,
             "time window [t0, t1] of the RMS differences (empty: where run and reference "
             "overlap)",
             report_stage),
      text("report.compare[].column", "", {}, "probe column as in probes.csv, e.g. \"tip.ux [m]\"",
           report_stage),
      text("report.compare[].file", "", {},
           "reference CSV relative to the scene: a header line, then numbers", report_stage),
      text("report.compare[].label", "\"\"", {},
           "legend and table name of the reference (empty: the file name)", report_stage),
      integer("report.compare[].time_column", "0", 0, 1000,
              "0-based column of the reference's time [s]", report_stage),
      integer("report.compare[].value_column", "1", 0, 1000,
              "0-based column of the reference's value", report_stage),
      number("report.compare[].scale", "1.0", "1", -inf, inf,
             "factor from the reference's unit to the probe's SI unit", report_stage),
      number("report.compare[].time_scale", "1.0", "s", 0, inf,
             "factor from the reference's time unit to seconds (a dimensionless time T: "
             "t = time_scale·T + time_offset)",
             report_stage, true),
      number("report.compare[].time_offset", "0.0", "s", -inf, inf,
             "added to the reference's (scaled) times (a reference with another time origin)",
             report_stage),

      // [map]
      text("map.target", "\"surface\"", {"surface", "file"},
           "surface: the structure's own boundary surface (optionally refined to map.max_edge); "
           "file: the surface mesh in map.file",
           map_stage),
      text("map.file", "\"\"", {},
           "target surface for map.target = \"file\", relative to the scene: a surface mesh "
           "(.stl, .obj, .ply; in map.length_unit) or a gmsh script (.geo, meshed at "
           "map.mesh_size; curves "
           "in 2-D, surfaces in 3-D, oriented with the fluid on their normal side)",
           map_stage),
      text("map.length_unit", "\"m\"", {"m", "cm", "mm", "in", "ft"},
           "unit of the lengths in a surface-mesh map.file (a .geo script is in metres)",
           map_stage),
      number("map.mesh_size", "0.0", "m", 0, inf,
             "element size of a .geo target (map.file), e.g. half the fluid's dx", map_stage),
      number("map.max_edge", "0.0", "m", 0, inf,
             "when > 0, the target surface is refined until no edge is longer (the fluid's "
             "resolution)",
             map_stage),
      number("map.support_factor", "6.0", "1", 1, 100,
             "RBF support radius in mean source node spacings (4: ~2e-3 relative interpolation "
             "error on smooth fields, 6: ~3e-4, 8: ~6e-5; measured in tests/rbf)",
             map_stage),
      number("map.support_radius", "0.0", "m", 0, inf,
             "when > 0, a fixed RBF support radius instead of map.support_factor", map_stage),
      number("map.far_factor", "2.0", "1", 0, inf,
             "target vertices farther than this many source spacings from the structure's "
             "surface nodes are an error",
             map_stage, true),
  };
  return keys;
}

}  // namespace hm::io
