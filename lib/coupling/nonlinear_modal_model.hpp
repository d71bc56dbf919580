#pragma once
// A geometrically nonlinear reduced structure model: the Saint Venant–Kirchhoff body restricted
// to the basis V = [Φ, Θ] of its linear modes and their static modal derivatives (fsi-modes with
// modes.derivatives; fem/reduced_basis.hpp), its internal force the exact cubic of the reduced
// coordinates q (fem/reduced_stvk.hpp), integrated implicitly (fem/reduced_dynamics.hpp: the
// energy-conserving midpoint rule or generalised-α) behind the structure-model seam.
//
// The coupling's interface is the basis itself, mapped onto the wall (fsi-map: V_w, the
// ModalSurface's shapes): the interface coordinates are q, so
//  * the wall is u_w = V_w q (its velocity and acceleration likewise);
//  * the load is the generalised force Vᵀ(Hᵀ f_w + M T (g − Ẍ)) = s·V_wᵀ f_w + Γ_V·(g − Ẍ) (− the
//    Euler term), exactly what the coupled body computes (BodyLoad::generalised) when its
//    interface is the mapped basis with Γ_V = VᵀMT;
//  * the added mass M̂ is measured on every basis vector (one pressure solve each);
//  * the affine answer of a step is the exact linearisation of the reduced step about its
//    predictor: ā(F) = ā_p + S (F − Fⁿ), S = dā/dF_end (ReducedDynamics::
//    mean_acceleration_response), since the generalised load is all the model sees.
// Within the step the fluid sees the predictor's positions with the iterate's velocity
// v + Δt·ā and acceleration ā (as for linear modes); the corrector solves the step under the
// fluid's final load.
// The model's error is its basis: the derivatives carry the shortening a bending body drags with
// it (the gate's rising tip, which linear modes lack); the error grows with the rotation (the
// elastica at 1 rad: 8 modes with their derivatives within 0.5 % of the full model, linear modes
// alone locked; tests/fem/test_reduced.cpp).
// Cost: r = n + k(k+1)/2 vectors for n modes and the derivatives of k; M̂ takes r pressure solves
// per measurement and a step ~r⁴ operations (the cubic tensor), so k is kept small.
// Rayleigh damping α M_r + β K1 (α, β fitted to the modal damping ratio at the two lowest modes,
// as for nonlinear_fe). Units: as in flexible_body.hpp (q [m·√kg], F [N/√kg]).
#include <memory>
#include <string>

#include "coupling/structure_model.hpp"
#include "fem/reduced_dynamics.hpp"
#include "fem/reduced_stvk.hpp"

namespace hm::coupling {

/// What the model is built from.
struct NonlinearModalParts {
  /// The reduced tensors of V (modes.h5); the interface's shapes are V mapped onto the wall.
  std::unique_ptr<fem::ReducedStvk> tensors;
  fem::DynamicsOptions dynamics;
  std::string context;  ///< names the body in errors ("structure 'gate'")
};

template <int D>
class NonlinearModalModel final : public StructureModel<D> {
 public:
  /// InputError when the tensors' basis size differs from the interface's.
  NonlinearModalModel(std::shared_ptr<const ModalSurface<D>> interface, NonlinearModalParts parts);

  const char* kind() const override { return "nonlinear_modal"; }
  const ModalSurface<D>& interface() const override { return *basis_; }

  void reset(double t) override;
  void settle(const BodyLoad& load) override;
  void start(const BodyLoad& load, const Eigen::MatrixXd* added_mass) override;
  AffineAnswer predict(double dt) override;
  WallFields wall_in_step(const Eigen::VectorXd& mean_acceleration) const override;
  void correct(const BodyLoad& load) override;

  double time() const override { return dynamics_->state().time; }
  const Eigen::VectorXd& q() const override { return dynamics_->state().q; }
  const Eigen::VectorXd& q_dot() const override { return dynamics_->state().v; }
  const Eigen::VectorXd& q_ddot() const override { return dynamics_->state().a; }
  const Eigen::VectorXd& load() const override { return dynamics_->state().load; }
  WallFields wall() const override;
  ldd::Vec<D> displacement(Eigen::Index vertex) const override;
  double deformation() const override;
  double max_speed() const override;
  StructureEnergy energy() const override;
  int solver_iterations() const override { return iterations_; }

  /// The energy balance so far (its start, the work, the damping); the rest of the state is
  /// the interface coordinates.
  std::map<std::string, Eigen::VectorXd> extra_state() const override;
  void restore(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot,
               const Eigen::VectorXd& q_ddot, const Eigen::VectorXd& load,
               const std::map<std::string, Eigen::VectorXd>& extra) override;

  const fem::ReducedDynamics& dynamics() const { return *dynamics_; }

 private:
  /// Solves the step to the generalised load `load_end`; StructureFailed naming the body, the
  /// time and Newton's failure when it does not converge.
  void solve(double dt, const Eigen::VectorXd& load_end);
  /// The largest |V_w x| over the wall's vertices [m, m/s].
  double largest_on_wall(const Eigen::VectorXd& x) const;

  std::shared_ptr<const ModalSurface<D>> basis_;
  NonlinearModalParts parts_;
  std::unique_ptr<fem::ReducedDynamics> dynamics_;
  // Within a step: its length, the predictor's positions and the start's velocity.
  double step_dt_ = 0.0;
  Eigen::VectorXd predicted_q_;
  int iterations_ = 0;
};

}  // namespace hm::coupling
