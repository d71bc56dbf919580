// The paper's cantilever check (LDD-SPEC §2.2 item 4) with a synthetic set of modes: a tip load F
// applied suddenly at t = 0 gives the exact tip response
//   u_tip(t) = Σ_i Φ_i(tip)·[Φ_i(tip)·F]/ω_i² · [1 − e^{−ζω_i t}(cos ω_d,i t + ζ/√(1−ζ²)·sin ω_d,i
//   t)].
// CFPI steps with ω_max·Δt ≈ 7.6 (no stability limit) reproduce it to ≤ 1e-8 relative over the
// whole history, and with damping settle on the truncated static solution Σ_i Φ_i(tip)² F/ω_i².
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "modal/cfpi.hpp"
#include "modal/fields.hpp"

namespace hm::modal {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTipLoad = 10.0;  // N
constexpr int kTip = 0;            // row of Φ holding the tip deflection DOF

struct SyntheticModes {
  Eigen::VectorXd
      omega;            // rad/s: first four cantilever frequencies (ratios 1 : 6.27 : 17.5 : 34.4)
  Eigen::MatrixXd phi;  // 3 DOFs (tip, mid-span, quarter-span) × 4 modes, 1/√kg
};

SyntheticModes cantilever_modes() {
  SyntheticModes m;
  m.omega = 2 * kPi * Eigen::Vector4d(3.52, 22.03, 61.70, 120.9);
  m.phi.resize(3, 4);
  m.phi << 0.90, -0.90, 0.90, -0.90,  //
      0.31, 0.64, -0.13, -0.61,       //
      0.09, 0.37, 0.62, 0.52;
  return m;
}

long double exact_tip(const SyntheticModes& m, double zeta, long double t) {
  long double u = 0;
  for (Eigen::Index i = 0; i < m.omega.size(); ++i) {
    const long double w = m.omega[i], p = m.phi(kTip, i), s = std::sqrt(1.0L - zeta * zeta);
    const long double wd = w * s;
    u += p * (p * kTipLoad) / (w * w) *
         (1 - std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta / s * std::sin(wd * t)));
  }
  return u;
}

// Runs n steps of dt under the sudden tip load; returns the tip displacement history.
std::vector<double> cfpi_tip_history(const SyntheticModes& m, double dt, int n,
                                     CfpiIntegrator& integ) {
  const Eigen::VectorXd F = m.phi.row(kTip).transpose() * kTipLoad;  // modal force Φᵀf
  integ.set_state(Eigen::VectorXd::Zero(4), Eigen::VectorXd::Zero(4), F);
  std::vector<double> u;
  for (int k = 1; k <= n; ++k) {
    integ.step(F, F, dt);
    u.push_back(reconstruct_fields(m.phi, integ.y(), integ.v(), integ.a()).displacement[kTip]);
  }
  return u;
}

TEST(CfpiCantilever, StepResponseMatchesModalSuperposition) {
  const SyntheticModes m = cantilever_modes();
  const double dt = 0.01;  // ω_1·Δt = 0.22, ω_4·Δt = 7.6
  const int n = 300;
  for (double zeta : {0.0, 0.02, 0.3}) {
    CfpiIntegrator integ(m.omega, Eigen::VectorXd::Constant(4, zeta));
    const std::vector<double> u = cfpi_tip_history(m, dt, n, integ);
    double err = 0, scale = 0;
    for (int k = 1; k <= n; ++k) {
      const double ref = static_cast<double>(exact_tip(m, zeta, k * dt));
      err = std::max(err, std::fabs(u[k - 1] - ref));
      scale = std::max(scale, std::fabs(ref));
    }
    EXPECT_LE(err / scale, 1e-8) << "zeta=" << zeta;
    std::printf("cantilever zeta=%.2f: max relative tip error %.2e over %d steps\n", zeta,
                err / scale, n);
  }
}

TEST(CfpiCantilever, DampedResponseSettlesOnTruncatedStaticSolution) {
  const SyntheticModes m = cantilever_modes();
  const double zeta = 0.05, dt = 0.01;
  const int n = 3000;  // e^{−ζω_1 t} at t = 30 s is 5e-15
  CfpiIntegrator integ(m.omega, Eigen::VectorXd::Constant(4, zeta));
  const std::vector<double> u = cfpi_tip_history(m, dt, n, integ);
  const double u_static =
      (m.phi.row(kTip).array().square() * kTipLoad / m.omega.array().square().transpose()).sum();
  EXPECT_NEAR(u.back(), u_static, 1e-10 * u_static);
  const PhysicalFields f = reconstruct_fields(m.phi, integ.y(), integ.v(), integ.a());
  EXPECT_LE(f.velocity.cwiseAbs().maxCoeff(), 1e-10 * u_static * m.omega[0]);
  EXPECT_LE(f.acceleration.cwiseAbs().maxCoeff(), 1e-10 * u_static * m.omega[3] * m.omega[3]);
}

TEST(ModalFields, SuperposesModesAndChecksSizes) {
  const SyntheticModes m = cantilever_modes();
  const Eigen::Vector4d y(1.0, -2.0, 0.5, 0.25), v(0.1, 0.2, 0.3, 0.4), a(-1, 0, 1, 2);
  const PhysicalFields f = reconstruct_fields(m.phi, y, v, a);
  for (int dof = 0; dof < 3; ++dof) {
    double u = 0;
    for (int i = 0; i < 4; ++i) u += m.phi(dof, i) * y[i];
    EXPECT_NEAR(f.displacement[dof], u, 1e-15);
  }
  EXPECT_TRUE(f.velocity.isApprox(m.phi * v));
  EXPECT_TRUE(f.acceleration.isApprox(m.phi * a));
  try {
    modal_superposition(m.phi, Eigen::VectorXd::Zero(5));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("4 modes (columns) but the modal coordinate vector has 5"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace hm::modal
