#pragma once
// Logging goes to stderr through spdlog; stdout is kept for results a user may pipe
// (fsi-inspect's summary, --print-config-reference).
#include <spdlog/spdlog.h>

namespace hm {

enum class Verbosity { quiet, normal, verbose };

/// Sets up the process-wide logger (called once by each stage's main).
void configure_logging(Verbosity verbosity);

}  // namespace hm
