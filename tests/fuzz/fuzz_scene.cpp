// libFuzzer harness: the scene reader (io::Scene) on any text, with --set overrides. The input is
// scene text; leading lines "#set KEY=VALUE" are taken as --set overrides (a TOML comment, so a
// seed scene stays a scene). A bad scene must end in an InputError naming what is wrong; any other
// exception, a crash, a hang or a sanitizer report is a defect.
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "fuzz_input.hpp"
#include "io/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(hm::fuzz::as_text(data, size));
  std::vector<std::string> overrides;
  while (text.rfind("#set ", 0) == 0) {
    const auto end = text.find('\n');
    overrides.push_back(text.substr(5, end == std::string::npos ? std::string::npos : end - 5));
    text = end == std::string::npos ? std::string() : text.substr(end + 1);
  }
  try {
    const hm::io::Scene scene = hm::io::Scene::parse(text, "fuzz/scene.toml", overrides);
    for (const char* stage : {"fsi-mesh", "fsi-modes", "fsi-map", "fsi-simulate", "fsi-report"})
      (void)scene.parameters_for(stage);
    (void)scene.resolved_text();
  } catch (const hm::InputError&) {
  }
  return 0;
}
