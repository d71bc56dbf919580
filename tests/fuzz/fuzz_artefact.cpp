// libFuzzer harness: the artefact reader every stage and fsi-inspect open (io::ArtefactReader
// with the schema a stage expects, then every declared dataset read; io::summarise, which walks
// any artefact). The first byte chooses the expected schema, the rest is the HDF5 file. Seeds are
// small valid artefacts of each schema (tests/fuzz/seeds/artefact/). A bad file must end in an
// InputError naming the file; anything else is a defect. A mutated body fails the seal
// (io/seal): what reaches HDF5 and the schema checks is a seed's body, under any schema byte and
// any padding of the seal's block.
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "fuzz_input.hpp"
#include "io/artefact.hpp"
#include "io/schema.hpp"

namespace {

/// The dataset paths of `spec` present in the file: itself, or every child of a "/group/*".
std::vector<std::string> present_paths(const hm::io::ArtefactReader& reader,
                                       const hm::io::DatasetSpec& spec) {
  if (!spec.path.ends_with("*")) {
    if (reader.has(spec.path)) return {spec.path};
    return {};
  }
  const std::string group = spec.path.substr(0, spec.path.size() - 1);
  const std::string group_name = group.substr(0, group.size() - 1);
  std::vector<std::string> paths;
  if (!reader.has(group_name)) return paths;
  for (const std::string& child : reader.children(group_name)) paths.push_back(group + child);
  return paths;
}

void read_declared(const hm::io::ArtefactReader& reader, const hm::io::SchemaSpec& schema) {
  for (const hm::io::DatasetSpec& spec : schema.datasets)
    for (const std::string& path : present_paths(reader, spec)) {
      if (spec.type == hm::io::DType::f64) (void)reader.read_values(path);
      if (spec.type == hm::io::DType::i64) (void)reader.read_index_values(path);
      (void)reader.dims(path);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::vector<const hm::io::SchemaSpec*> schemas = hm::io::all_schemas();
  const hm::io::SchemaSpec& expected = *schemas[data[0] % schemas.size()];
  const auto path = hm::fuzz::input_file(hm::fuzz::as_text(data + 1, size - 1), "artefact.h5");
  try {
    (void)hm::io::summarise(path, 64);
  } catch (const hm::InputError&) {
  }
  try {
    const hm::io::ArtefactReader reader(path, expected);
    read_declared(reader, expected);
    (void)reader.string_attribute(hm::io::attr::status);
  } catch (const hm::InputError&) {
  }
  return 0;
}
