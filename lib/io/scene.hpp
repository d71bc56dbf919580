#pragma once
// Scene files (TOML): one per case. Every key is declared once (scene_keys.cpp) with its type,
// default, unit, allowed range and a one-line description; the reader rejects unknown keys (with
// line and a suggestion), wrong types and out-of-range values, fills in defaults, and produces
// the canonical text of the parameters each stage uses (stored in its artefact for provenance).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>
#include <Eigen/Core>

namespace hm::io {

enum class KeyType { number, integer, boolean, string, vector, string_list };

struct KeyDecl {
  std::string path;  ///< dotted; "[]" marks an array of tables: "structure.group[].name"
  KeyType type = KeyType::number;
  std::string default_text;  ///< TOML literal of the default; "" = required within its section
  std::string unit;          ///< SI unit ("1" dimensionless, "" for strings/flags)
  double min = -1e300, max = 1e300;
  bool min_exclusive = false, max_exclusive = false;
  std::vector<std::string> choices;  ///< allowed strings, also each of a string_list (empty: any)
  int vector_size = -1;              ///< required length of a vector; -1 any; 0 = case.dimension
  std::string doc;
  std::vector<std::string> stages;  ///< stages whose artefacts depend on this key
};

struct SectionDecl {
  std::string path;  ///< "structure", "structure.material", "structure.group[]"
  bool required = false;
  std::string doc;
};

/// The declared keys and sections (scene_keys.cpp).
const std::vector<KeyDecl>& scene_keys();
const std::vector<SectionDecl>& scene_sections();

/// Markdown reference of every key, generated from the declarations.
std::string scene_reference_markdown();

/// A validated scene with defaults filled in. Accessors take dotted paths relative to the view.
class SceneView {
 public:
  SceneView(const toml::table* table, std::string prefix, std::filesystem::path file)
      : table_(table), prefix_(std::move(prefix)), file_(std::move(file)) {}

  bool has(const std::string& key) const;
  double number(const std::string& key) const;
  long long integer(const std::string& key) const;
  bool boolean(const std::string& key) const;
  std::string string(const std::string& key) const;
  Eigen::VectorXd vector(const std::string& key) const;
  std::vector<std::string> strings(const std::string& key) const;  ///< string_list keys
  SceneView section(const std::string& key) const;
  std::vector<SceneView> array(const std::string& key) const;  ///< array of tables
  /// A path in the scene resolved against the scene file's folder.
  std::filesystem::path file_path(const std::string& key) const;
  /// "scene.toml:12: structure.material.youngs_modulus" for messages.
  std::string where(const std::string& key) const;
  const std::filesystem::path& file() const { return file_; }
  std::string full(const std::string& key) const;

 private:
  const toml::node& node(const std::string& key) const;
  const toml::table* table_;
  std::string prefix_;
  std::filesystem::path file_;
};

class Scene : public SceneView {
 public:
  /// Parses and validates; InputError listing every problem (file, line, key, value, accepted).
  /// `overrides` are "KEY=VALUE" settings from the command line (--set), applied before the
  /// validation: KEY a dotted path, an element of an array of tables by index
  /// ("wall[0].mesh_size"); VALUE a TOML value (0.005, [0.0,0.01], "text"; a bare word is taken
  /// as a string). InputError naming the setting when its path or value cannot be applied.
  static Scene load(const std::filesystem::path& path,
                    const std::vector<std::string>& overrides = {});
  static Scene parse(const std::string& text, const std::filesystem::path& path,
                     const std::vector<std::string>& overrides = {});

  /// Canonical "key = value" lines of every key that `stage` depends on (defaults included).
  std::string parameters_for(const std::string& stage) const;
  /// Every resolved key (for the echo at start).
  std::string resolved_text() const;
  int dimension() const { return static_cast<int>(integer("case.dimension")); }

  Scene(const Scene& other);
  Scene& operator=(const Scene&) = delete;

 private:
  Scene(toml::table table, std::filesystem::path path);
  std::string canonical(const std::vector<std::string>& stages_filter) const;
  toml::table resolved_;
};

}  // namespace hm::io
