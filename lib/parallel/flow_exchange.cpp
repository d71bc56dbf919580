#include "parallel/flow_exchange.hpp"

#include <mpi.h>

#include <mutex>
#include <stdexcept>

namespace hm::parallel {

template <int D>
FlowExchange<D>::FlowExchange(double rebalance_above)
    : processes_(parallel::processes()), rebalance_above_(rebalance_above) {
  if (!(rebalance_above > 1.0))
    throw std::invalid_argument("FlowExchange: rebalance_above must be > 1");
}

template <int D>
FlowExchange<D>::~FlowExchange() = default;

template <int D>
ldd::Migration FlowExchange<D>::migrate(PointBlock<D>& owned) {
  ldd::Migration m;
  MigrationReport moved;
  if (!decomposition_) {
    decomposition_ = std::make_unique<Decomposition<D>>(owned);  // draws regions, sends
    m.rebalanced = true;
  } else if (decomposition_->imbalance(owned) > rebalance_above_) {
    moved = decomposition_->balance(owned);
    m.rebalanced = true;
  } else {
    moved = decomposition_->migrate(owned);
  }
  m.sent = moved.sent;
  m.received = moved.received;
  return m;
}

template <int D>
PointBlock<D> FlowExchange<D>::gather_ghosts(const PointBlock<D>& owned, double radius) {
  halo_ = std::make_unique<Halo<D>>(decomposition_->halo(owned, radius));
  return halo_->ghosts();
}

template <int D>
std::vector<double> FlowExchange<D>::refresh(std::span<const double> owned, int width) const {
  return halo_->refresh(owned, width);
}

template <int D>
void FlowExchange<D>::max(std::span<double> values) const {
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_MAX,
                MPI_COMM_WORLD);
}

template <int D>
void FlowExchange<D>::sum(std::span<double> values) const {
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM,
                MPI_COMM_WORLD);
}

template <int D>
void FlowExchange<D>::sum(std::span<std::int64_t> values) const {
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_INT64_T, MPI_SUM,
                MPI_COMM_WORLD);
}

template <int D>
std::int64_t FlowExchange<D>::sum_before(std::int64_t value) const {
  std::int64_t before = 0;
  MPI_Exscan(&value, &before, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
  return processes_.rank == 0 ? 0 : before;  // MPI_Exscan leaves rank 0's undefined
}

template <int D>
PointBlock<D> FlowExchange<D>::gather(const PointBlock<D>& owned) const {
  return gather_on_first(owned);
}

template <int D>
bool FlowExchange<D>::owns(const ldd::Vec<D>& x) const {
  if (const auto mine = decomposition_->in_own_region(x)) return *mine;
  // Zoltan does not say its point assignment is safe from several threads at once.
  const std::lock_guard lock(owner_mutex_);
  return decomposition_->owner_of(x) == processes_.rank;
}

template class FlowExchange<2>;
template class FlowExchange<3>;

}  // namespace hm::parallel
