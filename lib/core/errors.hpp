#pragma once
// Errors of hydromodal. User errors (bad arguments, bad input files, numerical failure of a
// well-posed request) are exceptions carrying the exit code a stage's main() maps them to.
// Broken invariants of our own code are HM_ASSERT failures (InternalError, exit code 4).
// HM_ASSERT is compiled out of release builds: its condition must never have side effects.
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace hm {

/// Documented exit codes of every stage executable.
enum class ExitCode : int {
  ok = 0,
  usage = 1,              ///< bad command line
  invalid_input = 2,      ///< a scene, artefact or geometry file is missing, malformed or invalid
  numerical_failure = 3,  ///< a solver did not converge, a run diverged
  internal_error = 4,     ///< a bug: an internal invariant failed
};

class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ExitCode code() const { return code_; }

 private:
  ExitCode code_;
};

struct UsageError : Error {
  explicit UsageError(const std::string& m) : Error(ExitCode::usage, m) {}
};
struct InputError : Error {
  explicit InputError(const std::string& m) : Error(ExitCode::invalid_input, m) {}
};
struct NumericalError : Error {
  explicit NumericalError(const std::string& m) : Error(ExitCode::numerical_failure, m) {}
};
struct InternalError : Error {
  explicit InternalError(const std::string& m) : Error(ExitCode::internal_error, m) {}
};

/// Throws InputError with a formatted message: name the file/key/dataset, the bad value and
/// what would be accepted.
template <typename... Args>
[[noreturn]] void input_error(fmt::format_string<Args...> f, Args&&... args) {
  throw InputError(fmt::format(f, std::forward<Args>(args)...));
}
template <typename... Args>
[[noreturn]] void numerical_error(fmt::format_string<Args...> f, Args&&... args) {
  throw NumericalError(fmt::format(f, std::forward<Args>(args)...));
}

[[noreturn]] void assertion_failed(const char* expr, const char* file, int line,
                                   const std::string& message);

}  // namespace hm

#if !defined(NDEBUG) || defined(HM_ENABLE_ASSERTIONS)
#define HM_ASSERT(cond, ...)                                                                     \
  do {                                                                                           \
    if (!(cond)) ::hm::assertion_failed(#cond, __FILE__, __LINE__, fmt::format("" __VA_ARGS__)); \
  } while (0)
#else
// Compiled out, but `cond` stays referenced so that it raises no unused-variable warnings.
#define HM_ASSERT(cond, ...) \
  do {                       \
    if (false) (void)(cond); \
  } while (0)
#endif
