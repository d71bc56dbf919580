// fsi-inspect FILE [--json] — summary of any hydromodal artefact; exits 2 on a file that is not
// a valid artefact.
#include <iostream>

#include "driver/inspect.hpp"
#include "io/schema.hpp"
#include "stage_main.hpp"

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = "fsi-inspect",
      .summary =
          "Print the schema, provenance and datasets (shapes, units) of a hydromodal artefact.",
      .positional = "FILE",
      .positional_help = "artefact (.h5) to inspect",
      .inputs = {},
      .has_output = false,
      .has_validate = false,
      .flags = {
          {"json", "print the summary as JSON"},
          {"print-schemas", "print the reference of every artefact schema (Markdown) and exit"}}};
  // --print-schemas needs no FILE: answer it before the usual argument checks.
  for (int i = 1; i < argc; ++i)
    if (std::string_view(argv[i]) == "--print-schemas") {
      std::cout << hm::io::schema_reference_markdown();
      return 0;
    }
  return hm::stages::run_stage(argc, argv, info, [](const hm::stages::StageArgs& args) {
    std::cout << (args.flags.at("json") ? hm::driver::inspect_json(args.positional)
                                        : hm::driver::inspect_text(args.positional));
  });
}
