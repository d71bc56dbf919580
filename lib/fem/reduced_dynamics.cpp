#include "fem/reduced_dynamics.hpp"

#include <algorithm>
#include <initializer_list>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "core/errors.hpp"
#include "fem/dense_newton.hpp"

namespace hm::fem {
namespace {

/// The largest norm among the terms a residual sums (they cancel at the solution).
double largest_norm(std::initializer_list<const Eigen::VectorXd*> terms) {
  double scale = 1e-300;
  for (const Eigen::VectorXd* term : terms) scale = std::max(scale, term->norm());
  return scale;
}

}  // namespace

ReducedDynamics::ReducedDynamics(const ReducedStvk& model, DynamicsOptions options)
    : model_(model), options_(options) {
  validate(options_, "reduced structure dynamics");
  damping_ =
      options_.rayleigh_alpha * model_.mass() + options_.rayleigh_beta * model_.linear_stiffness();
  const double rho = options_.rho_infinity;
  alpha_m_ = (2.0 * rho - 1.0) / (rho + 1.0);
  alpha_f_ = rho / (rho + 1.0);
  gamma_ = 0.5 - alpha_m_ + alpha_f_;
  beta_ = 0.25 * (1.0 - alpha_m_ + alpha_f_) * (1.0 - alpha_m_ + alpha_f_);
}

void ReducedDynamics::start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                            const Eigen::VectorXd& load) {
  HM_ASSERT(q.size() == model_.size() && v.size() == q.size() && load.size() == q.size(),
            "reduced state of sizes {}, {}, {} for a basis of {}", q.size(), v.size(), load.size(),
            model_.size());
  const ReducedEvaluation e = model_.evaluate(q, false);
  state_ = {};
  state_.time = t;
  state_.q = q;
  state_.v = v;
  state_.load = load;
  state_.internal = e.force + damping_force(v);
  state_.damping_power = v.dot(damping_force(v));
  state_.a = model_.mass().llt().solve(load - state_.internal);
  energy_ = {};
  energy_.kinetic = 0.5 * v.dot(model_.mass() * v);
  energy_.strain = e.strain_energy;
  start_energy_ = energy_.kinetic + energy_.strain;
  trial_ = state_;
}

void ReducedDynamics::restore(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                              const Eigen::VectorXd& a, const Eigen::VectorXd& load,
                              const EnergyBalance& energy, double start_energy) {
  const ReducedEvaluation e = model_.evaluate(q, false);
  state_ = {t, q, v, a, load, e.force + damping_force(v), v.dot(damping_force(v))};
  energy_ = energy;
  energy_.kinetic = 0.5 * v.dot(model_.mass() * v);
  energy_.strain = e.strain_energy;
  energy_.numerical_dissipation =
      energy_.external_work - energy_.damping - (energy_.kinetic + energy_.strain - start_energy);
  start_energy_ = start_energy;
  trial_ = state_;
}

Eigen::VectorXd ReducedDynamics::newmark_acceleration(double dt, const Eigen::VectorXd& q1) const {
  const ReducedState& s = state_;
  return (q1 - s.q - dt * s.v - dt * dt * (0.5 - beta_) * s.a) / (beta_ * dt * dt);
}

ReducedDynamics::Residual ReducedDynamics::alpha_residual(double dt,
                                                          const Eigen::VectorXd& load_end,
                                                          const Eigen::VectorXd& q1,
                                                          bool jacobian) const {
  const ReducedState& s = state_;
  const double af = alpha_f_, am = alpha_m_;
  const Eigen::VectorXd a1 = newmark_acceleration(dt, q1);
  const Eigen::VectorXd v1 = s.v + dt * ((1.0 - gamma_) * s.a + gamma_ * a1);
  const ReducedEvaluation e = model_.evaluate(q1, jacobian);
  const Eigen::VectorXd internal = e.force + damping_force(v1);
  const Eigen::VectorXd inertia_end = (1.0 - am) * (model_.mass() * a1);
  const Eigen::VectorXd inertia_start = am * (model_.mass() * s.a);
  Residual out;
  out.value = inertia_end + inertia_start + (1.0 - af) * internal + af * s.internal -
              (1.0 - af) * load_end - af * s.load;
  out.scale =
      largest_norm({&inertia_end, &inertia_start, &internal, &s.internal, &load_end, &s.load});
  if (jacobian) out.jacobian = alpha_matrix(dt, e.tangent);
  return out;
}

Eigen::MatrixXd ReducedDynamics::alpha_matrix(double dt, const Eigen::MatrixXd& k_end) const {
  return (1.0 - alpha_m_) / (beta_ * dt * dt) * model_.mass() +
         (1.0 - alpha_f_) * (k_end + gamma_ / (beta_ * dt) * damping_);
}

Eigen::MatrixXd ReducedDynamics::midpoint_matrix(double dt, const Eigen::MatrixXd& k_mid,
                                                 const Eigen::MatrixXd& k_end) const {
  return 2.0 / (dt * dt) * model_.mass() + (2.0 * k_mid + k_end) / 6.0 + damping_ / dt;
}

ReducedDynamics::Residual ReducedDynamics::midpoint_residual(double dt,
                                                             const Eigen::VectorXd& load_end,
                                                             const Eigen::VectorXd& f0,
                                                             const Eigen::VectorXd& q1,
                                                             bool jacobian) const {
  const ReducedState& s = state_;
  const Eigen::VectorXd v_mid = (q1 - s.q) / dt;
  const ReducedEvaluation mid = model_.evaluate(0.5 * (s.q + q1), jacobian);
  const ReducedEvaluation end = model_.evaluate(q1, jacobian);
  // The exact mean of the cubic force along the step (Simpson), plus the damping at v_m.
  const Eigen::VectorXd forces = (f0 + 4.0 * mid.force + end.force) / 6.0 + damping_force(v_mid);
  // M_r (v₁ − v₀)/Δt with v₁ = 2 v_m − v₀.
  const Eigen::VectorXd momentum_end = model_.mass() * (2.0 * v_mid / dt);
  const Eigen::VectorXd momentum_start = model_.mass() * (2.0 * s.v / dt);
  Residual out;
  out.value = momentum_end - momentum_start + forces - 0.5 * (s.load + load_end);
  out.scale = largest_norm({&momentum_end, &momentum_start, &forces, &s.load, &load_end});
  if (jacobian) out.jacobian = midpoint_matrix(dt, mid.tangent, end.tangent);
  return out;
}

const NewtonReport& ReducedDynamics::solve_step(double dt, const Eigen::VectorXd& load_end) {
  HM_ASSERT(dt > 0.0, "time step {} s", dt);
  HM_ASSERT(load_end.size() == model_.size(), "load of {} entries for a basis of {}",
            load_end.size(), model_.size());
  const ReducedState start = state_;
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

NewtonReport ReducedDynamics::solve_substeps(double dt, const Eigen::VectorXd& load_end,
                                             int halvings_left, StepTotals& totals) {
  NewtonReport report = solve_single(dt, load_end);
  totals.iterations += report.iterations;
  if (report.converged) {
    totals.work += 0.5 * (state_.load + load_end).dot(trial_.q - state_.q);
    totals.damping += trial_damping_;
    ++totals.substeps;
    state_ = trial_;
    return report;
  }
  if (halvings_left == 0) return report;
  const Eigen::VectorXd load_mid = 0.5 * (state_.load + load_end);
  report = solve_substeps(0.5 * dt, load_mid, halvings_left - 1, totals);
  if (!report.converged) return report;
  return solve_substeps(0.5 * dt, load_end, halvings_left - 1, totals);
}

NewtonReport ReducedDynamics::solve_single(double dt, const Eigen::VectorXd& load_end) {
  const bool midpoint = options_.scheme == TimeScheme::energy_conserving;
  const Eigen::VectorXd f0 = midpoint ? model_.force(state_.q) : Eigen::VectorXd();
  const DenseEquations equations = [&](const Eigen::VectorXd& q1, bool jacobian) {
    Residual r = midpoint ? midpoint_residual(dt, load_end, f0, q1, jacobian)
                          : alpha_residual(dt, load_end, q1, jacobian);
    return DenseSystem{std::move(r.value), std::move(r.jacobian), true, r.scale};
  };
  Eigen::VectorXd q1 = state_.q;  // predictor: the last displacement (as the full model)
  NewtonReport report = dense_newton_solve(q1, equations, options_.newton);
  finish_trial(dt, q1, load_end);
  return report;
}

void ReducedDynamics::finish_trial(double dt, const Eigen::VectorXd& q1,
                                   const Eigen::VectorXd& load_end) {
  const ReducedState& s = state_;
  trial_.time = s.time + dt;
  trial_.q = q1;
  trial_.load = load_end;
  response_start_ = s.q;
  response_dt_ = dt;
  if (options_.scheme == TimeScheme::energy_conserving) {
    const Eigen::VectorXd v_mid = (q1 - s.q) / dt;
    trial_.v = 2.0 * v_mid - s.v;
    trial_.a = (trial_.v - s.v) / dt;
    response_weight_ = 0.5 * 2.0 / (dt * dt);  // dF/dF_end · dā/dq₁
    trial_damping_ = dt * v_mid.dot(damping_force(v_mid));
  } else {
    trial_.a = newmark_acceleration(dt, q1);
    trial_.v = s.v + dt * ((1.0 - gamma_) * s.a + gamma_ * trial_.a);
    response_weight_ = (1.0 - alpha_f_) * gamma_ / (beta_ * dt * dt);
  }
  trial_.internal = model_.force(q1) + damping_force(trial_.v);
  trial_.damping_power = trial_.v.dot(damping_force(trial_.v));
  if (options_.scheme != TimeScheme::energy_conserving)
    trial_damping_ = 0.5 * dt * (s.damping_power + trial_.damping_power);  // trapezoidal rule
}

void ReducedDynamics::commit() {
  HM_ASSERT(report_.converged, "committing a step whose Newton solve failed");
  state_ = trial_;
  energy_.external_work += trial_work_;
  energy_.damping += trial_damping_;
  energy_.kinetic = 0.5 * state_.v.dot(model_.mass() * state_.v);
  energy_.strain = model_.strain_energy(state_.q);
  energy_.numerical_dissipation =
      energy_.external_work - energy_.damping - (energy_.kinetic + energy_.strain - start_energy_);
}

Eigen::MatrixXd ReducedDynamics::mean_acceleration_response() const {
  HM_ASSERT(report_.converged, "no converged trial step to linearise about");
  // ā = (v₁ − v₀)/Δt moves with q₁ as γ/(βΔt²) (generalised-α) or 2/Δt² (midpoint); q₁ with
  // F_end as (1 − α_f) J⁻¹ or ½ J⁻¹, J the Newton matrix at the trial (of its last substep).
  const double dt = response_dt_;
  const Eigen::VectorXd& q1 = trial_.q;
  const Eigen::MatrixXd jacobian =
      options_.scheme == TimeScheme::energy_conserving
          ? midpoint_matrix(dt, model_.tangent(0.5 * (response_start_ + q1)), model_.tangent(q1))
          : alpha_matrix(dt, model_.tangent(q1));
  const Eigen::Index r = model_.size();
  return response_weight_ * jacobian.partialPivLu().solve(Eigen::MatrixXd::Identity(r, r));
}

}  // namespace hm::fem
