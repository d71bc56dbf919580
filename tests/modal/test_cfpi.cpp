// CFPI against closed-form solutions (LDD-SPEC §2). Tolerance: max_n |x_n − x_ref,n| divided by
// max_n |x_ref,n| ≤ 1e-10 over the whole history, for y, v and the modal acceleration a.
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "modal/cfpi.hpp"
#include "modal/newmark.hpp"
#include "test_cfpi_reference.hpp"

namespace hm::modal {
namespace {

using test::ld;
using test::State;
constexpr double kPi = std::numbers::pi;
const double kZetas[] = {0.0, 0.02, 0.5, 1.0, 2.0};
const double kThetas[] = {1e-4, 0.5, 3.0, 50.0, 1000.0};  // ω·Δt

// A load case: initial state, sampled load F(t), and the reference solution at the sample times.
// For loads that are not piecewise linear (harmonic) the reference is the exact solution for the
// piecewise-linear interpolant of the samples, obtained segment by segment from the closed form
// of test_cfpi_reference.hpp in long double.
struct LoadCase {
  std::string name;
  double y0 = 0, v0 = 0;
  std::function<double(double)> load;  // F(t) [N/√kg]
  bool linear_in_time = false;         // F(t) = F(0) + r·t exactly: reference evaluated directly
};

struct History {
  std::vector<double> y, v, a;
  double load_scale = 0;  // max |F| over the history
};

struct Errors {
  double y = 0, v = 0, a = 0;
};

double relative_max_error(const std::vector<double>& x, const std::vector<double>& ref,
                          double scale = 0) {
  double err = 0;
  for (size_t n = 0; n < x.size(); ++n) {
    err = std::max(err, std::fabs(x[n] - ref[n]));
    scale = std::max(scale, std::fabs(ref[n]));
  }
  return scale > 0 ? err / scale : err;  // a history that is identically zero must be met exactly
}

// a = F − 2ζωv − ω²y is a difference of the load and the restoring forces, so its error is
// measured relative to max(|a_ref|, |F|): for a heavily damped mode sampled at ω·Δt ≫ 1 the true
// acceleration at the sample times is ~e^{−ζωΔt}·F and only round-off of F remains.
Errors compare(const History& h, const History& ref) {
  return {relative_max_error(h.y, ref.y), relative_max_error(h.v, ref.v),
          relative_max_error(h.a, ref.a, ref.load_scale)};
}

int step_count(double theta) {
  return std::max(200, static_cast<int>(std::ceil(2 * 2 * kPi / theta)));  // ≥ 2 periods
}

History reference_history(const LoadCase& c, double omega, double zeta, double dt, int n) {
  History h{{c.y0}, {c.v0}, {c.load(0.0) - 2 * zeta * omega * c.v0 - omega * omega * c.y0}};
  State s{c.y0, c.v0};
  const ld F0 = c.load(0.0), r = (c.load(dt) - c.load(0.0)) / static_cast<ld>(dt);
  for (int k = 1; k <= n; ++k) {
    const double t = k * dt;
    if (c.linear_in_time) {
      s = test::linear_load_response(omega, zeta, c.y0, c.v0, F0, r, static_cast<ld>(t));
    } else {
      const ld Fa = c.load((k - 1) * dt), Fb = c.load(t);
      s = test::linear_load_response(omega, zeta, s.y, s.v, Fa, (Fb - Fa) / dt, dt);
    }
    h.y.push_back(static_cast<double>(s.y));
    h.v.push_back(static_cast<double>(s.v));
    h.a.push_back(static_cast<double>(c.load(t) - 2 * zeta * omega * s.v - omega * omega * s.y));
    h.load_scale = std::max(h.load_scale, std::fabs(c.load(t)));
  }
  return h;
}

History cfpi_history(const LoadCase& c, double omega, double zeta, double dt, int n) {
  CfpiIntegrator integ(Eigen::VectorXd::Constant(1, omega), Eigen::VectorXd::Constant(1, zeta));
  integ.set_state(Eigen::VectorXd::Constant(1, c.y0), Eigen::VectorXd::Constant(1, c.v0),
                  Eigen::VectorXd::Constant(1, c.load(0.0)));
  History h{{integ.y()[0]}, {integ.v()[0]}, {integ.a()[0]}};
  for (int k = 1; k <= n; ++k) {
    integ.step(Eigen::VectorXd::Constant(1, c.load((k - 1) * dt)),
               Eigen::VectorXd::Constant(1, c.load(k * dt)), dt);
    h.y.push_back(integ.y()[0]);
    h.v.push_back(integ.v()[0]);
    h.a.push_back(integ.a()[0]);
  }
  return h;
}

History newmark_history(const LoadCase& c, double omega, double zeta, double dt, int n) {
  NewmarkIntegrator integ(Eigen::VectorXd::Constant(1, omega), Eigen::VectorXd::Constant(1, zeta));
  integ.set_state(Eigen::VectorXd::Constant(1, c.y0), Eigen::VectorXd::Constant(1, c.v0),
                  Eigen::VectorXd::Constant(1, c.load(0.0)));
  History h{{integ.y()[0]}, {integ.v()[0]}, {integ.a()[0]}};
  for (int k = 1; k <= n; ++k) {
    integ.step(Eigen::VectorXd::Constant(1, c.load(k * dt)), dt);
    h.y.push_back(integ.y()[0]);
    h.v.push_back(integ.v()[0]);
    h.a.push_back(integ.a()[0]);
  }
  return h;
}

// ω = 2π·7 rad/s; loads scaled by ω² so that the static deflection is O(1).
constexpr double kOmega = 2 * kPi * 7.0;

std::vector<LoadCase> load_cases() {
  const double w = kOmega, w2 = w * w;
  return {
      {"step", 0, 0, [w2](double) { return w2; }, true},
      {"ramp", 0, 0, [w, w2](double t) { return w2 * w * t; }, true},
      {"free decay", 1.0, 0.3 * w, [](double) { return 0.0; }, true},
      {"harmonic 0.37w", 0.2, -0.1 * w, [w, w2](double t) { return w2 * std::sin(0.37 * w * t); }},
      {"resonance", 0, 0, [w, w2](double t) { return w2 * std::sin(w * t); }},
  };
}

TEST(Cfpi, MatchesClosedFormsForAllDampingsAndStepSizes) {
  double worst = 0;
  for (const LoadCase& c : load_cases())
    for (double zeta : kZetas)
      for (double theta : kThetas) {
        const double dt = theta / kOmega;
        const int n = step_count(theta);
        const Errors e = compare(cfpi_history(c, kOmega, zeta, dt, n),
                                 reference_history(c, kOmega, zeta, dt, n));
        worst = std::max({worst, e.y, e.v, e.a});
        if (std::max({e.y, e.v, e.a}) > 1e-11)
          fmt::print("  {} zeta={} w*dt={}: y {:.1e} v {:.1e} a {:.1e}\n", c.name, zeta, theta, e.y,
                     e.v, e.a);
        EXPECT_LE(e.y, 1e-10) << c.name << " zeta=" << zeta << " w*dt=" << theta;
        EXPECT_LE(e.v, 1e-10) << c.name << " zeta=" << zeta << " w*dt=" << theta;
        EXPECT_LE(e.a, 1e-10) << c.name << " zeta=" << zeta << " w*dt=" << theta;
      }
  fmt::print("CFPI worst relative error over 5 loads x 5 zeta x 5 w*dt (y, v, a): {:.2e}\n", worst);
}

// Newmark average acceleration on the same cases at ω·Δt = 3: documented contrast (period
// error ω̄Δt = 2·atan(ωΔt/2)), not a requirement on Newmark.
TEST(Cfpi, NewmarkAverageAccelerationHasLargePeriodErrorAtThree) {
  const double theta = 3.0, dt = theta / kOmega;
  const int n = step_count(theta);
  for (const LoadCase& c : load_cases())
    for (double zeta : kZetas) {
      const History ref = reference_history(c, kOmega, zeta, dt, n);
      const Errors nm = compare(newmark_history(c, kOmega, zeta, dt, n), ref);
      const Errors cf = compare(cfpi_history(c, kOmega, zeta, dt, n), ref);
      fmt::print("w*dt=3 {:15s} zeta={:4.2f}: Newmark AA y err {:.2e} v err {:.2e} | CFPI {:.1e}\n",
                 c.name, zeta, nm.y, nm.v, cf.y);
      if (zeta <= 0.02 && c.name != "ramp") {  // the ramp response is smooth: small error
        EXPECT_GT(nm.y, 1e-2) << c.name << " zeta=" << zeta;
      }
    }
  // The free oscillation of Newmark AA rotates by 2·atan(θ/2) per step instead of θ.
  const double expected_angle = 2 * std::atan(theta / 2);
  NewmarkIntegrator nm(Eigen::VectorXd::Constant(1, kOmega), Eigen::VectorXd::Zero(1));
  nm.set_state(Eigen::VectorXd::Ones(1), Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1));
  nm.step(Eigen::VectorXd::Zero(1), dt);
  EXPECT_NEAR(std::acos(nm.y()[0]), expected_angle, 1e-12);
  fmt::print(
      "Newmark AA phase per step at w*dt=3: {:.6f} rad (exact 3.0, i.e. {:.1f}% frequency "
      "error)\n",
      expected_angle, 100 * (expected_angle / theta - 1));
}

// Each coefficient against the long-double 4×4 augmented matrix exponential, from ω·Δt = 1e-6 to
// 1e4 and across critical damping and strong over-damping: relative to max(|ref|, natural scale)
// where the natural scales are 1 (a11, a22), min(1, θ) (a12, a21, c_v), min(1, θ²) (c_y, d_v·θ)
// and min(θ, θ³) (d_y·θ) in units ω = 1.
// Reference propagator (ω = 1): the long-double augmented matrix exponential while it needs few
// squarings (‖θM‖ ≤ 100), else the long-double closed forms with unit inputs (no cancellation
// there since θ is large); each squaring would double the round-off of the exponential.
test::Mat4 reference_coefficients(double zeta, double theta) {
  if (theta * (2 + 2 * zeta) <= 100) return test::augmented_expm(zeta, theta);
  test::Mat4 E{};
  const State y0 = test::free_response(1, zeta, 1, 0, theta);
  const State v0 = test::free_response(1, zeta, 0, 1, theta);
  const State unit = test::linear_load_response(1, zeta, 0, 0, 1, 0, theta);
  const State ramp = test::linear_load_response(1, zeta, 0, 0, 0, 1, theta);
  E[0] = {y0.y, v0.y, unit.y, ramp.y};
  E[1] = {y0.v, v0.v, unit.v, ramp.v};
  return E;
}

TEST(Cfpi, CoefficientsKeepFullPrecisionFromTinyToHugeSteps) {
  const double thetas[] = {1e-6, 1e-4, 1e-2, 0.3, 0.66, 1.0, 1.9, 2.1, 5.0, 50.0, 1e3, 1e4};
  const double zetas[] = {0.0, 0.02, 0.5, 1 - 1e-9, 1.0, 1 + 1e-9, 1.2, 1.3, 2.0, 10.0, 100.0};
  double worst = 0;
  for (double theta : thetas)
    for (double zeta : zetas) {
      const CfpiCoefficients c = cfpi_coefficients(1.0, zeta, theta);
      const test::Mat4 E = reference_coefficients(zeta, theta);
      const double s1 = std::min(1.0, theta), s2 = std::min(1.0, theta * theta),
                   s3 = std::min(theta, theta * theta * theta);
      const struct {
        const char* name;
        double value;
        ld ref;
        double scale;
      } checks[] = {{"a11", c.a11, E[0][0], 1.0}, {"a12", c.a12, E[0][1], s1},
                    {"a21", c.a21, E[1][0], s1},  {"a22", c.a22, E[1][1], 1.0},
                    {"c_y", c.c_y, E[0][2], s2},  {"d_y", c.d_y * theta, E[0][3], s3},
                    {"c_v", c.c_v, E[1][2], s1},  {"d_v", c.d_v * theta, E[1][3], s2}};
      for (const auto& k : checks) {
        const double ref = static_cast<double>(k.ref);
        const double err = std::fabs(k.value - ref) / std::max(std::fabs(ref), k.scale);
        worst = std::max(worst, err);
        EXPECT_LE(err, 1e-13) << k.name << " zeta=" << zeta << " w*dt=" << theta
                              << " value=" << k.value << " ref=" << ref;
      }
    }
  fmt::print("CFPI coefficients: worst relative error vs long-double expm: {:.2e}\n", worst);
}

// Over-damped, ω·Δt = 1e4, ζ = 2 (huge cosh × tiny exponential if formed naively).
TEST(Cfpi, HugeStepOverdampedIsFiniteAndExact) {
  const CfpiCoefficients c = cfpi_coefficients(1.0, 2.0, 1e4);
  for (double x : {c.a11, c.a12, c.a21, c.a22, c.c_y, c.d_y, c.c_v, c.d_v})
    EXPECT_TRUE(std::isfinite(x));
  EXPECT_EQ(c.a11, 0.0);  // e^{−1e4/(2+√3)} underflows: the state is forgotten
  EXPECT_NEAR(c.c_y, 1.0, 1e-15);
  EXPECT_NEAR(c.d_y, (1e4 - 4.0) / 1e4, 1e-15);  // ramp response θ − 2ζ (ω = 1)
}

// Rigid-body modes (ω = 0): exact double integration of the linear load.
TEST(Cfpi, RigidBodyModeIntegratesLinearLoadExactly) {
  CfpiIntegrator integ(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, 0.05));
  const double y0 = 0.3, v0 = -1.2, F0 = 2.0, r = 5.0, dt = 0.013;
  integ.set_state(Eigen::VectorXd::Constant(1, y0), Eigen::VectorXd::Constant(1, v0),
                  Eigen::VectorXd::Constant(1, F0));
  double worst = 0;
  for (int k = 1; k <= 500; ++k) {
    const double t0 = (k - 1) * dt, t = k * dt;
    integ.step(Eigen::VectorXd::Constant(1, F0 + r * t0), Eigen::VectorXd::Constant(1, F0 + r * t),
               dt);
    const double y = y0 + v0 * t + F0 * t * t / 2 + r * t * t * t / 6;
    const double v = v0 + F0 * t + r * t * t / 2;
    worst = std::max({worst, std::fabs(integ.y()[0] - y) / std::fabs(y),
                      std::fabs(integ.v()[0] - v) / std::fabs(v)});
    ASSERT_DOUBLE_EQ(integ.a()[0], F0 + r * t);
  }
  EXPECT_LE(worst, 1e-12);
}

// Resonance F = sin(ωt), ζ = 0, against the continuous solution y = (sin ωt − ωt cos ωt)/(2ω²):
// the only error is the piecewise-linear sampling of the load, second order in Δt.
TEST(Cfpi, ResonanceSamplingErrorIsSecondOrder) {
  const double w = kOmega, T = 4 * 2 * kPi / w;
  std::vector<double> errors;
  for (int per_period : {16, 32, 64, 128}) {
    const double dt = 2 * kPi / w / per_period;
    CfpiIntegrator integ(Eigen::VectorXd::Constant(1, w), Eigen::VectorXd::Zero(1));
    double err = 0, scale = 0;
    for (int k = 1; k * dt <= T + 1e-12; ++k) {
      integ.step(Eigen::VectorXd::Constant(1, std::sin(w * (k - 1) * dt)),
                 Eigen::VectorXd::Constant(1, std::sin(w * k * dt)), dt);
      const double t = k * dt, y = (std::sin(w * t) - w * t * std::cos(w * t)) / (2 * w * w);
      err = std::max(err, std::fabs(integ.y()[0] - y));
      scale = std::max(scale, std::fabs(y));
    }
    errors.push_back(err / scale);
  }
  for (size_t i = 1; i < errors.size(); ++i) {
    const double rate = std::log2(errors[i - 1] / errors[i]);
    fmt::print("resonance sampling error {:.3e} -> {:.3e}: order {:.3f}\n", errors[i - 1],
               errors[i], rate);
    EXPECT_GT(rate, 2.0 - 0.1);
  }
}

TEST(Cfpi, CoefficientsAreRecomputedOnlyWhenTheStepChanges) {
  CfpiIntegrator integ(Eigen::Vector2d(3.0, 40.0), Eigen::Vector2d(0.1, 1.5));
  const Eigen::VectorXd F = Eigen::Vector2d(1.0, -2.0);
  integ.step(F, F, 0.01);
  const CfpiCoefficients first = integ.coefficients(1);
  EXPECT_EQ(first.a12, cfpi_coefficients(40.0, 1.5, 0.01).a12);
  integ.step(F, F, 0.02);
  EXPECT_EQ(integ.coefficients(1).a12, cfpi_coefficients(40.0, 1.5, 0.02).a12);
  EXPECT_NE(integ.coefficients(1).a12, first.a12);
}

TEST(Cfpi, RejectsInvalidParametersWithTheValue) {
  try {
    CfpiIntegrator bad(Eigen::Vector2d(1.0, -3.0), Eigen::Vector2d(0.0, 0.0));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mode 1: omega = -3"), std::string::npos) << e.what();
  }
  try {
    cfpi_coefficients(1.0, 0.1, 0.0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("dt = 0 s"), std::string::npos) << e.what();
  }
  CfpiIntegrator integ(Eigen::Vector2d(1.0, 2.0), Eigen::Vector2d(0.0, 0.0));
  try {
    integ.step(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(2), 0.1);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("F0 has 3 entries; expected one per mode (2)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace hm::modal
