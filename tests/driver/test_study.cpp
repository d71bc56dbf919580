// fsi-study (driver/study_stage.hpp): the study file's checks, the make variables of its runs,
// and the observed order of convergence.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "../common/replaced.hpp"
#include "../common/scratch.hpp"
#include "core/errors.hpp"
#include "driver/study_stage.hpp"

using hm::test::replaced;

namespace hm::driver {
namespace {

constexpr const char* scene_text = R"([case]
name = "tank"
dimension = 2

[[wall]]
name = "tank"
kind = "rectangle"
origin = [0.0, 0.0]
size = [1.0, 1.0]
faces = ["xmin", "xmax", "ymin"]
mesh_size = 0.04

[fluid]
dx = 0.02

[[fluid.region]]
origin = [0.0, 0.0]
size = [1.0, 0.5]

[time]
end = 0.1

[[probe]]
name = "P1"
kind = "pressure"
position = [0.5, 0.1]
)";

constexpr const char* study_text = R"(scene = "scene.toml"
column = "P1.p [Pa]"
set = ["time.end=0.05"]

[[series]]
name = "resolution"
parameter = "fluid.dx"
set = ["wall[0].mesh_size=0.08"]
runs = [
  { name = "dx2", set = ["fluid.dx=0.02"] },
  { name = "dx1", set = ["fluid.dx=0.01"] },
]
)";

std::filesystem::path write_case(const std::string& name, const std::string& study) {
  const auto dir = test::fresh_dir(name);
  std::ofstream(dir / "scene.toml") << scene_text;
  std::ofstream(dir / "study.toml") << study;
  return dir / "study.toml";
}

std::string error_of(const std::string& name, const std::string& study) {
  try {
    load_study(write_case(name, study));
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Study, RunsCarryTheStudysSeriesAndOwnSettings) {
  const Study study = load_study(write_case("study_ok", study_text));
  ASSERT_EQ(study.series.size(), 1u);
  const StudySeries& s = study.series[0];
  ASSERT_EQ(s.runs.size(), 2u);
  EXPECT_EQ(s.runs[1].set,
            (std::vector<std::string>{"time.end=0.05", "wall[0].mesh_size=0.08", "fluid.dx=0.01"}));
  EXPECT_EQ(s.runs[1].value, "0.01");
  const std::string rules = study_make_rules(study);
  EXPECT_NE(rules.find("STUDY_RUNS := resolution/dx2 resolution/dx1\n"), std::string::npos);
  EXPECT_NE(rules.find(
                "STUDY_SET.resolution/dx1 := time.end=0.05 wall[0].mesh_size=0.08 fluid.dx=0.01\n"),
            std::string::npos);
  EXPECT_NE(rules.find("STUDY_SCENE := " + (study.file.parent_path() / "scene.toml").string()),
            std::string::npos);
}

TEST(Study, BadStudiesAreRefusedWithTheKeyAndValue) {
  EXPECT_NE(error_of("study_key", replaced(study_text, "column", "colum"))
                .find("unknown key 'colum' in the study"),
            std::string::npos);
  EXPECT_NE(error_of("study_param", replaced(study_text, "\"fluid.dx=0.01\"", "\"time.end=0.04\""))
                .find("run resolution/dx1: its settings do not set the series' parameter "
                      "'fluid.dx'"),
            std::string::npos);
  EXPECT_NE(error_of("study_name", replaced(study_text, "name = \"dx1\"", "name = \"dx 1\""))
                .find("use letters, digits"),
            std::string::npos);
  EXPECT_NE(error_of("study_dup", replaced(study_text, "name = \"dx1\"", "name = \"dx2\""))
                .find("two runs named \"dx2\""),
            std::string::npos);
  EXPECT_NE(error_of("study_blank", replaced(study_text, "fluid.dx=0.01", "fluid.dx = 0.01"))
                .find("holds a blank"),
            std::string::npos);
  // A run's settings are checked against the scene before any run is made.
  EXPECT_NE(error_of("study_scene", replaced(study_text, "fluid.dx=0.01", "fluid.dx=-0.01"))
                .find("fluid.dx = -0.01 is out of range"),
            std::string::npos);
  EXPECT_NE(error_of("study_ref", "reference = \"none\"\n" + std::string(study_text))
                .find("no [[report.compare]] entry labelled \"none\""),
            std::string::npos);
  EXPECT_NE(
      error_of("study_file", replaced(study_text, "scene.toml", "nope.toml")).find("no such file"),
      std::string::npos);
}

// e ∝ h^p: the order comes back for refinement (h falls) and for mode counts (n rises).
TEST(Study, ObservedOrder) {
  EXPECT_NEAR(observed_order(0.02, 3 * std::pow(0.02, 1.5), 0.01, 3 * std::pow(0.01, 1.5)), 1.5,
              1e-12);
  EXPECT_NEAR(observed_order(2, 1.0 / 8, 4, 1.0 / 64), 3.0, 1e-12);
  EXPECT_TRUE(std::isnan(observed_order(0.01, 0.0, 0.005, 0.1)));  // the finest run itself
  EXPECT_TRUE(std::isnan(observed_order(0.01, 0.1, 0.01, 0.1)));
  EXPECT_TRUE(std::isnan(observed_order(std::nan(""), 0.1, 0.01, 0.05)));  // not a number
}

}  // namespace
}  // namespace hm::driver
