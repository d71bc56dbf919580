#include "driver/inspect.hpp"

#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/artefact.hpp"

namespace hm::driver {
namespace {

std::string shape_text(const io::Dims& dims) {
  std::vector<std::string> parts;
  for (auto d : dims) parts.push_back(std::to_string(d));
  return parts.empty() ? "scalar" : fmt::format("{}", fmt::join(parts, " × "));
}

std::string leaf(const std::string& path) {
  return path.substr(path.rfind('/') + 1);
}

std::string preview(const std::vector<double>& values) {
  constexpr std::size_t shown = 6;
  std::vector<std::string> parts;
  for (std::size_t i = 0; i < std::min(shown, values.size()); ++i)
    parts.push_back(fmt::format("{:.6g}", values[i]));
  return fmt::format("[{}{}]", fmt::join(parts, ", "), values.size() > shown ? ", …" : "");
}

}  // namespace

std::string inspect_text(const std::filesystem::path& artefact) {
  const io::ArtefactSummary s = io::summarise(artefact);
  const io::Provenance& p = s.provenance;
  std::string out = fmt::format(
      "{}\n  schema        {} v{}\n  stage         {} ({})\n  created       {}\n"
      "  status        {}\n",
      artefact.string(), p.schema, p.schema_version, p.stage, p.tool_version, p.created_utc,
      p.status);
  for (const auto& input : p.inputs)
    out += fmt::format("  input {:<8} {} (sha256 {})\n", input.role, input.path,
                       input.sha256.substr(0, 16));
  out += "  attributes\n";
  for (const auto& a : s.attributes) {
    if (a.name.rfind(io::attr::input_prefix, 0) == 0 || a.name == io::attr::parameters) continue;
    out += fmt::format("    {:<28} {}\n", a.name, a.text);
  }
  out += "  datasets\n";
  for (const auto& d : s.datasets) {
    out += fmt::format("    {:<40} {:<8} {:<18} [{}]  {}\n", d.path, d.dtype, shape_text(d.dims),
                       d.unit.empty() ? "-" : d.unit, d.description);
    if (!d.values.empty() && d.values.size() <= 32) out += "      " + preview(d.values) + "\n";
  }
  out += "  parameters\n";
  for (std::size_t start = 0; start < p.parameters.size();) {
    const auto end = p.parameters.find('\n', start);
    out += "    " + p.parameters.substr(start, end - start) + "\n";
    start = end == std::string::npos ? p.parameters.size() : end + 1;
  }
  return out;
}

std::string inspect_json(const std::filesystem::path& artefact) {
  const io::ArtefactSummary s = io::summarise(artefact);
  const io::Provenance& p = s.provenance;
  nlohmann::ordered_json j;
  j["file"] = artefact.string();
  j["schema"] = p.schema;
  j["schema_version"] = p.schema_version;
  j["stage"] = p.stage;
  j["tool_version"] = p.tool_version;
  j["created_utc"] = p.created_utc;
  j["status"] = p.status;
  j["parameters"] = p.parameters;
  j["inputs"] = nlohmann::json::array();
  for (const auto& input : p.inputs)
    j["inputs"].push_back({{"role", input.role}, {"path", input.path}, {"sha256", input.sha256}});
  nlohmann::ordered_json attributes;
  for (const auto& a : s.attributes) {
    if (a.number && a.integer)
      attributes[a.name] = static_cast<std::int64_t>(*a.number);
    else if (a.number)
      attributes[a.name] = *a.number;
    else
      attributes[a.name] = a.text;
  }
  j["attributes"] = attributes;
  std::map<std::string, int> leaf_count;
  for (const auto& d : s.datasets) ++leaf_count[leaf(d.path)];
  j["datasets"] = nlohmann::json::array();
  for (const auto& d : s.datasets) {
    nlohmann::ordered_json entry{{"path", d.path},
                                 {"dtype", d.dtype},
                                 {"shape", d.dims},
                                 {"unit", d.unit},
                                 {"description", d.description}};
    if (!d.values.empty()) entry["values"] = d.values;
    j["datasets"].push_back(entry);
    if (!d.values.empty() && leaf_count[leaf(d.path)] == 1 && !j.contains(leaf(d.path)))
      j[leaf(d.path)] = d.values;
  }
  return j.dump(2) + "\n";
}

}  // namespace hm::driver
