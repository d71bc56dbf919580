// Scene files: declared keys only, types and ranges checked, defaults filled, canonical text.
#include <gtest/gtest.h>

#include "../common/replaced.hpp"
#include "core/errors.hpp"
#include "io/scene.hpp"

using hm::io::Scene;

using hm::test::replaced;

namespace {

const char* gate_scene = R"(# elastic gate, structure only
[case]
name = "elastic_gate"
dimension = 2

[structure]
clamped = "clamped"

[structure.geometry]
kind = "rectangle"
origin = [0.1, 0.0]
size = [0.005, 0.079]

[structure.mesh]
size = 0.001

[[structure.group]]
name = "clamped"
min = [0.09, 0.0789]
max = [0.11, 0.08]

[structure.material]
youngs_modulus = 12e6
poisson_ratio = 0.4
density = 1100
)";

std::string error_of(const std::string& text) {
  try {
    Scene::parse(text, "scene.toml");
  } catch (const hm::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

TEST(Scene, ValidSceneResolvesDefaults) {
  const Scene scene = Scene::parse(gate_scene, "/cases/gate/scene.toml");
  EXPECT_EQ(scene.dimension(), 2);
  EXPECT_DOUBLE_EQ(scene.number("structure.material.youngs_modulus"), 12e6);
  EXPECT_EQ(scene.string("structure.formulation"), "plane_strain");  // default
  EXPECT_EQ(scene.integer("modes.count"), 10);                       // default section
  EXPECT_EQ(scene.vector("structure.geometry.size").size(), 2);
  ASSERT_EQ(scene.array("structure.group").size(), 1u);
  EXPECT_EQ(scene.array("structure.group")[0].string("name"), "clamped");
  EXPECT_EQ(scene.file_path("structure.geometry.kind"), "/cases/gate/rectangle");
  EXPECT_EQ(scene.where("structure.mesh.size"), "scene.toml:15: structure.mesh.size");
}

TEST(Scene, UnknownKeyNamesKeyLineAndSuggestion) {
  const std::string message = error_of(replaced(gate_scene, "youngs_modulus", "youngs_modulos"));
  EXPECT_NE(message.find("scene.toml:23: unknown key 'structure.material.youngs_modulos'"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("did you mean 'structure.material.youngs_modulus'?"), std::string::npos)
      << message;
  // (the misspelling also leaves the required key missing: both are reported at once)
  EXPECT_NE(message.find("missing required key 'structure.material.youngs_modulus'"),
            std::string::npos)
      << message;

  const std::string section = error_of(std::string(gate_scene) + "\n[strcture.extra]\nx = 1\n");
  EXPECT_NE(section.find("unknown key 'strcture'"), std::string::npos) << section;
  EXPECT_NE(section.find("did you mean 'structure'?"), std::string::npos) << section;
}

TEST(Scene, OutOfRangeWrongTypeAndBadChoiceNameKeyValueAndRange) {
  const std::string nu =
      error_of(replaced(gate_scene, "poisson_ratio = 0.4", "poisson_ratio = 0.5"));
  EXPECT_NE(
      nu.find("structure.material.poisson_ratio = 0.5 is out of range: expected -1 < value < 0.5"),
      std::string::npos)
      << nu;
  const std::string e =
      error_of(replaced(gate_scene, "youngs_modulus = 12e6", "youngs_modulus = -1"));
  EXPECT_NE(e.find("youngs_modulus = -1 is out of range: expected 0 < value [Pa]"),
            std::string::npos)
      << e;
  const std::string type = error_of(replaced(gate_scene, "density = 1100", "density = \"heavy\""));
  EXPECT_NE(type.find("density = \"heavy\" has the wrong type: expected a number [kg/m^3]"),
            std::string::npos)
      << type;
  const std::string choice =
      error_of(replaced(gate_scene, "kind = \"rectangle\"", "kind = \"rectangel\""));
  EXPECT_NE(choice.find("expected one of rectangle, box, file (did you mean \"rectangle\"?)"),
            std::string::npos)
      << choice;
  const std::string size =
      error_of(replaced(gate_scene, "size = [0.005, 0.079]", "size = [0.005, 0.079, 1]"));
  EXPECT_NE(size.find("has 3 values, expected 2 (case.dimension)"), std::string::npos) << size;
  const std::string dim = error_of(replaced(gate_scene, "dimension = 2", "dimension = 4"));
  EXPECT_NE(dim.find("case.dimension = 4 is out of range: expected 2 ≤ value ≤ 3"),
            std::string::npos)
      << dim;
}

TEST(Scene, MissingSectionAndSyntaxErrors) {
  const std::string no_case = error_of("[modes]\ncount = 3\n");
  EXPECT_NE(no_case.find("missing required section [case]"), std::string::npos) << no_case;
  const std::string syntax = error_of("[case\nname = 1\n");
  EXPECT_NE(syntax.find("scene.toml:1:"), std::string::npos) << syntax;
  EXPECT_NE(syntax.find("TOML syntax error"), std::string::npos) << syntax;
}

TEST(Scene, AValueWhereASectionBelongsIsAnError) {
  // Found by fuzz_scene: `--set solver=  #` replaced the [solver] table by a string, and filling
  // the section's defaults then dereferenced a null table (UBSan).
  std::string message;
  try {
    Scene::parse(gate_scene, "scene.toml", {"solver=1"});
  } catch (const hm::InputError& e) {
    message = e.what();
  }
  EXPECT_NE(
      message.find("scene.toml (--set): solver is a section: expected a table [solver], got a "
                   "value"),
      std::string::npos)
      << message;
  const std::string wall = error_of("wall = 3\n" + std::string(gate_scene));
  EXPECT_NE(wall.find("wall is an array of tables: expected [[wall]] sections"), std::string::npos)
      << wall;
}

TEST(Scene, AnIntegerBeyondADoublesPrecisionIsReadAsTheNearestDouble) {
  // Found by fuzz_scene: toml++'s value<double>() is empty for 66666666666666666 (> 2^53), and the
  // range check threw std::bad_optional_access out of the reader.
  const Scene scene =
      Scene::parse(gate_scene, "scene.toml", {"structure.mesh.size=66666666666666666"});
  EXPECT_EQ(scene.number("structure.mesh.size"), 66666666666666666.0);
  const std::string negative =
      error_of(std::string(gate_scene) + "\n[time]\nend = -66666666666666666\n");
  EXPECT_NE(negative.find("time.end = -66666666666666666 is out of range"), std::string::npos)
      << negative;
}

TEST(Scene, AFloatDimensionIsAWrongTypeNotAConversion) {
  // Found by fuzz_scene: the vector-size check converted `dimension = 7e96` to an integer (UB).
  const std::string message = error_of(replaced(gate_scene, "dimension = 2", "dimension = 7e96"));
  EXPECT_NE(message.find("case.dimension = 7e+96 has the wrong type: expected an integer"),
            std::string::npos)
      << message;
}

TEST(Scene, CanonicalParametersArePerStageAndIgnoreFormatting) {
  const Scene a = Scene::parse(gate_scene, "scene.toml");
  const Scene b =
      Scene::parse(replaced(replaced(gate_scene, "density = 1100", "density   =   1100.0  # kg/m3"),
                            "# elastic gate, structure only", "# comment changed"),
                   "scene.toml");
  EXPECT_EQ(a.parameters_for("fsi-modes"), b.parameters_for("fsi-modes"));
  EXPECT_NE(a.parameters_for("fsi-mesh").find("structure.mesh.size = 0.001"), std::string::npos);
  EXPECT_EQ(a.parameters_for("fsi-mesh").find("youngs_modulus"), std::string::npos)
      << "material must not make the mesh stale";
  const Scene c = Scene::parse(
      replaced(gate_scene, "youngs_modulus = 12e6", "youngs_modulus = 11e6"), "scene.toml");
  EXPECT_NE(a.parameters_for("fsi-modes"), c.parameters_for("fsi-modes"));
  EXPECT_EQ(a.parameters_for("fsi-mesh"), c.parameters_for("fsi-mesh"));
  EXPECT_NE(a.parameters_for("fsi-mesh").find("structure.group[0].name = \"clamped\""),
            std::string::npos);
}

TEST(Scene, ReferenceIsGeneratedFromDeclarations) {
  const std::string ref = hm::io::scene_reference_markdown();
  for (const auto& key : hm::io::scene_keys()) {
    const std::string leaf = key.path.substr(key.path.rfind('.') + 1);
    EXPECT_NE(ref.find("| `" + leaf + "` |"), std::string::npos) << key.path;
  }
  EXPECT_NE(ref.find("## [structure.material]"), std::string::npos);
}

namespace {

std::string override_error(const std::vector<std::string>& overrides) {
  try {
    Scene::parse(gate_scene, "scene.toml", overrides);
  } catch (const hm::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

// --set KEY=VALUE: values replace the file's, missing sections are created, array-of-table
// elements are addressed by index, and every override is validated like the file.
TEST(Scene, OverridesReplaceAndAreValidated) {
  const Scene scene =
      Scene::parse(gate_scene, "scene.toml",
                   {"structure.material.youngs_modulus=13e6", "modes.count = 3",
                    "structure.group[0].name=top", "structure.clamped=top",
                    "structure.geometry.size=[0.006,0.079]", "structure.formulation=plane_stress"});
  EXPECT_DOUBLE_EQ(scene.number("structure.material.youngs_modulus"), 13e6);
  EXPECT_EQ(scene.integer("modes.count"), 3);  // [modes] is not in the file: created
  EXPECT_EQ(scene.array("structure.group")[0].string("name"), "top");
  EXPECT_DOUBLE_EQ(scene.vector("structure.geometry.size")[0], 0.006);
  EXPECT_EQ(scene.string("structure.formulation"), "plane_stress");  // a bare word: a string
  // The canonical parameters record the overridden values, so the artefacts' provenance does.
  EXPECT_NE(scene.parameters_for("fsi-modes").find("structure.material.youngs_modulus = 13000000"),
            std::string::npos);

  EXPECT_NE(override_error({"structure.material.youngs_modulos=1"})
                .find("scene.toml (--set): unknown key 'structure.material.youngs_modulos'; did "
                      "you mean 'structure.material.youngs_modulus'?"),
            std::string::npos);
  EXPECT_NE(override_error({"structure.material.poisson_ratio=0.7"}).find("is out of range"),
            std::string::npos);
  EXPECT_NE(override_error({"structure.group[1].name=x"})
                .find("has 1 [[group]] entry, so there is no group[1]"),
            std::string::npos);
  EXPECT_NE(override_error({"structure.mesh"}).find("expected KEY=VALUE"), std::string::npos);
  EXPECT_NE(override_error({"structure.mesh=1"}).find("is a section, not a key"),
            std::string::npos);
  EXPECT_NE(override_error({"structure.material.youngs_modulus.x=1"}).find("is a value"),
            std::string::npos);
  EXPECT_NE(override_error({"modes.count=[1,"}).find("is not a TOML value"), std::string::npos);
  EXPECT_NE(override_error({"structure.group[x].name=a"}).find("is not a key or key[index]"),
            std::string::npos);
  // Found by fuzzing (tests/fuzz/regressions/scene): an index without its ']' was read past the
  // end of the text.
  EXPECT_NE(override_error({"structure.group[0=a"}).find("(no closing ']')"), std::string::npos);
}
