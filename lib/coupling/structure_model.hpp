#pragma once
// The structure-model seam (DESIGN.md, "Seams"): what a coupled body (flexible_body.hpp) asks of
// the structure under it, whatever model that is — linear modes integrated exactly by CFPI
// (linear_modal_model.hpp) or a geometrically nonlinear body (nonlinear_fe_model.hpp, ...).
//
// The coupling sees a model through
//  * its interface coordinates q (m of them) and their wall shapes Φ_w, the mapped linear modes
//    of ModalSurface::shapes (D·n_vertices × m): the fluid's added mass M̂ is measured on Φ_w, and
//    the strong coupling iterates the step's mean interface acceleration ā (flexible_body.hpp);
//  * loads (BodyLoad): the forces on the wall's vertices and the body's uniform acceleration
//    g − Ẍ, with their generalised force F = s·Φ_wᵀ f + Γ·(g − Ẍ) (− the Euler term) on q;
//  * a step in three calls: predict(Δt) solves the step under the load of its start (F_p = Fⁿ)
//    and returns the affine answer ā(F) ≈ S·F + r of the mean interface acceleration to the
//    step's end load — exact for linear modes, the linearisation about the predictor otherwise;
//    wall_in_step(ā) gives the wall the fluid sees for an iterate ā (the predictor's positions,
//    velocities and accelerations from ā); correct(load) solves the step under the fluid's
//    final load and keeps it;
//  * its state: interface coordinates q, q̇, q̈ and F of the kept state (for a full model the
//    mass-weighted projections q = Φᵀ M u onto the linear modes), the wall's fields, energies.
// Everything is in the body's frame: a carrier's rigid motion is the coupled body's business.
// Units: as in flexible_body.hpp (q [m·√kg], F [N/√kg]); fields in m, m/s, m/s²; energies in J
// (2-D: per the structure's thickness, like its mass).
#include <map>
#include <memory>
#include <string>

#include <Eigen/Core>

#include "core/errors.hpp"
#include "ldd/common.hpp"

namespace hm::coupling {

template <int D>
struct ModalSurface;

/// A structure model that cannot take its step (Newton not converging, an element inverted):
/// the run stops (exit 3) with this report; the time loop writes the flow's state as the
/// diverged snapshot first.
struct StructureFailed : NumericalError {
  explicit StructureFailed(const std::string& report) : NumericalError(report) {}
};

/// The loads on a structure at one instant, in the body's frame.
struct BodyLoad {
  /// Forces on the wall's vertices, D per vertex [N] (2-D: already times the thickness s).
  Eigen::VectorXd wall_force;
  /// Uniform acceleration of the body's weight and its carrier's translation, g − Ẍ [m/s²].
  Eigen::VectorXd acceleration;
  /// A rotating carrier's angular acceleration α [rad/s²] about `pivot` [m] (body frame): the
  /// Euler load −ρ α × (X − c) (the centrifugal and Coriolis loads are left out).
  Eigen::Vector3d angular_acceleration = Eigen::Vector3d::Zero();
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();
  /// The generalised force of both on the interface coordinates [N/√kg].
  Eigen::VectorXd generalised;
};

/// The wall's fields, D per vertex in the body frame: displacement [m], velocity [m/s] and
/// acceleration [m/s²] relative to the reference surface.
struct WallFields {
  Eigen::VectorXd u, v, a;
};

/// The mean interface acceleration of a step as a function of its end load: ā = S·F + r.
struct AffineAnswer {
  Eigen::MatrixXd slope;   ///< S [1]
  Eigen::VectorXd offset;  ///< r [m·√kg/s²]
};

/// Energy of the structure since the start of the run [J].
struct StructureEnergy {
  double kinetic = 0.0;
  double strain = 0.0;
  double external_work = 0.0;  ///< of the fluid's loads and the body's weight
  double damping = 0.0;        ///< taken by the structural damping
  /// external_work − damping − (kinetic + strain − their start): what the time integration
  /// removed (or, for CFPI, the error of the trapezoidal rule the work is summed with).
  double numerical_dissipation = 0.0;
};

template <int D>
class StructureModel {
 public:
  virtual ~StructureModel() = default;

  /// The scene's name of the model ("linear_modal", "nonlinear_fe", ...).
  virtual const char* kind() const = 0;
  /// The interface (the mapped linear modes), shared with the coupled body.
  virtual const ModalSurface<D>& interface() const = 0;

  /// Resets to the undeformed shape at time t [s], moving with the interface's initial
  /// velocity (none: at rest); the load is not yet known.
  virtual void reset(double t) = 0;
  /// Deforms to the static equilibrium under `load` (structure.static_start), at rest.
  virtual void settle(const BodyLoad& load) = 0;
  /// Takes `load` as the load of the present state, which fixes the acceleration. With the added
  /// mass M̂ of the strong coupling (nullptr: none) the load is made consistent with the fluid's
  /// reaction to that acceleration: q̈ solves (I + M̂)q̈ = q̈_dry and the load loses M̂·q̈.
  virtual void start(const BodyLoad& load, const Eigen::MatrixXd* added_mass) = 0;

  /// Solves the step of dt [s] under the load of its start and returns the affine answer.
  virtual AffineAnswer predict(double dt) = 0;
  /// The wall within the step for a mean interface acceleration ā: the predictor's positions,
  /// velocities v + Δt·a and accelerations a of ā.
  virtual WallFields wall_in_step(const Eigen::VectorXd& mean_acceleration) const = 0;
  /// Solves the step under the fluid's final load and keeps it. StructureFailed naming the
  /// failure (step, element) when a nonlinear solve does not converge, here or in predict().
  virtual void correct(const BodyLoad& load) = 0;

  virtual double time() const = 0;
  /// Interface coordinates of the kept state and its load.
  virtual const Eigen::VectorXd& q() const = 0;
  virtual const Eigen::VectorXd& q_dot() const = 0;
  virtual const Eigen::VectorXd& q_ddot() const = 0;
  virtual const Eigen::VectorXd& load() const = 0;
  /// The wall's fields of the kept state.
  virtual WallFields wall() const = 0;
  /// Displacement of one wall vertex [m] of the kept state.
  virtual ldd::Vec<D> displacement(Eigen::Index vertex) const = 0;
  /// The largest elastic displacement of a wall vertex [m] (rigid-body motion left out).
  virtual double deformation() const = 0;
  /// The largest speed of a wall vertex [m/s].
  virtual double max_speed() const = 0;
  virtual StructureEnergy energy() const = 0;
  /// Newton iterations of the last step (0 for a linear model).
  virtual int solver_iterations() const { return 0; }

  /// Model state beyond the interface coordinates, for checkpoints: named vectors (empty for
  /// the linear modes, whose state is q, q̇, q̈ and F).
  virtual std::map<std::string, Eigen::VectorXd> extra_state() const { return {}; }
  /// Continues from a checkpoint: the interface state and extra_state() as written.
  virtual void restore(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot,
                       const Eigen::VectorXd& q_ddot, const Eigen::VectorXd& load,
                       const std::map<std::string, Eigen::VectorXd>& extra) = 0;
};

}  // namespace hm::coupling
