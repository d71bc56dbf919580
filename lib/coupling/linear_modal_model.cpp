#include "coupling/linear_modal_model.hpp"

#include <Eigen/Dense>

#include "core/errors.hpp"
#include "coupling/flexible_body.hpp"

namespace hm::coupling {

template <int D>
LinearModalModel<D>::LinearModalModel(std::shared_ptr<const ModalSurface<D>> modes)
    : modes_(std::move(modes)) {
  y_ = v_ = a_ = F_ = Eigen::VectorXd::Zero(modes_->modes());
}

template <int D>
WallFields LinearModalModel<D>::fields(const Eigen::VectorXd& y, const Eigen::VectorXd& v,
                                       const Eigen::VectorXd& a) const {
  return {modes_->shapes * y, modes_->shapes * v, modes_->shapes * a};
}

template <int D>
WallFields LinearModalModel<D>::wall() const {
  return fields(y_, v_, a_);
}

template <int D>
ldd::Vec<D> LinearModalModel<D>::displacement(Eigen::Index vertex) const {
  return modes_->shapes.middleRows(D * vertex, D) * y_;
}

template <int D>
double LinearModalModel<D>::deformation() const {
  const Eigen::VectorXd elastic = (modes_->omega.array() > 0.0).select(y_, 0.0);
  double largest = 0.0;
  for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(modes_->x0.size()); ++k)
    largest = std::max(largest, (modes_->shapes.middleRows(D * k, D) * elastic).norm());
  return largest;
}

template <int D>
double LinearModalModel<D>::max_speed() const {
  double speed = 0.0;
  for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(modes_->x0.size()); ++k)
    speed = std::max(speed, (modes_->shapes.middleRows(D * k, D) * v_).norm());
  return speed;
}

template <int D>
double LinearModalModel<D>::mechanical_energy() const {
  const Eigen::ArrayXd w = modes_->omega.array();
  return 0.5 * v_.squaredNorm() + 0.5 * (w * w * y_.array().square()).sum();
}

template <int D>
double LinearModalModel<D>::damping_power() const {
  return (2.0 * modes_->zeta.array() * modes_->omega.array() * v_.array().square()).sum();
}

template <int D>
StructureEnergy LinearModalModel<D>::energy() const {
  StructureEnergy e;
  e.kinetic = 0.5 * v_.squaredNorm();
  e.strain = mechanical_energy() - e.kinetic;
  e.external_work = external_work_;
  e.damping = damping_;
  e.numerical_dissipation = external_work_ - damping_ - (mechanical_energy() - start_energy_);
  return e;
}

template <int D>
Eigen::VectorXd LinearModalModel<D>::modal_acceleration() const {
  const Eigen::ArrayXd w = modes_->omega.array();
  return (F_.array() - 2.0 * modes_->zeta.array() * w * v_.array() - w * w * y_.array()).matrix();
}

template <int D>
void LinearModalModel<D>::reset(double t) {
  const Eigen::Index m = modes_->modes();
  y_ = Eigen::VectorXd::Zero(m);
  v_ = modes_->initial_velocity.size() == m ? modes_->initial_velocity : Eigen::VectorXd::Zero(m);
  a_ = F_ = Eigen::VectorXd::Zero(m);
  time_ = t;
  coefficient_dt_ = -1.0;
}

template <int D>
void LinearModalModel<D>::settle(const BodyLoad& load) {
  for (Eigen::Index i = 0; i < modes_->modes(); ++i) {
    const double w = modes_->omega[i];
    y_[i] = w > 0.0 ? load.generalised[i] / (w * w) : 0.0;
  }
}

template <int D>
void LinearModalModel<D>::start(const BodyLoad& load, const Eigen::MatrixXd* added_mass) {
  const Eigen::VectorXd& hydro = load.generalised;
  if (added_mass != nullptr) {
    const Eigen::Index m = modes_->modes();
    const Eigen::MatrixXd lhs = Eigen::MatrixXd::Identity(m, m) + *added_mass;
    const Eigen::VectorXd omega2 = modes_->omega.array().square();
    a_ = lhs.ldlt().solve(hydro - omega2.cwiseProduct(y_));
    F_ = hydro - *added_mass * a_;
  } else {
    F_ = hydro;
  }
  a_ = modal_acceleration();
  start_energy_ = mechanical_energy();
  external_work_ = damping_ = 0.0;
}

template <int D>
void LinearModalModel<D>::update_coefficients(double dt) {
  if (dt == coefficient_dt_) return;
  const Eigen::Index m = modes_->modes();
  coefficients_.resize(static_cast<std::size_t>(m));
  for (Eigen::Index i = 0; i < m; ++i)
    coefficients_[static_cast<std::size_t>(i)] =
        modal::cfpi_coefficients(modes_->omega[i], modes_->zeta[i], dt);
  coefficient_dt_ = dt;
}

template <int D>
AffineAnswer LinearModalModel<D>::predict(double dt) {
  const Eigen::Index m = modes_->modes();
  update_coefficients(dt);
  y_free_.resize(m);
  v_free_.resize(m);
  y_step_.resize(m);
  AffineAnswer answer{Eigen::MatrixXd::Zero(m, m), Eigen::VectorXd(m)};
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto& c = coefficients_[static_cast<std::size_t>(i)];
    y_free_[i] = c.a11 * y_[i] + c.a12 * v_[i] + (c.c_y - c.d_y) * F_[i];
    v_free_[i] = c.a21 * y_[i] + c.a22 * v_[i] + (c.c_v - c.d_v) * F_[i];
    // The wall acceleration the fluid sees is the step's mean, (ẏ^{n+1} − ẏ^n)/Δt: the PPE's
    // wall rows are consistent (the wall nodes' u* = U^{n+1} − Δt·A equals U^n, the velocity
    // the fluid beside the wall starts from) only when ΔU = Δt·A. With the end-of-step
    // acceleration ÿ^{n+1}, u* carried a spurious −(Δt/2)ΔA that cut the piston's added mass by
    // a quarter (tests/coupling/test_flexible_body.cpp).
    answer.slope(i, i) = c.d_v / dt;
    answer.offset[i] = (v_free_[i] - v_[i]) / dt;
    // The positions the fluid uses: the predictor F_p = Fⁿ.
    y_step_[i] = y_free_[i] + c.d_y * F_[i];
  }
  return answer;
}

template <int D>
WallFields LinearModalModel<D>::wall_in_step(const Eigen::VectorXd& mean_acceleration) const {
  // The wall's velocity follows its mean acceleration exactly (ẏ^{n+1} = ẏ^n + Δt·ā), so the
  // wall nodes' u* stays Uⁿ + Δt·g whatever the iterate (see predict).
  return fields(y_step_, v_ + coefficient_dt_ * mean_acceleration, mean_acceleration);
}

template <int D>
void LinearModalModel<D>::correct(const BodyLoad& load) {
  const Eigen::VectorXd& measured = load.generalised;
  const double power_before = damping_power();
  const Eigen::VectorXd y_before = y_, F_before = F_;
  for (Eigen::Index i = 0; i < modes_->modes(); ++i) {
    const auto& c = coefficients_[static_cast<std::size_t>(i)];
    y_[i] = y_free_[i] + c.d_y * measured[i];
    v_[i] = v_free_[i] + c.d_v * measured[i];
  }
  F_ = measured;
  time_ += coefficient_dt_;
  a_ = modal_acceleration();
  external_work_ += 0.5 * (F_before + F_).dot(y_ - y_before);
  damping_ += 0.5 * coefficient_dt_ * (power_before + damping_power());
}

template <int D>
std::map<std::string, Eigen::VectorXd> LinearModalModel<D>::extra_state() const {
  return {{"energy_balance", Eigen::Vector3d(start_energy_, external_work_, damping_)}};
}

template <int D>
void LinearModalModel<D>::restore(double time, const Eigen::VectorXd& q,
                                  const Eigen::VectorXd& q_dot, const Eigen::VectorXd& q_ddot,
                                  const Eigen::VectorXd& load,
                                  const std::map<std::string, Eigen::VectorXd>& extra) {
  time_ = time;
  y_ = q;
  v_ = q_dot;
  a_ = q_ddot;
  F_ = load;
  coefficient_dt_ = -1.0;
  // The energy balance restarts from the checkpoint's state when it did not keep one.
  const auto balance = extra.find("energy_balance");
  if (balance != extra.end() && balance->second.size() == 3) {
    start_energy_ = balance->second[0];
    external_work_ = balance->second[1];
    damping_ = balance->second[2];
  } else {
    start_energy_ = mechanical_energy();
    external_work_ = damping_ = 0.0;
  }
}

template class LinearModalModel<2>;
template class LinearModalModel<3>;

}  // namespace hm::coupling
