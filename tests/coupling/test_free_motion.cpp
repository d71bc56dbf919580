// A body in free translation (coupling/free_motion.hpp): a free-free mode set's rigid-body
// modes, as an eigensolver returns them (any orthonormal basis of the rigid subspace, ω ≈ ±ε),
// are replaced by the one translation along the free axis with the body's mass; and a body
// falling through air follows z0 + v0·t − g t²/2 exactly (CFPI integrates ω = 0 exactly).
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Dense>

#include "core/errors.hpp"
#include "coupling/free_motion.hpp"
#include "coupling/run.hpp"
#include "ldd/seeding.hpp"
#include "mesh/wall_mesher.hpp"
#include "plate_rig.hpp"

namespace hm::coupling {
namespace {

using ldd::Vec;
constexpr double g = 9.81;  // [m/s²]

/// Four vertices of a square with lumped masses: rigid modes (x, y, rotation) mixed by a
/// rotation of their basis, and one elastic mode M-orthogonal to them, Γ = ΦᵀM T.
struct SquareBody {
  ModalSurface<2> modes;
  double mass = 0.0;
};

SquareBody square_body(bool with_rigid_modes) {
  SquareBody b;
  const std::vector<double> m{1.0, 2.0, 1.5, 0.5};  // [kg]
  const std::vector<Vec<2>> x{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  b.modes.x0 = x;
  b.mass = 5.0;
  Eigen::VectorXd lumped(8);
  for (int v = 0; v < 4; ++v) lumped.segment<2>(2 * v).setConstant(m[v]);
  const Eigen::MatrixXd M = lumped.asDiagonal();
  Eigen::MatrixXd basis(8, 4);  // tx, ty, rotation about the origin, an elastic shape
  for (int v = 0; v < 4; ++v) {
    basis.block<2, 1>(2 * v, 0) << 1, 0;
    basis.block<2, 1>(2 * v, 1) << 0, 1;
    basis.block<2, 1>(2 * v, 2) << -x[v].y(), x[v].x();
    basis.block<2, 1>(2 * v, 3) << (v % 2 ? 1.0 : -1.0), (v < 2 ? 0.5 : -0.3);
  }
  // M-orthonormalise (Gram–Schmidt): the rigid subspace first, then the elastic shape.
  for (int j = 0; j < 4; ++j) {
    for (int k = 0; k < j; ++k)
      basis.col(j) -= (basis.col(k).transpose() * M * basis.col(j))(0) * basis.col(k);
    basis.col(j) /= std::sqrt((basis.col(j).transpose() * M * basis.col(j))(0));
  }
  // An eigensolver returns some orthonormal basis of the rigid subspace.
  const Eigen::Matrix3d mix =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  basis.leftCols(3) = basis.leftCols(3) * mix;
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(8, 2);
  for (int v = 0; v < 4; ++v) T.block<2, 2>(2 * v, 0).setIdentity();
  if (with_rigid_modes) {
    b.modes.shapes = basis;
    b.modes.omega = Eigen::Vector4d(2e-7, 1e-8, 3e-7, 50.0);
  } else {  // a clamped set: elastic modes only (the last shape, given a frequency)
    b.modes.shapes = basis.rightCols(1);
    b.modes.omega = Eigen::VectorXd::Constant(1, 50.0);
  }
  b.modes.zeta = Eigen::VectorXd::Zero(b.modes.omega.size());
  b.modes.participation = b.modes.shapes.transpose() * M * T;
  return b;
}

TEST(FreeTranslation, ReplacesTheRigidModesByTheTranslationWithTheBodysMass) {
  SquareBody b = square_body(true);
  const Eigen::VectorXd elastic = b.modes.shapes.col(3);
  const FreeTranslation free = make_free_translation<2>(b.modes, 1, -2.0, "test");
  EXPECT_EQ(free.rigid_dropped, 3);
  EXPECT_EQ(free.mode, 1);
  EXPECT_NEAR(free.mass, b.mass, 1e-12 * b.mass);
  ASSERT_EQ(b.modes.modes(), 2);
  EXPECT_TRUE(b.modes.shapes.col(0).isApprox(elastic, 1e-14));
  EXPECT_EQ(b.modes.omega[0], 50.0);
  EXPECT_EQ(b.modes.omega[1], 0.0);
  for (int v = 0; v < 4; ++v) {
    EXPECT_EQ(b.modes.shapes(2 * v, 1), 0.0);
    EXPECT_NEAR(b.modes.shapes(2 * v + 1, 1), 1 / std::sqrt(b.mass), 1e-14);
  }
  EXPECT_NEAR(b.modes.participation(1, 1), std::sqrt(b.mass), 1e-12);
  EXPECT_NEAR(b.modes.initial_velocity[1], -2.0 * std::sqrt(b.mass), 1e-12);
  EXPECT_EQ(b.modes.initial_velocity[0], 0.0);
}

TEST(FreeTranslation, RefusesAClampedSetAndAnElasticModeWithMomentum) {
  SquareBody clamped = square_body(false);
  EXPECT_THROW(make_free_translation<2>(clamped.modes, 1, 0.0, "test"), InputError);
  SquareBody lopsided = square_body(true);
  lopsided.modes.participation(3, 1) = 0.1;  // as for a set missing a rigid-body mode
  EXPECT_THROW(make_free_translation<2>(lopsided.modes, 1, 0.0, "test"), InputError);
}

// A plate dropped through the air above a water layer, at −1 m/s: the exact parabola, the fluid
// untouched (strong coupling: the added-mass solves give zero in the air).
TEST(FreeTranslation, FreeFallThroughAirIsExact) {
  const double v0 = -1.0, end = 0.05;
  Eigen::Matrix<double, 3, 2> level;
  level << 0.1, 0.25, 0.2, 0.25, 0.3, 0.25;
  test::PlateRig rig = test::plate_rig(level, 0.4);
  ldd::FlowSolver<2>& flow = *rig.flow;
  const mesh::SurfaceMesh &tank = rig.tank, &plate = rig.plate;
  SquareBody b = square_body(true);  // its modes on the plate's three vertices
  ModalSurface<2> modes;
  for (int k = 0; k < 3; ++k) modes.x0.push_back(plate.vertices.row(k).transpose());
  modes.shapes = b.modes.shapes.topRows(6);
  modes.omega = b.modes.omega;
  modes.zeta = b.modes.zeta;
  modes.participation = b.modes.participation;
  const FreeTranslation free = make_free_translation<2>(modes, 1, v0, "test");
  std::vector<FlexibleBody<2>> bodies;
  bodies.emplace_back("plate", std::move(modes), 1, CouplingOptions{}, flow.walls()[1]);
  std::vector<WallMotion> motions{{tank.vertices, std::nullopt}, {plate.vertices, std::nullopt}};
  const RunResult r = run<2>(flow, motions, {.end = end}, {}, std::span(bodies));
  ASSERT_EQ(r.status, RunStatus::completed) << r.divergence_report;
  double worst = 0.0;
  for (std::size_t k = 0; k < r.modal[0].time.size(); ++k) {
    const double t = r.modal[0].time[k];
    const double z = r.modal[0].y[k][free.mode] / std::sqrt(free.mass);
    worst = std::max(worst, std::abs(z - (v0 * t - 0.5 * g * t * t)));
  }
  const double fall = -(v0 * end - 0.5 * g * end * end);
  std::printf("free fall: %zu steps, worst error %.3g of the fall %.3g m\n", r.monitors.size(),
              worst / fall, fall);
  EXPECT_LT(worst, 1e-10 * fall);
  EXPECT_LT(bodies[0].deformation(), 1e-12 * fall);  // the elastic mode stays at rest
}

}  // namespace
}  // namespace hm::coupling
