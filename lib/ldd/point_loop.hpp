#pragma once
// The one driver of the flow's per-point loops. A kernel (ldd/kernels.hpp) computes what a step
// does at one point from that point and its neighbours; these functions run it over the points
// a process owns, [0, owned), on OpenMP threads. Kernels write only their own point's entries,
// so points may run in any order on any thread. The points from `owned` on are not visited: a
// distributed run keeps there the ghost copies of other processes' points within the support
// radius, which kernels read as neighbours and never write. A run in one process owns all its
// points (owned = size).
//
// Reductions are per thread, merged in thread order, so that a result depends on the thread
// count only where the merge is not exact (max and integer counts are exact).
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "ldd/common.hpp"

namespace hm::ldd {

/// How the points are shared among threads: `even` in equal contiguous blocks (kernels of
/// equal cost, the default); `balanced` in chunks of 256 taken as threads finish (kernels whose
/// cost varies from point to point: the wall clearance, which skips most points).
enum class LoopBalance { even, balanced };

/// kernel(i) for every owned point i.
template <typename Kernel>
void for_each_point(Index owned, Kernel&& kernel, LoopBalance balance = LoopBalance::even) {
  if (balance == LoopBalance::even) {
#pragma omp parallel for schedule(static)
    for (Index i = 0; i < owned; ++i) kernel(i);
  } else {
#pragma omp parallel for schedule(dynamic, 256)
    for (Index i = 0; i < owned; ++i) kernel(i);
  }
}

/// Totals over the owned points: kernel(i, totals) adds point i to a thread's `Totals` (which
/// starts as `zero`); the threads' totals are merged in thread order by
/// `Totals::merge(const Totals&)`.
template <typename Totals, typename Kernel>
Totals reduce_points(Index owned, const Totals& zero, Kernel&& kernel) {
#ifdef _OPENMP
  std::vector<Totals> per_thread(static_cast<std::size_t>(omp_get_max_threads()), zero);
#pragma omp parallel
  {
    Totals& mine = per_thread[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(static)
    for (Index i = 0; i < owned; ++i) kernel(i, mine);
  }
  Totals total = zero;
  for (const Totals& t : per_thread) total.merge(t);
  return total;
#else
  Totals total = zero;
  for (Index i = 0; i < owned; ++i) kernel(i, total);
  return total;
#endif
}

}  // namespace hm::ldd
