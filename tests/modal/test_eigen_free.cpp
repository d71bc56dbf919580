// Free-free blocks: the rigid-body modes come out at λ ≈ 0 (negative shift), and their
// participation factors carry the total mass and the moments of inertia.
#include <gtest/gtest.h>

#include <cstdio>

#include "mesh/structured.hpp"
#include "modal/modes.hpp"
#include "test_eigen_checks.hpp"

namespace hm::modal {
namespace {

using testing::expect_mode_invariants;

const fem::ElasticModel kAluminium{{7e10, 0.33, 2700.0}, fem::PlaneAssumption::plane_stress, 0.01};

void expect_rigid_modes(const ModeSet& modes, int rigid, const Eigen::VectorXd& inertia,
                        double mass) {
  expect_mode_invariants(modes);
  const double first_elastic = modes.frequency_hz(rigid);
  std::printf("%d-D free-free: max |f| of the rigid modes %.2e Hz, first elastic %.2f Hz\n",
              modes.dim, modes.frequency_hz.head(rigid).cwiseAbs().maxCoeff(), first_elastic);
  for (int i = 0; i < rigid; ++i) EXPECT_LT(std::abs(modes.frequency_hz(i)), 1e-3 * first_elastic);
  // The rigid modes span the rigid motions: their effective masses sum to the total mass in
  // every direction and to the moments of inertia about the centroid.
  const Eigen::VectorXd translational =
      modes.translational_effective_mass.topRows(rigid).colwise().sum().transpose();
  const Eigen::VectorXd rotational =
      modes.rotational_effective_mass.topRows(rigid).colwise().sum().transpose();
  for (int d = 0; d < modes.dim; ++d) EXPECT_NEAR(translational(d), mass, 1e-9 * mass);
  for (Eigen::Index k = 0; k < inertia.size(); ++k)
    EXPECT_NEAR(rotational(k), inertia(k), 1e-9 * inertia(k));
  // Elastic modes carry no rigid-body participation.
  EXPECT_LT(
      modes.translational_participation.bottomRows(modes.count() - rigid).cwiseAbs().maxCoeff(),
      1e-6 * std::sqrt(mass));
}

TEST(FreeFree, BlockHasSixRigidBodyModes) {
  const double a = 0.4, b = 0.3, c = 0.2;
  const mesh::StructureMesh m = mesh::structured_box(a, b, c, 4, 3, 2);
  const ModeSet modes = compute_modes(m, kAluminium, {}, {12, {}, "block"}, {},
                                      Eigen::Vector3d(a / 2, b / 2, c / 2), {}, "block");
  const double mass = 2700.0 * a * b * c;
  const Eigen::Vector3d inertia(mass * (b * b + c * c) / 12, mass * (a * a + c * c) / 12,
                                mass * (a * a + b * b) / 12);
  expect_rigid_modes(modes, 6, inertia, mass);
}

TEST(FreeFree, PlateHasThreeRigidBodyModes) {
  const double a = 0.4, b = 0.3;
  const mesh::StructureMesh m = mesh::structured_rectangle(a, b, 6, 4);
  const ModeSet modes = compute_modes(m, kAluminium, {}, {8, {}, "plate"}, {},
                                      Eigen::Vector3d(a / 2, b / 2, 0.0), {}, "plate");
  const double mass = 2700.0 * a * b * 0.01;
  expect_rigid_modes(modes, 3, Eigen::VectorXd::Constant(1, mass * (a * a + b * b) / 12), mass);
}

}  // namespace
}  // namespace hm::modal
