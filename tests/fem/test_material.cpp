// Material validation messages (a tested interface) and the Voigt elasticity matrices.
#include <gtest/gtest.h>

#include <Eigen/LU>

#include "core/errors.hpp"
#include "fem/material.hpp"

namespace hm::fem {
namespace {

std::string input_error_text(const ElasticModel& model, int dim) {
  try {
    validate(model, dim, "scene.toml: bodies.gate.material");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expect_contains(const std::string& text, std::initializer_list<const char*> parts) {
  ASSERT_FALSE(text.empty()) << "no InputError thrown";
  for (const char* p : parts) EXPECT_NE(text.find(p), std::string::npos) << text << " lacks " << p;
}

TEST(Material, RejectsNonPositiveYoungsModulus) {
  for (double e : {0.0, -5.0}) {
    const std::string text = input_error_text({{e, 0.3, 1000.0}}, 3);
    expect_contains(text, {"scene.toml: bodies.gate.material", "Young's modulus", "> 0"});
    EXPECT_NE(text.find(fmt::format("E = {} Pa", e)), std::string::npos) << text;
  }
}

TEST(Material, RejectsPoissonRatioOutsideOpenInterval) {
  for (double nu : {0.5, 0.7, -1.0}) {
    const std::string text = input_error_text({{1e9, nu, 1000.0}}, 3);
    expect_contains(text, {"bodies.gate.material", "Poisson's ratio", "(-1, 0.5)"});
    EXPECT_NE(text.find(fmt::format("ν = {}", nu)), std::string::npos) << text;
  }
}

TEST(Material, RejectsNonPositiveDensityAndThickness) {
  expect_contains(input_error_text({{1e9, 0.3, -1.0}}, 3), {"density", "-1 kg/m³", "> 0"});
  expect_contains(input_error_text({{1e9, 0.3, 1.0}, PlaneAssumption::plane_stress, 0.0}, 2),
                  {"thickness = 0 m", "> 0"});
  EXPECT_NO_THROW(validate(ElasticModel{{1e9, 0.3, 1.0}, PlaneAssumption::plane_stress, 0.0}, 3,
                           "3-D ignores thickness"));
}

TEST(Material, PlaneMatricesFollowFrom3D) {
  const Material m{2.1e11, 0.3, 7850.0};
  const Eigen::MatrixXd d3 = elasticity_matrix({m}, 3);
  // Plane strain: rows/columns xx, yy, xy of the 3-D matrix.
  const std::array<int, 3> in_plane{0, 1, 5};
  Eigen::MatrixXd strain(3, 3), stress_compliance(3, 3);
  const Eigen::MatrixXd c3 = d3.inverse();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      strain(i, j) = d3(in_plane[i], in_plane[j]);
      stress_compliance(i, j) = c3(in_plane[i], in_plane[j]);
    }
  EXPECT_LT((elasticity_matrix({m, PlaneAssumption::plane_strain}, 2) - strain).norm(),
            1e-12 * strain.norm());
  // Plane stress: inverse of the in-plane block of the compliance.
  const Eigen::MatrixXd stress = stress_compliance.inverse();
  EXPECT_LT((elasticity_matrix({m, PlaneAssumption::plane_stress}, 2) - stress).norm(),
            1e-12 * stress.norm());
  // Uniaxial stress: σ_xx / ε_xx = E.
  EXPECT_NEAR(1.0 / c3(0, 0), m.youngs_modulus_pa, 1e-12 * m.youngs_modulus_pa);
}

}  // namespace
}  // namespace hm::fem
