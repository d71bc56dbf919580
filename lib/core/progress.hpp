#pragma once
// Progress of long work. On a terminal: one redrawn bar with rate and ETA. Otherwise (a log
// file, CI): a plain line at most every `plain_interval` seconds, so logs stay short.
#include <chrono>
#include <string>

namespace hm {

class Progress {
 public:
  /// `total` is in `unit` (e.g. "steps", "s" of simulated time); quiet disables output.
  Progress(std::string label, double total, std::string unit, bool quiet = false);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void update(double done);
  void finish();  ///< the work is complete: draws the final 100 % line

  static double plain_interval_s;

 private:
  void draw(bool final_line);
  std::string label_, unit_;
  double total_, done_ = 0;
  bool quiet_, tty_, finished_ = false;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace hm
