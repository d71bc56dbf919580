#include "modal/newmark.hpp"

#include <utility>

#include "core/errors.hpp"

namespace hm::modal {

NewmarkIntegrator::NewmarkIntegrator(Eigen::VectorXd omega, Eigen::VectorXd zeta, double beta,
                                     double gamma)
    : omega_(std::move(omega)), zeta_(std::move(zeta)), beta_(beta), gamma_(gamma) {
  if (omega_.size() != zeta_.size())
    input_error("Newmark: {} circular frequencies but {} damping ratios; expected one per mode",
                omega_.size(), zeta_.size());
  y_ = v_ = a_ = Eigen::VectorXd::Zero(omega_.size());
}

void NewmarkIntegrator::set_state(const Eigen::VectorXd& y, const Eigen::VectorXd& v,
                                  const Eigen::VectorXd& F) {
  HM_ASSERT(y.size() == omega_.size() && v.size() == omega_.size() && F.size() == omega_.size(),
            "Newmark: state sizes differ from the number of modes");
  y_ = y;
  v_ = v;
  a_ = F.array() - 2 * zeta_.array() * omega_.array() * v_.array() -
       omega_.array().square() * y_.array();
}

void NewmarkIntegrator::step(const Eigen::VectorXd& F1, double dt) {
  HM_ASSERT(F1.size() == omega_.size(), "Newmark: load size differs from the number of modes");
  for (Eigen::Index i = 0; i < omega_.size(); ++i) {
    const double w = omega_[i], c = 2 * zeta_[i] * w;
    const double y_pred = y_[i] + dt * v_[i] + dt * dt * (0.5 - beta_) * a_[i];
    const double v_pred = v_[i] + dt * (1 - gamma_) * a_[i];
    const double a1 =
        (F1[i] - c * v_pred - w * w * y_pred) / (1 + c * gamma_ * dt + w * w * beta_ * dt * dt);
    y_[i] = y_pred + beta_ * dt * dt * a1;
    v_[i] = v_pred + gamma_ * dt * a1;
    a_[i] = a1;
  }
}

}  // namespace hm::modal
