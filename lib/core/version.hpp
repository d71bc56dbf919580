#pragma once
#include <string_view>

namespace hm {
/// Tool version written into every artefact: "<semver>+<git hash>[-dirty]".
std::string_view tool_version();
}  // namespace hm
