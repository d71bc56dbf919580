#pragma once
// A geometrically nonlinear structure model: the total-Lagrangian finite-element body of
// lib/fem (Saint Venant–Kirchhoff or neo-Hookean, tri6 / tet10) integrated implicitly
// (generalised-α or the energy-conserving midpoint rule) behind the structure-model seam.
//
// The wall is placed where the body is: its displacement carried to the fluid's wall (FeWallMap:
// the boundary nodes, or fsi-map's RBF onto another surface). Its loads are the wall's vertex
// forces carried back conservatively plus the weight and the tank's translation as a body force
// M·T·(g − Ẍ) and a rotating tank's Euler load −M(α × (X − c)).
// The coupling's interface stays the linear modes Φ (mapped: Φ_w): the interface coordinates are
// the mass-weighted projections q = Φᵀ M u, the added mass M̂ is measured on Φ_w as for linear
// modes, and the affine answer of a step is the linearisation about its predictor,
//   ā(F) = α_p + S (F − Fⁿ),   S = Φᵀ M (∂ū/∂f) M Φ,
// ū the step's mean acceleration and ∂ū/∂f its response to the end load (one solve with the
// last Newton matrix per mode): a load change in the modal subspace is taken as M Φ δF, the load
// whose modal content is δF. The corrector solves the step under the fluid's final vertex
// forces (one Newton solve), so the body's step is exact to the Newton tolerance.
// The fluid sees the wall's velocity and acceleration in the modal subspace, Φ_w q̇ and Φ_w ā,
// while the wall's position is the body's own. What the body does beyond the interface modes is
// light and wet: handed to the fluid it would be coupled explicitly, a staggered scheme that is
// unstable at an added mass above the body's own (the gate's flow diverged at 0.085 s with 5
// modes, the elastic plate's at its impact with 10; with the modal kinematics both run, and the
// gate's tip peak moves by 1.3 % from 5 to 10 modes). The price is that the wall's normal
// velocity misses the deformation beyond the modes, which grows when too few are kept.
// Rayleigh damping: α M + β K₀ (the β part objective, lib/fem) with α, β fitted to the modal
// damping ratio at the two lowest modes (RayleighFit), plus the scene's own α and β.
// Units: SI; 2-D per the structure's thickness.
#include <memory>

#include "coupling/fe_wall_map.hpp"
#include "coupling/structure_model.hpp"
#include "fem/dof_map.hpp"
#include "fem/hyperelastic_body.hpp"
#include "fem/nonlinear_dynamics.hpp"

namespace hm::coupling {

/// Rayleigh coefficients α [1/s], β [s] giving the damping ratio ζ at ω₁ and ω₂ [rad/s]:
/// α = 2ζω₁ω₂/(ω₁ + ω₂), β = 2ζ/(ω₁ + ω₂) (ζ = 0 or no positive ω: none).
struct RayleighFit {
  double alpha = 0.0, beta = 0.0;
};
RayleighFit rayleigh_for(double zeta, double omega1, double omega2);

/// What the model is built from; the body, its clamped DOFs and the wall map it owns.
struct NonlinearFeParts {
  std::unique_ptr<fem::HyperelasticBody> body;
  std::unique_ptr<fem::DofMap> dofs;
  std::unique_ptr<FeWallMap> wall_map;
  /// The linear modes as full DOF vectors, mass-normalised (n_dofs × m) [1/√kg]: the columns of
  /// the interface's shapes before mapping.
  Eigen::MatrixXd modes;
  fem::DynamicsOptions dynamics;
  std::string context;  ///< names the body in errors ("structure 'gate'")
};

template <int D>
class NonlinearFeModel final : public StructureModel<D> {
 public:
  /// InputError when the parts do not fit each other or the interface (DOF and vertex counts).
  NonlinearFeModel(std::shared_ptr<const ModalSurface<D>> interface, NonlinearFeParts parts);

  const char* kind() const override { return "nonlinear_fe"; }
  const ModalSurface<D>& interface() const override { return *modes_; }

  void reset(double t) override;
  void settle(const BodyLoad& load) override;
  void start(const BodyLoad& load, const Eigen::MatrixXd* added_mass) override;
  AffineAnswer predict(double dt) override;
  WallFields wall_in_step(const Eigen::VectorXd& mean_acceleration) const override;
  void correct(const BodyLoad& load) override;

  double time() const override { return dynamics_->state().time; }
  const Eigen::VectorXd& q() const override { return q_; }
  const Eigen::VectorXd& q_dot() const override { return q_dot_; }
  const Eigen::VectorXd& q_ddot() const override { return q_ddot_; }
  const Eigen::VectorXd& load() const override { return F_; }
  WallFields wall() const override { return wall_; }
  ldd::Vec<D> displacement(Eigen::Index vertex) const override;
  double deformation() const override;
  double max_speed() const override;
  StructureEnergy energy() const override;
  int solver_iterations() const override { return iterations_; }

  std::map<std::string, Eigen::VectorXd> extra_state() const override;
  void restore(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot,
               const Eigen::VectorXd& q_ddot, const Eigen::VectorXd& load,
               const std::map<std::string, Eigen::VectorXd>& extra) override;

  const fem::NonlinearDynamics& dynamics() const { return *dynamics_; }

 private:
  /// The structure's nodal load of `load`: Hᵀ f_w + M T (g − Ẍ) − M(α × (X − c)) [N].
  Eigen::VectorXd nodal_load(const BodyLoad& load) const;
  /// Solves the step to `load_end` [N]; NumericalError naming the body, the time and Newton's
  /// failure when it does not converge.
  void solve(double dt, const Eigen::VectorXd& load_end);
  /// q = Φᵀ M x.
  Eigen::VectorXd project(const Eigen::VectorXd& full) const;
  /// Interface coordinates and wall fields of the kept state.
  void update_kept();

  std::shared_ptr<const ModalSurface<D>> modes_;
  NonlinearFeParts parts_;
  Eigen::MatrixXd mass_modes_;  ///< M Φ (n_dofs × m) [√kg]
  std::unique_ptr<fem::NonlinearDynamics> dynamics_;
  Eigen::VectorXd q_, q_dot_, q_ddot_, F_;
  WallFields wall_;
  // Within a step: its length, the predictor's wall positions and interface acceleration.
  double step_dt_ = 0.0;
  Eigen::VectorXd predicted_u_, predicted_alpha_;
  int iterations_ = 0;
};

}  // namespace hm::coupling
