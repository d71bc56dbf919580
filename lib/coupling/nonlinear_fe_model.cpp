#include "coupling/nonlinear_fe_model.hpp"

#include <fmt/ranges.h>
#include <Eigen/Dense>

#include "core/errors.hpp"
#include "core/log.hpp"
#include "coupling/flexible_body.hpp"
#include "fem/nonlinear_static.hpp"

namespace hm::coupling {

RayleighFit rayleigh_for(double zeta, double omega1, double omega2) {
  if (!(zeta > 0.0) || !(omega1 > 0.0)) return {};
  if (!(omega2 > 0.0)) omega2 = omega1;
  return {2.0 * zeta * omega1 * omega2 / (omega1 + omega2), 2.0 * zeta / (omega1 + omega2)};
}

template <int D>
NonlinearFeModel<D>::NonlinearFeModel(std::shared_ptr<const ModalSurface<D>> interface,
                                      NonlinearFeParts parts)
    : modes_(std::move(interface)), parts_(std::move(parts)) {
  const fem::HyperelasticBody& body = *parts_.body;
  if (body.dim() != D)
    input_error("{}: the structure mesh is {}-D, the case {}-D", parts_.context, body.dim(), D);
  if (parts_.modes.rows() != body.dof_count() || parts_.modes.cols() != modes_->modes())
    input_error("{}: {} × {} mode shapes for a body of {} DOFs with {} interface modes",
                parts_.context, parts_.modes.rows(), parts_.modes.cols(), body.dof_count(),
                modes_->modes());
  if (parts_.wall_map->wall_vertices() != static_cast<Eigen::Index>(modes_->x0.size()))
    input_error("{}: the wall map reaches {} vertices, the wall has {}", parts_.context,
                parts_.wall_map->wall_vertices(), modes_->x0.size());
  mass_modes_ = body.mass() * parts_.modes;
  dynamics_ = std::make_unique<fem::NonlinearDynamics>(body, *parts_.dofs, parts_.dynamics);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(body.dof_count());
  dynamics_->start(0.0, zero, zero, zero);
  update_kept();
}

template <int D>
Eigen::VectorXd NonlinearFeModel<D>::project(const Eigen::VectorXd& full) const {
  return mass_modes_.transpose() * full;
}

template <int D>
void NonlinearFeModel<D>::update_kept() {
  const fem::DynamicState& s = dynamics_->state();
  q_ = project(s.u);
  q_dot_ = project(s.v);
  q_ddot_ = project(s.a);
  // The wall's position is the body's; its velocity and acceleration are those of the interface
  // modes (the file comment).
  wall_ = {parts_.wall_map->to_wall(s.u), modes_->shapes * q_dot_, modes_->shapes * q_ddot_};
}

template <int D>
Eigen::VectorXd NonlinearFeModel<D>::nodal_load(const BodyLoad& load) const {
  const fem::HyperelasticBody& body = *parts_.body;
  Eigen::VectorXd f =
      parts_.wall_map->to_structure(load.wall_force) + body.body_force(load.acceleration);
  if (load.angular_acceleration.isZero(0.0)) return f;
  // The Euler load −M (α × (X − c)) of a rotating carrier, at the reference positions.
  const auto& nodes = body.mesh().nodes;
  Eigen::VectorXd euler(body.dof_count());
  for (Eigen::Index n = 0; n < nodes.rows(); ++n) {
    Eigen::Vector3d arm = -load.pivot;
    arm.head<D>() += nodes.row(n).transpose();
    euler.segment<D>(D * n) = load.angular_acceleration.cross(arm).head<D>();
  }
  return f - body.mass() * euler;
}

template <int D>
void NonlinearFeModel<D>::reset(double t) {
  const Eigen::Index n = parts_.body->dof_count();
  const Eigen::VectorXd v = modes_->initial_velocity.size() == modes_->modes()
                                ? Eigen::VectorXd(parts_.modes * modes_->initial_velocity)
                                : Eigen::VectorXd::Zero(n);
  dynamics_->start(t, Eigen::VectorXd::Zero(n), v, Eigen::VectorXd::Zero(n));
  F_ = Eigen::VectorXd::Zero(modes_->modes());
  update_kept();
}

template <int D>
void NonlinearFeModel<D>::settle(const BodyLoad& load) {
  fem::StaticLoad dead;
  dead.dead = nodal_load(load);
  fem::StaticOptions options;
  options.newton = parts_.dynamics.newton;
  const fem::StaticResult r =
      fem::solve_static(*parts_.body, *parts_.dofs, dead, options, parts_.context);
  const Eigen::Index n = parts_.body->dof_count();
  dynamics_->start(dynamics_->state().time, r.u, Eigen::VectorXd::Zero(n), dead.dead);
  update_kept();
}

template <int D>
void NonlinearFeModel<D>::start(const BodyLoad& load, const Eigen::MatrixXd* added_mass) {
  const fem::DynamicState s = dynamics_->state();
  Eigen::VectorXd nodal = nodal_load(load);
  F_ = load.generalised;
  if (added_mass != nullptr) {
    // The dry acceleration's modal content Φᵀ M M⁻¹(f − f_int − C v) = Φᵀ(f − f_int − C v);
    // the wet one solves (I + M̂)q̈ = q̈_dry, and the load loses the fluid's reaction M̂ q̈, as
    // the nodal load M Φ(−M̂ q̈) whose modal content it is.
    dynamics_->start(s.time, s.u, s.v, nodal);
    const Eigen::VectorXd dry = project(dynamics_->state().a);
    const Eigen::Index m = modes_->modes();
    const Eigen::VectorXd wet = (Eigen::MatrixXd::Identity(m, m) + *added_mass).ldlt().solve(dry);
    const Eigen::VectorXd reaction = -(*added_mass * wet);
    nodal += mass_modes_ * reaction;
    F_ += reaction;
  }
  dynamics_->start(s.time, s.u, s.v, nodal);
  update_kept();
}

template <int D>
void NonlinearFeModel<D>::solve(double dt, const Eigen::VectorXd& load_end) {
  const fem::NewtonReport& report = dynamics_->solve_step(dt, load_end);
  iterations_ += report.iterations;
  if (!report.converged)
    throw StructureFailed(fmt::format(
        "{}: the step from t = {:.9g} s to {:.9g} s did not converge, not even in parts of "
        "1/2^{} of it ({} parts converged before): {}",
        parts_.context, time(), time() + dt, parts_.dynamics.max_step_halvings, report.substeps,
        report.failure));
}

template <int D>
AffineAnswer NonlinearFeModel<D>::predict(double dt) {
  step_dt_ = dt;
  iterations_ = 0;
  const fem::DynamicState& s = dynamics_->state();
  solve(dt, s.load);  // the predictor F_p = Fⁿ
  const fem::DynamicState& trial = dynamics_->trial();
  const Eigen::VectorXd mean = (trial.v - s.v) / dt;
  predicted_u_ = parts_.wall_map->to_wall(trial.u);
  predicted_alpha_ = project(mean);
  AffineAnswer answer;
  answer.slope = mass_modes_.transpose() * dynamics_->mean_acceleration_response(mass_modes_);
  answer.offset = predicted_alpha_ - answer.slope * F_;
  spdlog::debug(
      "{}: predictor to t = {:.6g} s: {} Newton iterations; mean interface "
      "acceleration [{:.4g}], kept [{:.4g}]",
      parts_.context, time() + dt, iterations_, fmt::join(predicted_alpha_, ", "),
      fmt::join(q_ddot_, ", "));
  return answer;
}

template <int D>
WallFields NonlinearFeModel<D>::wall_in_step(const Eigen::VectorXd& mean_acceleration) const {
  const Eigen::VectorXd a = modes_->shapes * mean_acceleration;
  return {predicted_u_, modes_->shapes * (q_dot_ + step_dt_ * mean_acceleration), a};
}

template <int D>
void NonlinearFeModel<D>::correct(const BodyLoad& load) {
  solve(step_dt_, nodal_load(load));
  dynamics_->commit();
  F_ = load.generalised;
  update_kept();
}

template <int D>
ldd::Vec<D> NonlinearFeModel<D>::displacement(Eigen::Index vertex) const {
  return wall_.u.segment<D>(D * vertex);
}

template <int D>
double NonlinearFeModel<D>::deformation() const {
  double largest = 0.0;
  for (Eigen::Index k = 0; k < wall_.u.size() / D; ++k)
    largest = std::max(largest, wall_.u.segment<D>(D * k).norm());
  return largest;
}

template <int D>
double NonlinearFeModel<D>::max_speed() const {
  double largest = 0.0;
  for (Eigen::Index k = 0; k < wall_.v.size() / D; ++k)
    largest = std::max(largest, wall_.v.segment<D>(D * k).norm());
  return largest;
}

template <int D>
StructureEnergy NonlinearFeModel<D>::energy() const {
  const fem::EnergyBalance& e = dynamics_->energy();
  return {e.kinetic, e.strain, e.external_work, e.damping, e.numerical_dissipation};
}

template <int D>
std::map<std::string, Eigen::VectorXd> NonlinearFeModel<D>::extra_state() const {
  const fem::DynamicState& s = dynamics_->state();
  const fem::EnergyBalance& e = dynamics_->energy();
  return {
      {"u", s.u},
      {"v", s.v},
      {"a", s.a},
      {"load", s.load},
      {"energy_balance", Eigen::Vector3d(dynamics_->start_energy(), e.external_work, e.damping)}};
}

template <int D>
void NonlinearFeModel<D>::restore(double time, const Eigen::VectorXd&, const Eigen::VectorXd&,
                                  const Eigen::VectorXd&, const Eigen::VectorXd& load,
                                  const std::map<std::string, Eigen::VectorXd>& extra) {
  const Eigen::Index n = parts_.body->dof_count();
  for (const char* name : {"u", "v", "a", "load", "energy_balance"}) {
    const auto it = extra.find(name);
    const Eigen::Index size = std::string_view(name) == "energy_balance" ? 3 : n;
    if (it == extra.end() || it->second.size() != size)
      input_error(
          "{}: the checkpoint has no nonlinear structure state '{}' of {} values "
          "(written by another structure model?)",
          parts_.context, name, size);
  }
  const Eigen::VectorXd& balance = extra.at("energy_balance");
  fem::EnergyBalance e;
  e.external_work = balance[1];
  e.damping = balance[2];
  dynamics_->restore(time, extra.at("u"), extra.at("v"), extra.at("a"), extra.at("load"), e,
                     balance[0]);
  F_ = load;
  update_kept();
}

template class NonlinearFeModel<2>;
template class NonlinearFeModel<3>;

}  // namespace hm::coupling
