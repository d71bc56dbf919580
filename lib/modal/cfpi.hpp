#pragma once
// CFPI: exact time stepping of uncoupled modal equations (LDD-SPEC §2).
//
// Per mode i:  ÿ + 2ζω ẏ + ω² y = F(t),  with F linear inside each step [t, t+Δt]
// (F(τ) = F0 + (F1 − F0)·τ/Δt). The update is the exact solution of that ODE, in the slope form
// of LDD-SPEC §2.4 (Nigam–Jennings recurrence):
//
//   y1 = a11·y0 + a12·v0 + c_y·F0 + d_y·(F1 − F0)
//   v1 = a21·y0 + a22·v0 + c_v·F0 + d_v·(F1 − F0)
//
// Units: ω in rad/s, ζ dimensionless, Δt in s. With mass-normalised modes the modal force F is in
// N/√kg, y in m·√kg, v in m·√kg/s, a in m·√kg/s².
//
// Validity: every ζ ≥ 0 (under-, critically and over-damped) and ω ≥ 0. The coefficients keep full
// relative precision from ω·Δt = 1e-6 to 1e4 and beyond: small steps use a Taylor series of the
// augmented 4×4 propagator, large steps closed forms (cos/sin with combined exponents near
// critical damping, the two real decay rates for clearly over-damped modes).
//
// ω = 0 (rigid-body modes of a free-free body): the update is the exact double integration of the
// linear load, y1 = y0 + v0·Δt + F0·Δt²/2 + (F1 − F0)·Δt²/6. ζ is ignored for such modes (a rigid
// mode has no stiffness to define a damping ratio against). Modes with ω·Δt·(1 + 2ζ) < 1e-60 are
// treated the same way (the neglected terms are of relative size (ω·Δt)²).
#include <vector>

#include <Eigen/Core>

namespace hm::modal {

/// Slope-form coefficients of one exact step of one mode (see the file comment).
struct CfpiCoefficients {
  double a11 = 1, a12 = 0, a21 = 0, a22 = 1;  ///< free response (y0, v0) → (y1, v1)
  double c_y = 0, d_y = 0;                    ///< load: y1 += c_y·F0 + d_y·(F1 − F0)
  double c_v = 0, d_v = 0;                    ///< load: v1 += c_v·F0 + d_v·(F1 − F0)
};

/// Coefficients of one step of length dt [s] for a mode of circular frequency omega [rad/s]
/// (≥ 0) and damping ratio zeta (≥ 0). Throws InputError for negative or non-finite arguments.
CfpiCoefficients cfpi_coefficients(double omega, double zeta, double dt);

/// Integrates a whole set of modes with CFPI. Coefficients are cached and recomputed only when
/// Δt changes. After each step y(), v() and the modal acceleration a() = F1 − 2ζωv − ω²y (used by
/// the fluid's wall condition) refer to the end of the step.
class CfpiIntegrator {
 public:
  /// omega [rad/s] ≥ 0 and zeta ≥ 0 per mode (same length). State starts at rest.
  CfpiIntegrator(Eigen::VectorXd omega, Eigen::VectorXd zeta);

  /// Sets y, v and the load F at the current time (which defines a = F − 2ζωv − ω²y).
  void set_state(const Eigen::VectorXd& y, const Eigen::VectorXd& v, const Eigen::VectorXd& F);

  /// Advances by dt [s] with the modal load going linearly from F0 (start) to F1 (end).
  void step(const Eigen::VectorXd& F0, const Eigen::VectorXd& F1, double dt);

  Eigen::Index n_modes() const { return omega_.size(); }
  const Eigen::VectorXd& y() const { return y_; }
  const Eigen::VectorXd& v() const { return v_; }
  const Eigen::VectorXd& a() const { return a_; }
  const Eigen::VectorXd& omega() const { return omega_; }
  const Eigen::VectorXd& zeta() const { return zeta_; }
  /// Coefficients in use for mode i (valid after the first step).
  const CfpiCoefficients& coefficients(Eigen::Index i) const { return coeffs_[i]; }

 private:
  void update_coefficients(double dt);
  void check_size(const Eigen::VectorXd& x, const char* what) const;

  Eigen::VectorXd omega_, zeta_;
  Eigen::VectorXd y_, v_, a_;
  std::vector<CfpiCoefficients> coeffs_;
  double cached_dt_ = -1.0;
};

}  // namespace hm::modal
