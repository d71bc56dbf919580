// Bad input to mode extraction, with the text its error must contain.
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "mesh/structured.hpp"
#include "modal/modes.hpp"

namespace hm::modal {
namespace {

std::string input_error_text(const fem::ElasticModel& model, std::vector<std::string> clamped,
                             const ModeRequest& request) {
  const mesh::StructureMesh m = mesh::structured_rectangle(0.1, 0.01, 4, 1);
  try {
    compute_modes(m, model, clamped, request, {}, Eigen::Vector3d::Zero(), {},
                  "scene.toml: bodies.gate");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expect_contains(const std::string& text, std::initializer_list<const char*> parts) {
  ASSERT_FALSE(text.empty()) << "no InputError thrown";
  for (const char* p : parts) EXPECT_NE(text.find(p), std::string::npos) << text << " lacks " << p;
}

const fem::ElasticModel kRubber{{12e6, 0.4, 1100.0}};

TEST(ModeInputErrors, NonPositiveYoungsModulus) {
  fem::ElasticModel bad = kRubber;
  bad.material.youngs_modulus_pa = 0.0;
  expect_contains(input_error_text(bad, {"xmin"}, {4, {}, "modes"}),
                  {"scene.toml: bodies.gate", "Young's modulus E = 0 Pa", "> 0"});
}

TEST(ModeInputErrors, IncompressiblePoissonRatio) {
  fem::ElasticModel bad = kRubber;
  bad.material.poisson_ratio = 0.5;
  expect_contains(input_error_text(bad, {"xmin"}, {4, {}, "modes"}),
                  {"scene.toml: bodies.gate", "Poisson's ratio ν = 0.5", "(-1, 0.5)"});
}

TEST(ModeInputErrors, MissingClampGroup) {
  expect_contains(input_error_text(kRubber, {"base"}, {4, {}, "modes"}),
                  {"scene.toml: bodies.gate", "'base'", "xmax, xmin, ymax, ymin"});
}

TEST(ModeInputErrors, MoreModesThanFreeDofs) {
  // 9 × 3 nodes, 3 clamped: 48 free DOFs.
  expect_contains(input_error_text(kRubber, {"xmin"}, {49, {}, "bodies.gate.modes"}),
                  {"bodies.gate.modes", "49 modes requested", "only 48 free DOFs"});
}

TEST(ModeInputErrors, RequestNeedsCountOrFrequency) {
  expect_contains(input_error_text(kRubber, {"xmin"}, {0, {}, "bodies.gate.modes"}),
                  {"bodies.gate.modes", "not neither"});
  expect_contains(input_error_text(kRubber, {"xmin"}, {3, 100.0, "bodies.gate.modes"}),
                  {"not both"});
  expect_contains(input_error_text(kRubber, {"xmin"}, {0, -1.0, "bodies.gate.modes"}),
                  {"maximum frequency = -1 Hz", "> 0"});
}

TEST(ModeInputErrors, AllFreeDofsFallBackToTheDenseSolver) {
  // Asking for every free DOF is legal; Lanczos cannot, the dense solver answers.
  const mesh::StructureMesh m = mesh::structured_rectangle(0.1, 0.01, 4, 1);
  const ModeSet modes = compute_modes(m, kRubber, std::vector<std::string>{"xmin"},
                                      {48, {}, "modes"}, {}, Eigen::Vector3d::Zero(), {}, "gate");
  EXPECT_EQ(modes.count(), 48);
  EXPECT_LT(modes.orthogonality_error, 1e-10);
  EXPECT_LT(modes.residuals.maxCoeff(), 1e-8);
}

}  // namespace
}  // namespace hm::modal
