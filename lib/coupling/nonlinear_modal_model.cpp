#include "coupling/nonlinear_modal_model.hpp"

#include <algorithm>

#include <Eigen/Dense>

#include "core/errors.hpp"
#include "coupling/flexible_body.hpp"
#include "fem/reduced_static.hpp"

namespace hm::coupling {

template <int D>
NonlinearModalModel<D>::NonlinearModalModel(std::shared_ptr<const ModalSurface<D>> interface,
                                            NonlinearModalParts parts)
    : basis_(std::move(interface)), parts_(std::move(parts)) {
  const Eigen::Index r = parts_.tensors->size();
  if (basis_->modes() != r)
    input_error("{}: the reduced model has {} basis vectors, its wall interface {}", parts_.context,
                r, basis_->modes());
  if (basis_->participation.size() > 0 && basis_->participation.rows() != r)
    input_error("{}: {} participation factors for {} basis vectors", parts_.context,
                basis_->participation.rows(), r);
  dynamics_ = std::make_unique<fem::ReducedDynamics>(*parts_.tensors, parts_.dynamics);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(r);
  dynamics_->start(0.0, zero, zero, zero);
}

template <int D>
void NonlinearModalModel<D>::reset(double t) {
  const Eigen::Index r = parts_.tensors->size();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(r);
  dynamics_->start(t, zero, basis_->initial_velocity.size() == r ? basis_->initial_velocity : zero,
                   zero);
}

template <int D>
void NonlinearModalModel<D>::settle(const BodyLoad& load) {
  fem::StaticOptions options;
  options.newton = parts_.dynamics.newton;
  const fem::ReducedStaticResult r = fem::solve_reduced_static(
      *parts_.tensors, {load.generalised, {}, {}}, options, parts_.context);
  dynamics_->start(time(), r.q, Eigen::VectorXd::Zero(r.q.size()), load.generalised);
}

template <int D>
void NonlinearModalModel<D>::start(const BodyLoad& load, const Eigen::MatrixXd* added_mass) {
  const fem::ReducedState s = dynamics_->state();
  Eigen::VectorXd F = load.generalised;
  if (added_mass != nullptr) {
    // The wet acceleration solves (M_r + M̂) q̈ = F − f_r(q) − C q̇; the load loses the fluid's
    // reaction M̂ q̈ (as for the linear modes, whose M_r is I).
    dynamics_->start(s.time, s.q, s.v, F);
    const Eigen::VectorXd net = F - dynamics_->state().internal;
    const Eigen::VectorXd wet = (parts_.tensors->mass() + *added_mass).ldlt().solve(net);
    F -= *added_mass * wet;
  }
  dynamics_->start(s.time, s.q, s.v, F);
}

template <int D>
void NonlinearModalModel<D>::solve(double dt, const Eigen::VectorXd& load_end) {
  const fem::NewtonReport& report = dynamics_->solve_step(dt, load_end);
  iterations_ += report.iterations;
  if (!report.converged)
    throw StructureFailed(fmt::format(
        "{}: the reduced step from t = {:.9g} s to {:.9g} s did not converge, not even in "
        "parts of 1/2^{} of it ({} parts converged before): {}",
        parts_.context, time(), time() + dt, parts_.dynamics.max_step_halvings, report.substeps,
        report.failure));
}

template <int D>
AffineAnswer NonlinearModalModel<D>::predict(double dt) {
  step_dt_ = dt;
  iterations_ = 0;
  const fem::ReducedState& s = dynamics_->state();
  solve(dt, s.load);  // the predictor F_p = Fⁿ
  const fem::ReducedState& trial = dynamics_->trial();
  predicted_q_ = trial.q;
  AffineAnswer answer;
  answer.slope = dynamics_->mean_acceleration_response();
  answer.offset = (trial.v - s.v) / dt - answer.slope * s.load;
  return answer;
}

template <int D>
WallFields NonlinearModalModel<D>::wall_in_step(const Eigen::VectorXd& mean_acceleration) const {
  const Eigen::MatrixXd& v = basis_->shapes;
  return {v * predicted_q_, v * (dynamics_->state().v + step_dt_ * mean_acceleration),
          v * mean_acceleration};
}

template <int D>
void NonlinearModalModel<D>::correct(const BodyLoad& load) {
  solve(step_dt_, load.generalised);
  dynamics_->commit();
}

template <int D>
WallFields NonlinearModalModel<D>::wall() const {
  const Eigen::MatrixXd& v = basis_->shapes;
  const fem::ReducedState& s = dynamics_->state();
  return {v * s.q, v * s.v, v * s.a};
}

template <int D>
ldd::Vec<D> NonlinearModalModel<D>::displacement(Eigen::Index vertex) const {
  return basis_->shapes.middleRows(D * vertex, D) * q();
}

template <int D>
double NonlinearModalModel<D>::largest_on_wall(const Eigen::VectorXd& x) const {
  double largest = 0.0;
  for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(basis_->x0.size()); ++k)
    largest = std::max(largest, (basis_->shapes.middleRows(D * k, D) * x).norm());
  return largest;
}

template <int D>
double NonlinearModalModel<D>::deformation() const {
  return largest_on_wall(q());
}

template <int D>
double NonlinearModalModel<D>::max_speed() const {
  return largest_on_wall(q_dot());
}

template <int D>
StructureEnergy NonlinearModalModel<D>::energy() const {
  const fem::EnergyBalance& e = dynamics_->energy();
  return {e.kinetic, e.strain, e.external_work, e.damping, e.numerical_dissipation};
}

template <int D>
std::map<std::string, Eigen::VectorXd> NonlinearModalModel<D>::extra_state() const {
  const fem::EnergyBalance& e = dynamics_->energy();
  return {
      {"energy_balance", Eigen::Vector3d(dynamics_->start_energy(), e.external_work, e.damping)}};
}

template <int D>
void NonlinearModalModel<D>::restore(double time, const Eigen::VectorXd& q,
                                     const Eigen::VectorXd& q_dot, const Eigen::VectorXd& q_ddot,
                                     const Eigen::VectorXd& load,
                                     const std::map<std::string, Eigen::VectorXd>& extra) {
  const auto balance = extra.find("energy_balance");
  if (balance == extra.end() || balance->second.size() != 3)
    input_error(
        "{}: the checkpoint has no energy balance of the reduced structure (3 values; written by "
        "another structure model?)",
        parts_.context);
  fem::EnergyBalance e;
  e.external_work = balance->second[1];
  e.damping = balance->second[2];
  dynamics_->restore(time, q, q_dot, q_ddot, load, e, balance->second[0]);
}

template class NonlinearModalModel<2>;
template class NonlinearModalModel<3>;

}  // namespace hm::coupling
