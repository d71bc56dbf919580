#pragma once
// Atomic output: a stage writes to a temporary file in the target folder and renames it over the
// output path only when complete, so a failed or killed stage never leaves a file at its output
// path. Temporary files still open when SIGINT/SIGTERM/SIGHUP arrives are removed by the handler
// that `install_interrupt_cleanup()` sets up (SIGKILL leaves a hidden ".*.tmp-*" file beside the
// output, never the output itself).
#include <filesystem>

namespace hm::io {

class AtomicOutput {
 public:
  explicit AtomicOutput(std::filesystem::path final_path);
  ~AtomicOutput();  ///< removes the temporary file unless committed
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  const std::filesystem::path& temp_path() const { return temp_path_; }
  const std::filesystem::path& final_path() const { return final_path_; }
  /// fsyncs the temporary file and renames it to the final path.
  void commit();

 private:
  std::filesystem::path final_path_, temp_path_;
  int slot_ = -1;
  bool committed_ = false;
};

/// Installs signal handlers that delete uncommitted temporary outputs, then re-raise.
void install_interrupt_cleanup();

}  // namespace hm::io
