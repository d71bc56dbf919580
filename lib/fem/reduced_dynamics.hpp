#pragma once
// Implicit time integration of the reduced Saint Venant–Kirchhoff model (fem/reduced_stvk.hpp),
//   M_r q̈ + C_r q̇ + f_r(q) = Vᵀ f_ext(t),   C_r = α M_r + β K1   (Rayleigh; K1 = VᵀK₀V),
// M_r = VᵀMV (the identity for an M-orthonormal basis), the generalised load linear in time
// inside a step. The schemes, options (fem::DynamicsOptions), trial/commit API and energy
// balance (fem::EnergyBalance) are those of the full model (fem/nonlinear_dynamics.hpp):
//
// * generalised-α (Chung & Hulbert 1993) with ρ∞: the Galerkin projection of the full scheme —
//   the same equations restricted to span(V), so the reduced and full trajectories differ by the
//   basis alone;
// * energy-conserving: the implicit midpoint rule with the exact average of the force along the
//   step, f̄ = ∫₀¹ f_r(q₀ + s Δq) ds = (f_r(q₀) + 4 f_r(q_m) + f_r(q₁))/6 (Simpson's rule is exact
//   for the cubic f_r), a discrete gradient: Δqᵀ f̄ = W(q₁) − W(q₀) exactly. Without load and
//   damping ½q̇ᵀM_r q̇ + W(q) is kept to the Newton tolerance at any step. (The full model uses
//   Simo & Tarnow's discrete gradient; both are second order and conserving, they differ by
//   O(Δq²) in the force.)
//
// Differences from the full model: the β part of the damping is β K1 q̇, linear — it damps a
// rigid rotation, which the full model's objective viscous stress does not (immaterial for
// small rotations and small β); there are no elements, hence no inversion check.
// Each step is solved by dense Newton (fem/dense_newton.hpp) on the r unknowns, a failing step
// halved up to max_step_halvings times. Units: SI; q, v, a in the units of the basis (with an
// M-orthonormal V, m·√kg and its rates), generalised loads Vᵀf.
#include <Eigen/Core>

#include "fem/nonlinear_dynamics.hpp"
#include "fem/reduced_stvk.hpp"

namespace hm::fem {

struct ReducedState {
  double time = 0.0;           ///< [s]
  Eigen::VectorXd q, v, a;     ///< reduced displacement, velocity, acceleration
  Eigen::VectorXd load;        ///< Vᵀ f_ext at `time`
  Eigen::VectorXd internal;    ///< f_r(q) + C_r v
  double damping_power = 0.0;  ///< vᵀ C_r v [W]
};

class ReducedDynamics {
 public:
  /// `model` must outlive this object. InputError for invalid options.
  ReducedDynamics(const ReducedStvk& model, DynamicsOptions options);

  /// The state at time t: q, v under the generalised load `load`; the acceleration a from
  /// M_r a = load − f_r(q) − C_r v.
  void start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
             const Eigen::VectorXd& load);
  /// Continues from a kept state (a checkpoint): q, v, a and the load at time t, and the energy
  /// balance so far with the energy it started from [J].
  void restore(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
               const Eigen::VectorXd& a, const Eigen::VectorXd& load, const EnergyBalance& energy,
               double start_energy);
  double start_energy() const { return start_energy_; }

  /// Solves the step to t + dt with the generalised load going linearly to `load_end` (in
  /// substeps if Newton needs them); the state stays until commit().
  const NewtonReport& solve_step(double dt, const Eigen::VectorXd& load_end);
  /// Keeps the last trial as the new state (its report must have converged).
  void commit();

  const ReducedState& state() const { return state_; }
  const ReducedState& trial() const { return trial_; }
  const EnergyBalance& energy() const { return energy_; }
  const ReducedStvk& model() const { return model_; }
  const DynamicsOptions& options() const { return options_; }

  /// dā/dF_end (r × r): the response of the trial's mean acceleration ā = (v₁ − v₀)/Δt to its
  /// end load, linearised about the trial (of its last substep). The coupling's interface
  /// Jacobian in the reduced space: a full load f maps to Vᵀf, ā to V ā.
  Eigen::MatrixXd mean_acceleration_response() const;

 private:
  struct StepTotals {
    double work = 0.0, damping = 0.0;
    int iterations = 0, substeps = 0;
  };
  NewtonReport solve_substeps(double dt, const Eigen::VectorXd& load_end, int halvings_left,
                              StepTotals& totals);
  NewtonReport solve_single(double dt, const Eigen::VectorXd& load_end);
  struct Residual {
    Eigen::VectorXd value;
    Eigen::MatrixXd jacobian;
    double scale = 1.0;
  };
  Residual alpha_residual(double dt, const Eigen::VectorXd& load_end, const Eigen::VectorXd& q1,
                          bool jacobian) const;
  Residual midpoint_residual(double dt, const Eigen::VectorXd& load_end, const Eigen::VectorXd& f0,
                             const Eigen::VectorXd& q1, bool jacobian) const;
  Eigen::MatrixXd alpha_matrix(double dt, const Eigen::MatrixXd& k_end) const;
  Eigen::MatrixXd midpoint_matrix(double dt, const Eigen::MatrixXd& k_mid,
                                  const Eigen::MatrixXd& k_end) const;
  void finish_trial(double dt, const Eigen::VectorXd& q1, const Eigen::VectorXd& load_end);
  Eigen::VectorXd newmark_acceleration(double dt, const Eigen::VectorXd& q1) const;
  Eigen::VectorXd damping_force(const Eigen::VectorXd& v) const { return damping_ * v; }

  const ReducedStvk& model_;
  DynamicsOptions options_;
  Eigen::MatrixXd damping_;  ///< C_r = α M_r + β K1
  double alpha_m_ = 0.0, alpha_f_ = 0.0, gamma_ = 0.5, beta_ = 0.25;
  ReducedState state_, trial_;
  EnergyBalance energy_;
  double start_energy_ = 0.0;
  double trial_damping_ = 0.0, trial_work_ = 0.0;
  /// The trial's last substep, to linearise about: dā/dF = response_weight_·J⁻¹.
  double response_weight_ = 0.0, response_dt_ = 0.0;
  Eigen::VectorXd response_start_;
  NewtonReport report_;
};

}  // namespace hm::fem
