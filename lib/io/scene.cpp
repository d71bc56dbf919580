#include "io/scene.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/text.hpp"

namespace hm::io {
namespace {

/// A TOML number as a double. toml++'s value<double>() is empty for an integer a double cannot
/// hold exactly (beyond 2^53, e.g. 66666666666666666, found by fuzz_scene); the nearest double
/// is what a number key means.
double number_of(const toml::node& node) {
  if (const auto* integer = node.as_integer()) return static_cast<double>(integer->get());
  return node.as_floating_point()->get();
}

std::string parent_of(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? "" : path.substr(0, dot);
}
std::string leaf_of(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? path : path.substr(dot + 1);
}
std::string joined(const std::string& prefix, const std::string& key) {
  return prefix.empty() ? key : prefix + "." + key;
}

const KeyDecl* find_key(const std::string& normalised_path) {
  for (const auto& decl : scene_keys())
    if (decl.path == normalised_path) return &decl;
  return nullptr;
}
const SectionDecl* find_section(const std::string& normalised_path) {
  for (const auto& decl : scene_sections())
    if (decl.path == normalised_path) return &decl;
  return nullptr;
}

std::string type_name(KeyType type) {
  switch (type) {
    case KeyType::number:
      return "a number";
    case KeyType::integer:
      return "an integer";
    case KeyType::boolean:
      return "true or false";
    case KeyType::string:
      return "a string";
    case KeyType::vector:
      return "an array of numbers";
    case KeyType::string_list:
      return "an array of strings";
  }
  return "?";
}

std::string range_text(const KeyDecl& d) {
  const bool has_min = d.min > -1e299, has_max = d.max < 1e299;
  if (!has_min && !has_max) return "";
  std::string out;
  if (has_min) out += fmt::format("{} {} ", d.min, d.min_exclusive ? "<" : "≤");
  out += "value";
  if (has_max) out += fmt::format(" {} {}", d.max_exclusive ? "<" : "≤", d.max);
  return out;
}

std::string format_value(const toml::node& node) {
  if (auto v = node.as_floating_point()) return fmt::format("{}", v->get());  // shortest exact
  if (auto v = node.as_integer()) return fmt::format("{}", v->get());
  if (auto v = node.as_boolean()) return v->get() ? "true" : "false";
  if (auto v = node.as_string()) return fmt::format("\"{}\"", v->get());
  if (auto a = node.as_array()) {
    std::vector<std::string> parts;
    for (const auto& element : *a) parts.push_back(format_value(element));
    return "[" + join(parts, ", ") + "]";
  }
  return "?";
}

// ---- --set KEY=VALUE ----------------------------------------------------------------------------

/// VALUE as the TOML value of the key "v" of a table; a bare word that is no TOML value is
/// taken as a string.
toml::table parsed_override_value(const std::string& setting, const std::string& value) {
  try {
    return toml::parse("v = " + value);
  } catch (const toml::parse_error&) {
    const bool bare_word = !value.empty() && value.find_first_of("\"'[]{}=\n") == std::string::npos;
    if (!bare_word)
      input_error(
          "--set {}: '{}' is not a TOML value (a number, true/false, \"text\", or an "
          "array such as [0.0,0.01])",
          setting, value);
    return toml::table{{"v", value}};
  }
}

/// One segment of a --set path: a key, or a key with an index into an array of tables.
struct PathSegment {
  std::string key;
  std::optional<std::size_t> index;
};

std::vector<PathSegment> override_path(const std::string& setting, const std::string& key) {
  std::vector<PathSegment> segments;
  for (const auto& part : split_fields(key, '.')) {
    PathSegment segment{part, std::nullopt};
    if (const auto open = part.find('['); open != std::string::npos) {
      const auto close = part.find(']', open);
      if (close == std::string::npos)  // found by fuzzing: "wall[0" once read past the text
        input_error("--set {}: '{}' is not a key or key[index] (no closing ']')", setting, part);
      std::size_t index = 0;
      const char* first = part.data() + open + 1;
      const auto [end, error] = std::from_chars(first, part.data() + close, index);
      if (close != part.size() - 1 || error != std::errc{} || end != part.data() + close)
        input_error("--set {}: '{}' is not a key or key[index]", setting, part);
      segment = {part.substr(0, open), index};
    }
    if (segment.key.empty()) input_error("--set {}: the key '{}' has an empty part", setting, key);
    segments.push_back(segment);
  }
  return segments;
}

/// Applies "KEY=VALUE" to the parsed scene: creates missing tables on the way, never new
/// elements of an array of tables (the scene must have them).
void apply_override(toml::table& root, const std::string& setting,
                    const std::filesystem::path& file) {
  const auto equals = setting.find('=');
  if (equals == std::string::npos || equals == 0)
    input_error("--set '{}': expected KEY=VALUE, e.g. fluid.dx=0.005 or wall[0].mesh_size=0.02",
                setting);
  const std::string key(trimmed(std::string_view(setting).substr(0, equals))),
      value(trimmed(std::string_view(setting).substr(equals + 1)));
  const auto segments = override_path(setting, key);
  toml::table* table = &root;
  for (std::size_t i = 0; i + 1 < segments.size(); ++i) {
    const auto& [name, index] = segments[i];
    toml::node* node = table->get(name);
    if (index) {
      auto* array = node ? node->as_array() : nullptr;
      if (!array || !array->is_array_of_tables() || *index >= array->size())
        input_error("--set {}: {} has {} [[{}]] entr{}, so there is no {}[{}]", setting,
                    file.string(), array ? array->size() : 0, name,
                    array && array->size() == 1 ? "y" : "ies", name, *index);
      table = array->get(*index)->as_table();
      continue;
    }
    if (!node) node = table->insert(name, toml::table{}).first->second.as_table();
    if (!node->is_table())
      input_error("--set {}: '{}' in {} is a value, not a section", setting, name, file.string());
    table = node->as_table();
  }
  const auto& [leaf, leaf_index] = segments.back();
  if (leaf_index) input_error("--set {}: the last part of the key cannot have an index", setting);
  if (const toml::node* existing = table->get(leaf); existing && existing->is_table())
    input_error("--set {}: '{}' is a section, not a key", setting, key);
  const toml::table parsed = parsed_override_value(setting, value);
  table->insert_or_assign(leaf, *parsed.get("v"));
}

class Validator {
 public:
  Validator(toml::table& root, std::filesystem::path file) : root_(root), file_(std::move(file)) {}

  void run() {
    walk(root_, "", "");
    fill_and_require(root_, "", "");
    check_vector_sizes(root_, "", "");
    if (!errors_.empty())
      throw InputError(fmt::format("{}: {} problem{} in the scene:\n  {}", file_.string(),
                                   errors_.size(), errors_.size() == 1 ? "" : "s",
                                   join(errors_, "\n  ")));
  }

 private:
  std::string at(const toml::node& node) const {
    const auto line = node.source().begin.line;
    return line ? fmt::format("{}:{}", file_.filename().string(), line)
                : fmt::format("{} (--set)", file_.filename().string());
  }

  bool is_known_prefix(const std::string& normalised) const {
    if (find_section(normalised)) return true;
    for (const auto& d : scene_keys())
      if (d.path.rfind(normalised + ".", 0) == 0) return true;
    return false;
  }

  std::vector<std::string> candidates_under(const std::string& normalised_prefix) const {
    std::set<std::string> names;
    for (const auto& d : scene_keys()) {
      if (parent_of(d.path) == normalised_prefix) names.insert(leaf_of(d.path));
    }
    for (const auto& s : scene_sections()) {
      std::string p = s.path;
      if (p.ends_with("[]")) p.resize(p.size() - 2);
      if (parent_of(p) == normalised_prefix) names.insert(leaf_of(p));
    }
    return {names.begin(), names.end()};
  }

  void unknown(const toml::node& node, const std::string& normalised_prefix,
               const std::string& actual_path, const std::string& key) {
    const auto siblings = candidates_under(normalised_prefix);
    std::string suggestion = closest_match(key, siblings);
    std::string hint;
    if (!suggestion.empty())
      hint = fmt::format("; did you mean '{}'?", joined(actual_prefix_of(actual_path), suggestion));
    else if (!siblings.empty())
      hint = fmt::format("; known keys here: {}", join(siblings, ", "));
    errors_.push_back(fmt::format("{}: unknown key '{}'{}", at(node), actual_path, hint));
  }
  static std::string actual_prefix_of(const std::string& actual_path) {
    return parent_of(actual_path);
  }

  void walk(toml::table& table, const std::string& normalised, const std::string& actual) {
    for (auto&& [k, node] : table) {
      const std::string key(k.str());
      const std::string n = joined(normalised, key), a = joined(actual, key);
      if (auto* sub = node.as_table()) {
        if (is_known_prefix(n) && !find_key(n))
          walk(*sub, n, a);
        else
          unknown(node, normalised, a, key);
      } else if (auto* array = node.as_array();
                 array && array->is_array_of_tables() && find_section(n + "[]")) {
        for (std::size_t i = 0; i < array->size(); ++i)
          walk(*array->get(i)->as_table(), n + "[]", fmt::format("{}[{}]", a, i));
      } else if (const KeyDecl* decl = find_key(n)) {
        check_value(*decl, node, a);
      } else {
        unknown(node, normalised, a, key);
      }
    }
  }

  void check_value(const KeyDecl& d, toml::node& node, const std::string& path) {
    const auto bad_type = [&] {
      errors_.push_back(fmt::format("{}: {} = {} has the wrong type: expected {}{}", at(node), path,
                                    format_value(node), type_name(d.type),
                                    d.unit.empty() || d.unit == "1" ? "" : " [" + d.unit + "]"));
    };
    switch (d.type) {
      case KeyType::number:
        if (!node.is_number()) return bad_type();
        return check_range(d, number_of(node), node, path);
      case KeyType::integer:
        if (!node.is_integer()) return bad_type();
        return check_range(d, static_cast<double>(node.as_integer()->get()), node, path);
      case KeyType::boolean:
        if (!node.is_boolean()) return bad_type();
        return;
      case KeyType::string:
        if (!node.is_string()) return bad_type();
        return check_choice(d, node.as_string()->get(), node, path);
      case KeyType::string_list: {
        auto* array = node.as_array();
        if (!array || !std::all_of(array->begin(), array->end(),
                                   [](const toml::node& e) { return e.is_string(); }))
          return bad_type();
        for (const auto& element : *array) check_choice(d, element.as_string()->get(), node, path);
        return;
      }
      case KeyType::vector: {
        auto* array = node.as_array();
        if (!array || !std::all_of(array->begin(), array->end(),
                                   [](const toml::node& e) { return e.is_number(); }))
          return bad_type();
        for (const auto& element : *array) check_range(d, number_of(element), node, path);
        return;
      }
    }
  }

  void check_choice(const KeyDecl& d, const std::string& value, const toml::node& node,
                    const std::string& path) {
    if (d.choices.empty() ||
        std::find(d.choices.begin(), d.choices.end(), value) != d.choices.end())
      return;
    const std::string guess = closest_match(value, d.choices);
    errors_.push_back(fmt::format(
        "{}: {} = \"{}\" is not allowed: expected one of {}{}", at(node), path, value,
        join(d.choices, ", "), guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess)));
  }

  void check_range(const KeyDecl& d, double value, const toml::node& node,
                   const std::string& path) {
    const bool below = d.min_exclusive ? value <= d.min : value < d.min;
    const bool above = d.max_exclusive ? value >= d.max : value > d.max;
    if (below || above || !std::isfinite(value))
      errors_.push_back(fmt::format("{}: {} = {} is out of range: expected {}{}", at(node), path,
                                    format_value(node), range_text(d),
                                    d.unit.empty() || d.unit == "1" ? "" : " [" + d.unit + "]"));
  }

  /// Fills defaults and reports missing required keys/sections under `table`.
  void fill_and_require(toml::table& table, const std::string& normalised,
                        const std::string& actual) {
    for (const auto& d : scene_keys()) {
      if (parent_of(d.path) != normalised) continue;
      const std::string key = leaf_of(d.path);
      if (table.contains(key)) continue;
      if (d.default_text.empty()) {
        errors_.push_back(fmt::format("{}: missing required key '{}' ({}{})",
                                      file_.filename().string(), joined(actual, key), d.doc,
                                      d.unit.empty() || d.unit == "1" ? "" : ", in " + d.unit));
        continue;
      }
      auto parsed = toml::parse("v = " + d.default_text);
      table.insert(key, *parsed["v"].node());
    }
    for (const auto& s : scene_sections()) {
      const bool is_array = s.path.ends_with("[]");
      const std::string path = is_array ? s.path.substr(0, s.path.size() - 2) : s.path;
      if (parent_of(path) != normalised) continue;
      const std::string key = leaf_of(path);
      if (is_array) {
        if (auto* array = table[key].as_array()) {
          for (std::size_t i = 0; i < array->size(); ++i)
            if (auto* element = array->get(i)->as_table())
              fill_and_require(*element, s.path, fmt::format("{}[{}]", joined(actual, key), i));
        } else if (table.contains(key)) {
          errors_.push_back(fmt::format(
              "{}: {} is an array of tables: expected [[{}]] sections, got a single value or table",
              at(*table.get(key)), joined(actual, key), joined(actual, key)));
        }
        continue;
      }
      if (auto* sub = table[key].as_table()) {
        fill_and_require(*sub, path, joined(actual, key));
      } else if (table.contains(key)) {
        // A value where the section belongs (`solver = 1`, `--set solver=`).
        errors_.push_back(fmt::format("{}: {} is a section: expected a table [{}], got a value",
                                      at(*table.get(key)), joined(actual, key),
                                      joined(actual, key)));
      } else if (s.required) {
        errors_.push_back(fmt::format("{}: missing required section [{}] ({})",
                                      file_.filename().string(), joined(actual, key), s.doc));
      } else if (all_defaults(path)) {
        table.insert(key, toml::table{});
        fill_and_require(*table[key].as_table(), path, joined(actual, key));
      }
    }
  }

  static bool all_defaults(const std::string& section) {
    for (const auto& d : scene_keys())
      if (d.path.rfind(section + ".", 0) == 0 && d.default_text.empty()) return false;
    for (const auto& s : scene_sections())
      if (s.path.rfind(section + ".", 0) == 0 && s.required) return false;
    return true;
  }

  void check_vector_sizes(toml::table& table, const std::string& normalised,
                          const std::string& actual) {
    // Only an integer counts: value<long long>() converts a float, out of range for 7e96 (UB,
    // found by fuzz_scene); a non-integer dimension is reported by its own type check.
    const auto* dimension = root_["case"]["dimension"].as_integer();
    const long long dim = dimension ? dimension->get() : 3;
    for (auto&& [k, node] : table) {
      const std::string key(k.str());
      const std::string n = joined(normalised, key), a = joined(actual, key);
      if (auto* sub = node.as_table()) {
        check_vector_sizes(*sub, n, a);
      } else if (auto* array = node.as_array(); array && array->is_array_of_tables()) {
        for (std::size_t i = 0; i < array->size(); ++i)
          check_vector_sizes(*array->get(i)->as_table(), n + "[]", fmt::format("{}[{}]", a, i));
      } else if (const KeyDecl* d = find_key(n); d && d->type == KeyType::vector && array) {
        const long long expected = d->vector_size == 0 ? dim : d->vector_size;
        if (expected > 0 && !array->empty() && static_cast<long long>(array->size()) != expected)
          errors_.push_back(fmt::format("{}: {} = {} has {} values, expected {}{}", at(node), a,
                                        format_value(node), array->size(), expected,
                                        d->vector_size == 0 ? " (case.dimension)" : ""));
      }
    }
  }

  toml::table& root_;
  std::filesystem::path file_;
  std::vector<std::string> errors_;
};

}  // namespace

// ---- SceneView ----------------------------------------------------------------------------------

std::string SceneView::full(const std::string& key) const {
  return joined(prefix_, key);
}

const toml::node& SceneView::node(const std::string& key) const {
  const auto view = toml::node_view<const toml::node>(table_).at_path(key);
  if (!view) input_error("{}: the scene has no key '{}'", file_.string(), full(key));
  return *view.node();
}

bool SceneView::has(const std::string& key) const {
  return static_cast<bool>(toml::node_view<const toml::node>(table_).at_path(key));
}
double SceneView::number(const std::string& key) const {
  return number_of(node(key));
}
long long SceneView::integer(const std::string& key) const {
  return node(key).value<long long>().value();
}
bool SceneView::boolean(const std::string& key) const {
  return node(key).value<bool>().value();
}
std::string SceneView::string(const std::string& key) const {
  return node(key).value<std::string>().value();
}
Eigen::VectorXd SceneView::vector(const std::string& key) const {
  const auto* array = node(key).as_array();
  HM_ASSERT(array, "{} is not an array", full(key));
  Eigen::VectorXd out(array->size());
  for (std::size_t i = 0; i < array->size(); ++i) out[i] = number_of(*array->get(i));
  return out;
}
std::vector<std::string> SceneView::strings(const std::string& key) const {
  const auto* array = node(key).as_array();
  HM_ASSERT(array, "{} is not an array", full(key));
  std::vector<std::string> out;
  for (const auto& element : *array) out.push_back(element.value<std::string>().value());
  return out;
}

SceneView SceneView::section(const std::string& key) const {
  const auto* table = node(key).as_table();
  HM_ASSERT(table, "{} is not a table", full(key));
  return SceneView(table, full(key), file_);
}
std::vector<SceneView> SceneView::array(const std::string& key) const {
  std::vector<SceneView> out;
  if (!has(key)) return out;
  const auto* array = node(key).as_array();
  HM_ASSERT(array, "{} is not an array", full(key));
  for (std::size_t i = 0; i < array->size(); ++i)
    out.emplace_back(array->get(i)->as_table(), fmt::format("{}[{}]", full(key), i), file_);
  return out;
}
std::filesystem::path SceneView::file_path(const std::string& key) const {
  std::filesystem::path p = string(key);
  return p.is_absolute() ? p : file_.parent_path() / p;
}
std::string SceneView::where(const std::string& key) const {
  const auto view = toml::node_view<const toml::node>(table_).at_path(key);
  const auto line = view ? view.node()->source().begin.line : 0;
  return line ? fmt::format("{}:{}: {}", file_.filename().string(), line, full(key))
              : fmt::format("{}: {}", file_.filename().string(), full(key));
}

// ---- Scene --------------------------------------------------------------------------------------

Scene::Scene(toml::table table, std::filesystem::path path)
    : SceneView(nullptr, "", path), resolved_(std::move(table)) {
  static_cast<SceneView&>(*this) = SceneView(&resolved_, "", path);
}

Scene::Scene(const Scene& other)
    : SceneView(nullptr, "", other.file()), resolved_(other.resolved_) {
  static_cast<SceneView&>(*this) = SceneView(&resolved_, "", other.file());
}

Scene Scene::parse(const std::string& text, const std::filesystem::path& path,
                   const std::vector<std::string>& overrides) {
  toml::table table;
  try {
    table = toml::parse(text, path.string());
  } catch (const toml::parse_error& e) {
    input_error("{}:{}:{}: TOML syntax error: {}", path.string(), e.source().begin.line,
                e.source().begin.column, e.description());
  }
  for (const auto& setting : overrides) apply_override(table, setting, path);
  Validator(table, path).run();
  return Scene(std::move(table), path);
}

Scene Scene::load(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path);
  if (!in)
    input_error("cannot read the scene file '{}': no such file or no permission", path.string());
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse(buffer.str(), path, overrides);
}

std::string Scene::canonical(const std::vector<std::string>& stages_filter) const {
  std::vector<std::string> lines;
  const auto wanted = [&](const KeyDecl& d) {
    if (stages_filter.empty()) return true;
    return std::any_of(d.stages.begin(), d.stages.end(), [&](const std::string& s) {
      return std::find(stages_filter.begin(), stages_filter.end(), s) != stages_filter.end();
    });
  };
  // Walk the resolved table in declaration order so the text is canonical.
  for (const auto& d : scene_keys()) {
    if (!wanted(d)) continue;
    const auto bracket = d.path.find("[]");
    if (bracket == std::string::npos) {
      if (auto view = toml::node_view<const toml::node>(&resolved_).at_path(d.path))
        lines.push_back(fmt::format("{} = {}", d.path, format_value(*view.node())));
      continue;
    }
    const std::string array_path = d.path.substr(0, bracket), rest = d.path.substr(bracket + 3);
    const auto* array =
        toml::node_view<const toml::node>(&resolved_).at_path(array_path).as_array();
    if (!array) continue;
    for (std::size_t i = 0; i < array->size(); ++i)
      if (auto view = toml::node_view<const toml::node>(array->get(i)).at_path(rest))
        lines.push_back(
            fmt::format("{}[{}].{} = {}", array_path, i, rest, format_value(*view.node())));
  }
  std::sort(lines.begin(), lines.end());
  return join(lines, "\n") + "\n";
}

std::string Scene::parameters_for(const std::string& stage) const {
  return canonical({stage});
}
std::string Scene::resolved_text() const {
  return canonical({});
}

// ---- reference ----------------------------------------------------------------------------------

std::string scene_reference_markdown() {
  std::string out =
      "# Scene keys\n\nGenerated by `<stage> --print-config-reference` from the declarations in "
      "`lib/io/scene_keys.cpp`. A key without a default is required when its section is present. "
      "Units are SI.\n";
  for (const auto& section : scene_sections()) {
    out += fmt::format("\n## [{}]{}\n\n{}\n\n", section.path, section.required ? " (required)" : "",
                       section.doc);
    out +=
        "| key | type | default | unit | allowed | used by | meaning "
        "|\n|---|---|---|---|---|---|---|\n";
    for (const auto& d : scene_keys()) {
      if (parent_of(d.path) != section.path) continue;
      std::string allowed = d.choices.empty() ? range_text(d) : join(d.choices, ", ");
      if (d.type == KeyType::vector)
        allowed += (allowed.empty() ? "" : "; ") +
                   (d.vector_size == 0  ? std::string("case.dimension values")
                    : d.vector_size > 0 ? fmt::format("{} values", d.vector_size)
                                        : "");
      out += fmt::format("| `{}` | {} | {} | {} | {} | {} | {} |\n", leaf_of(d.path),
                         type_name(d.type),
                         d.default_text.empty() ? "**required**" : "`" + d.default_text + "`",
                         d.unit.empty() ? "—" : d.unit, allowed.empty() ? "—" : allowed,
                         join(d.stages, ", "), d.doc);
    }
  }
  return out;
}

}  // namespace hm::io
