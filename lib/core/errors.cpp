#include "core/errors.hpp"

namespace hm {

void assertion_failed(const char* expr, const char* file, int line, const std::string& message) {
  throw InternalError(
      fmt::format("internal error (please report): assertion '{}' failed at {}:{}{}{}", expr, file,
                  line, message.empty() ? "" : ": ", message));
}

}  // namespace hm
