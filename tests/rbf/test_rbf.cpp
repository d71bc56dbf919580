// RBF mapping (Wendland C2 + linear polynomial): exactness, identity, convergence, conservation,
// quality report and input errors.
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "point_sets.hpp"
#include "rbf/interpolator.hpp"

namespace hm::rbf {
namespace {

using test::fibonacci_sphere;
using test::jittered_grid;
using test::random_box;

// Columns: 1, each coordinate, and a general affine combination (+ a rigid rotation about z in
// 3-D: u = ω × x has components −y, x).
Eigen::MatrixXd affine_fields(const Points& x) {
  Eigen::MatrixXd f(x.rows(), x.cols() + 3);
  f.col(0).setOnes();
  for (Eigen::Index k = 0; k < x.cols(); ++k) f.col(1 + k) = x.col(k);
  f.col(x.cols() + 1) = 2.0 * x.col(0) - 3.0 * x.col(1) + Eigen::VectorXd::Constant(x.rows(), 5.0);
  if (x.cols() == 3) f.col(x.cols() + 1) += 0.7 * x.col(2);
  f.col(x.cols() + 2) = -x.col(1);  // rotation about z (x component); y component is column 1
  return f;
}

double max_relative_error(const Eigen::MatrixXd& got, const Eigen::MatrixXd& expected) {
  double worst = 0;
  for (Eigen::Index k = 0; k < got.cols(); ++k) {
    const double scale = std::max(expected.col(k).cwiseAbs().maxCoeff(), 1e-300);
    worst = std::max(worst, (got.col(k) - expected.col(k)).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

TEST(RbfMapping, ReproducesAffineFieldsOnCurvedSurface3D) {
  const Points src = fibonacci_sphere(1500, 0.8);
  const Points tgt = fibonacci_sphere(4000, 0.8 * (1 + 1e-3), 0.3);  // faceting-like offset
  const RbfInterpolator H(src, tgt);
  const double err = max_relative_error(H.apply(affine_fields(src)), affine_fields(tgt));
  fmt::print("affine fields on a sphere: max relative error {:.2e}\n", err);
  EXPECT_LE(err, 1e-10);
}

TEST(RbfMapping, ReproducesAffineFieldsIn2D) {
  const Points src = random_box(800, 2, -2.0, 3.0, 11);
  const Points tgt = random_box(3000, 2, -1.9, 2.9, 12);
  const RbfInterpolator H(src, tgt);
  EXPECT_LE(max_relative_error(H.apply(affine_fields(src)), affine_fields(tgt)), 1e-10);
}

TEST(RbfMapping, TargetsEqualToSourcesGiveTheIdentity) {
  for (int dim : {2, 3}) {
    const Points src = dim == 3 ? fibonacci_sphere(2000) : random_box(1500, 2, 0.0, 1.0);
    const Eigen::MatrixXd fields = Eigen::MatrixXd::Random(src.rows(), 4);
    const RbfInterpolator H(src, src);
    const double err = max_relative_error(H.apply(fields), fields);
    fmt::print("identity map {}-D: max relative deviation {:.2e}\n", dim, err);
    EXPECT_LE(err, 1e-12) << dim << "-D";
  }
}

// A flat plate in 3-D (all sources on z = 0.25) and colinear sources in 2-D: the linear polynomial
// is degenerate; the unsupported direction is dropped and in-plane affine fields stay exact.
TEST(RbfMapping, FlatPlateAndColinearSourcesAreHandled) {
  const Points plate = jittered_grid(40, 2.0, 0.3, 3, 0.25);
  const Points plate_targets = jittered_grid(97, 2.0, 0.4, 3, 0.25, 5);
  const RbfInterpolator H(plate, plate_targets);
  EXPECT_EQ(H.quality_report(Eigen::MatrixXd()).dropped_directions, 1);
  EXPECT_LE(max_relative_error(H.apply(affine_fields(plate)), affine_fields(plate_targets)), 1e-10);

  Points line(300, 2), line_targets(1000, 2);
  for (Eigen::Index i = 0; i < line.rows(); ++i) {
    const double s = 3.0 * i / 299.0 + 0.002 * std::sin(7.0 * i);  // uneven spacing along the line
    line.row(i) << s, 2 * s + 1;
  }
  for (Eigen::Index i = 0; i < line_targets.rows(); ++i) {
    const double s = 3.0 * i / 999.0;
    line_targets.row(i) << s, 2 * s + 1;
  }
  const RbfInterpolator L(line, line_targets);
  EXPECT_EQ(L.quality_report(Eigen::MatrixXd()).dropped_directions, 1);
  EXPECT_LE(max_relative_error(L.apply(affine_fields(line)), affine_fields(line_targets)), 1e-10);
}

double smooth_field(double x, double y, double z) {
  return std::sin(2.0 * x + 0.5) * std::cos(1.5 * y) + 0.5 * z * z;
}

// Smooth field on the unit sphere, source lattices of 500 → 2000 points, FIXED support radius
// 0.4 m (non-stationary: the stationary default saturates, see interpolator.hpp). Measured orders
// 5.1 and 5.4 (pre-asymptotic; the theory for Wendland C2 guarantees less); asserted > 4, i.e.
// well above the required 2 − 0.1.
TEST(RbfMapping, SmoothFieldConvergesUnderRefinementWithFixedSupport) {
  const Points tgt = fibonacci_sphere(5000, 1.0, 0.7);
  Eigen::VectorXd exact(tgt.rows());
  for (Eigen::Index i = 0; i < tgt.rows(); ++i)
    exact[i] = smooth_field(tgt(i, 0), tgt(i, 1), tgt(i, 2));
  std::vector<double> h, err;
  RbfOptions fixed;
  fixed.support_radius = 0.4;
  for (Eigen::Index n : {500, 1000, 2000}) {
    const Points src = fibonacci_sphere(n);
    Eigen::MatrixXd f(n, 1);
    for (Eigen::Index i = 0; i < n; ++i) f(i, 0) = smooth_field(src(i, 0), src(i, 1), src(i, 2));
    const RbfInterpolator H(src, tgt, fixed);
    h.push_back(H.source_spacing());
    err.push_back((H.apply(f).col(0) - exact).cwiseAbs().maxCoeff() / exact.cwiseAbs().maxCoeff());
  }
  for (size_t i = 1; i < h.size(); ++i) {
    const double order = std::log(err[i - 1] / err[i]) / std::log(h[i - 1] / h[i]);
    fmt::print("smooth field: h {:.4f} -> {:.4f}, error {:.3e} -> {:.3e}, order {:.2f}\n", h[i - 1],
               h[i], err[i - 1], err[i], order);
    EXPECT_GT(order, 4.0);
  }
}

// Φ_fᵀ f_f = Φ_sᵀ (Hᵀ f_f) with Φ_f = H Φ_s; total force and moment are kept.
TEST(RbfMapping, TransposeMapConservesModalForcesForceAndMoment) {
  const Points src = fibonacci_sphere(1200, 0.5);
  const Points tgt = fibonacci_sphere(5000, 0.5, 1.1);
  const RbfInterpolator H(src, tgt);
  const Eigen::MatrixXd modes_s = Eigen::MatrixXd::Random(src.rows(), 6);
  const Eigen::MatrixXd forces_f = Eigen::MatrixXd::Random(tgt.rows(), 3);
  const Eigen::MatrixXd modes_f = H.apply(modes_s);
  const Eigen::MatrixXd forces_s = H.apply_transpose(forces_f);
  const Eigen::MatrixXd gen_f = modes_f.transpose() * forces_f;
  const Eigen::MatrixXd gen_s = modes_s.transpose() * forces_s;
  const double rel = (gen_f - gen_s).cwiseAbs().maxCoeff() / gen_f.cwiseAbs().maxCoeff();
  fmt::print("generalised forces fluid vs structure side: relative difference {:.2e}\n", rel);
  EXPECT_LE(rel, 1e-12);
  const double total = forces_f.cwiseAbs().colwise().sum().maxCoeff();
  EXPECT_LE((forces_s.colwise().sum() - forces_f.colwise().sum()).cwiseAbs().maxCoeff(),
            1e-12 * total);
  for (int k = 0; k < 3; ++k) {  // first moments Σ x_k f
    const Eigen::RowVectorXd ms = src.col(k).transpose() * forces_s;
    const Eigen::RowVectorXd mf = tgt.col(k).transpose() * forces_f;
    EXPECT_LE((ms - mf).cwiseAbs().maxCoeff(), 1e-12 * total);
  }
}

TEST(RbfMapping, QualityReportCountsFarTargetsAndEstimatesErrors) {
  const Points src = fibonacci_sphere(3000);
  Points tgt = fibonacci_sphere(2000, 1.0, 0.2);
  const double h = RbfInterpolator(src, src).source_spacing();
  tgt.row(17) *= 1.0 + 3.0 * h;  // 3 spacings off the surface: beyond 2h, within the support 4h
  tgt.row(1234) *= 1.0 + 2.5 * h;
  const RbfInterpolator H(src, tgt);
  Eigen::MatrixXd fields(src.rows(), 2);
  for (Eigen::Index i = 0; i < src.rows(); ++i) {
    fields(i, 0) = 3.0 * src(i, 0) - src(i, 2);
    fields(i, 1) = smooth_field(src(i, 0), src(i, 1), src(i, 2));
  }
  const QualityReport q = H.quality_report(fields);
  fmt::print(
      "quality: spacing {:.4g} support {:.4g} far {} worst #{} at {:.4g} cond {:.3g} "
      "neighbours {:.1f} field errors {:.2e} {:.2e}\n",
      q.source_spacing, q.support_radius, q.far_targets, q.worst_target, q.worst_target_distance,
      q.condition_estimate, q.mean_neighbours, q.field_error[0], q.field_error[1]);
  EXPECT_NEAR(q.support_radius, 4.0 * q.source_spacing, 1e-14);
  EXPECT_EQ(q.far_targets, 2);
  EXPECT_EQ(q.worst_target, 17);
  EXPECT_GT(q.worst_target_distance, 2.9 * h);
  EXPECT_EQ(q.polynomial_terms, 4);
  EXPECT_GT(q.condition_estimate, 1.0);
  EXPECT_LT(q.condition_estimate, 1e8);
  EXPECT_LE(q.field_error[0], 1e-10);  // linear: exact even with 10 % of the points left out
  // The leave-some-out estimate (sources 10 % sparser) bounds the actual error at the targets
  // from above without exaggerating it by more than a factor 30.
  Eigen::MatrixXd exact(tgt.rows(), 1);
  for (Eigen::Index i = 0; i < tgt.rows(); ++i)
    exact(i, 0) = smooth_field(tgt(i, 0), tgt(i, 1), tgt(i, 2));
  Eigen::VectorXd deviation = (H.apply(fields.col(1)) - exact).cwiseAbs();
  deviation[17] = deviation[1234] = 0;  // the two targets moved off the surface
  const double actual = deviation.maxCoeff() / fields.col(1).cwiseAbs().maxCoeff();
  fmt::print("smooth field: leave-some-out estimate {:.2e}, actual error at targets {:.2e}\n",
             q.field_error[1], actual);
  EXPECT_GE(q.field_error[1], actual);
  EXPECT_LE(q.field_error[1], 30 * actual);
}

TEST(RbfMapping, SupportRadiusCanBeOverridden) {
  const Points src = fibonacci_sphere(500);
  RbfOptions o;
  o.support_radius = 0.5;
  const RbfInterpolator H(src, src, o);
  EXPECT_DOUBLE_EQ(H.support_radius(), 0.5);
}

std::string error_of(const Points& src, const Points& tgt) {
  try {
    RbfInterpolator H(src, tgt);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

void expect_contains(const std::string& message, const std::string& part) {
  EXPECT_NE(message.find(part), std::string::npos)
      << "message: " << message << "\nexpected: " << part;
}

TEST(RbfMappingErrors, EmptySourceSet) {
  expect_contains(error_of(Points(0, 3), fibonacci_sphere(10)), "source point set is empty");
}

TEST(RbfMappingErrors, UnitsDifferByAThousand) {
  const Points src = fibonacci_sphere(400, 0.5);         // metres
  const Points tgt = fibonacci_sphere(900, 500.0, 0.1);  // millimetres
  const std::string m = error_of(src, tgt);
  expect_contains(m, "units differ by ~1000? (mm vs m)");
  expect_contains(m, "times the source bounding box");
  expect_contains(error_of(tgt, src), "units differ by ~1000? (mm vs m)");
}

TEST(RbfMappingErrors, DisjointMeshes) {
  const Points src = fibonacci_sphere(400, 0.5);
  Points tgt = fibonacci_sphere(900, 0.5, 0.1);
  tgt.topRows(30).col(0).array() += 3.0;  // 30 targets moved 3 m away
  tgt(4, 0) += 1.0;                       // the worst one
  const std::string m = error_of(src, tgt);
  expect_contains(m, "30 of 900 target points lie farther than the support radius");
  expect_contains(m, "worst: target 4 at (");
  expect_contains(m, "do not overlap");
}

TEST(RbfMappingErrors, DuplicateSourcesAndDimensionMismatch) {
  Points src = fibonacci_sphere(100);
  src.row(42) = src.row(7);
  expect_contains(error_of(src, src), "source points 7 and 42 coincide");
  expect_contains(error_of(fibonacci_sphere(50), random_box(10, 2, 0, 1)),
                  "source points have 3 coordinates but target points 2");
}

}  // namespace
}  // namespace hm::rbf
