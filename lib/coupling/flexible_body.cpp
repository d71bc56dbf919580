#include "coupling/flexible_body.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include <Eigen/Dense>

#include "core/errors.hpp"
#include "core/log.hpp"
#include "coupling/linear_modal_model.hpp"
#include "ldd/probes.hpp"

namespace hm::coupling {

namespace {

/// Sub-iterations of a step that release the wall nodes in tension afresh; later ones keep the
/// set (ldd::TensionRelease::kept). Released afresh throughout, 3-6 % of the elastic plate's
/// steps and 12 % of the gate's ended at the 20-solve limit above the tolerance. Kept from the
/// third solve on, a reduced-model plate in water (NonlinearModalBody.ModerateDeflection...)
/// peaked 2.1 % lower than afresh and took 4.48 solves a step against 3.41: the set was taken
/// too early. From the fifth on: the same peak as afresh, 3.16 solves, and no step at the limit.
constexpr int kFreshReleaseIterations = 4;

/// The carrier's rigid state at t (at rest, unrotated, without one).
motion::RigidState carrier_state(const std::optional<motion::RigidMotion>& carrier, double t) {
  return carrier ? carrier->state(t) : motion::RigidState{};
}

bool rotates(const motion::RigidState& s) {
  return !s.rotation.isIdentity(0.0) || s.omega.squaredNorm() > 0.0 || s.alpha.squaredNorm() > 0.0;
}

template <int D>
Eigen::Vector3d widen(const ldd::Vec<D>& v) {
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  w.head<D>() = v;
  return w;
}

}  // namespace

const char* to_string(CouplingScheme scheme) {
  return scheme == CouplingScheme::strong ? "strong" : "explicit";
}

template <int D>
FlexibleBody<D>::FlexibleBody(std::string name, ModalSurface<D> modes, int wall,
                              const CouplingOptions& options, const ldd::WallMesh<D>& wall_mesh)
    : name_(std::move(name)),
      modes_(std::make_shared<const ModalSurface<D>>(std::move(modes))),
      wall_(wall),
      options_(options) {
  check_interface(wall_mesh);
  model_ = std::make_unique<LinearModalModel<D>>(modes_);
}

template <int D>
FlexibleBody<D>::FlexibleBody(std::string name, std::shared_ptr<const ModalSurface<D>> modes,
                              std::unique_ptr<StructureModel<D>> model, int wall,
                              const CouplingOptions& options, const ldd::WallMesh<D>& wall_mesh)
    : name_(std::move(name)),
      modes_(std::move(modes)),
      model_(std::move(model)),
      wall_(wall),
      options_(options) {
  HM_ASSERT(&model_->interface() == modes_.get(), "the model of body '{}' has another interface",
            name_);
  check_interface(wall_mesh);
}

template <int D>
void FlexibleBody<D>::check_interface(const ldd::WallMesh<D>& wall_mesh) {
  const ModalSurface<D>& modes = *modes_;
  const auto n = static_cast<Eigen::Index>(modes.x0.size());
  const Eigen::Index m = modes.modes();
  if (modes.x0.size() != wall_mesh.vertices().size() || modes.shapes.rows() != D * n)
    input_error("flexible body '{}': {} mode-shape rows for {} vertices; its wall '{}' has {}",
                name_, modes.shapes.rows(), n, wall_mesh.name(), wall_mesh.vertices().size());
  if (modes.initial_velocity.size() != 0 && modes.initial_velocity.size() != m)
    input_error("flexible body '{}': {} initial modal velocities for {} modes", name_,
                modes.initial_velocity.size(), m);
  if (modes.omega.size() != m || modes.zeta.size() != m)
    input_error("flexible body '{}': {} modes but {} frequencies and {} damping ratios", name_, m,
                modes.omega.size(), modes.zeta.size());
  if ((modes.omega.array() < 0).any() || (modes.zeta.array() < 0).any())
    input_error("flexible body '{}': negative natural frequency or damping ratio", name_);
  if (!(options_.load_scale > 0.0))
    input_error("flexible body '{}': load scale (2-D thickness) {} m must be > 0", name_,
                options_.load_scale);
  ldd::Vec<D> lower = modes.x0.front(), upper = lower;
  for (const auto& x : modes.x0) {
    lower = lower.cwiseMin(x);
    upper = upper.cwiseMax(x);
  }
  size_ = (upper - lower).norm();
}

template <int D>
double FlexibleBody<D>::max_speed() const {
  const double speed = model_->max_speed();
  if (!carrier_) return speed;
  const motion::RigidState s = carrier_->state(model_->time());
  return speed + s.velocity.norm() + s.omega.norm() * carrier_reach_;
}

template <int D>
double FlexibleBody<D>::peak_pressure(const ldd::FlowSolver<D>& flow) const {
  const auto& points = flow.points();
  double peak = 0.0;
  for (ldd::Index i = 0; i < flow.owned(); ++i)
    if (points.kind[i] == ldd::PointKind::wall && points.host[i].body == wall_)
      peak = std::max(peak, points.pressure[i]);
  if (const auto* processes = flow.processes()) processes->max(std::span(&peak, 1));
  return peak;
}

template <int D>
double FlexibleBody<D>::stretch() const {
  return size_ > 0.0 ? deformation() / size_ : 0.0;
}

template <int D>
void FlexibleBody<D>::set_carrier(motion::RigidMotion carrier) {
  carrier_ = std::move(carrier);
  // The farthest the body reaches from the (material) pivot, its deformation allowed for.
  const Eigen::Vector3d pivot = carrier_->state(0.0).pivot;
  carrier_reach_ = 0.0;
  for (const auto& x : modes_->x0)
    carrier_reach_ = std::max(carrier_reach_, (widen<D>(x) - pivot).norm() + size_);
}

template <int D>
Eigen::VectorXd FlexibleBody<D>::body_acceleration(double t) const {
  const motion::RigidState s = carrier_state(carrier_, t);
  const Eigen::Vector3d load = s.rotation.transpose() * (widen<D>(gravity_) - s.acceleration);
  return load.head<D>();
}

template <int D>
Eigen::VectorXd FlexibleBody<D>::inertial_force(double t) const {
  const ModalSurface<D>& modes = *modes_;
  const Eigen::Index m = modes.modes();
  if (modes.participation.size() == 0) return Eigen::VectorXd::Zero(m);
  const motion::RigidState s = carrier_state(carrier_, t);
  // Body-frame gravity and tank acceleration: Γ·Rᵀ(g − Ẍ).
  const Eigen::Vector3d load = s.rotation.transpose() * (widen<D>(gravity_) - s.acceleration);
  Eigen::VectorXd F = modes.participation * load.head<D>();
  if (!rotates(s)) return F;
  // The Euler term −Γ_rot(c)·α of the rotation about the pivot c (spec §4.3); the centrifugal
  // and Coriolis terms, of order Ω²r and Ωu̇ against g, are left out (1e-2 g for the paper's
  // rolling tanks).
  if (modes.rotation_participation.rows() != m)
    input_error(
        "flexible body '{}': its tank rotates but the mode set has no rotational "
        "participation factors",
        name_);
  const Eigen::Vector3d alpha = s.rotation.transpose() * s.alpha;
  // Γ_rot about the pivot: Φᵀ M (e_k × (x − c)) = Γ_rot(q)_k + Γ·(e_k × (q − c)), q the modes'
  // reference point; the pivot in the body frame is the material pivot s.pivot.
  const Eigen::Vector3d q_minus_c = modes.rotation_reference - s.pivot;
  for (int k = (D == 2 ? 2 : 0); k < 3; ++k) {
    const int column = D == 2 ? 0 : k;
    const Eigen::Vector3d arm = Eigen::Vector3d::Unit(k).cross(q_minus_c);
    const Eigen::VectorXd about_pivot =
        modes.rotation_participation.col(column) + modes.participation * arm.head<D>();
    F -= about_pivot * alpha[k];
  }
  return F;
}

template <int D>
void FlexibleBody<D>::place(ldd::WallMesh<D>& wall, const WallFields& fields, double t) const {
  const motion::RigidState s = carrier_state(carrier_, t);
  const Eigen::Matrix3d& R = s.rotation;
  const Eigen::Vector3d c = s.pivot + s.translation;
  const std::size_t n = modes_->x0.size();
  std::vector<ldd::Vec<D>> x(n), xv(n), xa(n);
  const Eigen::VectorXd &u = fields.u, &uv = fields.v, &ua = fields.a;
  for (std::size_t k = 0; k < n; ++k) {
    const auto row = static_cast<Eigen::Index>(D * k);
    // x = c + R(x0 + u − c0): the body's point in the tank frame carried by the tank (c0 the
    // material pivot); v and a with the rigid, relative and Coriolis parts (spec §4.1).
    const Eigen::Vector3d r =
        R * (widen<D>(ldd::Vec<D>(modes_->x0[k] + u.segment<D>(row))) - s.pivot);
    const Eigen::Vector3d rel_v = R * widen<D>(ldd::Vec<D>(uv.segment<D>(row)));
    const Eigen::Vector3d rel_a = R * widen<D>(ldd::Vec<D>(ua.segment<D>(row)));
    x[k] = (c + r).head<D>();
    xv[k] = (s.velocity + s.omega.cross(r) + rel_v).head<D>();
    xa[k] = (s.acceleration + s.alpha.cross(r) + s.omega.cross(s.omega.cross(r)) +
             2.0 * s.omega.cross(rel_v) + rel_a)
                .head<D>();
  }
  wall.move(x, xv, xa);
  placed_rotation_ = R.topLeftCorner<D, D>();
}

namespace {

/// The fluid's forces on the wall's vertices, in the body's frame, D per vertex [N/m in 2-D].
/// A distributed flow: each process loads from the quadrature points of its own region, the
/// forces summed over the processes (every process then holds the whole).
template <int D>
Eigen::VectorXd wall_forces(const ldd::FlowSolver<D>& flow, int wall_index, bool viscous,
                            const Eigen::Matrix<double, D, D>& rotation,
                            std::span<const double> pressure) {
  const auto& wall = flow.walls()[static_cast<std::size_t>(wall_index)];
  const ldd::PointExchange<D>* processes = flow.processes();
  ldd::QuadraturePoints<D> own_region;
  if (processes != nullptr)
    own_region = [processes](const ldd::Vec<D>& x) { return processes->owns(x); };
  auto loads =
      ldd::wall_pressure_loads<D>(flow.points(), wall, wall_index, flow.dx(), pressure, own_region);
  if (viscous && pressure.empty()) {
    const auto shear =
        ldd::wall_viscous_loads<D>(flow.points(), wall, flow.dx(),
                                   flow.options().density * flow.options().viscosity, own_region);
    for (std::size_t k = 0; k < loads.vertex_force.size(); ++k)
      loads.vertex_force[k] += shear.vertex_force[k];
  }
  Eigen::VectorXd f(D * static_cast<Eigen::Index>(loads.vertex_force.size()));
  for (std::size_t k = 0; k < loads.vertex_force.size(); ++k)  // in the tank's (body's) frame
    f.segment<D>(static_cast<Eigen::Index>(D * k)) = rotation.transpose() * loads.vertex_force[k];
  if (processes != nullptr) processes->sum(std::span(f.data(), static_cast<std::size_t>(f.size())));
  return f;
}

}  // namespace

template <int D>
Eigen::VectorXd FlexibleBody<D>::modal_force(const ldd::FlowSolver<D>& flow,
                                             std::span<const double> pressure) const {
  const Eigen::VectorXd f =
      wall_forces<D>(flow, wall_, options_.viscous_traction, placed_rotation_, pressure);
  return options_.load_scale * (modes_->shapes.transpose() * f);
}

template <int D>
BodyLoad FlexibleBody<D>::load(const ldd::FlowSolver<D>& flow, double t) const {
  const Eigen::VectorXd f =
      wall_forces<D>(flow, wall_, options_.viscous_traction, placed_rotation_, {});
  BodyLoad load;
  load.generalised = options_.load_scale * (modes_->shapes.transpose() * f) + inertial_force(t);
  load.wall_force = options_.load_scale * f;
  load.acceleration = body_acceleration(t);
  const motion::RigidState s = carrier_state(carrier_, t);
  if (rotates(s)) {
    load.angular_acceleration = s.rotation.transpose() * s.alpha;
    load.pivot = s.pivot;
  }
  return load;
}

template <int D>
void FlexibleBody<D>::measure_added_mass(ldd::FlowSolver<D>& flow, double) {
  const auto& points = flow.points();
  const auto& wall = flow.walls()[static_cast<std::size_t>(wall_)];
  const Eigen::Index m = modes_->modes();
  Eigen::MatrixXd added(m, m);
  std::vector<ldd::Vec<D>> acceleration(static_cast<std::size_t>(points.size()));
  for (Eigen::Index mode = 0; mode < m; ++mode) {
    for (ldd::Index i = 0; i < points.size(); ++i) {
      acceleration[i].setZero();
      if (points.kind[i] != ldd::PointKind::wall || points.host[i].body != wall_) continue;
      const auto& h = points.host[i];
      for (int c = 0; c < D; ++c) {
        const auto vertex = static_cast<Eigen::Index>(wall.element(h.element)[c]);
        acceleration[i] +=
            h.barycentric[c] *
            (placed_rotation_ * modes_->shapes.template block<D, 1>(D * vertex, mode));
      }
    }
    added.col(mode) = -modal_force(flow, flow.acceleration_pressure(acceleration));
  }
  added_mass_ = 0.5 * (added + added.transpose());
}

template <int D>
void FlexibleBody<D>::start(ldd::FlowSolver<D>& flow) {
  const double t = flow.time();
  model_->reset(t);
  gravity_ = flow.options().gravity;
  auto& wall = flow.walls()[static_cast<std::size_t>(wall_)];
  place(wall, model_->wall(), t);
  const BodyLoad hydro = load(flow, t);
  if (options_.static_start) model_->settle(hydro);
  if (options_.scheme == CouplingScheme::strong) {
    measure_added_mass(flow, flow.stable_dt(0.0).first);
    initial_added_mass_ = added_mass_;
    model_->start(hydro, &added_mass_);
  } else {
    model_->start(hydro, nullptr);
  }
  place(wall, model_->wall(), t);
}

template <int D>
BodyState FlexibleBody<D>::state() const {
  return {model_->time(),       y(), v(), a(), F(), added_mass_, initial_added_mass_,
          model_->extra_state()};
}

template <int D>
void FlexibleBody<D>::restore(const BodyState& state) {
  const Eigen::Index m = modes_->modes();
  if (state.y.size() != m || state.v.size() != m || state.a.size() != m || state.F.size() != m)
    input_error("flexible body '{}': the checkpoint holds {} modes, the mode set {}", name_,
                state.y.size(), m);
  model_->restore(state.time, state.y, state.v, state.a, state.F, state.model);
  added_mass_ = state.added_mass;
  initial_added_mass_ = state.initial_added_mass;
  placed_rotation_ = carrier_state(carrier_, state.time).rotation.topLeftCorner<D, D>();
}

template <int D>
Eigen::VectorXd FlexibleBody<D>::answer_to(const Eigen::VectorXd& generalised) const {
  return answer_.slope * generalised + answer_.offset;
}

namespace {

/// Runs f and adds its wall-clock time to `seconds`.
template <class F>
decltype(auto) timed(double& seconds, F&& f) {
  const auto start = std::chrono::steady_clock::now();
  struct Add {
    double& seconds;
    std::chrono::steady_clock::time_point start;
    ~Add() {
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
  } add{seconds, start};
  return f();
}

}  // namespace

template <int D>
void FlexibleBody<D>::predict(ldd::WallMesh<D>& wall, double dt) {
  step_dt_ = dt;
  model_seconds_ = 0.0;
  answer_ = timed(model_seconds_, [&] { return model_->predict(dt); });
  // The predictor F_p = Fⁿ.
  a_step_ = answer_to(F());
  place(wall, timed(model_seconds_, [&] { return model_->wall_in_step(a_step_); }),
        model_->time() + dt);
  iterations_ = 0;
  if (added_mass_.size() > 0) jacobian_ = -added_mass_;
}

template <int D>
double FlexibleBody<D>::iterate(ldd::WallMesh<D>& wall, const BodyLoad& load) {
  const Eigen::VectorXd& measured = load.generalised;
  const Eigen::Index m = modes_->modes();
  // R(ā) = S·G(ā) + r − ā: the structure's answer to the fluid's load minus what the fluid saw.
  const Eigen::VectorXd answer = answer_to(measured);
  const Eigen::VectorXd residual = answer - a_step_;
  if (added_mass_.size() == 0) {  // explicit: no iteration
    const double scale = std::max({answer.norm(), a_step_.norm(), 1e-300});
    return residual.norm() / scale;
  }
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(m, m);
  // Scale: the acceleration the present load gives the wet structure (the answer itself passes
  // through zero at every turning point of the motion).
  const Eigen::VectorXd wet =
      (identity + answer_.slope * added_mass_).partialPivLu().solve(answer_.slope * measured);
  const double scale = std::max({answer.norm(), a_step_.norm(), wet.norm(), 1e-300});
  const double relative = residual.norm() / scale;
  // Good Broyden update of the fluid's Jacobian dG/dā from the last pair of iterates: the
  // measured M̂ misses what the no-tension pass and the free surface add, and lags the geometry.
  if (iterations_ > 0) {
    const Eigen::VectorXd da = a_step_ - last_a_, dF = measured - last_F_;
    const double norm2 = da.squaredNorm();
    if (norm2 > 0.0) jacobian_ += (dF - jacobian_ * da) * da.transpose() / norm2;
  }
  Eigen::VectorXd delta = -(answer_.slope * jacobian_ - identity).partialPivLu().solve(residual);
  // A residual that grew: half a step (the iteration met a nonlinearity, e.g. wall nodes
  // released from tension, or a Jacobian far off).
  if (iterations_ > 0 && residual.norm() > last_residual_) delta *= 0.5;
  last_a_ = a_step_;
  last_F_ = measured;
  last_residual_ = residual.norm();
  ++iterations_;
  a_step_ += delta;
  place(wall, timed(model_seconds_, [&] { return model_->wall_in_step(a_step_); }),
        model_->time() + step_dt_);
  return relative;
}

template <int D>
void FlexibleBody<D>::correct(const BodyLoad& measured) {
  timed(model_seconds_, [&] { model_->correct(measured); });
}

template <int D>
ldd::StepMonitor coupled_step(ldd::FlowSolver<D>& flow, std::span<FlexibleBody<D>> bodies,
                              double dt, std::vector<CouplingMonitor>& coupling) {
  using Clock = std::chrono::steady_clock;
  const auto since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  coupling.assign(bodies.size(), CouplingMonitor{});
  double own = 0.0, added = 0.0;  // coupling seconds of all bodies (one clock for all)
  auto wall_of = [&](const FlexibleBody<D>& b) -> ldd::WallMesh<D>& {
    return flow.walls()[static_cast<std::size_t>(b.wall())];
  };
  auto t = Clock::now();
  for (auto& body : bodies) {
    body.set_gravity(flow.options().gravity);
    body.predict(wall_of(body), dt);
  }
  own += since(t);
  flow.begin_step(dt);
  t = Clock::now();
  const long step = flow.step_count() + 1;
  bool strong = false;
  int max_iterations = 1;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const auto& o = bodies[b].options();
    if (o.scheme != CouplingScheme::strong) continue;
    strong = true;
    max_iterations = std::max(max_iterations, o.max_iterations);
    if (bodies[b].added_mass().size() == 0 || step % std::max(1L, o.added_mass_interval) == 0) {
      bodies[b].measure_added_mass(flow, dt);
      coupling[b].added_mass_measured = true;
    }
  }
  added += since(t);
  own += since(t);
  std::vector<BodyLoad> measured(bodies.size());
  for (int iteration = 1;; ++iteration) {
    // The wall nodes in tension are released afresh in the first sub-iterations only; later
    // ones keep that set, so that the PPE is linear in the interface's motion and the
    // quasi-Newton iteration converges.
    flow.solve_pressure(iteration <= kFreshReleaseIterations ? ldd::TensionRelease::fresh
                                                             : ldd::TensionRelease::kept);
    t = Clock::now();
    bool converged = true;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      measured[b] = bodies[b].load(flow, flow.time() + dt);
      const Eigen::VectorXd seen = bodies[b].fluid_acceleration();
      const double residual = bodies[b].iterate(wall_of(bodies[b]), measured[b]);
      coupling[b].iterations = iteration;
      coupling[b].residual = residual;
      const bool body_strong = bodies[b].options().scheme == CouplingScheme::strong;
      coupling[b].converged = !body_strong || residual <= bodies[b].options().tolerance;
      spdlog::debug(
          "coupling: step {} iteration {}: body {} residual {:.3e}, F = [{:.6g}] at ā = [{:.6g}]",
          step, iteration, bodies[b].name(), residual, fmt::join(measured[b].generalised, ", "),
          fmt::join(seen, ", "));
      converged = converged && coupling[b].converged;
    }
    const bool done = !strong || converged || iteration >= max_iterations;
    if (!done) flow.refresh_wall_kinematics();
    own += since(t);
    if (done) break;
  }
  const ldd::StepMonitor m = flow.finish_step();
  t = Clock::now();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    bodies[b].correct(measured[b]);
    coupling[b].stretch = bodies[b].stretch();
    coupling[b].deformation = bodies[b].deformation();
    coupling[b].peak_pressure = bodies[b].peak_pressure(flow);
    coupling[b].solver_iterations = bodies[b].model().solver_iterations();
    coupling[b].energy = bodies[b].model().energy();
    coupling[b].structure_seconds = bodies[b].model_seconds();
  }
  own += since(t);
  for (auto& c : coupling) {
    c.seconds = own / static_cast<double>(coupling.size());
    c.added_mass_seconds = added / static_cast<double>(coupling.size());
  }
  return m;
}

template class FlexibleBody<2>;
template class FlexibleBody<3>;
template ldd::StepMonitor coupled_step<2>(ldd::FlowSolver<2>&, std::span<FlexibleBody<2>>, double,
                                          std::vector<CouplingMonitor>&);
template ldd::StepMonitor coupled_step<3>(ldd::FlowSolver<3>&, std::span<FlexibleBody<3>>, double,
                                          std::vector<CouplingMonitor>&);

}  // namespace hm::coupling
