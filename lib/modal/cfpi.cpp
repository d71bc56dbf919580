#include "modal/cfpi.hpp"

#include <cmath>
#include <utility>

#include <Eigen/Dense>

#include "core/errors.hpp"

namespace hm::modal {
namespace {

// Dimensionless propagator: ω = 1, step θ = ω·Δt. A21 = −A12. G1 and G2 are the responses at θ
// to a unit constant load and to a unit-slope ramp (zero initial state).
struct Dimensionless {
  double A11, A12, A22, G1, G2;
};

// Taylor series of exp(θ·M) for the augmented state (y, v, f, f'):
//   M = [[0,1,0,0], [-1,-2ζ,1,0], [0,0,0,1], [0,0,0,0]].
// Used while ‖θ·M‖ ≲ 2: the terms do not cancel, and each entry — in particular the small ones,
// G1 ≈ θ²/2 and G2 ≈ θ³/6 — keeps full relative precision.
Dimensionless taylor_propagator(double zeta, double theta) {
  Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
  M(0, 1) = 1;
  M(1, 0) = -1;
  M(1, 1) = -2 * zeta;
  M(1, 2) = 1;
  M(2, 3) = 1;
  M *= theta;
  Eigen::Matrix4d E = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d term = Eigen::Matrix4d::Identity();
  for (int k = 1; k < 60; ++k) {
    term = (term * M) / k;
    E += term;
    const bool converged =
        ((term.array().abs() <= 1e-18 * E.array().abs()) || (term.array() == 0.0)).all();
    if (converged) break;
  }
  return {E(0, 0), E(0, 1), E(1, 1), E(0, 2), E(0, 3)};
}

// Closed form with cos/sin (ζ < 1) or cosh/sinh (ζ > 1), continuous through ζ = 1 because
// cos(X) and sin(X)/X are even in the "frequency" X = θ·√|1 − ζ²|. The damping factor
// e^{−ζθ} is folded into the hyperbolic functions for large X so that no huge·tiny product forms.
Dimensionless trig_propagator(double zeta, double theta) {
  const double s2 = 1.0 - zeta * zeta;
  const double X = theta * std::sqrt(std::fabs(s2));
  const double e = std::exp(-zeta * theta);
  double eC = 0, eS = 0;  // e·cos(X), e·sin(X)/X  (or the hyperbolic versions)
  if (X < 1e-3) {
    const double x2 = s2 >= 0 ? -X * X : X * X;
    eC = e * (1.0 + x2 / 2 + x2 * x2 / 24 + x2 * x2 * x2 / 720);
    eS = e * (1.0 + x2 / 6 + x2 * x2 / 120 + x2 * x2 * x2 / 5040);
  } else if (s2 >= 0) {
    eC = e * std::cos(X);
    eS = e * std::sin(X) / X;
  } else if (X < 20) {
    eC = e * std::cosh(X);
    eS = e * std::sinh(X) / X;
  } else {
    const double q = std::sqrt((zeta - 1) * (zeta + 1));
    const double slow = std::exp(-theta / (zeta + q));  // e^{X − ζθ}, exponent formed stably
    const double fast = std::exp(-X - zeta * theta);
    eC = 0.5 * (slow + fast);
    eS = 0.5 * (slow - fast) / X;
  }
  Dimensionless d{};
  d.A11 = eC + zeta * theta * eS;
  d.A12 = theta * eS;
  d.A22 = eC - zeta * theta * eS;
  d.G1 = 1.0 - d.A11;
  d.G2 = theta - 2 * zeta * d.G1 - d.A12;
  return d;
}

// φ1(z) = (e^z − 1)/z and φ2(z) = (e^z − 1 − z)/z², accurate for every z ≤ 0.
double phi1(double z) {
  return z == 0.0 ? 1.0 : std::expm1(z) / z;
}
double phi2(double z) {
  if (std::fabs(z) < 0.5) {
    double sum = 0, term = 0.5;  // z^k/(k+2)!
    for (int k = 0; k < 30 && std::fabs(term) > 1e-19 * std::fabs(sum); ++k) {
      sum += term;
      term *= z / (k + 3);
    }
    return sum;
  }
  return (std::expm1(z) - z) / (z * z);
}

// Clearly over-damped modes (ζ > 1.25): the two real decay rates z_s = −θ/(ζ+q) (slow) and
// z_f = −θ(ζ+q) (fast), q = √(ζ²−1), differ by a factor ≥ 4, so divided differences of e^z,
// φ1 and φ2 between them are well conditioned. This keeps precision where the slow rate is tiny
// (large ζ), which the cosh/sinh form loses in G1 = 1 − A11.
Dimensionless overdamped_propagator(double zeta, double theta) {
  const double q = std::sqrt((zeta - 1) * (zeta + 1));
  const double p = zeta + q;
  const double zs = -theta / p, zf = -theta * p, dz = 2 * theta * q;
  const double es = std::exp(zs), ef = std::exp(zf);
  Dimensionless d{};
  d.A11 = (zs * ef - zf * es) / dz;
  d.A12 = theta * (es - ef) / dz;
  d.A22 = (zs * es - zf * ef) / dz;
  d.G1 = theta * theta * (phi1(zs) - phi1(zf)) / dz;
  d.G2 = theta * theta * theta * (phi2(zs) - phi2(zf)) / dz;
  return d;
}

Dimensionless dimensionless_propagator(double zeta, double theta) {
  if (theta * (1 + 2 * zeta) <= 2.0) return taylor_propagator(zeta, theta);
  if (zeta <= 1.25) return trig_propagator(zeta, theta);
  return overdamped_propagator(zeta, theta);
}

CfpiCoefficients rigid_body_coefficients(double dt) {
  CfpiCoefficients c;
  c.a11 = 1;
  c.a12 = dt;
  c.a21 = 0;
  c.a22 = 1;
  c.c_y = dt * dt / 2;
  c.d_y = dt * dt / 6;
  c.c_v = dt;
  c.d_v = dt / 2;
  return c;
}

}  // namespace

CfpiCoefficients cfpi_coefficients(double omega, double zeta, double dt) {
  if (!(std::isfinite(omega) && omega >= 0))
    input_error("CFPI: circular frequency omega = {} rad/s; expected a finite value >= 0", omega);
  if (!(std::isfinite(zeta) && zeta >= 0))
    input_error("CFPI: damping ratio zeta = {}; expected a finite value >= 0", zeta);
  if (!(std::isfinite(dt) && dt > 0))
    input_error("CFPI: time step dt = {} s; expected a finite value > 0", dt);

  const double theta = omega * dt;
  if (theta * (1 + 2 * zeta) < 1e-60) return rigid_body_coefficients(dt);

  const Dimensionless d = dimensionless_propagator(zeta, theta);
  const double w2 = omega * omega;
  CfpiCoefficients c;
  c.a11 = d.A11;
  c.a12 = d.A12 / omega;
  c.a21 = -omega * d.A12;
  c.a22 = d.A22;
  c.c_y = d.G1 / w2;
  c.d_y = d.G2 / (theta * w2);
  c.c_v = d.A12 / omega;  // velocity response to a unit constant load = impulse response g(Δt)
  c.d_v = d.G1 / (theta * omega);
  return c;
}

CfpiIntegrator::CfpiIntegrator(Eigen::VectorXd omega, Eigen::VectorXd zeta)
    : omega_(std::move(omega)), zeta_(std::move(zeta)) {
  if (omega_.size() != zeta_.size())
    input_error(
        "CFPI: {} circular frequencies but {} damping ratios; expected one of each per mode",
        omega_.size(), zeta_.size());
  for (Eigen::Index i = 0; i < omega_.size(); ++i) {
    if (!(std::isfinite(omega_[i]) && omega_[i] >= 0))
      input_error("CFPI: mode {}: omega = {} rad/s; expected a finite value >= 0", i, omega_[i]);
    if (!(std::isfinite(zeta_[i]) && zeta_[i] >= 0))
      input_error("CFPI: mode {}: zeta = {}; expected a finite value >= 0", i, zeta_[i]);
  }
  y_ = v_ = a_ = Eigen::VectorXd::Zero(omega_.size());
  coeffs_.resize(omega_.size());
}

void CfpiIntegrator::check_size(const Eigen::VectorXd& x, const char* what) const {
  if (x.size() != omega_.size())
    input_error("CFPI: {} has {} entries; expected one per mode ({})", what, x.size(),
                omega_.size());
}

void CfpiIntegrator::set_state(const Eigen::VectorXd& y, const Eigen::VectorXd& v,
                               const Eigen::VectorXd& F) {
  check_size(y, "modal displacement y");
  check_size(v, "modal velocity v");
  check_size(F, "modal force F");
  y_ = y;
  v_ = v;
  a_ = F.array() - 2 * zeta_.array() * omega_.array() * v_.array() -
       omega_.array().square() * y_.array();
}

void CfpiIntegrator::update_coefficients(double dt) {
  if (dt == cached_dt_) return;
  for (Eigen::Index i = 0; i < omega_.size(); ++i)
    coeffs_[i] = cfpi_coefficients(omega_[i], zeta_[i], dt);
  cached_dt_ = dt;
}

void CfpiIntegrator::step(const Eigen::VectorXd& F0, const Eigen::VectorXd& F1, double dt) {
  check_size(F0, "modal force F0");
  check_size(F1, "modal force F1");
  update_coefficients(dt);
  for (Eigen::Index i = 0; i < omega_.size(); ++i) {
    const CfpiCoefficients& c = coeffs_[i];
    const double dF = F1[i] - F0[i];
    const double y1 = c.a11 * y_[i] + c.a12 * v_[i] + c.c_y * F0[i] + c.d_y * dF;
    const double v1 = c.a21 * y_[i] + c.a22 * v_[i] + c.c_v * F0[i] + c.d_v * dF;
    y_[i] = y1;
    v_[i] = v1;
    const double w = omega_[i];
    a_[i] = F1[i] - (w == 0.0 ? 0.0 : 2 * zeta_[i] * w * v1 + w * w * y1);
  }
}

}  // namespace hm::modal
