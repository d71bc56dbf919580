#include "ldd/flow.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <sstream>

#include <fmt/format.h>
#include <Eigen/SparseCore>

#include "core/log.hpp"
#include "ldd/kernels.hpp"
#include "ldd/point_loop.hpp"
#include "ldd/volume.hpp"
#include "linsolve/petsc_solver.hpp"

namespace hm::ldd {
namespace {

using Clock = std::chrono::steady_clock;

/// Adds the seconds since `since` to `into` and restarts the clock.
void lap(Clock::time_point& since, double& into) {
  const auto now = Clock::now();
  into += std::chrono::duration<double>(now - since).count();
  since = now;
}

bool is_fluid(const PointSet<2>& p, Index i) {
  return p.kind[i] == PointKind::fluid;
}
bool is_fluid(const PointSet<3>& p, Index i) {
  return p.kind[i] == PointKind::fluid;
}

template <typename T>
void permute(std::vector<T>& v, std::span<const Index> order) {
  std::vector<T> out(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) out[k] = v[static_cast<std::size_t>(order[k])];
  v.swap(out);
}

template <int D>
std::string describe_point(const PointSet<D>& p, Index i, double value, const char* what) {
  Eigen::IOFormat f(6, Eigen::DontAlignCols, ", ", ", ", "", "", "[", "]");
  std::ostringstream pos, vel;
  pos << p.position[i].transpose().format(f);
  vel << p.velocity[i].transpose().format(f);
  return fmt::format("point {} ({}) at {} m, u = {} m/s, p = {:.6g} Pa, {} = {:.6g}", i,
                     p.kind[i] == PointKind::fluid ? "fluid" : "wall node", pos.str(), vel.str(),
                     p.pressure[i], what, value);
}

void require(bool ok, const std::string& message) {
  if (!ok) throw InputError(message);
}

/// Doubles a travelling point carries: velocity, pressure, kind, type, the wall node's normal,
/// velocity, acceleration and host (body, element, barycentric), ∇u, |Δu/Δt|, the wall
/// clearance bound and the velocity at the step's start.
template <int D>
constexpr int travelling_width = 6 * D + D* D + 7;

/// Writes an Eigen vector or matrix's entries at `f` and moves past them.
template <typename Dense>
void put(double*& f, const Dense& v) {
  f = std::copy_n(v.data(), v.size(), f);
}

/// Reads an Eigen vector or matrix's entries from `f` and moves past them.
template <typename Dense>
Dense take(const double*& f) {
  Dense v;
  std::copy_n(f, v.size(), v.data());
  f += v.size();
  return v;
}

/// The share of a step's work a point stands for, by which the regions are drawn [CHOICE]: 1 +
/// its neighbours (travelling_owned_points), as the operators, PBD, the smoothing and its PPE row
/// all cost in proportion to them (the interior of a water column holds more than its surface); a
/// dry wall node (inactive) has an empty list and no PPE row: 1. Before any list exists (the
/// set-up's regions): 1 + the lattice's neighbours within h for a fluid point or a wall node not
/// known to be dry (a wet wall node costs a fluid point's work: measured, 3-D dam break at 2
/// processes, the operators 2.6 µs a fluid point or wet wall node alike). Regions of equal counts
/// gave the process with the water column 1.6× the other's fluid work; wet nodes at half a fluid
/// point's weight left one process 22 % more fluid points and wet nodes than the other; weights by
/// kind alone left the process with the column's interior 12 % more operator time (0.291 against
/// 0.260 s a step).
float work_weight(PointKind kind, PointType type, double neighbours) {
  if (kind == PointKind::wall && type == PointType::inactive) return 1.0f;  // an empty list
  return static_cast<float>(1.0 + neighbours);
}

/// Where unpack puts a travelling point's state.
template <int D>
struct PointArrays {
  PointSet<D>& points;
  std::vector<Mat<D>>& velocity_gradient;
  std::vector<double>& acceleration;
  std::vector<double>& wall_distance;
  std::vector<Vec<D>>& old_velocity;
  std::vector<std::int64_t>& id;
};

/// Appends the points of `block` (travelling_width fields each) to `into`.
template <int D>
void unpack(const TravellingPoints<D>& block, PointArrays<D> into) {
  HM_ASSERT(block.width == travelling_width<D>, "flow: {} fields a travelling point, not {}",
            block.width, travelling_width<D>);
  auto& points = into.points;
  for (std::size_t k = 0; k < block.size(); ++k) {
    const double* f = block.fields.data() + k * travelling_width<D>;
    const auto velocity = take<Vec<D>>(f);
    const double pressure = *f++;
    const auto kind = static_cast<PointKind>(*f++);
    const auto type = static_cast<PointType>(*f++);
    const auto normal = take<Vec<D>>(f);
    const auto wall_velocity = take<Vec<D>>(f);
    const auto wall_acceleration = take<Vec<D>>(f);
    WallHost<D> host;
    host.body = static_cast<int>(*f++);
    host.element = static_cast<Index>(*f++);
    host.barycentric = take<Vec<D>>(f);
    const Index i = kind == PointKind::fluid
                        ? points.add_fluid(block.position[k], velocity)
                        : points.add_wall_node(block.position[k], normal, host);
    points.velocity[i] = velocity;
    points.pressure[i] = pressure;
    points.type[i] = type;
    points.wall_velocity[i] = wall_velocity;
    points.wall_acceleration[i] = wall_acceleration;
    into.velocity_gradient.push_back(take<Mat<D>>(f));
    into.acceleration.push_back(*f++);
    into.wall_distance.push_back(*f++);
    into.old_velocity.push_back(take<Vec<D>>(f));
    into.id.push_back(block.id[k]);
  }
}

template <int D>
TravellingPoints<D> reordered(const TravellingPoints<D>& block, std::span<const Index> order) {
  TravellingPoints<D> out{.width = block.width};
  for (const Index k : order)
    out.add(block.position[k], block.id[k], block.fields.data() + std::size_t(k) * block.width);
  return out;
}

}  // namespace

const char* to_string(StepLimit limit) {
  switch (limit) {
    case StepLimit::cfl:
      return "cfl";
    case StepLimit::viscous:
      return "viscous";
    case StepLimit::acceleration:
      return "acceleration";
    case StepLimit::maximum:
      return "maximum";
    case StepLimit::output:
      return "output";
  }
  return "?";
}

double bounded_step(double dt, double remaining) {
  if (remaining <= dt) return remaining;
  if (remaining < 1.5 * dt) return 0.5 * remaining;
  return dt;
}

PhaseSeconds PhaseSeconds::from_values(std::span<const double> v) {
  HM_ASSERT(v.size() >= count, "{} phase values for {} phases", v.size(), count);
  return {v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]};
}

double PhaseSeconds::total() const {
  const auto v = values();
  return std::accumulate(v.begin(), v.end(), 0.0);
}

PhaseSeconds& PhaseSeconds::operator+=(const PhaseSeconds& o) {
  const auto a = values(), b = o.values();
  std::array<double, count> sum;
  for (std::size_t k = 0; k < count; ++k) sum[k] = a[k] + b[k];
  return *this = from_values(sum);
}

std::string DivergenceReport::text() const {
  std::string s =
      fmt::format("the flow diverged at step {} (t = {:.6g} s): {}", step, time, criterion);
  if (!worst_points.empty()) s += "; worst points:";
  for (const auto& w : worst_points) s += "\n  " + w;
  return s;
}

FlowDiverged::FlowDiverged(DivergenceReport report)
    : NumericalError(report.text()), report_(std::move(report)) {}

// ---------------------------------------------------------------------------------------------
// Set-up

namespace {

/// `ppe`, once its preconditioner is known to be built in (InputError naming those that are).
const SolverOptions& available_ppe_options(const SolverOptions& ppe) {
  if (!is_available(ppe.preconditioner)) {
    std::string names;
    for (const auto m : linsolve::available_methods())
      names += fmt::format(", {}", linsolve::to_string(m));
    throw InputError(fmt::format(
        "flow: the PPE preconditioner \"{}\" is not built into this hydromodal (built in: "
        "automatic{}; the PETSc ones need a build with petsc-dev installed)",
        to_string(ppe.preconditioner), names));
  }
  return ppe;
}

/// Whether point i is an unknown of the PPE (its row is solved for), not Dirichlet or inactive.
template <int D>
bool is_unknown(const PointSet<D>& points, Index i) {
  return points.type[i] == PointType::interior || points.type[i] == PointType::wall;
}

/// The PPE's solver in a distributed flow: PETSc's BiCGSTAB with BoomerAMG (GAMG when chosen)
/// over the processes, the rows of each process's unknowns on it.
std::unique_ptr<linsolve::LinearSolver> make_distributed_ppe_solver(const SolverOptions& ppe) {
  if (ppe.preconditioner == Preconditioner::jacobi || ppe.preconditioner == Preconditioner::ilu)
    throw InputError(
        fmt::format("flow: the PPE preconditioner \"{}\" runs in one process; over several, use "
                    "\"boomeramg\", \"gamg\" or \"automatic\" (BoomerAMG)",
                    to_string(ppe.preconditioner)));
  const auto method = ppe.preconditioner == Preconditioner::gamg ? linsolve::Method::gamg
                                                                 : linsolve::Method::boomeramg;
  auto solver = linsolve::make_distributed_solver(
      method,
      {.tolerance = ppe.tolerance, .max_iterations = ppe.max_iterations, .amg_drop = ppe.amg_drop});
  if (!solver)
    throw InputError(
        "flow: a flow over several processes needs the PETSc solvers, and this hydromodal was "
        "built without them (install petsc-dev and build again)");
  return solver;
}

}  // namespace

template <int D>
FlowSolver<D>::FlowSolver(std::vector<WallMesh<D>> walls, std::span<const Vec<D>> fluid,
                          std::span<const Vec<D>> velocity, const FlowOptions<D>& options,
                          double t0, std::shared_ptr<PointExchange<D>> processes)
    : options_(options),
      walls_(std::move(walls)),
      ppe_solver_(available_ppe_options(options.ppe)),
      viscous_solver_({.primary = linsolve::Method::jacobi},
                      {.tolerance = 1e-8, .max_iterations = 500}),
      exchange_(std::move(processes)),
      time_(t0) {
  const auto& o = options_;
  require(o.dx > 0.0, fmt::format("flow: dx = {} m must be > 0", o.dx));
  require(o.density > 0.0, fmt::format("flow: density = {} kg/m³ must be > 0", o.density));
  require(o.viscosity >= 0.0, fmt::format("flow: viscosity = {} m²/s must be ≥ 0", o.viscosity));
  require(o.support_factor >= 1.5 && o.support_factor <= 4.0,
          fmt::format("flow: support_factor = {} must be in [1.5, 4]", o.support_factor));
  require(o.pbd_iterations >= 0, "flow: pbd_iterations must be ≥ 0");
  require(o.wall_node_spacing >= 0.0625 && o.wall_node_spacing <= 1.0,
          fmt::format("flow: wall_node_spacing = {} must be in [1/16, 1]", o.wall_node_spacing));
  require(o.cfl > 0.0 && o.cfl <= 1.0, fmt::format("flow: cfl = {} must be in (0, 1]", o.cfl));
  require(!walls_.empty(), "flow: a flow needs at least one wall");
  require(!fluid.empty(), "flow: no fluid points");
  require(velocity.empty() || velocity.size() == fluid.size(),
          "flow: one initial velocity per fluid point is needed");
  if (exchange_) {
    require(o.viscous == ViscousScheme::explicit_euler || o.viscosity == 0.0,
            "flow: the implicit viscosity is not distributed over processes (viscous = "
            "\"explicit\" runs on any number)");
    distributed_ppe_ = make_distributed_ppe_solver(o.ppe);
  }

  for (std::size_t k = 0; k < fluid.size(); ++k)
    points_.add_fluid(fluid[k], velocity.empty() ? Vec<D>::Zero() : velocity[k]);
  for (std::size_t b = 0; b < walls_.size(); ++b)
    add_wall_nodes<D>(points_, walls_[b], static_cast<int>(b), o.wall_node_spacing * o.dx);

  const auto [lower, upper] = wall_box();
  const double h = support();
  n0_ = lattice_number_density<D>(o.dx, h);
  options_.free_surface.reference_density = n0_;
  speed_limit_ = o.speed_limit > 0.0
                     ? o.speed_limit
                     : 50.0 * std::sqrt(std::max(o.gravity.norm(), 1.0) * (upper - lower).norm());

  const auto n = static_cast<std::size_t>(points_.size());
  id_.resize(n);
  std::iota(id_.begin(), id_.end(), std::int64_t{0});
  owned_ = points_.size();
  grad_u_.assign(n, Mat<D>::Zero());
  acceleration_.assign(n, 0.0);
  wall_distance_.assign(n, -1.0);  // unknown: checked below
  resort();
  keep_clear_of_walls(true);
  if (exchange_) {
    keep_every_processes_share();
    redistribute(/*sort=*/true);
  }
  const auto [volume, fluid_points] = measured_volume();
  initial_volume_ = volume;
  initial_fluid_ = static_cast<Index>(fluid_points);
  rebuild_neighbours();
  classify_points();

  // Pressure at t0: one projection of u* = u + Δt g without moving anything.
  const double dt = stable_dt(0.0).first;
  std::vector<Vec<D>> viscous;
  const auto predicted = predict(dt, viscous);
  StepMonitor m;
  project(dt, predicted, viscous, TensionRelease::fresh, m);
  if (!m.ppe_converged)
    numerical_error(
        "flow: the initial pressure solve did not converge ({} iterations, residual "
        "{:.3g}; {})",
        m.ppe_iterations, m.ppe_residual, m.ppe_failure);
}

template <int D>
FlowState<D> FlowSolver<D>::state() const {
  HM_ASSERT(!in_step(), "flow: state() within step {}", step_ + 1);
  FlowState<D> s;
  if (exchange_) {  // no neighbour lists: they were the processes'
    gather_on_first(s);
    s.neighbours.offsets.assign(1, 0);
  } else {
    s.points = points_;
    s.neighbours = neighbours_;
    s.velocity_gradient = grad_u_;
    s.wall_distance = wall_distance_;
    s.acceleration = acceleration_;
    s.id = id_;
  }
  for (const auto& w : walls_) {
    s.wall_x.push_back(w.vertices());
    std::vector<Vec<D>> v, a;
    for (std::size_t k = 0; k < w.vertices().size(); ++k) {
      v.push_back(w.vertex_velocity(static_cast<Index>(k)));
      a.push_back(w.vertex_acceleration(static_cast<Index>(k)));
    }
    s.wall_v.push_back(std::move(v));
    s.wall_a.push_back(std::move(a));
  }
  s.time = time_;
  s.step = step_;
  s.escaped = escaped_;
  s.last_volume_drift = last_volume_drift_;
  s.initial_volume = initial_volume_;
  s.initial_fluid = initial_fluid_;
  s.last_max_wall_speed = last_max_wall_speed_;
  s.last_max_speed = last_max_speed_;
  return s;
}

template <int D>
void FlowSolver<D>::restore(FlowState<D> s) {
  HM_ASSERT(!in_step(), "flow: restore() within step {}", step_ + 1);
  if (s.wall_x.size() != walls_.size())
    input_error("flow: the checkpoint has {} walls, the scene {}", s.wall_x.size(), walls_.size());
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    if (s.wall_x[w].size() != walls_[w].vertices().size())
      input_error("flow: wall '{}' has {} vertices in the checkpoint, {} in the scene",
                  walls_[w].name(), s.wall_x[w].size(), walls_[w].vertices().size());
    walls_[w].move(s.wall_x[w], s.wall_v[w], s.wall_a[w]);
  }
  const auto n = s.points.position.size();
  // A state of a distributed flow has no neighbour lists (they were the processes'), one of
  // an older checkpoint no ids (its points in id order).
  const bool with_lists = s.neighbours.points() == static_cast<Index>(n);
  HM_ASSERT(s.velocity_gradient.size() == n && s.wall_distance.size() == n &&
                s.acceleration.size() == n && (s.id.empty() || s.id.size() == n),
            "flow: inconsistent state of {} points", n);
  points_ = std::move(s.points);
  id_ = std::move(s.id);
  if (id_.empty()) {
    id_.resize(n);
    std::iota(id_.begin(), id_.end(), std::int64_t{0});
  }
  neighbours_ = std::move(s.neighbours);
  grad_u_ = std::move(s.velocity_gradient);
  wall_distance_ = std::move(s.wall_distance);
  acceleration_ = std::move(s.acceleration);
  time_ = s.time;
  step_ = s.step;
  escaped_ = s.escaped;
  last_volume_drift_ = s.last_volume_drift;
  initial_volume_ = s.initial_volume;
  initial_fluid_ = s.initial_fluid;
  last_max_wall_speed_ = s.last_max_wall_speed;
  last_max_speed_ = s.last_max_speed;
  outside_.clear();
  step_start_.clear();
  pending_old_velocity_.clear();
  owned_ = points_.size();
  if (exchange_) {  // each process its share, as the constructor deals them
    keep_every_processes_share();
    redistribute(/*sort=*/true);
  }
  // The lists of the last step rebuilt where they were not carried: built from the positions
  // the step ended with (a step does not move points after its neighbour search), as it built
  // them.
  // The wall-node weights with them (over processes the owners' weights reach the ghosts there:
  // a ghost's own estimate misses the nodes beyond the halo).
  if (exchange_ || !with_lists)
    rebuild_neighbours();
  else
    update_node_weights();
  // The operators of the last step are not carried between steps; those of the restored
  // points keep acceleration_pressure usable right away.
  ops_ = compute_operators<D>(points_.position, neighbours_, options_.operators, node_weight_);
}

template <int D>
std::pair<Vec<D>, Vec<D>> FlowSolver<D>::wall_box() const {
  Vec<D> lower = walls_[0].lower(), upper = walls_[0].upper();
  for (const auto& w : walls_) {
    lower = lower.cwiseMin(w.lower());
    upper = upper.cwiseMax(w.upper());
  }
  return {lower, upper};
}

template <int D>
void FlowSolver<D>::resort() {
  resort_by(spatial_order<D>(points_.position, support()));
}

template <int D>
void FlowSolver<D>::resort_by(std::span<const Index> order) {
  points_.reorder(order);
  permute(id_, order);
  // The velocities at the step's start follow (they give each point's acceleration).
  if (pending_old_velocity_.size() == order.size()) permute(pending_old_velocity_, order);
  permute(grad_u_, order);
  permute(acceleration_, order);
  permute(wall_distance_, order);
  outside_.clear();  // both hold only within a step, before the re-sort
  step_start_.clear();
}

// ---------------------------------------------------------------------------------------------
// Time step

template <int D>
std::pair<double, StepLimit> FlowSolver<D>::stable_dt(double wall_speed) const {
  const auto& o = options_;
  double u_max = wall_speed, a_max = o.gravity.norm();
  for (Index i = 0; i < owned(); ++i) {
    if (!is_fluid(points_, i)) continue;
    u_max = std::max(u_max, points_.velocity[i].norm());
    a_max = std::max(a_max, acceleration_[i]);
  }
  if (exchange_) {
    std::array<double, 2> limits{u_max, a_max};
    exchange_->max(limits);
    u_max = limits[0];
    a_max = limits[1];
  }
  double dt = o.dt_max;
  StepLimit limit = StepLimit::maximum;
  auto consider = [&](double candidate, StepLimit why) {
    if (candidate < dt) {
      dt = candidate;
      limit = why;
    }
  };
  if (u_max > 0.0) consider(o.cfl * o.dx / u_max, StepLimit::cfl);
  if (a_max > 0.0)
    consider(o.acceleration_number * std::sqrt(o.dx / a_max), StepLimit::acceleration);
  if (o.viscous == ViscousScheme::explicit_euler && o.viscosity > 0.0)
    consider(o.viscous_number * o.dx * o.dx / o.viscosity, StepLimit::viscous);
  return {dt, limit};
}

template <int D>
StepMonitor FlowSolver<D>::step(double dt) {
  begin_step(dt);
  solve_pressure();
  return finish_step();
}

template <int D>
void FlowSolver<D>::begin_step(double dt) {
  HM_ASSERT(dt > 0.0, "flow: step dt = {} must be > 0", dt);
  HM_ASSERT(!in_step(), "flow: begin_step while step {} is in progress", step_ + 1);
  StepMonitor& m = pending_;
  m = StepMonitor{};
  m.step = step_ + 1;
  m.dt = dt;
  if (!(dt >= options_.dt_min)) {
    DivergenceReport r;
    r.step = m.step;
    r.time = time_ + dt;
    r.criterion = fmt::format("time step {:.3g} s below dt_min = {:.3g} s", dt, options_.dt_min);
    throw FlowDiverged(r);
  }
  auto t = Clock::now();
  pending_stable_step_ = stable_dt(last_max_wall_speed_).first;
  pending_old_velocity_ = points_.velocity;
  advect(dt);
  lap(t, m.seconds.advect);
  regularise_positions(dt);
  lap(t, m.seconds.pbd);
  remove_escaped_points();
  const bool resort_due =
      options_.resort_interval > 0 && (step_ + 1) % options_.resort_interval == 0;
  if (exchange_)
    redistribute(resort_due);
  else if (resort_due)
    resort();
  rebuild_neighbours();
  lap(t, m.seconds.neighbours);
  ops_ = compute_operators<D>(points_.position, neighbours_, options_.operators, node_weight_);
  lap(t, m.seconds.operators);
  const auto surface = detect_free_surface<D>(points_, neighbours_, ops_, options_.free_surface,
                                              exchange_ ? owned_ : -1);
  mark_sparse_points_as_surface(surface.fluid_density);
  refresh_ghost_types();
  lap(t, m.seconds.free_surface);
  pending_predicted_ = predict(dt, pending_viscous_);
  lap(t, m.seconds.predictor);
  pending_types_ = points_.type;
  pending_dt_ = dt;
}

template <int D>
void FlowSolver<D>::solve_pressure(TensionRelease release) {
  HM_ASSERT(in_step(), "flow: solve_pressure outside a step");
  points_.type = pending_types_;  // undo the tension release of an earlier solve of this step
  if (release == TensionRelease::fresh) released_.clear();
  project(pending_dt_, pending_predicted_, pending_viscous_, release, pending_);
}

template <int D>
void FlowSolver<D>::refresh_wall_kinematics() {
  HM_ASSERT(in_step(), "flow: refresh_wall_kinematics outside a step");
  // Every wall is on every process: the ghost wall nodes follow theirs as the owners' do.
  update_wall_nodes<D>(points_, walls_);
  const auto& o = options_;
  const double dt = pending_dt_;
  for (Index i = 0; i < owned(); ++i)
    if (!is_fluid(points_, i))
      pending_predicted_[i] = points_.wall_velocity[i] +
                              dt * (o.gravity + pending_viscous_[i] - points_.wall_acceleration[i]);
  refresh_ghosts(pending_predicted_);  // the owners' viscous terms
}

template <int D>
StepMonitor FlowSolver<D>::finish_step() {
  HM_ASSERT(in_step(), "flow: finish_step outside a step");
  StepMonitor& m = pending_;
  const double dt = pending_dt_;
  auto t = Clock::now();
  correct(dt, pending_predicted_);
  smooth_velocity(dt, pending_stable_step_);
  time_ += dt;
  ++step_;
  update_monitors(dt, pending_old_velocity_, m);
  lap(t, m.seconds.corrector);
  m.time = time_;
  pending_dt_ = 0.0;
  pending_predicted_.clear();
  pending_viscous_.clear();
  pending_old_velocity_.clear();
  check_divergence(m);
  return m;
}

template <int D>
std::vector<double> FlowSolver<D>::acceleration_pressure(std::span<const Vec<D>> acceleration) {
  HM_ASSERT(acceleration.size() == static_cast<std::size_t>(points_.size()),
            "flow: {} accelerations for {} points", acceleration.size(), points_.size());
  const Index n = points_.size();
  PoissonData data;
  data.source.assign(static_cast<std::size_t>(n), 0.0);
  data.dirichlet.assign(static_cast<std::size_t>(n), 0.0);
  data.neumann.assign(static_cast<std::size_t>(n), 0.0);
  for (Index i = 0; i < n; ++i)
    if (!is_fluid(points_, i))
      data.neumann[i] = -options_.density * points_.wall_normal[i].dot(acceleration[i]);
  const std::vector<PointType> types = points_.type;  // assembly may demote weak wall rows
  std::vector<double> pressure(static_cast<std::size_t>(n), 0.0);
  if (exchange_) {
    solve_distributed_acceleration_pressure(data, pressure);
    points_.type = types;  // on the ghosts too: they were the owners' before the demotion
    return pressure;
  }
  const auto system = assemble_poisson<D>(points_, neighbours_, ops_, data, options_.dx);
  points_.type = types;
  const auto report = ppe_solver_.solve(system, pressure);
  if (!report.converged)
    numerical_error(
        "flow: the added-mass pressure solve did not converge ({} iterations, residual {:.3g}, "
        "{}: {})",
        report.iterations, report.residual, to_string(report.preconditioner), report.failure);
  return pressure;
}

template <int D>
void FlowSolver<D>::solve_distributed_acceleration_pressure(PoissonData& data,
                                                            std::vector<double>& pressure) {
  // The rows of this process's unknowns from zero (Dirichlet p = 0 at the free surface), on
  // the preconditioner of an identical matrix when there is one (every mode of an added-mass
  // measurement and the step's own PPE share it).
  const auto [rows, global] = assemble_distributed(data);
  const auto count = static_cast<Index>(rows.point_of.size());
  Eigen::VectorXd x = Eigen::VectorXd::Zero(count);
  const bool ready = set_up_distributed(rows.matrix);
  const auto stats = ready ? distributed_ppe_->solve(rows.rhs, x) : linsolve::SolveStats{};
  if (!ready || !stats.converged)
    numerical_error(
        "flow: the added-mass pressure solve over {} processes did not converge ({} iterations, "
        "residual {:.3g}: {})",
        exchange_->processes(), stats.iterations, stats.residual,
        ready ? stats.failure : distributed_ppe_->setup_failure());
  for (Index r = 0; r < count; ++r) pressure[rows.point_of[r]] = x[r];
  refresh_ghosts(pressure);  // the loads' averages read the ghost wall nodes too
}

// ---------------------------------------------------------------------------------------------
// Advection, clearance, PBD

template <int D>
void FlowSolver<D>::advect(double dt) {
  // Wall nodes follow their walls; the largest wall displacement shrinks every clearance bound.
  std::vector<Vec<D>> before;
  before.reserve(static_cast<std::size_t>(points_.size()));
  double wall_move = 0.0;
  for (Index i = 0; i < points_.size(); ++i)
    if (!is_fluid(points_, i)) before.push_back(points_.position[i]);
  update_wall_nodes<D>(points_, walls_);
  last_max_wall_speed_ = 0.0;
  for (Index i = 0, k = 0; i < points_.size(); ++i) {
    if (is_fluid(points_, i)) continue;
    wall_move = std::max(wall_move, (points_.position[i] - before[k++]).norm());
    last_max_wall_speed_ = std::max(last_max_wall_speed_, points_.wall_velocity[i].norm());
  }
  if (exchange_) {  // over every process's wall nodes, as in one piece
    std::array<double, 2> wall{wall_move, last_max_wall_speed_};
    exchange_->max(wall);
    wall_move = wall[0];
    last_max_wall_speed_ = wall[1];
  }
  step_start_ = points_.position;
  outside_.assign(static_cast<std::size_t>(points_.size()), 0);
  for_each_point(owned(), [&](Index i) {
    if (!is_fluid(points_, i)) return;
    const Vec<D> dr = dt * points_.velocity[i];
    points_.position[i] += dr;
    wall_distance_[i] -= dr.norm() + wall_move;
  });
  keep_clear_of_walls(false);
  refresh_ghosts(points_.position);
}

template <int D>
double FlowSolver<D>::typical_step() const {
  const double g = options_.gravity.norm();
  // Without gravity: the CFL step at 1 m/s.
  return g > 0.0 ? options_.acceleration_number * std::sqrt(options_.dx / g)
                 : options_.cfl * options_.dx;
}

template <int D>
void FlowSolver<D>::keep_clear_of_walls(bool all_points) {
  const double clearance = 0.5 * options_.pbd_distance * options_.dx;
  // Without a step start (the set-up) every point is taken to have come through every wall.
  const bool started = step_start_.size() == static_cast<std::size_t>(points_.size());
  for_each_point(
      owned(),
      [&](Index i) {
        if (!is_fluid(points_, i)) return;
        if (!all_points && wall_distance_[i] >= clearance) return;
        const auto c = kernels::wall_clearance<D>(walls_, points_.position[i], points_.velocity[i],
                                                  started ? &step_start_[i] : nullptr, clearance);
        points_.position[i] = c.position;
        points_.velocity[i] = c.velocity;
        if (c.outside) outside_[i] = 1;
        wall_distance_[i] = c.nearest;
      },
      LoopBalance::balanced);
}

template <int D>
void FlowSolver<D>::regularise_positions(double dt) {
  const auto& o = options_;
  if ((o.pbd_iterations == 0 && o.shifting == 0.0) || neighbours_.points() != points_.size())
    return;
  // The neighbour lists of the last step (radius h at the old positions) hold every pair that
  // can now be closer than d0: points moved at most C_u·dx since, and PBD moves them at most
  // n_pbd · clamp.
  const Index n = points_.size();
  // The shift per iteration is bounded by pbd_clamp·dx for a step of the typical length τ (the
  // acceleration limit under gravity) and proportionally less for shorter steps, so that points
  // are regularised at a rate in time [CHOICE]: with a fixed bound, the steps cut short before
  // an output time moved points by 0.4 dx in a sliver of time, the PPE turned the divergence of
  // that shift into (ρ/Δt)-sized pressures, and the K&O dam break at L/40 blew up at the wall
  // impact (T = 3.14; 200 m/s).
  const double d0 = o.pbd_distance * o.dx;
  const kernels::PbdParameters pbd{
      .distance = d0,
      .wall_distance = 0.5 * d0,
      .relaxation = o.pbd_relaxation,
      .clamp = o.pbd_clamp * o.dx * std::min(1.0, dt / typical_step())};
  std::vector<Vec<D>> shift(static_cast<std::size_t>(n), Vec<D>::Zero());
  std::vector<Vec<D>> total(static_cast<std::size_t>(n), Vec<D>::Zero());
  struct Moved {
    bool any = false;
    void merge(const Moved& other) { any = any || other.any; }
  };
  const auto cloud = this->cloud();
  for (int it = 0; it < o.pbd_iterations; ++it) {
    const auto moved = reduce_points(owned(), Moved{}, [&](Index i, Moved& m) {
      const auto displacement = kernels::pbd_displacement(cloud, i, pbd);
      shift[i] = displacement.value_or(Vec<D>::Zero());
      m.any = m.any || displacement.has_value();
    });
    if (largest(moved.any ? 1.0 : 0.0) == 0.0) break;  // on every process alike
    move_points(shift, total);
  }
  if (o.shifting > 0.0) shift_down_concentration_gradient(dt, total);
  // The velocity is carried to the shifted position (first-order Taylor, Lind et al. 2012).
  transport_velocity(total);
}

template <int D>
void FlowSolver<D>::transport_velocity(std::span<const Vec<D>> shift) {
  for_each_point(owned(), [&](Index i) {
    if (is_fluid(points_, i)) points_.velocity[i] += grad_u_[i] * shift[i];
  });
}

template <int D>
void FlowSolver<D>::shift_down_concentration_gradient(double dt, std::vector<Vec<D>>& total) {
  // Fickian shifting [CHOICE, Lind et al. 2012; D = A h_SPH |u| Δt of Skillen et al. 2013 with
  // h_SPH = dx]: PBD only pushes points apart, so nothing refills a region the flow empties —
  // a stagnation corner under an impact drained to a void whose collapse gave pressure spikes
  // of 5–10 ρgH (Lobovsky at H/80). Points within h of the free surface are not shifted: their
  // concentration deficit is the missing air, not a void. Moving them along the surface only
  // (Lind et al.) still let the layers below push the surface out (K&O at L/20: the interior
  // number density fell 5 %; with them left alone 2.4 %; ldd/volume.hpp says why that monitor
  // was replaced). Measured at Lobovsky H/40, sensor 1
  // after the impact: RMS deviation from its 5 ms running mean 0.47 → 0.17 ρgH, 13 → 0 of 159
  // samples below 0.2 ρgH.
  const auto& o = options_;
  const kernels::ShiftParameters shifting{.coefficient = o.shifting,
                                          .dx = o.dx,
                                          .dt = dt,
                                          .max_shift = o.pbd_clamp * o.dx,
                                          .h = support(),
                                          .n0 = n0_};
  std::vector<Vec<D>> shift(static_cast<std::size_t>(points_.size()), Vec<D>::Zero());
  const auto cloud = this->cloud();
  for_each_point(owned(), [&](Index i) { shift[i] = kernels::fickian_shift(cloud, i, shifting); });
  move_points(shift, total);
}

template <int D>
void FlowSolver<D>::move_points(std::span<const Vec<D>> shift, std::vector<Vec<D>>& total) {
  // Fluid points move by `shift` (added to `total`), then keep clear of the walls.
  for_each_point(owned(), [&](Index i) {
    if (!is_fluid(points_, i)) return;
    points_.position[i] += shift[i];
    total[i] += shift[i];
    wall_distance_[i] -= shift[i].norm();
  });
  keep_clear_of_walls(false);
  refresh_ghosts(points_.position);
}

template <int D>
void FlowSolver<D>::rebuild_neighbours() {
  neighbours_ = find_wet_neighbours<D>(points_, support());
  cut_pairs_through_thin_walls<D>(neighbours_, points_, walls_);
  // From the wall nodes' own search, dry ones included: the last wet node below a free surface
  // stands for its own share of the wall, not for the dry part above it too.
  update_node_weights();
  if (!exchange_) {
    deactivate_dry_wall_nodes<D>(points_, neighbours_);
    deactivate_wall_nodes_beyond_fluid<D>(points_, neighbours_, options_.free_surface);
    return;
  }
  // Each owner decides for its nodes; the ghosts' lists end at the halo's edge. The pairs of
  // the nodes made inactive go once their ghosts' types have arrived (one pass each).
  if (!node_weight_.empty()) refresh_ghosts(node_weight_);
  deactivate_dry_wall_nodes<D>(points_, neighbours_, owned_, InactivePairs::kept);
  refresh_ghost_types();
  remove_pairs_with_inactive<D>(points_, neighbours_);
  deactivate_wall_nodes_beyond_fluid<D>(points_, neighbours_, options_.free_surface, owned_,
                                        InactivePairs::kept);
  refresh_ghost_types();
  remove_pairs_with_inactive<D>(points_, neighbours_);
}

template <int D>
void FlowSolver<D>::update_node_weights() {
  if (options_.wall_node_weights)
    node_weight_ = wall_node_weights<D>(points_, neighbours_.radius, options_.dx);
  else
    node_weight_.clear();  // every point weight 1
}

template <int D>
void FlowSolver<D>::classify_points() {
  ops_ = compute_operators<D>(points_.position, neighbours_, options_.operators, node_weight_);
  const auto surface = detect_free_surface<D>(points_, neighbours_, ops_, options_.free_surface,
                                              exchange_ ? owned_ : -1);
  mark_sparse_points_as_surface(surface.fluid_density);
  refresh_ghost_types();
}

template <int D>
void FlowSolver<D>::mark_sparse_points_as_surface(std::span<const double> fluid_density) {
  // A fluid point whose number density is far below the lattice's is in spray or a film a few
  // points thick, even where the cone test finds neighbours all around (the middle of a droplet,
  // a film along a wall, a jet going round the open end of a wall): its Laplacian row rests on
  // a handful of points and can make the PPE nearly singular. Measured: the K&O dam break at
  // L/80 blew up at T = 2.1 from interior rows with 6–11 neighbours (p → 10⁸ Pa); at L/40 the
  // run-up jet passing the top end of the right wall gave an interior row with 2 fluid and 4
  // wall neighbours (total density 1.27 n0) and 5·10⁸ m/s one step later. Such points are
  // Dirichlet [CHOICE]: total density (fluid and wall) below sparse_density·n0, or fluid-only
  // density below half of that (a half space next to a flat wall has ≈ 0.55 n0 of fluid).
  const double total_limit = options_.sparse_density * n0_;
  const double fluid_limit = 0.5 * total_limit;
  HM_ASSERT(fluid_density.size() >= static_cast<std::size_t>(owned()),
            "flow: {} fluid densities for {} points", fluid_density.size(), owned());
  for_each_point(owned(), [&](Index i) {
    if (!is_fluid(points_, i) || points_.type[i] != PointType::interior) return;
    if (kernels::is_sparse(ops_.number_density[i], fluid_density[i], total_limit, fluid_limit))
      points_.type[i] = PointType::surface;
  });
}

// ---------------------------------------------------------------------------------------------
// Predictor, projection, corrector

template <int D>
std::vector<Vec<D>> FlowSolver<D>::predict(double dt, std::vector<Vec<D>>& viscous) {
  const auto& o = options_;
  const Index n = points_.size();
  // Wall nodes carry the wall velocity (no-slip in the viscous term).
  const std::span<const Vec<D>> u(points_.velocity);
  const auto cloud = this->cloud();
  viscous.assign(static_cast<std::size_t>(n), Vec<D>::Zero());
  if (o.viscosity > 0.0)
    for_each_point(owned(), [&](Index i) {
      viscous[i] = kernels::viscous_acceleration(cloud, i, u, o.viscosity);
    });
  std::vector<Vec<D>> predicted(static_cast<std::size_t>(n));
  for_each_point(owned(), [&](Index i) {
    predicted[i] = kernels::predicted_velocity(cloud, i, dt, o.gravity, viscous[i]);
  });
  if (o.viscous == ViscousScheme::implicit_euler && o.viscosity > 0.0)
    solve_implicit_viscosity(dt, predicted, viscous);
  refresh_ghosts(predicted);  // the PPE's divergence of u* reads them
  return predicted;
}

template <int D>
void FlowSolver<D>::solve_implicit_viscosity(double dt, std::vector<Vec<D>>& predicted,
                                             const std::vector<Vec<D>>& viscous) {
  // (I − Δtν L) u* = u + Δt g on fluid rows with operators; wall nodes are Dirichlet u = U,
  // other points keep their explicit prediction.
  const auto& o = options_;
  const Index n = points_.size();
  std::vector<Index> unknown(static_cast<std::size_t>(n), -1);
  std::vector<Index> point_of;
  for (Index i = 0; i < n; ++i)
    if (is_fluid(points_, i) && points_.type[i] != PointType::isolated && !ops_.isolated(i)) {
      unknown[i] = static_cast<Index>(point_of.size());
      point_of.push_back(i);
    }
  const auto m = static_cast<Index>(point_of.size());
  if (m == 0) return;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs(m, D);
  const double s = dt * o.viscosity;
  for (Index r = 0; r < m; ++r) {
    const Index i = point_of[r];
    double diagonal = 1.0;
    Vec<D> b = points_.velocity[i] + dt * o.gravity;
    for (auto k = neighbours_.offsets[i]; k < neighbours_.offsets[i + 1]; ++k) {
      const Index j = neighbours_.indices[k];
      const double c = s * ops_.laplacian[k];
      diagonal += c;
      if (unknown[j] >= 0)
        entries.emplace_back(r, unknown[j], -c);
      else
        b += c * (is_fluid(points_, j) ? predicted[j] : points_.wall_velocity[j]);
    }
    entries.emplace_back(r, r, diagonal);
    rhs.row(r) = b.transpose();
  }
  linsolve::CsrMatrix a(m, m);
  a.setFromTriplets(entries.begin(), entries.end());
  a.makeCompressed();
  for (int c = 0; c < D; ++c) {
    Eigen::VectorXd x(m);
    for (Index r = 0; r < m; ++r) x[r] = predicted[point_of[r]][c];
    const auto report = viscous_solver_.solve(a, rhs.col(c), x);  // one setup, D solves
    if (!report.converged)
      numerical_error("flow: the implicit viscous solve did not converge (component {}: {})", c,
                      report.failure);
    for (Index r = 0; r < m; ++r) predicted[point_of[r]][c] = x[r];
  }
  (void)viscous;
}

template <int D>
void FlowSolver<D>::project(double dt, std::span<const Vec<D>> predicted,
                            std::span<const Vec<D>> viscous, TensionRelease release,
                            StepMonitor& m) {
  const auto& o = options_;
  auto t = Clock::now();
  PpeOptions<D> po;
  po.density = o.density;
  po.gravity = o.gravity;
  po.dt = dt;
  po.dx = o.dx;
  po.volume_relaxation = o.volume_relaxation;
  po.reference_density = n0_;
  po.volume_time_scale =
      o.acceleration_number * std::sqrt(o.dx / std::max(o.gravity.norm(), 1e-12));
  auto data = ppe_data<D>(points_, neighbours_, ops_, predicted, viscous, po);
  if (o.surface_offset) set_surface_pressure(data.dirichlet);
  if (exchange_) {
    lap(t, m.seconds.ppe_assembly);
    project_distributed(data, release, m);
    return;
  }
  const bool may_release = release == TensionRelease::fresh;
  const int passes = may_release && o.release_wall_tension ? 2 : 1;
  auto system = assemble_poisson<D>(points_, neighbours_, ops_, data, o.dx);
  std::vector<Index> released;  // wall nodes made p = 0 by the last pass
  // Released nodes (types already SURFACE) get rows x = 0 on the assembled matrix, whose
  // preconditioner then serves; a pinned system is assembled again with them Dirichlet.
  const auto hold_at_zero = [&] {
    if (fix_at_zero(system, released)) return;
    system = assemble_poisson<D>(points_, neighbours_, ops_, data, o.dx);
    released.clear();  // Dirichlet in the new system, not fixed unknowns
  };
  if (!may_release && !released_.empty()) {  // the step's released nodes, as its re-solves had
    released = released_;
    for (const Index i : released) points_.type[i] = PointType::surface;
    hold_at_zero();
  }
  lap(t, m.seconds.ppe_assembly);
  for (int pass = 0; pass < passes; ++pass) {
    std::vector<double> warm_start;
    if (ppe_observer_) warm_start = points_.pressure;
    // The re-solve changes only the released nodes' rows (fix_at_zero): it keeps the first
    // pass's preconditioner, whose setup is most of an AMG solve's cost.
    // Their guess is their value (the system's residual then starts where a re-assembled
    // one's would), and so is their answer, exactly rather than to the tolerance.
    for (const Index i : released) points_.pressure[i] = 0.0;
    const bool rows_fixed = !released.empty();
    const auto report = ppe_solver_.solve(system, points_.pressure, rows_fixed);
    for (const Index i : released) points_.pressure[i] = 0.0;
    lap(t, m.seconds.ppe_solve);
    if (ppe_observer_) ppe_observer_(system, warm_start, report);
    m.ppe_iterations += report.iterations + report.discarded_iterations;
    m.ppe_residual = report.residual;
    m.ppe_converged = report.converged;
    m.ppe_failure = report.failure;
    m.ppe_passes = pass + 1;
    if (!report.converged) return;
    if (!may_release) break;
    // No tension at walls (§0.2 item 6): nodes pulling on the fluid become Dirichlet p = 0.
    released.clear();
    for (Index i = 0; i < points_.size(); ++i)
      if (points_.type[i] == PointType::wall && points_.pressure[i] < 0.0 && releases_tension(i)) {
        points_.type[i] = PointType::surface;
        released.push_back(i);
      }
    if (released.empty() || pass + 1 == passes) break;
    released_.insert(released_.end(), released.begin(), released.end());  // fixed in the re-solve
    hold_at_zero();
    lap(t, m.seconds.ppe_assembly);
  }
  for (Index i = 0; i < points_.size(); ++i)
    if (!is_fluid(points_, i) && releases_tension(i))
      points_.pressure[i] = std::max(points_.pressure[i], 0.0);
}

template <int D>
typename FlowSolver<D>::DistributedPoisson FlowSolver<D>::assemble_distributed(PoissonData& data) {
  refresh_ghosts(data.dirichlet);  // a row's Dirichlet neighbours may be ghosts
  demote_weak_neumann_rows<D>(points_, neighbours_, ops_, options_.dx, owned_, &data.wall_rows);
  refresh_ghost_types();
  // Global unknown numbers: this process's unknowns in point order, after the lower ranks'.
  std::int64_t mine = 0;
  for (Index i = 0; i < owned_; ++i) mine += is_unknown(points_, i);
  const std::int64_t first = exchange_->sum_before(mine), unknowns = total(mine);
  std::vector<double> number(static_cast<std::size_t>(points_.size()), -1.0);
  for (Index i = 0, next = 0; i < owned_; ++i)
    if (is_unknown(points_, i)) number[i] = static_cast<double>(first + next++);
  refresh_ghosts(number);
  DistributedPoisson system;
  system.global.assign(number.begin(), number.end());
  system.rows =
      assemble_poisson_rows<D>(points_, neighbours_, ops_, data, owned_, system.global, unknowns);
  return system;
}

template <int D>
bool FlowSolver<D>::set_up_distributed(const linsolve::CsrMatrix& matrix) {
  // The matrix last set up again (the strong coupling's sub-iterations and added-mass solves of
  // a step): its preconditioner serves, as in one piece (linsolve::SystemSolver). Every process
  // takes the same branch.
  const bool same_here = distributed_matrix_ && linsolve::same_matrix(matrix, *distributed_matrix_);
  if (total(same_here ? 0 : 1) == 0 && distributed_ppe_->reuse_for(matrix)) return true;
  distributed_matrix_.reset();
  if (!distributed_ppe_->setup(matrix)) return false;
  distributed_matrix_ = std::make_unique<linsolve::CsrMatrix>(matrix);
  return true;
}

template <int D>
void FlowSolver<D>::project_distributed(PoissonData& data, TensionRelease release, StepMonitor& m) {
  // Each process assembles the rows of its unknowns of the one system (ldd/ppe.hpp), with
  // global column numbers, and the solver runs over the processes. As in one piece, wall nodes
  // in tension are released and the system solved again on the same preconditioner, their rows
  // made x = 0 (fix_at_zero).
  auto t = Clock::now();
  auto [rows, global] = assemble_distributed(data);
  const auto count = static_cast<Index>(rows.point_of.size());
  std::vector<Index> row_of(static_cast<std::size_t>(owned_), -1);
  for (Index r = 0; r < count; ++r) row_of[rows.point_of[r]] = r;
  const auto fix_rows = [&](std::span<const Index> nodes) {
    for (const Index i : nodes) {  // the row becomes x = 0; its column stays
      const Index r = row_of[i];
      HM_ASSERT(r >= 0, "flow: released wall node {} is not an unknown", i);
      for (linsolve::CsrMatrix::InnerIterator e(rows.matrix, r); e; ++e)
        e.valueRef() = e.col() == global[static_cast<std::size_t>(i)] ? 1.0 : 0.0;
      rows.rhs[r] = 0.0;
    }
  };
  const bool may_release = release == TensionRelease::fresh;
  std::vector<Index> released;
  // Every process takes the same branch: whether any process has rows fixed.
  bool rows_fixed = false;
  if (!may_release) {
    released = released_;  // the step's released nodes: their rows x = 0, the step's matrix
    for (const Index i : released) {
      points_.type[i] = PointType::surface;
      points_.pressure[i] = 0.0;
    }
    fix_rows(released);
    rows_fixed = total(static_cast<std::int64_t>(released.size())) > 0;
  }
  lap(t, m.seconds.ppe_assembly);

  const int passes = may_release && options_.release_wall_tension ? 2 : 1;
  for (int pass = 0; pass < passes; ++pass) {
    Eigen::VectorXd x(count);
    for (Index r = 0; r < count; ++r) x[r] = points_.pressure[rows.point_of[r]];
    // reuse_for and setup agree over the processes: every process takes the same branch.
    bool ready = (pass > 0 || rows_fixed) && distributed_ppe_->reuse_for(rows.matrix);
    if (!ready) ready = set_up_distributed(rows.matrix);
    const auto stats = ready ? distributed_ppe_->solve(rows.rhs, x) : linsolve::SolveStats{};
    lap(t, m.seconds.ppe_solve);
    m.ppe_iterations += stats.iterations;
    m.ppe_residual = stats.residual;
    m.ppe_converged = ready && stats.converged;
    m.ppe_failure = ready ? stats.failure : distributed_ppe_->setup_failure();
    m.ppe_passes = pass + 1;
    for (Index i = 0; i < owned_; ++i)
      if (!is_unknown(points_, i))
        points_.pressure[i] =
            points_.type[i] == PointType::surface || points_.type[i] == PointType::isolated
                ? data.dirichlet[i]
                : 0.0;  // inactive
    if (m.ppe_converged || x.allFinite())
      for (Index r = 0; r < count; ++r) points_.pressure[rows.point_of[r]] = x[r];
    for (const Index i : released) points_.pressure[i] = 0.0;
    if (!m.ppe_converged || !may_release) break;
    // No tension at walls (§0.2 item 6).
    released.clear();
    for (Index i = 0; i < owned_; ++i)
      if (points_.type[i] == PointType::wall && points_.pressure[i] < 0.0 && releases_tension(i)) {
        points_.type[i] = PointType::surface;
        points_.pressure[i] = 0.0;
        released.push_back(i);
      }
    if (total(static_cast<std::int64_t>(released.size())) == 0 || pass + 1 == passes) break;
    released_.insert(released_.end(), released.begin(), released.end());  // fixed in the re-solve
    fix_rows(released);
    lap(t, m.seconds.ppe_assembly);
  }
  refresh_ghosts(points_.pressure);
  refresh_ghost_types();  // nodes released
  for (Index i = 0; i < points_.size(); ++i)
    if (!is_fluid(points_, i) && releases_tension(i))
      points_.pressure[i] = std::max(points_.pressure[i], 0.0);
}

template <int D>
bool FlowSolver<D>::releases_tension(Index i) const {
  return walls_[static_cast<std::size_t>(points_.host[i].body)].releases_tension();
}

template <int D>
void FlowSolver<D>::set_surface_pressure(std::vector<double>& dirichlet) const {
  const auto& o = options_;
  const double h = support();
  const auto cloud = this->cloud();
  for_each_point(owned(), [&](Index i) {
    if (!is_fluid(points_, i) || points_.type[i] != PointType::surface) return;
    if (const auto p = kernels::surface_pressure(cloud, i, h, o.dx, o.density, o.gravity))
      dirichlet[i] = *p;
  });
}

template <int D>
void FlowSolver<D>::correct(double dt, std::span<const Vec<D>> predicted) {
  const auto grad_p = gradient<D>(points_.position, neighbours_, ops_, points_.pressure);
  const double scale = dt / options_.density;
  const auto cloud = this->cloud();
  for_each_point(owned(), [&](Index i) {
    points_.velocity[i] = kernels::corrected_velocity(cloud, i, predicted[i], grad_p[i], scale);
  });
  refresh_ghosts(points_.velocity);
}

template <int D>
void FlowSolver<D>::smooth_velocity(double dt, double stable_step) {
  // ε per stable step [CHOICE]: ε·min(1, Δt/Δt_stable), Δt_stable the step the state allows
  // (§1.11). A step cut short for an output time smooths proportionally less, so the output
  // times do not change the flow: with ε per step, probes every 1 ms (345 steps instead of 215)
  // slowed the K&O front at L/20 by 3 %. A rate against the gravity time scale τ instead of
  // Δt_stable diverged at the wall impact, while the surge tip still ran away (before
  // slip_velocity_gradient); the stable step keeps the smoothing per CFL step as it was.
  const double eps = options_.smoothing * std::min(1.0, dt / stable_step);
  if (eps <= 0.0) return;
  std::vector<Vec<D>> smoothed(points_.velocity);
  const double h = support();
  const auto cloud = this->cloud();
  for_each_point(owned(), [&](Index i) {
    if (const auto change = kernels::smoothing_change(cloud, i, eps, h)) smoothed[i] += *change;
  });
  points_.velocity.swap(smoothed);
  refresh_ghosts(points_.velocity);  // the monitors' ∇u reads them
}

// ---------------------------------------------------------------------------------------------
// Monitors and divergence

template <int D>
double FlowSolver<D>::volume_drift() const {
  const auto [volume, fluid_points] = measured_volume();
  const double expected =
      initial_volume_ * static_cast<double>(fluid_points) / static_cast<double>(initial_fluid_);
  return expected > 0.0 ? volume / expected - 1.0 : 0.0;
}

template <int D>
std::pair<double, std::int64_t> FlowSolver<D>::measured_volume() const {
  std::vector<Vec<D>> fluid;
  fluid.reserve(static_cast<std::size_t>(points_.size()));
  for (Index i = 0; i < points_.size(); ++i)
    if (is_fluid(points_, i)) fluid.push_back(points_.position[i]);
  double volume = 0.0;
  auto fluid_points = static_cast<std::int64_t>(fluid.size());
  if (!exchange_) {
    volume = fluid_volume<D>(fluid, options_.dx, support());
  } else {
    // Each process counts the grid nodes of its region, from its fluid points and ghosts, on
    // one grid through the lowest fluid coordinates of all (less h).
    Vec<D> lowest = Vec<D>::Constant(std::numeric_limits<double>::max());
    for (const auto& x : fluid) lowest = lowest.cwiseMin(x);
    Vec<D> negated = -lowest;
    exchange_->max({negated.data(), D});
    const Vec<D> origin = -negated - Vec<D>::Constant(support());
    const auto in_region = [this](const Vec<D>& x) { return exchange_->owns(x); };
    volume = fluid_volume_share<D>(fluid, options_.dx, support(), origin, in_region);
    exchange_->sum({&volume, 1});
    fluid_points = 0;
    for (Index i = 0; i < owned_; ++i) fluid_points += is_fluid(points_, i);
    fluid_points = total(fluid_points);
  }
  return {volume, fluid_points};
}

template <int D>
void FlowSolver<D>::update_monitors(double dt, std::span<const Vec<D>> old_velocity,
                                    StepMonitor& m) {
  const auto grad = slip_velocity_gradient<D>(points_, neighbours_, ops_, points_.velocity);
  struct Totals {
    double max_divergence = 0.0, max_speed = 0.0;  // [1/s], [m/s]
    Index fluid = 0, surface = 0, isolated = 0, active_wall_nodes = 0;
    void merge(const Totals& o) {
      max_divergence = std::max(max_divergence, o.max_divergence);
      max_speed = std::max(max_speed, o.max_speed);
      fluid += o.fluid;
      surface += o.surface;
      isolated += o.isolated;
      active_wall_nodes += o.active_wall_nodes;
    }
  };
  auto totals = reduce_points(owned(), Totals{}, [&](Index i, Totals& t) {
    const auto type = points_.type[i];
    if (!is_fluid(points_, i)) {
      if (type != PointType::inactive) ++t.active_wall_nodes;
      grad_u_[i].setZero();
      return;
    }
    ++t.fluid;
    t.surface += type == PointType::surface;
    t.isolated += type == PointType::isolated;
    acceleration_[i] = (points_.velocity[i] - old_velocity[i]).norm() / dt;
    t.max_speed = std::max(t.max_speed, points_.velocity[i].norm());
    grad_u_[i] = grad[i];
    if (type == PointType::interior)
      t.max_divergence = std::max(t.max_divergence, std::abs(grad[i].trace()));
  });
  if (exchange_) {
    std::array<double, 2> largest{totals.max_divergence, totals.max_speed};
    std::array<std::int64_t, 4> counts{totals.fluid, totals.surface, totals.isolated,
                                       totals.active_wall_nodes};
    exchange_->max(largest);
    exchange_->sum(counts);
    totals = {largest[0],
              largest[1],
              static_cast<Index>(counts[0]),
              static_cast<Index>(counts[1]),
              static_cast<Index>(counts[2]),
              static_cast<Index>(counts[3])};
  }
  m.max_divergence = totals.max_divergence;
  m.max_speed = totals.max_speed;
  m.fluid = totals.fluid;
  m.surface = totals.surface;
  m.isolated = totals.isolated;
  m.wall_active = totals.active_wall_nodes;
  m.escaped = escaped_;
  // The volume costs about a neighbour search (a grid of dx/2 over the fluid): every
  // volume_interval steps, the last value in between.
  if (step_ % volume_interval == 1 || volume_interval == 1 || last_volume_drift_ == 0.0)
    last_volume_drift_ = volume_drift();
  m.volume_drift = last_volume_drift_;
  last_max_speed_ = totals.max_speed;
}

template <int D>
void FlowSolver<D>::remove_escaped_points() {
  // A fluid point outside the walls' present bounding box, widened by dx/2 (upwards without
  // limit: a splash falls back), has left the domain through an opening or a leak; so has one
  // found behind a wall it did not cross (keep_clear_of_walls): a jet over an open wall end.
  const double margin = 0.5 * options_.dx;
  const auto [box_lower, box_upper] = wall_box();
  std::vector<Index> kept;
  kept.reserve(static_cast<std::size_t>(points_.size()));
  for (Index i = 0; i < points_.size(); ++i) {
    if (i >= owned()) {  // a ghost: its owner decides
      kept.push_back(i);
      continue;
    }
    bool inside = outside_.empty() || !outside_[i];
    if (inside && is_fluid(points_, i)) {
      const auto& x = points_.position[i];
      for (int a = 0; a < D; ++a) {
        if (x[a] < box_lower[a] - margin) inside = false;
        if (a != D - 1 && x[a] > box_upper[a] + margin) inside = false;
      }
      if (!x.allFinite()) inside = true;  // reported as divergence instead
    }
    if (inside) kept.push_back(i);
  }
  const auto removed = points_.size() - static_cast<Index>(kept.size());
  escaped_ += static_cast<Index>(total(removed));
  if (removed == 0) return;
  owned_ -= removed;
  points_.retain(kept);
  permute(id_, kept);
  permute(grad_u_, kept);
  permute(acceleration_, kept);
  permute(wall_distance_, kept);
  if (!pending_old_velocity_.empty()) permute(pending_old_velocity_, kept);
  outside_.assign(kept.size(), 0);
  step_start_.clear();
  neighbours_ = Neighbours{};  // stale indices
}

template <int D>
void FlowSolver<D>::check_divergence(const StepMonitor& m) const {
  DivergenceReport r;
  r.step = m.step;
  r.time = m.time;
  // Worst points by a per-point value (largest first).
  auto worst = [&](auto value, const char* what) {
    std::vector<std::pair<double, Index>> v;
    for (Index i = 0; i < owned(); ++i) {
      const double x = value(i);
      if (std::isnan(x) || x > 0.0) v.emplace_back(std::isnan(x) ? 1e300 : x, i);
    }
    const std::size_t k = std::min<std::size_t>(5, v.size());
    std::partial_sort(v.begin(), v.begin() + static_cast<long>(k), v.end(),
                      [](const auto& a, const auto& b) { return a.first > b.first; });
    for (std::size_t q = 0; q < k; ++q)
      r.worst_points.push_back(describe_point<D>(points_, v[q].second, v[q].first, what));
  };
  auto not_finite = [&](Index i) {
    return points_.position[i].allFinite() && points_.velocity[i].allFinite() &&
                   std::isfinite(points_.pressure[i])
               ? 0.0
               : 1.0;
  };
  double any_not_finite = 0.0;
  for (Index i = 0; i < owned() && any_not_finite == 0.0; ++i) any_not_finite = not_finite(i);
  if (largest(any_not_finite) > 0.0) {  // every process throws
    r.criterion = "non-finite position, velocity or pressure";
    worst(not_finite, "non-finite");
    throw FlowDiverged(r);
  }
  if (!m.ppe_converged) {
    r.criterion = fmt::format(
        "the pressure Poisson equation did not converge ({} iterations, residual {:.3g}, "
        "tolerance {:.3g}; {})",
        m.ppe_iterations, m.ppe_residual, options_.ppe.tolerance, m.ppe_failure);
    worst([&](Index i) { return std::abs(points_.pressure[i]); }, "|p| [Pa]");
    throw FlowDiverged(r);
  }
  if (m.max_speed > speed_limit_) {
    r.criterion =
        fmt::format("fluid speed {:.4g} m/s above the limit {:.4g} m/s", m.max_speed, speed_limit_);
    worst([&](Index i) { return is_fluid(points_, i) ? points_.velocity[i].norm() : 0.0; },
          "|u| [m/s]");
    throw FlowDiverged(r);
  }
}

// ---------------------------------------------------------------------------------------------
// Over processes

template <int D>
TravellingPoints<D> FlowSolver<D>::travelling_owned_points() const {
  const Index n = owned();
  const bool in_step = pending_old_velocity_.size() == static_cast<std::size_t>(points_.size());
  TravellingPoints<D> block{.width = travelling_width<D>};
  block.position.assign(points_.position.begin(), points_.position.begin() + n);
  block.id.assign(id_.begin(), id_.begin() + n);
  block.fields.resize(static_cast<std::size_t>(n) * travelling_width<D>);
  block.weight.resize(static_cast<std::size_t>(n));
  const bool with_lists = neighbours_.points() == points_.size();
  const double reach = options_.support_factor;  // the lattice's neighbours within h = reach·dx
  const double lattice = D == 2 ? std::numbers::pi * reach * reach
                                : 4.0 / 3.0 * std::numbers::pi * reach * reach * reach;
  for_each_point(n, [&](Index i) {
    double* f = block.fields.data() + std::size_t(i) * travelling_width<D>;
    block.weight[i] = with_lists ? 1.0f + static_cast<float>(neighbours_.of(i).size())
                                 : work_weight(points_.kind[i], points_.type[i], lattice);
    const auto& host = points_.host[i];
    put(f, points_.velocity[i]);
    *f++ = points_.pressure[i];
    *f++ = static_cast<double>(points_.kind[i]);
    *f++ = static_cast<double>(points_.type[i]);
    put(f, points_.wall_normal[i]);
    put(f, points_.wall_velocity[i]);
    put(f, points_.wall_acceleration[i]);
    *f++ = host.body;
    *f++ = static_cast<double>(host.element);
    put(f, host.barycentric);
    put(f, grad_u_[i]);
    *f++ = acceleration_[i];
    *f++ = wall_distance_[i];
    put(f, in_step ? pending_old_velocity_[i] : points_.velocity[i]);
  });
  return block;
}

template <int D>
void FlowSolver<D>::gather_on_first(FlowState<D>& s) const {
  std::vector<Vec<D>> old_velocity;
  unpack<D>(exchange_->gather(travelling_owned_points()),
            {s.points, s.velocity_gradient, s.acceleration, s.wall_distance, old_velocity, s.id});
}

template <int D>
PointSet<D> FlowSolver<D>::output_points() const {
  if (!exchange_) return points_;
  FlowState<D> s;
  gather_on_first(s);
  return std::move(s.points);
}

template <int D>
void FlowSolver<D>::append(const TravellingPoints<D>& block) {
  unpack<D>(block, {points_, grad_u_, acceleration_, wall_distance_, pending_old_velocity_, id_});
}

template <int D>
void FlowSolver<D>::keep_every_processes_share() {
  // Every process holds all the points; each keeps every count-th, which the first migration
  // sends on to the regions it draws.
  std::vector<Index> share;
  for (Index i = exchange_->rank(); i < points_.size(); i += exchange_->processes())
    share.push_back(i);
  points_.retain(share);
  permute(grad_u_, share);
  permute(acceleration_, share);
  permute(wall_distance_, share);
  permute(id_, share);
  owned_ = points_.size();
}

template <int D>
void FlowSolver<D>::redistribute(bool sort) {
  auto mine = travelling_owned_points();
  last_migration_ = exchange_->migrate(mine);
  if (sort) mine = reordered(mine, spatial_order<D>(mine.position, support()));
  const auto ghosts = exchange_->gather_ghosts(mine, support());
  const bool in_step = pending_old_velocity_.size() == static_cast<std::size_t>(points_.size());
  points_ = PointSet<D>{};
  grad_u_.clear();
  acceleration_.clear();
  wall_distance_.clear();
  pending_old_velocity_.clear();
  id_.clear();
  append(mine);
  owned_ = points_.size();
  append(ghosts);
  if (!in_step) pending_old_velocity_.clear();
  outside_.clear();  // within a step, before the migration
  step_start_.clear();
  neighbours_ = Neighbours{};  // stale indices
}

template <int D>
void FlowSolver<D>::refresh_ghosts(std::vector<double>& field) const {
  if (!exchange_) return;
  const auto ghost = exchange_->refresh({field.data(), static_cast<std::size_t>(owned_)}, 1);
  std::copy(ghost.begin(), ghost.end(), field.begin() + owned_);
}

template <int D>
void FlowSolver<D>::refresh_ghosts(std::vector<Vec<D>>& field) const {
  if (!exchange_) return;
  static_assert(sizeof(Vec<D>) == D * sizeof(double), "a Vec<D> is D doubles");
  auto* values = reinterpret_cast<double*>(field.data());
  const auto ghost = exchange_->refresh({values, static_cast<std::size_t>(owned_) * D}, D);
  std::copy(ghost.begin(), ghost.end(), values + static_cast<std::size_t>(owned_) * D);
}

template <int D>
void FlowSolver<D>::refresh_ghost_types() {
  if (!exchange_) return;
  std::vector<double> type(static_cast<std::size_t>(points_.size()));
  for (Index i = 0; i < owned_; ++i) type[i] = static_cast<double>(points_.type[i]);
  refresh_ghosts(type);
  for (Index i = owned_; i < points_.size(); ++i) points_.type[i] = static_cast<PointType>(type[i]);
}

template <int D>
double FlowSolver<D>::largest(double value) const {
  if (exchange_) exchange_->max({&value, 1});
  return value;
}

template <int D>
std::int64_t FlowSolver<D>::total(std::int64_t value) const {
  if (exchange_) exchange_->sum(std::span<std::int64_t>(&value, 1));
  return value;
}

template class FlowSolver<2>;
template class FlowSolver<3>;
template struct FlowState<2>;
template struct FlowState<3>;

}  // namespace hm::ldd
