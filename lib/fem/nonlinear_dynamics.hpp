#pragma once
// Implicit time integration of a geometrically nonlinear body,
//   M ü + C(u) u̇ + f(u) = f_ext(t),   C(u) u̇ = α M u̇ + β ∫ B(F)ᵀ ℂ₀ Ė dV₀   (Rayleigh, objective β
// part: fem/hyperelastic_body.hpp), with the load linear in time inside a step:
//
// * generalised-α (Chung & Hulbert 1993) with spectral radius ρ∞ ∈ [0, 1] at infinite step:
//   α_m = (2ρ∞ − 1)/(ρ∞ + 1), α_f = ρ∞/(ρ∞ + 1), γ = ½ − α_m + α_f, β_N = ¼(1 − α_m + α_f)²,
//   M a_{1−α_m} + (1 − α_f)(f + f_d)(u₁, u̇₁) + α_f (f + f_d)(u₀, u̇₀) = f_ext(t_{1−α_f}),
//   with Newmark's u₁, u̇₁ in a₁. Second-order accurate, unconditionally stable; ρ∞ = 1 is the
//   trapezoidal rule (no numerical dissipation), smaller ρ∞ damps the unresolved high
//   frequencies, the lower ones barely.
// * energy-conserving: the implicit midpoint rule with the discrete-gradient force (Gonzalez
//   2000; Simo–Tarnow for StVK), M(u̇₁ − u̇₀)/Δt = f_ext,m − f_alg(u₀, u₁) − C u̇_m,
//   (u₁ − u₀)/Δt = u̇_m: without load and damping ½u̇ᵀMu̇ + ∫W is conserved exactly (to the Newton
//   tolerance) at any step. Its "acceleration" is the step's mean (u̇₁ − u̇₀)/Δt.
//
// Every step is solved by Newton (fem/newton.hpp) on the free DOFs; a step is first solved as a
// trial (solve_step) and then kept (commit), so that a coupling can re-solve it under other loads.
// The energy balance is kept: kinetic + strain energy, the work of the external loads (the
// trapezoidal rule on the step's linear load, exact for the midpoint scheme), the energy taken by
// the damping, and the rest — the integrator's own (numerical) dissipation.
// Units: SI (m, m/s, m/s², N, J, s).
#include <cstdint>
#include <initializer_list>
#include <string_view>

#include <Eigen/Core>

#include "fem/dof_map.hpp"
#include "fem/hyperelastic_body.hpp"
#include "fem/newton.hpp"

namespace hm::fem {

enum class TimeScheme : std::uint8_t { generalized_alpha, energy_conserving };
const char* to_string(TimeScheme scheme);
/// "generalized_alpha" | "energy_conserving"; InputError naming `context` otherwise.
TimeScheme time_scheme_from(std::string_view name, std::string_view context);

struct DynamicsOptions {
  TimeScheme scheme = TimeScheme::generalized_alpha;
  double rho_infinity = 0.8;    ///< generalised-α ρ∞ ∈ [0, 1]
  double rayleigh_alpha = 0.0;  ///< α [1/s]
  double rayleigh_beta = 0.0;   ///< β [s]
  /// A step whose Newton solve fails is split in two halves (the load still linear in time),
  /// and so on up to this many times (2⁶ = 64 substeps at most by default).
  int max_step_halvings = 6;
  NewtonOptions newton;
};

/// InputError naming `context` for ρ∞ outside [0, 1] or negative Rayleigh coefficients.
void validate(const DynamicsOptions& options, std::string_view context);

struct DynamicState {
  double time = 0.0;           ///< [s]
  Eigen::VectorXd u, v, a;     ///< full DOF displacement, velocity, acceleration
  Eigen::VectorXd load;        ///< f_ext at `time` [N]
  Eigen::VectorXd internal;    ///< (f + f_d)(u, v) [N]
  double damping_power = 0.0;  ///< u̇ᵀ C u̇ [W]
};

struct EnergyBalance {
  double kinetic = 0.0;        ///< ½ u̇ᵀ M u̇ [J]
  double strain = 0.0;         ///< ∫ W dV₀ [J]
  double external_work = 0.0;  ///< ∫ f_extᵀ u̇ dt since the start [J]
  double damping = 0.0;        ///< energy taken by the Rayleigh damping since the start [J]
  /// external_work − damping − (kinetic + strain − their start): what the integrator removed.
  double numerical_dissipation = 0.0;
};

class NonlinearDynamics {
 public:
  /// `body` and `dofs` must outlive this object.
  NonlinearDynamics(const HyperelasticBody& body, const DofMap& dofs, DynamicsOptions options);

  /// The state at time t: displacement u, velocity v (full DOFs, zero at clamped DOFs) under the
  /// external load `load`; the acceleration from M a = load − f(u) − C v.
  void start(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
             const Eigen::VectorXd& load);

  /// Continues from a kept state (a checkpoint): displacement, velocity, acceleration and load
  /// at time t, and the energy balance so far with the energy it started from [J].
  void restore(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               const Eigen::VectorXd& a, const Eigen::VectorXd& load, const EnergyBalance& energy,
               double start_energy);
  double start_energy() const { return start_energy_; }

  /// Solves the step to t + dt with the external load going linearly to `load_end`, in
  /// substeps if Newton needs them; the state stays as it is until commit(). The report says
  /// whether every Newton solve converged, their iterations summed and the substeps taken.
  const NewtonReport& solve_step(double dt, const Eigen::VectorXd& load_end);
  /// Keeps the last trial as the new state (its report must have converged).
  void commit();

  const DynamicState& state() const { return state_; }
  const DynamicState& trial() const { return trial_; }
  const EnergyBalance& energy() const { return energy_; }
  const HyperelasticBody& body() const { return body_; }
  const DofMap& dofs() const { return dofs_; }
  const DynamicsOptions& options() const { return options_; }

  /// ∂ū/∂f_end, the response of the trial's mean acceleration ū = (v₁ − v₀)/Δt to its end
  /// load, applied to `load` (full DOFs): the linearisation about the last trial (one solve with
  /// the last Newton matrix; of the last substep when the step was split). The coupling's
  /// interface Jacobian.
  Eigen::MatrixXd mean_acceleration_response(const Eigen::MatrixXd& load) const;

 private:
  struct StepTotals {
    double work = 0.0, damping = 0.0;
    int iterations = 0, substeps = 0;
  };
  NewtonReport solve_substeps(double dt, const Eigen::VectorXd& load_end, int halvings_left,
                              StepTotals& totals);
  /// One Newton solve from state_ to t + dt; the result in trial_, trial_damping_.
  NewtonReport solve_single(double dt, const Eigen::VectorXd& load_end);
  NewtonEquations alpha_equations(double dt, const Eigen::VectorXd& load_end) const;
  NewtonEquations midpoint_equations(double dt, const Eigen::VectorXd& load_end) const;
  void finish_trial(double dt, const Eigen::VectorXd& x, const Eigen::VectorXd& load_end);
  Eigen::VectorXd newmark_acceleration(double dt, const Eigen::VectorXd& u1) const;
  double force_scale(std::initializer_list<const Eigen::VectorXd*> terms) const;

  const HyperelasticBody& body_;
  const DofMap& dofs_;
  DynamicsOptions options_;
  double alpha_m_ = 0.0, alpha_f_ = 0.0, gamma_ = 0.5, beta_ = 0.25;
  DynamicState state_, trial_;
  EnergyBalance energy_;
  double start_energy_ = 0.0;
  double trial_damping_ = 0.0;         ///< damping energy of the trial step [J]
  double trial_work_ = 0.0;            ///< work of the external load over the trial step [J]
  double jacobian_mass_weight_ = 0.0;  ///< dā/du₁ factor of the trial's scheme [1/s²]
  TangentSolver solver_;
  NewtonReport report_;
};

}  // namespace hm::fem
