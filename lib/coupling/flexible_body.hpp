#pragma once
// A flexible body of a coupled run (LDD-SPEC §3): a wall of the flow whose vertices follow a
// structure model (structure_model.hpp: linear modes by CFPI, x_v = X_v + Σ_i Φ_{v,i} y_i, or a
// geometrically nonlinear body), loaded by the fluid through the consistent nodal pressure
// forces f on the wall's vertices (ldd::wall_pressure_loads) times s, the structure's thickness
// in 2-D (the flow's forces are per metre, the 2-D structure is per its thickness), and its
// weight and the tank's motion. The coupling works in the model's interface coordinates, the
// mapped linear modes Φ_w: generalised forces F_i = s·Φ_iᵀ f (+ Γ·(g − Ẍ)), and the modal
// added mass M̂. Below, y is the interface coordinate (for linear modes, the modal coordinate).
//
// One coupled step n → n+1 (coupled_step), spec §3.4:
//   1. predictor: F_p = F^n, the model's step under F_p (CFPI((y, ẏ)^n; F^n → F_p) for linear
//      modes) gives the wall positions of the step and the affine answer ā(F) = S·F + r of the
//      step's mean interface acceleration; the wall is placed there and the flow's step begins
//      (advection ... prediction);
//   2. the PPE is solved and F = s·Φᵀf measured;
//      explicit: once (the paper's staggered scheme; unstable when the fluid's added mass of a
//      mode exceeds its own, whatever the step — Causin, Gerbeau & Nobile 2005);
//      strong: sub-iterations until the interface residual — the mismatch between the modal
//      acceleration the fluid saw and the one the structure answers its load with — is below
//      the tolerance. Each iteration is one PPE solve at the advected positions with new wall
//      velocities and accelerations, updated by a quasi-Newton step whose Jacobian is the
//      measured added-mass matrix M̂ (spec §3.4 remedies 1–2): the structure answers a load F
//      with ā = S·F + r (linear modes: S = diag κ, κ and r from the CFPI coefficients, exact;
//      a nonlinear model: its linearisation about the predictor), the fluid a wall acceleration ā
//      with F ≈ F_k − M̂(ā − ā_k), so (I + S M̂) ā_{k+1} = S(F_k + M̂ ā_k) + r. With an exact
//      M̂ and a linear PPE one iteration converges; the no-tension pass makes it nonlinear, so
//      only the first four solves of a step release wall nodes in tension and the later ones
//      keep their set (ldd::TensionRelease::kept: linear again); M̂ lags the geometry, so the
//      Jacobian −M̂ is corrected by Broyden updates from the iterates of the step, and a step
//      whose residual grew is halved;
//   3. the flow's step finishes; corrector: the model's step on the load the fluid produced
//      (exact CFPI for linear modes; the wall positions the fluid used lag by O(Δt²·ΔF)).
// M̂_jk = −s·Φ_jᵀ f(p_k), p_k the PPE's answer to a unit acceleration of mode k alone
// (FlowSolver::acceleration_pressure), symmetrised, measured at the start and every
// added_mass_interval steps (the wetted surface changes).
// Units: y [m·√kg], ẏ [m·√kg/s], ÿ [m·√kg/s²], F [N/√kg], Φ [1/√kg], M̂ [1] (modal masses).
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "coupling/structure_model.hpp"
#include "ldd/flow.hpp"
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
  int solver_iterations = 0;  ///< Newton iterations of a nonlinear structure model in the step
  StructureEnergy energy;     ///< the structure's energy balance at the step's end [J]
  /// Wall-clock time of the coupling itself [s]: loads and modal forces, CFPI, wall updates
  /// (mode superposition, normals, tree refit, wall nodes); the PPE re-solves of the
  /// sub-iterations count as the flow's (StepMonitor::seconds), the added-mass solves here.
  double seconds = 0.0;
  double added_mass_seconds = 0.0;  ///< the part of `seconds` spent measuring M̂ [s]
  double structure_seconds = 0.0;   ///< the part of `seconds` spent in the structure model [s]
};

/// What a flexible body carries between steps (a checkpoint).
struct BodyState {
  double time = 0.0;  ///< [s]
  Eigen::VectorXd y, v, a, F;
  Eigen::MatrixXd added_mass, initial_added_mass;  ///< empty for the explicit scheme
  std::map<std::string, Eigen::VectorXd> model;    ///< StructureModel::extra_state()
};

template <int D>
class FlexibleBody {
 public:
  /// A body on linear modes (LinearModalModel). `wall`: the index of this body's wall in the
  /// flow. InputError when the modes' vertex count does not match the wall's or a
  /// frequency/damping is negative.
  FlexibleBody(std::string name, ModalSurface<D> modes, int wall, const CouplingOptions& options,
               const ldd::WallMesh<D>& wall_mesh);
  /// A body on any structure model; `modes` is its interface (the model's interface()).
  FlexibleBody(std::string name, std::shared_ptr<const ModalSurface<D>> modes,
               std::unique_ptr<StructureModel<D>> model, int wall, const CouplingOptions& options,
               const ldd::WallMesh<D>& wall_mesh);

  const std::string& name() const { return name_; }
  int wall() const { return wall_; }
  /// The interface: the mapped linear modes.
  const ModalSurface<D>& modes() const { return *modes_; }
  const StructureModel<D>& model() const { return *model_; }
  const CouplingOptions& options() const { return options_; }
  /// Interface coordinates of the present state, their rates and load (the modal state for
  /// linear modes).
  const Eigen::VectorXd& y() const { return model_->q(); }
  const Eigen::VectorXd& v() const { return model_->q_dot(); }
  const Eigen::VectorXd& a() const { return model_->q_ddot(); }
  const Eigen::VectorXd& F() const { return model_->load(); }
  const Eigen::MatrixXd& added_mass() const { return added_mass_; }
  /// M̂ at the start of the run (empty for the explicit scheme).
  const Eigen::MatrixXd& initial_added_mass() const { return initial_added_mass_; }
  /// Within a step: the interface acceleration the fluid's wall has now (the step's mean).
  const Eigen::VectorXd& fluid_acceleration() const { return a_step_; }
  /// Size of the body: the diagonal of its reference bounding box [m].
  double size() const { return size_; }

  /// Displacement of wall vertex v [m] at the current state (in the body's frame).
  ldd::Vec<D> displacement(Eigen::Index vertex) const { return model_->displacement(vertex); }
  /// Largest vertex speed at the current state [m/s], the carrier's motion included.
  double max_speed() const;
  /// The largest elastic displacement of a wall vertex [m]: the rigid-body translation of a
  /// free body (ω = 0) moves it without deforming it.
  double deformation() const { return model_->deformation(); }
  /// deformation() / size().
  double stretch() const;
  /// The largest pressure on the body's wall nodes in the flow's current state [Pa].
  double peak_pressure(const ldd::FlowSolver<D>& flow) const;

  /// The fluid's modal forces s·Φᵀf [N/√kg] for the flow's pressure (or `pressure`, e.g. the
  /// added-mass response, which is inviscid); with viscous_traction f includes the wall shear
  /// of the flow's velocity (not with `pressure` given).
  Eigen::VectorXd modal_force(const ldd::FlowSolver<D>& flow,
                              std::span<const double> pressure = {}) const;
  /// The loads on the structure at time t: the fluid's (as modal_force, the vertex forces kept
  /// for a model that needs them), the body's weight and the tank's motion.
  BodyLoad load(const ldd::FlowSolver<D>& flow, double t) const;
  /// Measures M̂ on the flow's current state for steps of dt [s] (one PPE solve per mode) and
  /// keeps it.
  void measure_added_mass(ldd::FlowSolver<D>& flow, double dt);

  /// Sets the state at the flow's start: undeformed, moving with the modes' initial velocity
  /// (else at rest), under the load of the fluid at rest; with the strong scheme the load and
  /// acceleration are made consistent with the fluid's reaction (F(0⁺) = F_h − M̂ ÿ(0), spec
  /// §3.5 item 3: starting from F_h kicks the body at its dry rate). With static_start: the
  /// static deformation under F_h (linear modes: y = F_h/ω² per elastic mode), at rest (the
  /// fluid points stay where they were seeded; the deformed wall pushes out those it overlaps at
  /// the first step).
  void start(ldd::FlowSolver<D>& flow);

  BodyState state() const;

  /// Clamps the body to a tank in rigid motion (sway, roll or a table): its surface moves with
  /// the tank, x = c + X(t) + R(t)(X0 + u − c), the structure's displacement u stays relative to
  /// the tank, the fluid's load is taken in the tank's frame (Rᵀ f) and the structure's load
  /// gains the base excitation and gravity Rᵀ(g − Ẍ) and, for a rotation, the Euler term
  /// −Γ_rot(c)·α (spec §4.3; the centrifugal and Coriolis loads are left out). Call before
  /// start().
  void set_carrier(motion::RigidMotion carrier);
  /// The modal force of the body's own weight and of the tank's motion at time t,
  /// Γ·Rᵀ(g − Ẍ) − Γ_rot(c)·α [N/√kg] (zero without participation factors; InputError on a
  /// rotating tank without rotational participation factors).
  Eigen::VectorXd inertial_force(double t) const;
  /// The gravity of the flow [m/s²] (taken at start() and by coupled_step).
  void set_gravity(const ldd::Vec<D>& g) { gravity_ = g; }
  /// Continues from `state` instead of start(); InputError when the mode count differs.
  void restore(const BodyState& state);

  /// Moves `wall` to the structure's wall fields (body frame) at time t (with a carrier, its
  /// rigid motion at t added).
  void place(ldd::WallMesh<D>& wall, const WallFields& fields, double t) const;

  // The steps of coupled_step, per body; predict places the wall at t + dt.
  void predict(ldd::WallMesh<D>& wall, double dt);
  /// After a PPE solve: the new load estimate; places the wall's velocity and acceleration for
  /// the next solve (positions unchanged) and returns the interface residual.
  double iterate(ldd::WallMesh<D>& wall, const BodyLoad& measured);
  void correct(const BodyLoad& measured);
  /// Wall-clock time spent in the structure model in the present step so far (its predictor,
  /// the wall it places for each sub-iteration, its corrector) [s].
  double model_seconds() const { return model_seconds_; }

 private:
  void check_interface(const ldd::WallMesh<D>& wall_mesh);
  /// The carrier's body-frame load of a uniform acceleration, Rᵀ(g − Ẍ) at time t [m/s²].
  Eigen::VectorXd body_acceleration(double t) const;
  Eigen::VectorXd answer_to(const Eigen::VectorXd& generalised) const;

  std::string name_;
  std::shared_ptr<const ModalSurface<D>> modes_;
  std::unique_ptr<StructureModel<D>> model_;
  std::optional<motion::RigidMotion> carrier_;
  double carrier_reach_ = 0.0;  ///< max_v |X_v − pivot| + size() [m] (set_carrier)
  /// The tank's rotation where the wall was last placed (the fluid's loads are rotated back).
  mutable Eigen::Matrix<double, D, D> placed_rotation_ = Eigen::Matrix<double, D, D>::Identity();
  ldd::Vec<D> gravity_ = ldd::Vec<D>::Zero();  ///< [m/s²], from the flow at start()
  int wall_;
  CouplingOptions options_;
  double size_ = 0.0;
  Eigen::MatrixXd added_mass_;  ///< M̂ (empty until measured)
  Eigen::MatrixXd initial_added_mass_;
  // Within a step: its length, the model's affine answer, the acceleration the fluid last saw.
  double step_dt_ = 0.0;
  AffineAnswer answer_;
  Eigen::VectorXd a_step_;
  // The sub-iterations of a step: the fluid's Jacobian dF/dā (from −M̂, Broyden-updated) and the
  // last iterate.
  Eigen::MatrixXd jacobian_;
  Eigen::VectorXd last_a_, last_F_;
  double last_residual_ = 0.0;
  int iterations_ = 0;
  double model_seconds_ = 0.0;
};

/// One coupled step of the flow and its flexible bodies (the file comment). The rigid walls in
/// motion must already be at t + dt. Returns the flow's monitor; `coupling` gets one monitor per
/// body. Throws ldd::FlowDiverged like FlowSolver::step.
template <int D>
ldd::StepMonitor coupled_step(ldd::FlowSolver<D>& flow, std::span<FlexibleBody<D>> bodies,
                              double dt, std::vector<CouplingMonitor>& coupling);

}  // namespace hm::coupling
