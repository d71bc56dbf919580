#pragma once
// gmsh is a process-wide singleton: one model, global options. GmshSession owns it for a scope —
// initialise on construction, finalise on destruction (also when an exception leaves the scope),
// so no gmsh state outlives a meshing call. Only one session may be open at a time.
#include <mutex>
#include <string>
#include <string_view>
#include <utility>

#include "core/errors.hpp"

namespace hm::mesh {

struct GmshSettings {
  int threads = 1;       ///< General.NumThreads (libgmsh uses OpenMP in the 1-D/2-D/3-D meshers)
  bool verbose = false;  ///< General.Terminal: gmsh's own messages on the terminal
};

class GmshSession {
 public:
  /// Throws InternalError when another session is open.
  explicit GmshSession(const GmshSettings& settings = {});
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  std::unique_lock<std::mutex> lock_;
  int openmp_threads_;  ///< OpenMP thread count before gmsh changed it, restored at the end
};

/// The message gmsh carries in an exception: gmsh 4.8 throws std::string (the last error);
/// newer versions throw std::runtime_error. Returns "" for anything else.
std::string gmsh_exception_message(std::exception_ptr error);

/// Runs `f` and turns a gmsh failure into InputError("<context>: gmsh: <message>"). hm::Error
/// passes through unchanged. Also reports an error gmsh only logged without throwing (4.8 does
/// this, e.g. for some file-reading failures).
template <typename F>
decltype(auto) gmsh_call(std::string_view context, F&& f);

namespace detail {
std::string gmsh_last_error();
[[noreturn]] void throw_gmsh_error(std::string_view context, const std::string& message);
}  // namespace detail

template <typename F>
decltype(auto) gmsh_call(std::string_view context, F&& f) {
  const std::string error_before = detail::gmsh_last_error();
  try {
    if constexpr (std::is_void_v<decltype(f())>) {
      std::forward<F>(f)();
      const std::string error_after = detail::gmsh_last_error();
      if (error_after != error_before && !error_after.empty())
        detail::throw_gmsh_error(context, error_after);
    } else {
      auto result = std::forward<F>(f)();
      const std::string error_after = detail::gmsh_last_error();
      if (error_after != error_before && !error_after.empty())
        detail::throw_gmsh_error(context, error_after);
      return result;
    }
  } catch (const hm::Error&) {
    throw;
  } catch (...) {
    detail::throw_gmsh_error(context, gmsh_exception_message(std::current_exception()));
  }
}

}  // namespace hm::mesh
