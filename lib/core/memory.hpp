#pragma once
// What this machine has left: the memory a stage may still take, for refusals up front (a run
// that cannot fit is refused with an estimate before it starts, not killed halfway).

namespace hm {

/// Memory this process may still take [bytes]: MemAvailable of /proc/meminfo (0 when unknown).
double available_memory();

/// Bytes as GiB, for messages.
inline double gibibytes(double bytes) {
  return bytes / 1073741824.0;
}

}  // namespace hm
