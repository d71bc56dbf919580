#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstring>
#include <random>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace hm::io {
namespace {

// Fixed-size table of temporary paths that a signal handler may unlink (async-signal-safe).
constexpr int max_slots = 16;
constexpr std::size_t max_path = 4096;
std::array<std::array<char, max_path>, max_slots> pending_paths{};
std::array<std::atomic<bool>, max_slots> slot_used{};

int register_pending(const std::filesystem::path& path) {
  const std::string text = path.string();
  if (text.size() >= max_path) return -1;
  for (int i = 0; i < max_slots; ++i) {
    bool expected = false;
    if (slot_used[i].compare_exchange_strong(expected, true)) {
      std::memcpy(pending_paths[i].data(), text.c_str(), text.size() + 1);
      return i;
    }
  }
  return -1;
}

void unregister_pending(int slot) {
  if (slot >= 0) slot_used[slot].store(false);
}

extern "C" void remove_pending_and_reraise(int signal_number) {
  for (int i = 0; i < max_slots; ++i)
    if (slot_used[i].load()) ::unlink(pending_paths[i].data());
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

std::string random_suffix() {
  std::random_device device;
  return std::to_string(::getpid()) + "-" + std::to_string(device() % 1000000);
}

}  // namespace

AtomicOutput::AtomicOutput(std::filesystem::path final_path) : final_path_(std::move(final_path)) {
  const auto folder =
      final_path_.has_parent_path() ? final_path_.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (!std::filesystem::is_directory(folder))
    input_error("cannot create the output folder '{}' for '{}'", folder.string(),
                final_path_.string());
  temp_path_ = folder / fmt::format(".{}.tmp-{}", final_path_.filename().string(), random_suffix());
  slot_ = register_pending(temp_path_);
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) {
    std::error_code ec;
    std::filesystem::remove(temp_path_, ec);
  }
  unregister_pending(slot_);
}

void AtomicOutput::commit() {
  HM_ASSERT(!committed_, "commit called twice for {}", final_path_.string());
  const int fd = ::open(temp_path_.c_str(), O_RDONLY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  std::error_code ec;
  std::filesystem::rename(temp_path_, final_path_, ec);
  if (ec)
    input_error("cannot move the finished output to '{}': {}", final_path_.string(), ec.message());
  committed_ = true;
}

void install_interrupt_cleanup() {
  struct sigaction action {};
  action.sa_handler = remove_pending_and_reraise;
  sigemptyset(&action.sa_mask);
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(signal_number, &action, nullptr);
}

}  // namespace hm::io
