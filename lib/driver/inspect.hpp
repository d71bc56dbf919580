#pragma once
// fsi-inspect: a readable summary of any hydromodal artefact, as text or JSON.
#include <filesystem>
#include <string>

namespace hm::driver {

/// Human-readable summary: schema, provenance, datasets with shapes and units.
std::string inspect_text(const std::filesystem::path& artefact);

/// The same as JSON. Keys: schema, schema_version, stage, tool_version, created_utc, status,
/// parameters, inputs [{role, path, sha256}], attributes {name: value}, datasets [{path, dtype,
/// shape, unit, description, values?}], and, for every small numeric dataset whose last path
/// component is unique in the file, that name as a top-level key with its values (e.g.
/// "frequencies_hz").
std::string inspect_json(const std::filesystem::path& artefact);

}  // namespace hm::driver
