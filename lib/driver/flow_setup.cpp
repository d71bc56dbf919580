#include "driver/flow_setup.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <Eigen/Geometry>

#include "core/errors.hpp"
#include "core/memory.hpp"
#include "core/text.hpp"
#include "driver/wall_io.hpp"
#include "ldd/seeding.hpp"
#include "linsolve/linear_solver.hpp"
#include "mesh/wall_mesher.hpp"
#include "motion/time_table.hpp"

namespace hm::driver {
namespace {

using io::SceneView;

Eigen::Vector3d as_3d(const Eigen::VectorXd& v) {
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (Eigen::Index a = 0; a < std::min<Eigen::Index>(3, v.size()); ++a) out[a] = v[a];
  return out;
}

/// A direction key: the given vector normalised, or `fallback` when it is empty ("[]").
Eigen::Vector3d direction_key(const SceneView& view, const std::string& key,
                              const Eigen::Vector3d& fallback) {
  const Eigen::VectorXd v = view.vector(key);
  if (v.size() == 0) return fallback;
  if (!(v.norm() > 0.0))
    input_error("{} = [{}] is a zero vector; a direction needs a non-zero length", view.where(key),
                fmt::join(v, ", "));
  return as_3d(v).normalized();
}

bool has_theta_column(const motion::TimeTable& table) {
  return std::any_of(table.columns.begin(), table.columns.end(),
                     [](const std::string& c) { return c.rfind("theta", 0) == 0; });
}

Eigen::Vector3d roll_axis(const SceneView& wall, int dim) {
  if (dim == 2) {
    if (wall.vector("roll_axis").size() != 0)
      input_error("{}: a 2-D case always rolls about z; remove roll_axis (3-D only)",
                  wall.where("roll_axis"));
    return Eigen::Vector3d::UnitZ();
  }
  return direction_key(wall, "roll_axis", Eigen::Vector3d::UnitZ());
}

Eigen::Vector3d roll_pivot(const SceneView& wall, const std::string& why) {
  const Eigen::VectorXd pivot = wall.vector("roll_pivot");
  if (pivot.size() == 0)
    input_error("{}: {} needs roll_pivot (m), the point the rotation axis passes through",
                wall.where("motion"), why);
  return as_3d(pivot);
}

/// Motion keys that are set although the wall's motion does not use them.
void reject_unused_motion_keys(const SceneView& wall, const std::string& kind) {
  const std::vector<std::pair<std::string, std::string>> owners{{"sway_amplitude", "sway"},
                                                                {"sway_period", "sway"},
                                                                {"roll_amplitude", "roll"},
                                                                {"roll_frequency", "roll"},
                                                                {"motion_table", "table"}};
  for (const auto& [key, owner] : owners) {
    if (owner == kind) continue;
    const bool set = key == "motion_table" ? !wall.string(key).empty() : wall.number(key) != 0.0;
    if (set)
      input_error("{} is given but {} = \"{}\": set motion = \"{}\" or remove the key",
                  wall.where(key), wall.full("motion"), kind, owner);
  }
}

/// The prescribed motion of a [[wall]] (empty for motion = "none"); `table_file` receives the
/// CSV file of a table motion.
std::optional<motion::RigidMotion> wall_motion(const SceneView& wall, int dim,
                                               std::filesystem::path* table_file = nullptr) {
  const std::string kind = wall.string("motion");
  reject_unused_motion_keys(wall, kind);
  const double ramp = wall.number("motion_ramp");
  if (kind == "none") return std::nullopt;
  if (kind == "sway") {
    const double amplitude = wall.number("sway_amplitude"), period = wall.number("sway_period");
    if (amplitude == 0.0 || period == 0.0)
      input_error(
          "{}: motion = \"sway\" needs sway_amplitude (m) and sway_period (s), both > 0 "
          "(given: {} m, {} s)",
          wall.where("motion"), amplitude, period);
    const Eigen::Vector3d direction =
        direction_key(wall, "sway_direction", Eigen::Vector3d::UnitX());
    return motion::sway_motion(dim, direction, amplitude, period, ramp);
  }
  if (kind == "roll") {
    const double amplitude = wall.number("roll_amplitude"),
                 frequency = wall.number("roll_frequency");
    if (amplitude == 0.0 || frequency == 0.0)
      input_error(
          "{}: motion = \"roll\" needs roll_amplitude (rad) and roll_frequency (Hz), both "
          "> 0 (given: {} rad, {} Hz)",
          wall.where("motion"), amplitude, frequency);
    return motion::roll_motion(dim, roll_pivot(wall, "motion = \"roll\""), roll_axis(wall, dim),
                               amplitude, frequency, ramp);
  }
  HM_ASSERT(kind == "table", "unknown motion '{}'", kind);
  if (wall.string("motion_table").empty())
    input_error(
        "{}: motion = \"table\" needs motion_table, a CSV file (t [s], x [m], y [m], "
        "z [m], theta [rad|deg]) relative to the scene",
        wall.where("motion"));
  const std::filesystem::path file = wall.file_path("motion_table");
  const motion::TimeTable table = motion::read_time_table(file);
  if (table_file) *table_file = file;
  const Eigen::Vector3d pivot = has_theta_column(table)
                                    ? roll_pivot(wall, "a motion_table with a theta column")
                                    : Eigen::Vector3d::Zero();
  return motion::table_motion(table, dim, pivot, roll_axis(wall, dim));
}

bool valid_probe_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

std::vector<std::string> scene_wall_names(const io::Scene& scene) {
  std::vector<std::string> names;
  for (const SceneView& wall : scene.array("wall")) names.push_back(wall.string("name"));
  return names;
}

void validate_probe(const SceneView& probe, const std::vector<std::string>& walls,
                    bool has_structure) {
  const std::string kind = probe.string("kind");
  if (kind == "displacement") {
    if (!has_structure)
      input_error(
          "{}: a displacement probe measures the structure, but the scene has no [structure]",
          probe.where("kind"));
    if (probe.vector("position").size() == 0)
      input_error("{}: a displacement probe needs position (m): the structure point to follow",
                  probe.where("kind"));
  }
  if ((kind == "pressure" || kind == "elevation") && probe.vector("position").size() == 0)
    input_error("{}: a {} probe needs position (m)", probe.where("kind"), kind);
  if (kind == "force") {
    const std::string wall = probe.string("wall");
    if (wall.empty())
      input_error("{}: a force probe needs wall, the name of a [[wall]] (walls: {})",
                  probe.where("kind"), fmt::join(walls, ", "));
    if (std::find(walls.begin(), walls.end(), wall) == walls.end()) {
      const std::string guess = closest_match(wall, walls);
      input_error("{} = \"{}\" is not a wall of the scene: expected one of {}{}",
                  probe.where("wall"), wall, fmt::join(walls, ", "),
                  guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess));
    }
  }
  if (const std::string host = probe.string("moves_with"); !host.empty()) {
    if (kind != "pressure" && kind != "elevation")
      input_error("{}: only pressure and elevation probes can move with a wall, not a {} probe",
                  probe.where("moves_with"), kind);
    if (std::find(walls.begin(), walls.end(), host) == walls.end()) {
      const std::string guess = closest_match(host, walls);
      input_error("{} = \"{}\" is not a wall of the scene: expected one of {}{}",
                  probe.where("moves_with"), host, fmt::join(walls, ", "),
                  guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess));
    }
  }
  if (kind == "front") {
    direction_key(probe, "direction", Eigen::Vector3d::UnitX());
    const Eigen::VectorXd band = probe.vector("band");
    if (band.size() == 2 && !(band[0] < band[1]))
      input_error("{} = [{}, {}]: the band needs low < high (m above the floor)",
                  probe.where("band"), band[0], band[1]);
  }
}

void validate_probes(const io::Scene& scene) {
  std::vector<std::string> walls = scene_wall_names(scene);
  const bool has_structure = scene.has("structure");
  if (has_structure) walls.push_back(structure_wall_name);
  std::set<std::string> seen;
  for (const SceneView& probe : scene.array("probe")) {
    const std::string name = probe.string("name");
    if (!valid_probe_name(name))
      input_error(
          "{} = \"{}\": a probe name is letters, digits and _ only (it prefixes the CSV "
          "columns)",
          probe.where("name"), name);
    if (!seen.insert(name).second)
      input_error("{} = \"{}\": another probe has this name; probe names must be unique",
                  probe.where("name"), name);
    validate_probe(probe, walls, has_structure);
  }
}

template <int D>
ldd::Vec<D> vec_of(const Eigen::VectorXd& v) {
  HM_ASSERT(v.size() == D, "vector of {} values for a {}-D case", v.size(), D);
  return v;
}

/// solver.preconditioner, refused (exit 2) when this build lacks it (the PETSc ones).
ldd::Preconditioner ppe_preconditioner(const SceneView& solver) {
  const std::string name = solver.string("preconditioner");
  for (const auto p :
       {ldd::Preconditioner::automatic, ldd::Preconditioner::jacobi, ldd::Preconditioner::ilu,
        ldd::Preconditioner::boomeramg, ldd::Preconditioner::gamg}) {
    if (name != ldd::to_string(p)) continue;
    if (!ldd::is_available(p)) {
      std::string built;
      for (const auto m : linsolve::available_methods())
        built += fmt::format(", \"{}\"", linsolve::to_string(m));
      input_error(
          "{} = \"{}\" is not built into this hydromodal: it needs PETSc (the Debian package "
          "petsc-dev, then rebuild). Built in: \"automatic\"{}",
          solver.where("preconditioner"), name, built);
    }
    return p;
  }
  input_error("{} = \"{}\": expected automatic, jacobi, ilu, boomeramg or gamg",
              solver.where("preconditioner"), name);
}

template <int D>
ldd::FlowOptions<D> flow_options(const io::Scene& scene) {
  ldd::FlowOptions<D> o;
  const SceneView fluid = scene.section("fluid"), time = scene.section("time"),
                  solver = scene.section("solver");
  o.density = fluid.number("density");
  o.viscosity = fluid.number("viscosity");
  const Eigen::VectorXd g = fluid.vector("gravity");
  o.gravity = g.size() == 0 ? default_gravity<D>() : vec_of<D>(g);
  o.dx = fluid.number("dx");
  o.support_factor = solver.number("support_factor");
  o.wall_node_spacing = solver.number("wall_node_spacing");
  o.wall_node_weights = solver.boolean("wall_node_weights");
  o.viscous = solver.string("viscosity") == "implicit" ? ldd::ViscousScheme::implicit_euler
                                                       : ldd::ViscousScheme::explicit_euler;
  o.pbd_iterations = static_cast<int>(solver.integer("pbd_iterations"));
  o.pbd_relaxation = solver.number("pbd_relaxation");
  o.pbd_distance = solver.number("pbd_distance");
  o.smoothing = solver.number("smoothing");
  o.shifting = solver.number("shifting");
  o.volume_relaxation = solver.number("volume_relaxation");
  o.release_wall_tension = solver.boolean("release_wall_tension");
  o.ppe.tolerance = solver.number("ppe_tolerance");
  o.ppe.max_iterations = static_cast<int>(solver.integer("ppe_max_iterations"));
  o.ppe.preconditioner = ppe_preconditioner(solver);
  o.ppe.amg_drop = solver.number("amg_drop");
  o.cfl = time.number("cfl");
  o.acceleration_number = time.number("acceleration_number");
  o.viscous_number = time.number("viscous_number");
  o.dt_max = time.number("dt_max");
  return o;
}

template <int D>
bool inside(const ldd::Box<D>& box, const ldd::Vec<D>& x) {
  const double tol = 1e-9 * (box.upper - box.lower).norm();
  return ((x - box.lower).array() >= -tol).all() && ((box.upper - x).array() >= -tol).all();
}

/// The first and last lattice points of a region's seed lattice (its corners inset by dx/2) and
/// its centre: where a region lies against a closed wall, without testing every point.
template <int D>
std::vector<ldd::Vec<D>> region_samples(const ldd::Box<D>& box, double dx) {
  std::vector<ldd::Vec<D>> samples{0.5 * (box.lower + box.upper)};
  for (int corner = 0; corner < (1 << D); ++corner) {
    ldd::Vec<D> x;
    for (int a = 0; a < D; ++a)
      x[a] = (corner >> a) & 1 ? std::max(box.lower[a], box.upper[a] - 0.5 * dx)
                               : std::min(box.upper[a], box.lower[a] + 0.5 * dx);
    samples.push_back(x);
  }
  return samples;
}

/// A closed file wall is a container (its normals, as read, point into it: the fluid inside) or,
/// with flip_normals = true, an obstacle (the fluid outside). The fluid regions must agree: a
/// region reaching outside a container, or lying wholly inside an obstacle, means the side is the
/// wrong one, and seeding would silently fill the obstacle or empty the tank (a closed STL
/// obstacle without flip_normals was seeded as a tank). InputError naming the wall, the region
/// and the key to set.
template <int D>
void check_sides_of_closed_walls(const io::Scene& scene, const FlowSetup<D>& setup) {
  const auto views = scene.array("wall");
  const auto regions = scene.array("fluid.region");
  const double dx = setup.options.dx;
  for (std::size_t w = 0; w < views.size(); ++w) {
    const auto& wall = setup.walls[w];
    if (wall.thin() || wall.open_boundary_count() != 0) continue;
    const bool container = wall.enclosed_measure() < 0.0;
    for (const SceneView& region : regions) {
      ldd::Box<D> box;
      box.lower = vec_of<D>(region.vector("origin"));
      box.upper = box.lower + vec_of<D>(region.vector("size"));
      int fluid_side = 0, other_side = 0;
      for (const auto& x : region_samples<D>(box, dx))
        wall.closest(x).signed_distance > 0.0 ? ++fluid_side : ++other_side;
      const std::string& name = setup.wall_names[w];
      if (container && other_side > 0)
        input_error(
            "{}: this fluid region reaches outside the closed wall '{}', which is a container "
            "(its normals point into it: the fluid inside). If '{}' is an obstacle with the "
            "fluid around it, set {} = true",
            region.where("origin"), name, name, views[w].full("flip_normals"));
      if (!container && fluid_side == 0)
        input_error(
            "{}: this fluid region lies inside the closed wall '{}', which is an obstacle "
            "({} = {}: the fluid outside it). If '{}' is the tank, {}",
            region.where("origin"), name, views[w].full("flip_normals"),
            views[w].boolean("flip_normals"), name,
            views[w].boolean("flip_normals") ? "remove flip_normals"
                                             : "its file's normals point out of it: set "
                                               "flip_normals = true");
    }
  }
}

/// Memory a run takes per point (fluid point or wall node) [bytes]: the point set, its neighbour
/// lists and operator weights, the PPE matrix and the preconditioner's setup. Measured as the
/// slope of fsi-simulate's peak resident memory between two resolutions (first steps): 2-D
/// dambreak_lobovsky smoke at dx 5 / 2.5 mm (8 088 / 30 576 points, BoomerAMG): 118 / 165 MB,
/// 2 130 bytes a point; 3-D hydrostatic_tank_3d smoke at dx 12.5 / 8.33 mm (16 172 / 47 487
/// points, Jacobi): 155 / 272 MB, 3 710 bytes a point. Taken twice over (a 3-D AMG setup, what
/// grows over a run).
constexpr double bytes_per_point_2d = 2.0 * 2130.0, bytes_per_point_3d = 2.0 * 3710.0;

/// The wall measure [m in 2-D, m² in 3-D] of a wall mesh.
template <int D>
double wall_measure(const ldd::WallMesh<D>& wall) {
  double sum = 0.0;
  for (ldd::Index e = 0; e < wall.element_count(); ++e) {
    const auto& c = wall.element(e);
    const auto& x = wall.vertices();
    if constexpr (D == 2)
      sum += (x[c[1]] - x[c[0]]).norm();
    else
      sum += 0.5 * (x[c[1]] - x[c[0]]).cross(x[c[2]] - x[c[0]]).norm();
  }
  return sum;
}

/// Refuses, before anything is seeded, a run whose points would not fit in the memory available:
/// an out-of-memory kill halfway through a run (or of the seeding itself) tells the user nothing.
/// InputError with the estimate (points, bytes) and the largest dx that fits.
template <int D>
void check_memory_fits(const io::Scene& scene, const FlowSetup<D>& setup) {
  const double dx = setup.options.dx;
  double fluid = 0.0, wall = 0.0;
  for (const SceneView& region : scene.array("fluid.region"))
    fluid += vec_of<D>(region.vector("size")).prod() / std::pow(dx, D);
  const double spacing = setup.options.wall_node_spacing * dx;
  for (const auto& w : setup.walls)
    wall += (w.thin() ? 2.0 : 1.0) * wall_measure(w) / std::pow(spacing, D - 1);
  const double per_point = D == 2 ? bytes_per_point_2d : bytes_per_point_3d;
  const double need = (fluid + wall) * per_point, have = 0.9 * available_memory();
  if (have <= 0.0 || need <= have) return;
  // Fluid points scale as dx^-D, wall nodes as dx^-(D-1): the dx at which the sum fits.
  double fit = dx;
  while ((fluid * std::pow(dx / fit, D) + wall * std::pow(dx / fit, D - 1)) * per_point > have)
    fit *= 1.05;
  input_error(
      "{}: fluid.dx = {} m gives about {:.3g} fluid points and {:.3g} wall nodes, which need about "
      "{:.3g} GiB ({:.0f} bytes a point); this machine has {:.3g} GiB available. The largest dx "
      "that fits is about {:.3g} m",
      scene.where("fluid.dx"), dx, fluid, wall, gibibytes(need), per_point, gibibytes(have / 0.9),
      fit);
}

/// Seeds every region; points of a region inside an earlier region are left out (the earlier
/// region fills the overlap).
template <int D>
void seed_regions(const io::Scene& scene, FlowSetup<D>& setup) {
  std::vector<ldd::Box<D>> seeded;
  for (const SceneView& region : scene.array("fluid.region")) {
    ldd::Box<D> box;
    box.lower = vec_of<D>(region.vector("origin"));
    box.upper = box.lower + vec_of<D>(region.vector("size"));
    const Eigen::VectorXd u = region.vector("velocity");
    const ldd::Vec<D> velocity = u.size() == 0 ? ldd::Vec<D>::Zero() : vec_of<D>(u);
    std::vector<ldd::Vec<D>> points;
    try {
      points = ldd::seed_box<D>(box, setup.options.dx, setup.walls);
    } catch (const InputError& e) {
      input_error("{} (size {}): {}", region.where("origin"),
                  fmt::format("[{}]", fmt::join(region.vector("size"), ", ")), e.what());
    }
    for (const auto& x : points) {
      const bool covered = std::any_of(seeded.begin(), seeded.end(),
                                       [&](const ldd::Box<D>& b) { return inside<D>(b, x); });
      if (covered) continue;
      setup.fluid.push_back(x);
      setup.velocity.push_back(velocity);
    }
    seeded.push_back(box);
  }
}

/// A probe on a wall's face measures there from the fluid side. Within on_face_tolerance·dx of a
/// (non-thin) wall's face, on either side, a probe is moved to fluid_side_offset·dx in front of
/// the face's closest point, along its (pseudo-)normal: it then reads the wall pressure there —
/// the face's wall nodes and the fluid of its half sphere — as a probe a hair inside the fluid
/// does. Without this a probe given "on" an STL face read 0 Pa for a whole run: the file is read
/// in single precision, so the face lay a few 1e-8 m beyond the coordinate given, the probe sat
/// inside the solid and every fluid point lay behind the face. The tolerance also takes in a
/// sensor given on a curved surface whose facets lie a little in front of it.
constexpr double on_face_tolerance = 0.05;  // [dx]
constexpr double fluid_side_offset = 1e-3;  // [dx]

/// What lies behind a wall's face, for the error of a probe placed there.
template <int D>
std::string behind(const ldd::WallMesh<D>& wall, const std::string& name) {
  if (wall.solid()) return fmt::format("inside the solid body '{}'", name);
  if (wall.open_boundary_count() == 0 && wall.enclosed_measure() < 0.0)
    return fmt::format("outside the container '{}'", name);
  return fmt::format("behind wall '{}' (on the side its normals point away from)", name);
}

/// The position a probe given at `x` measures at (see on_face_tolerance). InputError when it
/// lies deeper behind a wall's face (inside a solid, outside a container) — naming the probe,
/// its position and the nearest point on the fluid side — or on a thin wall, which has fluid on
/// both sides.
template <int D>
ldd::Vec<D> fluid_side_position(const SceneView& view, const FlowSetup<D>& setup,
                                const ldd::Vec<D>& given) {
  const double dx = setup.options.dx;
  const double tolerance = on_face_tolerance * dx, offset = fluid_side_offset * dx;
  ldd::Vec<D> x = given;
  for (int pass = 0; pass < D; ++pass)  // a corner where D faces meet
    for (std::size_t w = 0; w < setup.walls.size(); ++w) {
      const auto& wall = setup.walls[w];
      const auto c = wall.closest(x);
      const std::string& name = setup.wall_names[w];
      if (wall.thin()) {
        if (std::abs(c.signed_distance) < offset)
          input_error(
              "{} = [{}]: probe '{}' lies on the thin wall '{}' ({:.3g} m from it), which has "
              "fluid on both sides; move it off the wall, by more than {:.3g} m, to the side "
              "it measures",
              view.where("position"), fmt::join(given, ", "), view.string("name"), name,
              std::abs(c.signed_distance), offset);
        continue;
      }
      if (c.signed_distance < -tolerance)
        input_error(
            "{} = [{}]: probe '{}' lies {:.3g} m {}; the nearest point on the fluid side is "
            "[{:.6g}] m (a probe within {} dx = {:.3g} m of a face measures on it)",
            view.where("position"), fmt::join(given, ", "), view.string("name"), -c.signed_distance,
            behind(wall, name), fmt::join(ldd::Vec<D>(c.point + offset * c.normal), ", "),
            on_face_tolerance, tolerance);
      if (c.signed_distance < offset) x = c.point + offset * c.normal;
    }
  if (x != given)
    spdlog::info(
        "probe '{}' at [{}] is on a wall's face: it measures there from the fluid side, "
        "at [{:.6g}] m",
        view.string("name"), fmt::join(given, ", "), fmt::join(x, ", "));
  return x;
}

template <int D>
std::vector<coupling::Probe<D>> make_probes(const io::Scene& scene, const FlowSetup<D>& setup) {
  ldd::Vec<D> lower = setup.walls.front().lower(), upper = setup.walls.front().upper();
  for (const auto& w : setup.walls) {
    lower = lower.cwiseMin(w.lower());
    upper = upper.cwiseMax(w.upper());
  }
  const double dx = setup.options.dx, h = setup.options.support_factor * dx;
  std::vector<coupling::Probe<D>> probes;
  for (const SceneView& view : scene.array("probe")) {
    coupling::Probe<D> p;
    p.name = view.string("name");
    const std::string kind = view.string("kind");
    if (kind == "displacement") continue;  // the structure's (simulate_stage)
    p.kind = kind == "pressure"    ? coupling::ProbeKind::pressure
             : kind == "elevation" ? coupling::ProbeKind::elevation
             : kind == "front"     ? coupling::ProbeKind::front
                                   : coupling::ProbeKind::force;
    const Eigen::VectorXd position = view.vector("position");
    if (position.size() == D) {
      p.position = position;
      const double tol = on_face_tolerance * dx;  // a probe on a face, a hair off the box
      if (((p.position - lower).array() < -tol).any() ||
          ((upper - p.position).array() < -tol).any())
        input_error("{} = [{}] is outside the walls' bounding box [{}] – [{}] m",
                    view.where("position"), fmt::join(position, ", "), fmt::join(lower, ", "),
                    fmt::join(upper, ", "));
      p.position = fluid_side_position<D>(view, setup, p.position);
    }
    p.radius = view.number("radius") > 0.0 ? view.number("radius") : h;
    if (p.kind == coupling::ProbeKind::force) {
      const auto& names = setup.wall_names;
      p.wall = static_cast<int>(std::find(names.begin(), names.end(), view.string("wall")) -
                                names.begin());
    }
    if (const std::string host = view.string("moves_with"); !host.empty()) {
      const auto& names = setup.wall_names;
      const int index =
          static_cast<int>(std::find(names.begin(), names.end(), host) - names.begin());
      coupling::attach_probe<D>(p, setup.walls[static_cast<std::size_t>(index)], index);
    }
    p.direction = direction_key(view, "direction", Eigen::Vector3d::UnitX()).head<D>();
    const Eigen::VectorXd band = view.vector("band");
    const double floor = lower[D - 1];
    p.band_low = floor + (band.size() == 2 ? band[0] : 0.0);
    p.band_high = floor + (band.size() == 2 ? band[1] : 2.0 * dx);
    probes.push_back(std::move(p));
  }
  return probes;
}

}  // namespace

bool is_flow_scene(const io::Scene& scene) {
  return scene.has("fluid");
}

template <int D>
ldd::Vec<D> default_gravity() {
  ldd::Vec<D> g = ldd::Vec<D>::Zero();
  g[D - 1] = -9.81;
  return g;
}

void validate_flow_scene(const io::Scene& scene) {
  if (!is_flow_scene(scene)) return;
  const std::string file = scene.file().filename().string();
  if (!scene.has("time"))
    input_error("{}: a flow scene ([fluid]) needs a [time] section with at least time.end (s)",
                file);
  if (scene.array("fluid.region").empty())
    input_error(
        "{}: a flow scene needs at least one [[fluid.region]] (origin, size in m) to fill "
        "with fluid",
        file);
  if (scene.array("wall").empty())
    input_error("{}: a flow scene needs at least one [[wall]] to hold the fluid", file);
  for (const SceneView& wall : scene.array("wall")) {
    wall_motion(wall, scene.dimension());
    if (scene.has("structure") && wall.string("name") == structure_wall_name)
      input_error(
          "{} = \"{}\": in a scene with a [structure] this name is the structure's own wall "
          "(its mapped surface); give the rigid wall another name",
          wall.where("name"), structure_wall_name);
  }
  validate_probes(scene);
}

namespace {
/// A rigid wall of the scene: its nodes are thinned to the node spacing where its mesh is finer
/// (a detailed STL part). A closed one with the fluid outside (an obstacle: a bracket, a pillar)
/// is a solid body like the structure: the pairs through it are cut (its parts thinner than h
/// would otherwise couple the fluid on their two faces) and the nodes of the walls it stands on
/// that it covers are buried.
template <int D>
void configure_rigid_wall(ldd::WallMesh<D>& wall) {
  wall.set_thins_dense_nodes(true);
  if (!wall.thin() && wall.open_boundary_count() == 0 && wall.enclosed_measure() > 0.0)
    wall.set_solid(true);
}

/// The scene's [[wall]]s from `surfaces` (name → surface), with their motions.
template <int D>
void add_scene_walls(const io::Scene& scene,
                     const std::vector<std::pair<std::string, mesh::SurfaceMesh>>& surfaces,
                     FlowSetup<D>& setup) {
  for (const SceneView& wall : scene.array("wall")) {
    const std::string name = wall.string("name");
    const auto found = std::find_if(surfaces.begin(), surfaces.end(),
                                    [&](const auto& s) { return s.first == name; });
    HM_ASSERT(found != surfaces.end(), "no surface for wall '{}'", name);
    const mesh::SurfaceMesh& surface = found->second;
    if (surface.dim != D)
      input_error("{} = \"{}\": the wall mesh is {}-D, the case is {}-D", wall.where("name"), name,
                  surface.dim, D);
    std::filesystem::path table;
    setup.motions.push_back({surface.vertices, wall_motion(wall, D, &table)});
    if (!table.empty()) setup.motion_tables.push_back(table);
    setup.walls.emplace_back(surface, name, wall.boolean("thin"));
    configure_rigid_wall(setup.walls.back());
    setup.wall_names.push_back(name);
  }
}
}  // namespace

template <int D>
FlowSetup<D> flow_setup(const io::Scene& scene,
                        const std::vector<std::pair<std::string, mesh::SurfaceMesh>>& surfaces,
                        const mesh::SurfaceMesh* structure) {
  HM_ASSERT(scene.dimension() == D, "a {}-D flow set up from a {}-D scene", D, scene.dimension());
  if (!is_flow_scene(scene))
    input_error("{}: the scene has no [fluid] section, so there is no flow to run",
                scene.file().string());
  validate_flow_scene(scene);
  FlowSetup<D> setup;
  setup.options = flow_options<D>(scene);
  add_scene_walls<D>(scene, surfaces, setup);
  if (structure) {
    if (structure->dim != D)
      input_error("{}: the structure's surface is {}-D, the case is {}-D", scene.file().string(),
                  structure->dim, D);
    setup.structure_wall = static_cast<int>(setup.walls.size());
    setup.motions.push_back({structure->vertices, std::nullopt});
    setup.walls.emplace_back(*structure, structure_wall_name, false);
    setup.walls.back().set_solid(true);  // fluid on both faces of a gate thinner than h
    setup.walls.back().set_releases_tension(scene.boolean("coupling.release_tension"));
    setup.wall_names.push_back(structure_wall_name);
  }
  coupling::place_walls<D>(setup.walls, setup.motions, 0.0);
  check_sides_of_closed_walls<D>(scene, setup);
  check_memory_fits<D>(scene, setup);
  seed_regions<D>(scene, setup);
  const SceneView time = scene.section("time");
  setup.time.end = time.number("end");
  setup.time.snapshot_interval = time.number("snapshot_interval");
  setup.time.probe_interval = time.number("probe_interval");
  setup.time.checkpoint_interval = time.number("checkpoint_interval");
  setup.probes = make_probes<D>(scene, setup);
  return setup;
}

namespace {
template <int D>
void check_flow_geometry(const io::Scene& scene) {
  FlowSetup<D> setup;
  setup.options = flow_options<D>(scene);
  add_scene_walls<D>(scene, scene_wall_surfaces(scene), setup);
  coupling::place_walls<D>(setup.walls, setup.motions, 0.0);
  check_sides_of_closed_walls<D>(scene, setup);
  check_memory_fits<D>(scene, setup);
  make_probes<D>(scene, setup);
}
}  // namespace

void validate_flow_geometry(const io::Scene& scene) {
  if (!is_flow_scene(scene)) return;
  if (scene.dimension() == 2)
    check_flow_geometry<2>(scene);
  else
    check_flow_geometry<3>(scene);
}

std::vector<std::pair<std::string, mesh::SurfaceMesh>> scene_wall_surfaces(
    const io::Scene& scene, std::vector<std::filesystem::path>* files) {
  std::vector<std::pair<std::string, mesh::SurfaceMesh>> surfaces;
  for (const SceneView& wall : scene.array("wall")) {
    mesh::SurfaceMesh surface = mesh_scene_wall(wall, scene.dimension());
    if (files && wall.string("kind") == "file") files->push_back(wall.file_path("file"));
    surfaces.emplace_back(wall.string("name"), std::move(surface));
  }
  return surfaces;
}

template <int D>
FlowSetup<D> flow_setup(const io::Scene& scene, const io::ArtefactReader& mesh_artefact,
                        const mesh::SurfaceMesh* structure) {
  std::vector<std::pair<std::string, mesh::SurfaceMesh>> surfaces;
  for (const std::string& name : scene_wall_names(scene))
    surfaces.emplace_back(name, read_wall(mesh_artefact, name));
  return flow_setup<D>(scene, surfaces, structure);
}

template ldd::Vec<2> default_gravity<2>();
template ldd::Vec<3> default_gravity<3>();
template FlowSetup<2> flow_setup<2>(const io::Scene&,
                                    const std::vector<std::pair<std::string, mesh::SurfaceMesh>>&,
                                    const mesh::SurfaceMesh*);
template FlowSetup<3> flow_setup<3>(const io::Scene&,
                                    const std::vector<std::pair<std::string, mesh::SurfaceMesh>>&,
                                    const mesh::SurfaceMesh*);
template FlowSetup<2> flow_setup<2>(const io::Scene&, const io::ArtefactReader&,
                                    const mesh::SurfaceMesh*);
template FlowSetup<3> flow_setup<3>(const io::Scene&, const io::ArtefactReader&,
                                    const mesh::SurfaceMesh*);

}  // namespace hm::driver
