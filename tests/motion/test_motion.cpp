// Prescribed rigid wall motion: exact velocity/acceleration against finite differences (measured
// order), analytic values of sway and roll, rigidity, C² start-up ramp, CSV time tables (accuracy
// and order under refinement) and their input errors.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "motion/rigid_motion.hpp"

namespace hm::motion {
namespace {

using std::numbers::pi;

Vertices sample_vertices(int dim) {
  // A few vertices at different distances from pivots/axes, deterministic.
  Vertices x(7, dim);
  for (int i = 0; i < 7; ++i)
    for (int k = 0; k < dim; ++k) x(i, k) = std::sin(1.3 * i + 2.1 * k + 0.4) * (0.5 + 0.2 * i);
  return x;
}

double max_abs(const Vertices& m) {
  return m.cwiseAbs().maxCoeff();
}

struct FdErrors {
  double velocity = 0.0;      ///< |v − (x(t+h) − x(t−h))/2h|
  double acceleration = 0.0;  ///< |a − (x(t+h) − 2x(t) + x(t−h))/h²|
  double accel_from_v = 0.0;  ///< |a − (v(t+h) − v(t−h))/2h|
};

FdErrors fd_errors(const RigidMotion& m, const Vertices& x0, double t, double h) {
  const auto k = m.kinematics(t, x0);
  const auto kp = m.kinematics(t + h, x0);
  const auto km = m.kinematics(t - h, x0);
  return {max_abs(k.v - (kp.x - km.x) / (2.0 * h)),
          max_abs(k.a - (kp.x - 2.0 * k.x + km.x) / (h * h)),
          max_abs(k.a - (kp.v - km.v) / (2.0 * h))};
}

// Measured orders of the central differences between h and h/2 (expected 2: the exact v and a
// differ from the differences only by the O(h²) truncation error).
void expect_second_order(const RigidMotion& m, double t, const std::string& what) {
  const Vertices x0 = sample_vertices(m.dim());
  const double h = 1e-2;
  const FdErrors e1 = fd_errors(m, x0, t, h);
  const FdErrors e2 = fd_errors(m, x0, t, h / 2.0);
  const double pv = std::log2(e1.velocity / e2.velocity);
  const double pa = std::log2(e1.acceleration / e2.acceleration);
  const double pav = std::log2(e1.accel_from_v / e2.accel_from_v);
  fmt::print(
      "{}: FD errors at h = {}: v {:.2e}, a {:.2e}, a(v) {:.2e}; orders {:.3f} {:.3f} "
      "{:.3f}\n",
      what, h, e1.velocity, e1.acceleration, e1.accel_from_v, pv, pa, pav);
  EXPECT_GT(pv, 1.9) << what;
  EXPECT_GT(pa, 1.9) << what;
  EXPECT_GT(pav, 1.9) << what;
}

RigidMotion combined_3d() {
  const Eigen::Vector3d pivot(0.3, -0.2, 0.1);
  const Eigen::Vector3d axis(1.0, 2.0, 2.0);  // normalised by the constructor
  RigidMotion m(3, pivot, axis);
  m.add_translation(Eigen::Vector3d(1.0, 0.0, 0.0), ramped(sine_law(0.06, 1.0 / 1.94), 1.0));
  m.add_translation(Eigen::Vector3d(0.0, 0.6, 0.8), sine_law(0.02, 0.9, 0.3));
  m.set_rotation(ramped(sine_law(4.0 * pi / 180.0 * 5.0, 0.61), 0.8));
  return m;
}

TEST(MotionFiniteDifferences, SwayIsSecondOrderConsistent) {
  expect_second_order(sway_motion(2, {1.0, 1.0, 0.0}, 0.06, 1.94), 0.37, "sway 2-D");
  expect_second_order(sway_motion(3, {0.0, 0.0, 1.0}, 0.06, 1.94), 1.1, "sway 3-D");
}

TEST(MotionFiniteDifferences, RollIsSecondOrderConsistent) {
  expect_second_order(roll_motion(2, {0.1, -0.3, 0.0}, Eigen::Vector3d::UnitZ(), 0.5, 0.61), 0.2,
                      "roll 2-D");
  expect_second_order(roll_motion(3, {0.1, -0.3, 0.2}, {0.0, 1.0, 1.0}, 0.5, 0.61), 0.9,
                      "roll 3-D");
}

TEST(MotionFiniteDifferences, RampedRollIsSecondOrderConsistent) {
  // Inside the ramp, where r, r' and r'' all contribute.
  const auto m = roll_motion(2, {0.1, -0.3, 0.0}, Eigen::Vector3d::UnitZ(), 0.5, 0.61, 2.0);
  expect_second_order(m, 0.7, "ramped roll, early");
  expect_second_order(m, 1.4, "ramped roll, late");
}

TEST(MotionFiniteDifferences, CombinedSwayAndRollIsSecondOrderConsistent) {
  expect_second_order(combined_3d(), 0.55, "combined 3-D");
}

TEST(MotionAnalytic, SwayAtZeroCrossingAndAtExtremum) {
  const double A = 0.06, T = 1.94, w = 2.0 * pi / T;
  const Eigen::Vector3d d = Eigen::Vector3d(3.0, 4.0, 0.0) / 5.0;
  const auto m = sway_motion(2, {3.0, 4.0, 0.0}, A, T);
  const Vertices x0 = sample_vertices(2);
  const auto k0 = m.kinematics(0.0, x0);      // x = x0, v = A w d, a = 0
  const auto k1 = m.kinematics(T / 4.0, x0);  // x = x0 + A d, v = 0, a = −A w² d
  for (Eigen::Index i = 0; i < x0.rows(); ++i)
    for (int c = 0; c < 2; ++c) {
      EXPECT_NEAR(k0.x(i, c), x0(i, c), 1e-15);
      EXPECT_NEAR(k0.v(i, c), A * w * d(c), 1e-15);
      EXPECT_NEAR(k0.a(i, c), 0.0, 1e-15);
      EXPECT_NEAR(k1.x(i, c), x0(i, c) + A * d(c), 1e-15);
      EXPECT_NEAR(k1.v(i, c), 0.0, 1e-15);
      EXPECT_NEAR(k1.a(i, c), -A * w * w * d(c), 1e-14);
    }
}

TEST(MotionAnalytic, Roll2DSpeedAndCentripetalAccelerationAtMaximumRate) {
  const double theta0 = 4.0 * pi / 180.0, f = 0.61;
  const Eigen::Vector3d c(0.4, 0.15, 0.0);
  const auto m = roll_motion(2, c, Eigen::Vector3d::UnitZ(), theta0, f);
  const Vertices x0 = sample_vertices(2);
  // t = 0: θ = 0, θ̇ = θ0·2πf (maximum), θ̈ = 0  →  |v| = θ̇ r, v ⟂ r, a = −θ̇² (x − c).
  const double rate = theta0 * 2.0 * pi * f;
  const auto k = m.kinematics(0.0, x0);
  for (Eigen::Index i = 0; i < x0.rows(); ++i) {
    const Eigen::Vector2d r = x0.row(i).transpose() - c.head<2>();
    const Eigen::Vector2d v = k.v.row(i).transpose();
    const Eigen::Vector2d a = k.a.row(i).transpose();
    EXPECT_NEAR(v.norm(), rate * r.norm(), 1e-15);
    EXPECT_NEAR(v.x(), -rate * r.y(), 1e-15);  // counter-clockwise for θ̇ > 0
    EXPECT_NEAR(v.y(), rate * r.x(), 1e-15);
    EXPECT_NEAR(a.x(), -rate * rate * r.x(), 1e-15);
    EXPECT_NEAR(a.y(), -rate * rate * r.y(), 1e-15);
  }
}

TEST(MotionAnalytic, Roll2DAtMaximumAngleHasOnlyTheEulerTerm) {
  const double theta0 = 0.3, f = 0.61;
  const Eigen::Vector3d c(-0.2, 0.5, 0.0);
  const auto m = roll_motion(2, c, Eigen::Vector3d::UnitZ(), theta0, f);
  const Vertices x0 = sample_vertices(2);
  // t = 1/(4f): θ = θ0, θ̇ = 0, θ̈ = −θ0 (2πf)²: x = c + R(θ0)(x0 − c), v = 0, a = θ̈ ẑ × r.
  const double accel = -theta0 * std::pow(2.0 * pi * f, 2);
  const double cs = std::cos(theta0), sn = std::sin(theta0);
  const auto k = m.kinematics(0.25 / f, x0);
  for (Eigen::Index i = 0; i < x0.rows(); ++i) {
    const double rx0 = x0(i, 0) - c.x(), ry0 = x0(i, 1) - c.y();
    const double rx = cs * rx0 - sn * ry0, ry = sn * rx0 + cs * ry0;
    EXPECT_NEAR(k.x(i, 0), c.x() + rx, 1e-15);
    EXPECT_NEAR(k.x(i, 1), c.y() + ry, 1e-15);
    EXPECT_NEAR(k.v.row(i).norm(), 0.0, 1e-15);
    EXPECT_NEAR(k.a(i, 0), -accel * ry, 1e-14);
    EXPECT_NEAR(k.a(i, 1), accel * rx, 1e-14);
  }
}

TEST(MotionAnalytic, Roll3DCentripetalAccelerationPointsToTheAxisNotThePivot) {
  const Eigen::Vector3d c(0.1, 0.2, -0.3);
  const Eigen::Vector3d e = Eigen::Vector3d(1.0, -2.0, 2.0) / 3.0;
  const double theta0 = 0.2, f = 1.3, rate = theta0 * 2.0 * pi * f;
  const auto m = roll_motion(3, c, 3.0 * e, theta0, f);
  const Vertices x0 = sample_vertices(3);
  const auto k = m.kinematics(0.0, x0);
  for (Eigen::Index i = 0; i < x0.rows(); ++i) {
    const Eigen::Vector3d r = x0.row(i).transpose() - c;
    const Eigen::Vector3d r_perp = r - e * e.dot(r);  // distance vector from the axis
    const Eigen::Vector3d v = k.v.row(i).transpose();
    const Eigen::Vector3d a = k.a.row(i).transpose();
    EXPECT_NEAR(v.norm(), rate * r_perp.norm(), 1e-15);
    EXPECT_NEAR(v.dot(e), 0.0, 1e-15);
    // |a| ≈ 4 m/s² here: 1e-14 is a few rounding units.
    EXPECT_NEAR((a + rate * rate * r_perp).norm(), 0.0, 1e-14);
  }
}

TEST(MotionRigidity, DistancesAndRigidVelocityField) {
  const auto m = combined_3d();
  Vertices x0(40, 3);
  for (Eigen::Index i = 0; i < x0.rows(); ++i)
    for (int c = 0; c < 3; ++c) x0(i, c) = std::cos(0.7 * double(i) * (c + 1) + c) * 1.5;
  double worst_distance = 0.0, worst_rate = 0.0;
  for (double t : {0.0, 0.31, 0.77, 1.6, 4.2}) {
    const auto k = m.kinematics(t, x0);
    for (Eigen::Index i = 0; i < x0.rows(); ++i)
      for (Eigen::Index j = i + 1; j < x0.rows(); ++j) {
        const Eigen::Vector3d dx = (k.x.row(i) - k.x.row(j)).transpose();
        const Eigen::Vector3d dv = (k.v.row(i) - k.v.row(j)).transpose();
        worst_distance =
            std::max(worst_distance, std::abs(dx.norm() - (x0.row(i) - x0.row(j)).norm()));
        worst_rate = std::max(worst_rate, std::abs(dx.dot(dv)));  // d|dx|²/dt / 2 = 0
      }
  }
  fmt::print("rigidity: max distance change {:.2e} m, max |dx·dv| {:.2e} m²/s\n", worst_distance,
             worst_rate);
  EXPECT_LT(worst_distance, 1e-12);
  EXPECT_LT(worst_rate, 1e-12);
}

TEST(MotionRamp, PolynomialValuesAndEndConditions) {
  for (double s : {0.0, -1.0}) {
    const Jet r = smooth_ramp(s);
    EXPECT_EQ(r.value, 0.0);
    EXPECT_EQ(r.rate, 0.0);
    EXPECT_EQ(r.accel, 0.0);
  }
  const Jet half = smooth_ramp(0.5);  // symmetric: r = 1/2, r' = 30/16, r'' = 0
  EXPECT_NEAR(half.value, 0.5, 1e-15);
  EXPECT_NEAR(half.rate, 30.0 / 16.0, 1e-15);
  EXPECT_NEAR(half.accel, 0.0, 1e-15);
  // Approaching s = 1: 1 − r = 10ε³ − 15ε⁴ + 6ε⁵, r' = 30ε²(1 − ε)², r'' = −60ε(1 − ε)(1 − 2ε),
  // so r → 1, r' → 0, r'' → 0: the plateau (1, 0, 0) is reached with continuous r' and r''.
  const double eps = 1e-3;
  const Jet end = smooth_ramp(1.0 - eps);
  EXPECT_NEAR(1.0 - end.value, eps * eps * eps * (10.0 - 15.0 * eps + 6.0 * eps * eps), 1e-15);
  EXPECT_NEAR(end.rate, 30.0 * eps * eps * (1.0 - eps) * (1.0 - eps), 1e-15);
  EXPECT_NEAR(end.accel, -60.0 * eps * (1.0 - eps) * (1.0 - 2.0 * eps), 1e-14);
  const Jet one = smooth_ramp(1.0);
  EXPECT_EQ(one.value, 1.0);
  EXPECT_EQ(one.rate, 0.0);
  EXPECT_EQ(one.accel, 0.0);
}

TEST(MotionRamp, RampedLawIsC2AtBothEndsOfTheRamp) {
  const double T_ramp = 1.5;
  const ScalarLaw plain = sine_law(0.3, 0.61, 0.2);
  const ScalarLaw law = ramped(plain, T_ramp);
  // One-sided limits, ε small enough that the smooth variation (jerk·2ε ≈ 1e-11) is negligible
  // against the 1e-9 bound; a jump of the acceleration would show in full. (The jerk does jump at
  // the ramp end: the ramp is C², not C³.)
  const double eps = 1e-12;
  const Jet before = law(T_ramp - eps), after = law(T_ramp + eps), exact = plain(T_ramp);
  fmt::print("ramp end jumps: value {:.1e}, rate {:.1e}, accel {:.1e}\n",
             std::abs(after.value - before.value), std::abs(after.rate - before.rate),
             std::abs(after.accel - before.accel));
  EXPECT_NEAR(before.value, exact.value, 1e-9);
  EXPECT_NEAR(before.rate, exact.rate, 1e-9);
  EXPECT_NEAR(before.accel, exact.accel, 1e-9);
  EXPECT_NEAR(after.accel, before.accel, 1e-9);
  // At the start the body is at rest with zero acceleration from both sides (no impulsive start).
  const Jet start = law(eps), rest = law(-eps);
  EXPECT_NEAR(start.accel, 0.0, 1e-9);
  EXPECT_NEAR(start.rate, 0.0, 1e-9);
  EXPECT_EQ(rest.value, 0.0);
  EXPECT_EQ(rest.accel, 0.0);
  // Without the ramp the same law starts impulsively: this is what the ramp removes.
  EXPECT_GT(std::abs(plain(0.0).rate), 0.1);
}

// ---------------------------------------------------------------------------------------------
// CSV time tables

std::filesystem::path test_dir() {
  const auto dir = std::filesystem::path(HM_BINARY_DIR) / "test_motion_files";
  std::filesystem::create_directories(dir);
  return dir;
}

std::filesystem::path write_file(const std::string& name, const std::string& text) {
  const auto path = test_dir() / name;
  std::ofstream(path) << text;
  return path;
}

// Samples x = A sin(2πt/T) and θ [deg] = Θ sin(2πft) at n_per_period points per period T.
std::filesystem::path write_sine_table(int n_per_period) {
  const double A = 0.06, T = 1.94, theta0_deg = 4.0, f = 0.61;
  std::string text = "t [s], x [m], theta [deg]\n";
  const int n = 2 * n_per_period;  // two periods
  for (int i = 0; i <= n; ++i) {
    const double t = T * i / n_per_period;
    text += fmt::format("{:.17g},{:.17g}, {:.17g}\n", t, A * std::sin(2 * pi * t / T),
                        theta0_deg * std::sin(2 * pi * f * t));
  }
  return write_file(fmt::format("sine_{}.csv", n_per_period), text);
}

struct TableErrors {
  double x = 0.0, v = 0.0, a = 0.0;  // max vertex errors against the exact motion
};

TableErrors table_errors(int n_per_period) {
  const Eigen::Vector3d pivot(0.2, -0.1, 0.0);
  const auto table = read_time_table(write_sine_table(n_per_period));
  const auto from_table = table_motion(table, 2, pivot);
  RigidMotion exact_with_pivot(2, pivot);
  exact_with_pivot.add_translation(Eigen::Vector3d::UnitX(), sine_law(0.06, 1.0 / 1.94));
  exact_with_pivot.set_rotation(sine_law(4.0 * pi / 180.0, 0.61));
  const Vertices x0 = sample_vertices(2);
  TableErrors e;
  for (int i = 0; i <= 400; ++i) {  // the whole table, ends included
    const double t = 2.0 * 1.94 * i / 400.0;
    const auto kt = from_table.kinematics(t, x0);
    const auto ke = exact_with_pivot.kinematics(t, x0);
    e.x = std::max(e.x, max_abs(kt.x - ke.x));
    e.v = std::max(e.v, max_abs(kt.v - ke.v));
    e.a = std::max(e.a, max_abs(kt.a - ke.a));
  }
  return e;
}

TEST(MotionTable, ReproducesASampledSineWithSplineOrders) {
  // Not-a-knot cubic spline: errors O(h⁴), O(h³), O(h²) in position, velocity, acceleration.
  const TableErrors e1 = table_errors(20), e2 = table_errors(40), e3 = table_errors(80);
  for (const auto& [n, e] : {std::pair{20, e1}, std::pair{40, e2}, std::pair{80, e3}})
    fmt::print("table, {} samples/period: max error x {:.2e} m, v {:.2e} m/s, a {:.2e} m/s²\n", n,
               e.x, e.v, e.a);
  const double px = std::log2(e2.x / e3.x), pv = std::log2(e2.v / e3.v),
               pa = std::log2(e2.a / e3.a);
  fmt::print("table orders (40 -> 80): x {:.3f}, v {:.3f}, a {:.3f}\n", px, pv, pa);
  EXPECT_GT(px, 3.9);
  EXPECT_GT(pv, 2.9);
  EXPECT_GT(pa, 1.9);
  // Stated accuracy at 40 samples per period. Estimate for the position: (5/384)·h⁴·max|x''''|
  // with h = T/40 and x'''' ≤ A ω⁴ + θ0 ω_f⁴ |r| ≈ 25 m/s⁴ for these vertices (|r| ≤ 1.7 m):
  // 1.8e-6 m; the peak motion is ≈ 0.18 m displacement and ≈ 2.6 m/s² acceleration.
  EXPECT_LT(e2.x, 5e-6);
  EXPECT_LT(e2.v, 5e-4);
  EXPECT_LT(e2.a, 5e-2);
}

TEST(MotionTable, ColumnsInAnyOrderAndLinearDataIsExact) {
  const auto path =
      write_file("order.csv", "t [s],theta [rad],y [m]\n0,0,0\n1,0.5,1\n2,1,2\n3,1.5,3\n\n");
  const auto table = read_time_table(path);
  ASSERT_EQ(table.columns.size(), 2u);
  const auto m = table_motion(table, 2, Eigen::Vector3d::Zero());
  const auto s = m.state(1.5);  // linear data: the spline is exact
  EXPECT_NEAR(s.translation.y(), 1.5, 1e-14);
  EXPECT_NEAR(s.velocity.y(), 1.0, 1e-14);
  EXPECT_NEAR(s.acceleration.y(), 0.0, 1e-13);
  EXPECT_NEAR(s.omega.z(), 0.5, 1e-14);
  EXPECT_NEAR(std::atan2(s.rotation(1, 0), s.rotation(0, 0)), 0.75, 1e-14);
}

// Expects an InputError whose message contains every fragment.
void expect_input_error(const std::function<void()>& f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no InputError thrown";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    for (const auto& p : parts)
      EXPECT_NE(msg.find(p), std::string::npos) << msg << "\nlacks: " << p;
  }
}

TEST(MotionTableErrors, MissingFile) {
  const auto path = test_dir() / "does_not_exist.csv";
  expect_input_error([&] { read_time_table(path); }, {path.string(), "cannot be opened", "t [s]"});
}

TEST(MotionTableErrors, NonMonotonicTime) {
  const auto path = write_file("nonmono.csv", "t [s],x [m]\n0,0\n0.1,1\n0.1,2\n0.3,3\n");
  expect_input_error([&] { read_time_table(path); },
                     {path.string() + ":4:", "0.1", "strictly increasing"});
}

TEST(MotionTableErrors, WrongColumnCount) {
  const auto path = write_file("columns.csv", "t [s],x [m],y [m]\n0,0,0\n0.1,1\n");
  expect_input_error([&] { read_time_table(path); },
                     {path.string() + ":3:", "2 comma-separated values", "expected 3"});
}

TEST(MotionTableErrors, NonNumericValue) {
  const auto path = write_file("text.csv", "t [s],x [m]\n0,0\n0.1,abc\n");
  expect_input_error([&] { read_time_table(path); },
                     {path.string() + ":3:", "'abc'", "column 2", "x [m]", "not a finite number"});
  const auto trailing = write_file("trailing.csv", "t [s],x [m]\n0,0\n0.1x,1\n");
  expect_input_error([&] { read_time_table(trailing); }, {trailing.string() + ":3:", "'0.1x'"});
}

TEST(MotionTableErrors, HeaderProblems) {
  const auto no_time = write_file("no_time.csv", "time,x [m]\n0,0\n");
  expect_input_error([&] { read_time_table(no_time); },
                     {no_time.string() + ":1:", "'time'", "expected 't [s]'"});
  const auto unknown = write_file("unknown.csv", "t [s],x[m]\n0,0\n");
  expect_input_error([&] { read_time_table(unknown); },
                     {unknown.string() + ":1:", "'x[m]'", "did you mean 'x [m]'", "theta [deg]"});
  const auto twice = write_file("twice.csv", "t [s],theta [rad],theta [deg]\n0,0,0\n");
  expect_input_error([&] { read_time_table(twice); },
                     {twice.string() + ":1:", "theta [deg]", "twice"});
}

TEST(MotionTableErrors, TooFewRowsAndZIn2D) {
  const auto short_table = write_file("short.csv", "t [s],x [m]\n0,0\n1,1\n2,0\n");
  expect_input_error([&] { read_time_table(short_table); },
                     {short_table.string(), "3 data rows", "at least 4"});
  const auto z = write_file("z.csv", "t [s],z [m]\n0,0\n1,1\n2,0\n3,1\n");
  const auto table = read_time_table(z);
  expect_input_error([&] { table_motion(table, 2, Eigen::Vector3d::Zero()); },
                     {z.string(), "'z [m]'", "2-D"});
}

TEST(MotionTableErrors, TimeOutsideTheTable) {
  const auto path = write_file("range.csv", "t [s],x [m]\n0,0\n1,1\n2,0\n3,1\n");
  const auto m = table_motion(read_time_table(path), 3, Eigen::Vector3d::Zero());
  EXPECT_NO_THROW(m.state(3.0));
  expect_input_error([&] { m.state(3.5); }, {path.string(), "[0, 3] s", "t = 3.5 s"});
}

}  // namespace
}  // namespace hm::motion
