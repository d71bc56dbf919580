#pragma once
// The flow's points over MPI processes (ldd::PointExchange): regions from Zoltan's recursive
// coordinate bisection (Decomposition), points migrating to the owner of the region they moved
// into every step, and redrawn regions when the largest process holds more than
// `rebalance_above` × the mean; ghosts within the support radius along a kept Halo; reductions
// over MPI_COMM_WORLD.
#include <memory>
#include <mutex>

#include "ldd/exchange.hpp"
#include "parallel/decomposition.hpp"

namespace hm::parallel {

template <int D>
class FlowExchange final : public ldd::PointExchange<D> {
 public:
  /// `rebalance_above`: the imbalance (largest share over the mean) from which the regions are
  /// redrawn, > 1. Redrawing costs little beside a step (3-D dam break, 200 k points: the cuts
  /// and the migration 16 ms against a 3 s step at 2 processes), and the set-up's regions are
  /// drawn before the wall nodes' dryness is known: at 1.2 the larger region stayed at 1.14× the
  /// mean for good.
  explicit FlowExchange(double rebalance_above = 1.05);
  ~FlowExchange() override;

  int rank() const override { return processes_.rank; }
  int processes() const override { return processes_.count; }
  ldd::Migration migrate(PointBlock<D>& owned) override;
  PointBlock<D> gather_ghosts(const PointBlock<D>& owned, double radius) override;
  std::vector<double> refresh(std::span<const double> owned, int width) const override;
  void max(std::span<double> values) const override;
  void sum(std::span<double> values) const override;
  void sum(std::span<std::int64_t> values) const override;
  std::int64_t sum_before(std::int64_t value) const override;
  PointBlock<D> gather(const PointBlock<D>& owned) const override;
  bool owns(const ldd::Vec<D>& x) const override;

 private:
  Processes processes_;
  double rebalance_above_;
  std::unique_ptr<Decomposition<D>> decomposition_;  ///< made by the first migrate
  mutable std::mutex owner_mutex_;                   ///< owns() from several threads
  std::unique_ptr<Halo<D>> halo_;                    ///< of the last gather_ghosts
};

}  // namespace hm::parallel
