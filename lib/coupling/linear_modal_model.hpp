#pragma once
// Linear modes integrated exactly by CFPI (LDD-SPEC §2–3): the structure model of the paper.
// The interface coordinates are the modal coordinates y themselves, the wall the superposition
// x_v = X_v + Σ_i Φ_{v,i} y_i, each mode ÿ + 2ζωẏ + ω²y = F integrated exactly with F linear
// inside the step, so the step's mean acceleration is affine in its end load with a diagonal
// slope: ā_i = κ_i F_i + r_i, κ_i = d_v,i/Δt (exact; the strong coupling converges in one
// iteration with an exact M̂).
// Valid while the displacements stay small against the body (structure_stretch ≲ 5 %): linear
// modes move every point along a fixed direction, so a large rotation stretches the body.
#include <memory>
#include <vector>

#include "coupling/structure_model.hpp"
#include "modal/cfpi.hpp"

namespace hm::coupling {

template <int D>
class LinearModalModel final : public StructureModel<D> {
 public:
  explicit LinearModalModel(std::shared_ptr<const ModalSurface<D>> modes);

  const char* kind() const override { return "linear_modal"; }
  const ModalSurface<D>& interface() const override { return *modes_; }

  void reset(double t) override;
  void settle(const BodyLoad& load) override;
  void start(const BodyLoad& load, const Eigen::MatrixXd* added_mass) override;
  AffineAnswer predict(double dt) override;
  WallFields wall_in_step(const Eigen::VectorXd& mean_acceleration) const override;
  void correct(const BodyLoad& load) override;

  double time() const override { return time_; }
  const Eigen::VectorXd& q() const override { return y_; }
  const Eigen::VectorXd& q_dot() const override { return v_; }
  const Eigen::VectorXd& q_ddot() const override { return a_; }
  const Eigen::VectorXd& load() const override { return F_; }
  WallFields wall() const override;
  ldd::Vec<D> displacement(Eigen::Index vertex) const override;
  double deformation() const override;
  double max_speed() const override;
  StructureEnergy energy() const override;

  /// The energy balance so far (its start, the work, the damping), so a restart continues it.
  std::map<std::string, Eigen::VectorXd> extra_state() const override;
  void restore(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot,
               const Eigen::VectorXd& q_ddot, const Eigen::VectorXd& load,
               const std::map<std::string, Eigen::VectorXd>& extra) override;

 private:
  WallFields fields(const Eigen::VectorXd& y, const Eigen::VectorXd& v,
                    const Eigen::VectorXd& a) const;
  void update_coefficients(double dt);
  /// ÿ = F − 2ζωẏ − ω²y of the current state.
  Eigen::VectorXd modal_acceleration() const;
  double mechanical_energy() const;
  double damping_power() const;

  std::shared_ptr<const ModalSurface<D>> modes_;
  double time_ = 0.0;              ///< of the state [s]
  Eigen::VectorXd y_, v_, a_, F_;  ///< state at time_
  // Within a step: the CFPI coefficients and the parts of y1, v1 that do not depend on F1.
  std::vector<modal::CfpiCoefficients> coefficients_;
  double coefficient_dt_ = -1.0;
  Eigen::VectorXd y_free_, v_free_, y_step_;
  // The energy balance (StructureEnergy) summed over the kept steps.
  double start_energy_ = 0.0, external_work_ = 0.0, damping_ = 0.0;
};

}  // namespace hm::coupling
