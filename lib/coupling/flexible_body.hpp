#pragma once
// A flexible body of a coupled run (LDD-SPEC §3): a wall of the flow whose vertices follow the
// modal state, x_v = X_v + Σ_i Φ_{v,i} y_i (and the same sums of ẏ and ÿ for the wall velocity
// and acceleration), loaded by the fluid through the modal forces F_i = s·Φ_iᵀ f, f the
// consistent nodal pressure forces on the wall's vertices (ldd::wall_pressure_loads) and s the
// structure's thickness in 2-D (the flow's forces are per metre, the 2-D modes are
// mass-normalised for the thickness). The modes are integrated exactly by CFPI with the load
// linear inside each step.
//
// One coupled step n → n+1 (coupled_step), spec §3.4:
//   1. predictor: F_p = F^n, (y, ẏ)_p = CFPI((y, ẏ)^n; F^n → F_p), ÿ_p = F_p − 2ζωẏ_p − ω²y_p;
//      the wall is placed there and the flow's step begins (advection ... prediction);
//   2. the PPE is solved and F = s·Φᵀf measured;
//      explicit: once (the paper's staggered scheme; unstable when the fluid's added mass of a
//      mode exceeds its own, whatever the step — Causin, Gerbeau & Nobile 2005);
//      strong: sub-iterations until the interface residual — the mismatch between the modal
//      acceleration the fluid saw and the one the structure answers its load with — is below
//      the tolerance. Each iteration is one PPE solve at the advected positions with new wall
//      velocities and accelerations, updated by a quasi-Newton step whose Jacobian is the
//      measured added-mass matrix M̂ (spec §3.4 remedies 1–2): the structure answers a load F
//      with ÿ = κ∘F + r (κ, r from the CFPI coefficients), the fluid a wall acceleration ÿ with
//      F ≈ F_k − M̂(ÿ − ÿ_k), so (I + diag κ M̂) ÿ_{k+1} = κ∘(F_k + M̂ ÿ_k) + r. With an exact
//      M̂ and a linear PPE one iteration converges; the no-tension pass makes it nonlinear, and
//      M̂ lags the geometry, so the Jacobian −M̂ is corrected by Broyden updates from the
//      iterates of the step, and a step whose residual grew is halved;
//   3. the flow's step finishes; corrector: (y, ẏ)^{n+1} = CFPI((y, ẏ)^n; F^n → F^{n+1}) exactly
//      on the load the fluid produced (the wall positions the fluid used lag by O(Δt²·ΔF)).
// M̂_jk = −s·Φ_jᵀ f(p_k), p_k the PPE's answer to a unit acceleration of mode k alone
// (FlowSolver::acceleration_pressure), symmetrised, measured at the start and every
// added_mass_interval steps (the wetted surface changes).
// Units: y [m·√kg], ẏ [m·√kg/s], ÿ [m·√kg/s²], F [N/√kg], Φ [1/√kg], M̂ [1] (modal masses).
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include <optional>

#include "ldd/flow.hpp"
#include "modal/cfpi.hpp"
#include "motion/rigid_motion.hpp"

namespace hm::coupling {

/// The mode shapes of a body on the wall the fluid sees (hydromodal.mapped_modes).
template <int D>
struct ModalSurface {
  std::vector<ldd::Vec<D>> x0;  ///< reference vertex positions [m], the wall's vertex order
  Eigen::MatrixXd shapes;       ///< (n_vertices·D) × n_modes, DOF = D·vertex + c [1/√kg]
  Eigen::VectorXd omega;        ///< [rad/s]
  Eigen::VectorXd zeta;         ///< [1]
  /// Γ = ΦᵀM T, n_modes × D [√kg]: the modal force of a uniform acceleration (gravity, the
  /// tank's); empty = none (the body's own weight and base excitation are then left out).
  Eigen::MatrixXd participation;
  /// Φᵀ M R for unit rotations about `rotation_reference` [√kg·m]: n_modes × 1 (about z) in 2-D,
  /// n_modes × 3 (about x, y, z) in 3-D; needed on a rotating tank (the Euler term), else may be
  /// empty.
  Eigen::MatrixXd rotation_participation;
  Eigen::Vector3d rotation_reference = Eigen::Vector3d::Zero();  ///< [m]
  /// Modal velocities at the start [m·√kg/s]; empty = at rest (a body entering the water at a
  /// given speed: make_free_translation).
  Eigen::VectorXd initial_velocity;
  Eigen::Index modes() const { return shapes.cols(); }
};

enum class CouplingScheme : std::uint8_t { explicit_staggered, strong };
const char* to_string(CouplingScheme scheme);

struct CouplingOptions {
  CouplingScheme scheme = CouplingScheme::strong;
  double tolerance = 1e-3;        ///< interface residual (relative) that ends the sub-iterations
  int max_iterations = 20;        ///< PPE solves per step at most (strong)
  long added_mass_interval = 20;  ///< steps between added-mass measurements (strong)
  double load_scale = 1.0;        ///< s: 2-D, the structure's thickness [m]; 3-D 1
  /// Start from the static solution under the fluid's load at rest, y = F(0)/ω² (ẏ = 0), as an
  /// experiment that fills the tank with the structure in place does (spec §4.3), instead of
  /// from the undeformed shape with the load applied suddenly.
  bool static_start = false;
  /// Add the fluid's wall shear (ldd::wall_viscous_loads, μ = ρν) to the pressure loads.
  bool viscous_traction = false;
};

/// What the coupling did in one step.
struct CouplingMonitor {
  int iterations = 0;          ///< PPE solves of the step
  double residual = 0.0;       ///< interface residual after the last solve [1]
  bool converged = true;       ///< residual ≤ tolerance (explicit: always)
  double stretch = 0.0;        ///< max_v |Σ Φ_v y| / body size (linear-mode validity, flag > 5 %)
  double deformation = 0.0;    ///< max_v |Σ Φ_v y| of the elastic modes (ω > 0) [m]
  double peak_pressure = 0.0;  ///< largest pressure of the body's wall nodes at the step's end [Pa]
  bool added_mass_measured = false;
  /// Wall-clock time of the coupling itself [s]: loads and modal forces, CFPI, wall updates
  /// (mode superposition, normals, tree refit, wall nodes); the PPE re-solves of the
  /// sub-iterations count as the flow's (StepMonitor::seconds), the added-mass solves here.
  double seconds = 0.0;
  double added_mass_seconds = 0.0;  ///< the part of `seconds` spent measuring M̂ [s]
};

/// What a flexible body carries between steps (a checkpoint).
struct BodyState {
  double time = 0.0;  ///< [s]
  Eigen::VectorXd y, v, a, F;
  Eigen::MatrixXd added_mass, initial_added_mass;  ///< empty for the explicit scheme
};

template <int D>
class FlexibleBody {
 public:
  /// `wall`: the index of this body's wall in the flow. InputError when the modes' vertex count
  /// does not match the wall's or a frequency/damping is negative.
  FlexibleBody(std::string name, ModalSurface<D> modes, int wall, const CouplingOptions& options,
               const ldd::WallMesh<D>& wall_mesh);

  const std::string& name() const { return name_; }
  int wall() const { return wall_; }
  const ModalSurface<D>& modes() const { return modes_; }
  const CouplingOptions& options() const { return options_; }
  const Eigen::VectorXd& y() const { return y_; }
  const Eigen::VectorXd& v() const { return v_; }
  const Eigen::VectorXd& a() const { return a_; }
  const Eigen::VectorXd& F() const { return F_; }
  const Eigen::MatrixXd& added_mass() const { return added_mass_; }
  /// M̂ at the start of the run (empty for the explicit scheme).
  const Eigen::MatrixXd& initial_added_mass() const { return initial_added_mass_; }
  /// Within a step: the modal acceleration the fluid's wall has now (the step's mean).
  const Eigen::VectorXd& fluid_acceleration() const { return a_step_; }
  /// Size of the body: the diagonal of its reference bounding box [m].
  double size() const { return size_; }

  /// Displacement Σ Φ_v y of vertex v [m] at the current state.
  ldd::Vec<D> displacement(Eigen::Index vertex) const;
  /// Largest vertex speed |Σ Φ_v ẏ| at the current state [m/s].
  double max_speed() const;
  /// The largest elastic displacement max_v |Σ_{ω_i > 0} Φ_{v,i} y_i| [m]: the rigid-body
  /// translation of a free body (ω = 0) moves it without deforming it.
  double deformation() const;
  /// deformation() / size().
  double stretch() const;
  /// The largest pressure on the body's wall nodes in the flow's current state [Pa].
  double peak_pressure(const ldd::FlowSolver<D>& flow) const;

  /// The fluid's modal forces s·Φᵀf [N/√kg] for the flow's pressure (or `pressure`, e.g. the
  /// added-mass response, which is inviscid); with viscous_traction f includes the wall shear
  /// of the flow's velocity (not with `pressure` given).
  Eigen::VectorXd modal_force(const ldd::FlowSolver<D>& flow,
                              std::span<const double> pressure = {}) const;
  /// Measures M̂ on the flow's current state for steps of dt [s] (one PPE solve per mode) and
  /// keeps it.
  void measure_added_mass(ldd::FlowSolver<D>& flow, double dt);

  /// Sets the state at the flow's start: y = 0, v = the modes' initial velocity (else 0), and the
  /// load of the fluid at rest; with the strong scheme the load and acceleration are made
  /// consistent with the fluid's reaction (F(0⁺) = F_h − M̂ ÿ(0), spec §3.5 item 3: starting from
  /// F_h kicks the body at its dry rate). With static_start: y = F_h/ω² for every elastic mode, ÿ =
  /// 0 (the fluid points stay where they were seeded; the deformed wall pushes out those it
  /// overlaps at the first step).
  void start(ldd::FlowSolver<D>& flow);

  BodyState state() const { return {time_, y_, v_, a_, F_, added_mass_, initial_added_mass_}; }

  /// Clamps the body to a tank in rigid motion (sway, roll or a table): its surface moves with
  /// the tank, x = c + X(t) + R(t)(X0 + ΣΦy − c), the modes stay relative to the tank, the
  /// fluid's load is taken in the tank's frame (Φᵀ Rᵀ f) and the modal load gains the base
  /// excitation and gravity Γ·Rᵀ(g − Ẍ) and, for a rotation, the Euler term −Γ_rot(c)·α
  /// (spec §4.3; the centrifugal and Coriolis loads are left out). Call before start().
  void set_carrier(motion::RigidMotion carrier);
  /// The modal force of the body's own weight and of the tank's motion at time t,
  /// Γ·Rᵀ(g − Ẍ) − Γ_rot(c)·α [N/√kg] (zero without participation factors; InputError on a
  /// rotating tank without rotational participation factors).
  Eigen::VectorXd inertial_force(double t) const;
  /// The gravity of the flow [m/s²] (taken at start() and by coupled_step).
  void set_gravity(const ldd::Vec<D>& g) { gravity_ = g; }
  /// Continues from `state` instead of start(); InputError when the mode count differs.
  void restore(const BodyState& state);

  /// Moves `wall` to the modal state (y, v, a) at time t (positions, velocities,
  /// accelerations; with a carrier, its rigid motion at t added).
  void place(ldd::WallMesh<D>& wall, const Eigen::VectorXd& y, const Eigen::VectorXd& v,
             const Eigen::VectorXd& a, double t) const;

  // The steps of coupled_step, per body; predict places the wall at t + dt.
  void predict(ldd::WallMesh<D>& wall, double dt);
  /// After a PPE solve: the new load estimate; places the wall's velocity and acceleration for
  /// the next solve (positions unchanged) and returns the interface residual.
  double iterate(ldd::WallMesh<D>& wall, const Eigen::VectorXd& measured);
  void correct(const Eigen::VectorXd& measured);

 private:
  Eigen::VectorXd field(const Eigen::VectorXd& q, Eigen::Index vertex) const;
  void update_coefficients(double dt);
  /// ÿ = F − 2ζωẏ − ω²y of the current state.
  Eigen::VectorXd modal_acceleration() const;

  std::string name_;
  ModalSurface<D> modes_;
  std::optional<motion::RigidMotion> carrier_;
  double carrier_reach_ = 0.0;  ///< max_v |X_v − pivot| + size() [m] (set_carrier)
  /// The tank's rotation where the wall was last placed (the fluid's loads are rotated back).
  mutable Eigen::Matrix<double, D, D> placed_rotation_ = Eigen::Matrix<double, D, D>::Identity();
  ldd::Vec<D> gravity_ = ldd::Vec<D>::Zero();  ///< [m/s²], from the flow at start()
  double time_ = 0.0;                          ///< of the state y_, v_ [s]
  int wall_;
  CouplingOptions options_;
  double size_ = 0.0;
  Eigen::VectorXd y_, v_, a_, F_;  ///< state at the current time
  Eigen::MatrixXd added_mass_;     ///< M̂ (empty until measured)
  Eigen::MatrixXd initial_added_mass_;
  // Within a step: the CFPI coefficients and the parts of y1, v1 that do not depend on F1.
  std::vector<modal::CfpiCoefficients> coefficients_;
  Eigen::VectorXd y_free_, v_free_, kappa_, rest_;
  Eigen::VectorXd y_step_, a_step_;  ///< positions the fluid uses, acceleration it last saw
  // The sub-iterations of a step: the fluid's Jacobian dF/dā (from −M̂, Broyden-updated) and the
  // last iterate.
  Eigen::MatrixXd jacobian_;
  Eigen::VectorXd last_a_, last_F_;
  double last_residual_ = 0.0;
  int iterations_ = 0;
  double coefficient_dt_ = -1.0;
};

/// One coupled step of the flow and its flexible bodies (the file comment). The rigid walls in
/// motion must already be at t + dt. Returns the flow's monitor; `coupling` gets one monitor per
/// body. Throws ldd::FlowDiverged like FlowSolver::step.
template <int D>
ldd::StepMonitor coupled_step(ldd::FlowSolver<D>& flow, std::span<FlexibleBody<D>> bodies,
                              double dt, std::vector<CouplingMonitor>& coupling);

}  // namespace hm::coupling
