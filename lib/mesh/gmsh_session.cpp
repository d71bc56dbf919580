#include "mesh/gmsh_session.hpp"

#include <exception>

#include <omp.h>

#include <gmsh.h>

namespace hm::mesh {
namespace {
std::mutex& session_mutex() {
  static std::mutex m;
  return m;
}
}  // namespace

GmshSession::GmshSession(const GmshSettings& settings)
    : lock_(session_mutex(), std::try_to_lock), openmp_threads_(omp_get_max_threads()) {
  if (!lock_.owns_lock())
    throw InternalError("a gmsh session is already open (gmsh is a process-wide singleton)");
  gmsh::initialize(0, nullptr, false);
  try {
    gmsh::option::setNumber("General.Terminal", settings.verbose ? 1 : 0);
    gmsh::option::setNumber("General.NumThreads", settings.threads);
    gmsh::logger::start();
  } catch (...) {
    gmsh::finalize();
    omp_set_num_threads(openmp_threads_);
    throw InternalError("gmsh refused its start-up options: " +
                        gmsh_exception_message(std::current_exception()));
  }
}

GmshSession::~GmshSession() {
  try {
    gmsh::logger::stop();
    gmsh::finalize();
  } catch (...) {
    // A destructor must not throw; gmsh's finalize does not fail in practice.
  }
  // gmsh sets the process-wide OpenMP thread count to General.NumThreads (1 by default) and
  // leaves it there: every stage that meshed anything then ran its solvers on one thread
  // (measured: bench_flow at 1 and 2 threads within 3 % of each other). Restore it.
  omp_set_num_threads(openmp_threads_);
}

std::string gmsh_exception_message(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const std::string& message) {
    return message;
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "";
  }
}

namespace detail {

std::string gmsh_last_error() {
  std::string message;
  gmsh::logger::getLastError(message);
  return message;
}

void throw_gmsh_error(std::string_view context, const std::string& message) {
  throw InputError(fmt::format("{}: gmsh: {}", context,
                               message.empty() ? std::string("unknown failure") : message));
}

}  // namespace detail
}  // namespace hm::mesh
