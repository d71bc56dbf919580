#include "fem/nonlinear_dynamics.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/SparseCholesky>

#include "core/errors.hpp"

namespace hm::fem {

const char* to_string(TimeScheme scheme) {
  return scheme == TimeScheme::energy_conserving ? "energy_conserving" : "generalized_alpha";
}

TimeScheme time_scheme_from(std::string_view name, std::string_view context) {
  if (name == "generalized_alpha") return TimeScheme::generalized_alpha;
  if (name == "energy_conserving") return TimeScheme::energy_conserving;
  input_error(
      "{} = \"{}\" is not a time scheme; accepted: \"generalized_alpha\", "
      "\"energy_conserving\"",
      context, name);
}

void validate(const DynamicsOptions& o, std::string_view context) {
  if (!(o.rho_infinity >= 0.0 && o.rho_infinity <= 1.0))
    input_error("{}: ρ∞ = {} is invalid; it must lie in [0, 1]", context, o.rho_infinity);
  if (o.max_step_halvings < 0 || o.max_step_halvings > 20)
    input_error("{}: {} step halvings are invalid; allowed: 0 to 20", context, o.max_step_halvings);
  if (!(o.rayleigh_alpha >= 0.0) || !(o.rayleigh_beta >= 0.0))
    input_error("{}: Rayleigh coefficients α = {} 1/s, β = {} s are invalid; they must be ≥ 0",
                context, o.rayleigh_alpha, o.rayleigh_beta);
}

NonlinearDynamics::NonlinearDynamics(const HyperelasticBody& body, const DofMap& dofs,
                                     DynamicsOptions options)
    : body_(body), dofs_(dofs), options_(options) {
  validate(options_, "structure dynamics");
  const double rho = options_.rho_infinity;
  alpha_m_ = (2.0 * rho - 1.0) / (rho + 1.0);
  alpha_f_ = rho / (rho + 1.0);
  gamma_ = 0.5 - alpha_m_ + alpha_f_;
  beta_ = 0.25 * (1.0 - alpha_m_ + alpha_f_) * (1.0 - alpha_m_ + alpha_f_);
}

namespace {

/// (f + f_d)(u, v) with its strain energy and damping power.
BodyEvaluation internal_state(const HyperelasticBody& body, const DynamicsOptions& o,
                              const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
  EvaluationRequest request;
  request.velocity = &v;
  request.beta = o.rayleigh_beta;
  BodyEvaluation e = body.evaluate(u, request);
  if (o.rayleigh_alpha > 0.0) {
    const Eigen::VectorXd mass_damping = o.rayleigh_alpha * (body.mass() * v);
    e.force += mass_damping;
    e.damping_power += v.dot(mass_damping);
  }
  return e;
}

}  // namespace

double NonlinearDynamics::force_scale(std::initializer_list<const Eigen::VectorXd*> terms) const {
  // The largest of the terms the residual sums, each on its own: their sum cancels to round-off
  // at the solution, and a step far longer than the period makes every term large against it.
  double scale = 1e-300;
  for (const Eigen::VectorXd* term : terms)
    scale = std::max(scale, dofs_.free_values(*term).norm());
  return scale;
}

void NonlinearDynamics::start(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                              const Eigen::VectorXd& load) {
  state_.time = t;
  state_.u = u;
  state_.v = v;
  state_.load = load;
  const BodyEvaluation e = internal_state(body_, options_, u, v);
  state_.internal = e.force;
  state_.damping_power = e.damping_power;
  // M a = f_ext − f − C v on the free DOFs (the clamped ones stay at rest).
  const Eigen::SparseMatrix<double> m = dofs_.reduce(body_.mass());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> mass(m);
  state_.a = dofs_.full_values(mass.solve(dofs_.free_values(load - e.force)));
  energy_ = {};
  energy_.kinetic = 0.5 * v.dot(body_.mass() * v);
  energy_.strain = e.strain_energy;
  start_energy_ = energy_.kinetic + energy_.strain;
  trial_ = state_;
}

void NonlinearDynamics::restore(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                const Eigen::VectorXd& a, const Eigen::VectorXd& load,
                                const EnergyBalance& energy, double start_energy) {
  state_.time = t;
  state_.u = u;
  state_.v = v;
  state_.a = a;
  state_.load = load;
  const BodyEvaluation e = internal_state(body_, options_, u, v);
  state_.internal = e.force;
  state_.damping_power = e.damping_power;
  energy_ = energy;
  energy_.kinetic = 0.5 * v.dot(body_.mass() * v);
  energy_.strain = e.strain_energy;
  energy_.numerical_dissipation =
      energy_.external_work - energy_.damping - (energy_.kinetic + energy_.strain - start_energy);
  start_energy_ = start_energy;
  trial_ = state_;
}

Eigen::VectorXd NonlinearDynamics::newmark_acceleration(double dt,
                                                        const Eigen::VectorXd& u1) const {
  const DynamicState& s = state_;
  return (u1 - s.u - dt * s.v - dt * dt * (0.5 - beta_) * s.a) / (beta_ * dt * dt);
}

NewtonEquations NonlinearDynamics::alpha_equations(double dt,
                                                   const Eigen::VectorXd& load_end) const {
  return [this, dt, &load_end](const Eigen::VectorXd& x, bool jacobian) {
    const DynamicState& s = state_;
    const Eigen::VectorXd u1 = dofs_.full_values(x);
    const Eigen::VectorXd a1 = newmark_acceleration(dt, u1);
    const Eigen::VectorXd v1 = s.v + dt * ((1.0 - gamma_) * s.a + gamma_ * a1);
    const double af = alpha_f_, am = alpha_m_;
    EvaluationRequest request;
    request.velocity = &v1;
    request.beta = options_.rayleigh_beta;
    request.tangent = jacobian;
    request.stiffness_weight = 1.0 - af;
    request.damping_weight = (1.0 - af) * gamma_ / (beta_ * dt);
    request.mass_weight = (1.0 - am) / (beta_ * dt * dt) +
                          (1.0 - af) * options_.rayleigh_alpha * gamma_ / (beta_ * dt);
    BodyEvaluation e = body_.evaluate(u1, request);
    Eigen::VectorXd internal = e.force;
    if (options_.rayleigh_alpha > 0.0) internal += options_.rayleigh_alpha * (body_.mass() * v1);
    const Eigen::VectorXd inertia_end = (1.0 - am) * (body_.mass() * a1);
    const Eigen::VectorXd inertia_start = am * (body_.mass() * s.a);
    NewtonSystem out;
    out.residual = dofs_.free_values(inertia_end + inertia_start + (1.0 - af) * internal +
                                     af * s.internal - (1.0 - af) * load_end - af * s.load);
    out.scale =
        force_scale({&inertia_end, &inertia_start, &internal, &s.internal, &load_end, &s.load});
    out.min_det_f = e.min_det_f;
    out.worst_cell = e.worst_cell;
    if (jacobian) out.jacobian = dofs_.reduce(e.tangent);
    return out;
  };
}

NewtonEquations NonlinearDynamics::midpoint_equations(double dt,
                                                      const Eigen::VectorXd& load_end) const {
  return [this, dt, &load_end](const Eigen::VectorXd& x, bool jacobian) {
    const DynamicState& s = state_;
    const Eigen::VectorXd u1 = dofs_.full_values(x);
    const Eigen::VectorXd v_mid = (u1 - s.u) / dt;
    EvaluationRequest request;
    request.start = &s.u;
    request.velocity = &v_mid;
    request.beta = options_.rayleigh_beta;
    request.tangent = jacobian;
    request.damping_weight = 1.0 / dt;
    request.mass_weight = 2.0 / (dt * dt) + options_.rayleigh_alpha / dt;
    BodyEvaluation e = body_.evaluate(u1, request);
    Eigen::VectorXd forces = e.force;
    if (options_.rayleigh_alpha > 0.0) forces += options_.rayleigh_alpha * (body_.mass() * v_mid);
    // M (v₁ − v₀)/Δt with v₁ = 2 v_m − v₀.
    const Eigen::VectorXd momentum_end = body_.mass() * (2.0 * v_mid / dt);
    const Eigen::VectorXd momentum_start = body_.mass() * (2.0 * s.v / dt);
    NewtonSystem out;
    out.residual =
        dofs_.free_values(momentum_end - momentum_start + forces - 0.5 * (s.load + load_end));
    out.scale = force_scale({&momentum_end, &momentum_start, &forces, &s.load, &load_end});
    out.symmetric = false;
    out.min_det_f = e.min_det_f;
    out.worst_cell = e.worst_cell;
    if (jacobian) out.jacobian = dofs_.reduce(e.tangent);
    return out;
  };
}

const NewtonReport& NonlinearDynamics::solve_step(double dt, const Eigen::VectorXd& load_end) {
  HM_ASSERT(dt > 0.0, "time step {} s", dt);
  HM_ASSERT(load_end.size() == state_.u.size(), "load of {} entries for {} DOFs", load_end.size(),
            state_.u.size());
  const DynamicState start = state_;
  StepTotals totals;
  report_ = solve_substeps(dt, load_end, options_.max_step_halvings, totals);
  trial_ = state_;
  state_ = start;
  trial_work_ = totals.work;
  trial_damping_ = totals.damping;
  report_.iterations = totals.iterations;
  report_.substeps = totals.substeps;
  return report_;
}

NewtonReport NonlinearDynamics::solve_substeps(double dt, const Eigen::VectorXd& load_end,
                                               int halvings_left, StepTotals& totals) {
  NewtonReport report = solve_single(dt, load_end);
  totals.iterations += report.iterations;
  if (report.converged) {
    totals.work += 0.5 * (state_.load + load_end).dot(trial_.u - state_.u);
    totals.damping += trial_damping_;
    ++totals.substeps;
    state_ = trial_;
    return report;
  }
  if (halvings_left == 0) return report;
  // Newton's reach is a few tens of degrees of rotation a step: halve the step, the load
  // still linear in time across both halves.
  const Eigen::VectorXd load_mid = 0.5 * (state_.load + load_end);
  report = solve_substeps(0.5 * dt, load_mid, halvings_left - 1, totals);
  if (!report.converged) return report;
  return solve_substeps(0.5 * dt, load_end, halvings_left - 1, totals);
}

NewtonReport NonlinearDynamics::solve_single(double dt, const Eigen::VectorXd& load_end) {
  const DynamicState& s = state_;
  // Predictor: the last displacement. (Extrapolating with the velocity or the acceleration
  // moves points along straight lines, stretching a rotating body out of Newton's reach, and
  // with a step far longer than the period Newmark's velocities are not physical at all.)
  Eigen::VectorXd x = dofs_.free_values(s.u);
  const bool midpoint = options_.scheme == TimeScheme::energy_conserving;
  const NewtonEquations equations =
      midpoint ? midpoint_equations(dt, load_end) : alpha_equations(dt, load_end);
  NewtonReport report = newton_solve(x, equations, options_.newton, solver_);
  finish_trial(dt, x, load_end);
  return report;
}

void NonlinearDynamics::finish_trial(double dt, const Eigen::VectorXd& x,
                                     const Eigen::VectorXd& load_end) {
  const DynamicState& s = state_;
  trial_.time = s.time + dt;
  trial_.u = dofs_.full_values(x);
  trial_.load = load_end;
  if (options_.scheme == TimeScheme::energy_conserving) {
    const Eigen::VectorXd v_mid = (trial_.u - s.u) / dt;
    trial_.v = 2.0 * v_mid - s.v;
    trial_.a = (trial_.v - s.v) / dt;
    jacobian_mass_weight_ = 2.0 / (dt * dt);
    // The damping force of the step acts at the midpoint, on Δu = Δt·v_m.
    EvaluationRequest request;
    request.start = &s.u;
    request.velocity = &v_mid;
    request.beta = options_.rayleigh_beta;
    const BodyEvaluation mid = body_.evaluate(trial_.u, request);
    trial_damping_ = dt * mid.damping_power;
    if (options_.rayleigh_alpha > 0.0)
      trial_damping_ += dt * options_.rayleigh_alpha * v_mid.dot(body_.mass() * v_mid);
  } else {
    trial_.a = newmark_acceleration(dt, trial_.u);
    trial_.v = s.v + dt * ((1.0 - gamma_) * s.a + gamma_ * trial_.a);
    jacobian_mass_weight_ = gamma_ / (beta_ * dt * dt);
  }
  const BodyEvaluation e = internal_state(body_, options_, trial_.u, trial_.v);
  trial_.internal = e.force;
  trial_.damping_power = e.damping_power;
  if (options_.scheme != TimeScheme::energy_conserving) {
    trial_damping_ = 0.5 * dt * (s.damping_power + e.damping_power);  // trapezoidal rule
  }
}

void NonlinearDynamics::commit() {
  HM_ASSERT(report_.converged, "committing a step whose Newton solve failed");
  state_ = trial_;
  energy_.external_work += trial_work_;
  energy_.damping += trial_damping_;
  energy_.kinetic = 0.5 * state_.v.dot(body_.mass() * state_.v);
  energy_.strain = body_.strain_energy(state_.u);
  energy_.numerical_dissipation =
      energy_.external_work - energy_.damping - (energy_.kinetic + energy_.strain - start_energy_);
}

Eigen::MatrixXd NonlinearDynamics::mean_acceleration_response(const Eigen::MatrixXd& load) const {
  const double load_weight =
      options_.scheme == TimeScheme::energy_conserving ? 0.5 : 1.0 - alpha_f_;
  // ū = (v₁ − v₀)/Δt moves with u₁ as jacobian_mass_weight_·Δt·(…)/Δt: dū/du₁ = γ/(βΔt²)
  // (generalised-α) or 2/Δt² (midpoint); du₁/df = load_weight·J⁻¹.
  const Eigen::MatrixXd du = solver_.solve(Eigen::MatrixXd(dofs_.reduce(load)));
  return dofs_.expand((load_weight * jacobian_mass_weight_) * du);
}

}  // namespace hm::fem
