#pragma once
// The seam between the flow solver and the processes it runs over. A flow in one process has no
// PointExchange (FlowSolver gets none): it owns every point. A distributed flow (MPI; the
// implementation is parallel::FlowExchange) keeps on each process the points of its region of
// space, owned, and after them ghost copies of the other processes' points within the support
// radius, which the kernels read as neighbours and never write (ldd/point_loop.hpp). FlowSolver
// calls the exchange at fixed places of a step, every process at the same places (each call is
// collective):
//  * migrate and gather_ghosts, once a step after the points moved: points that left a region
//    go to its owner, the regions are redrawn when the load has drifted, new ghosts come;
//  * refresh, between the phases of a step: the owners' new values of a field reach the ghosts
//    (positions in PBD, types after the free surface, u* before the PPE, pressure after it, …);
//  * reductions: the step's limits, the monitors and every decision that must be the same on
//    every process.
// A point travels as its position, its global id (unique over the run, kept for its life) and
// `width` doubles of fields that the flow packs and unpacks.
#include <cstdint>
#include <span>
#include <vector>

#include "ldd/common.hpp"

namespace hm::ldd {

template <int D>
struct TravellingPoints {
  int width = 0;
  std::vector<Vec<D>> position;  ///< [m]
  std::vector<std::int64_t> id;
  std::vector<double> fields;  ///< size × width, point by point
  /// The work a point stands for, when the regions are drawn (empty: 1 each). Not carried by a
  /// migration: the owner sets it before the next.
  std::vector<float> weight;

  std::size_t size() const { return position.size(); }
  void add(const Vec<D>& x, std::int64_t point_id, const double* point_fields = nullptr) {
    position.push_back(x);
    id.push_back(point_id);
    if (width > 0) fields.insert(fields.end(), point_fields, point_fields + width);
  }
};

/// What migrate did on this process.
struct Migration {
  long sent = 0, received = 0;  ///< points sent to / received from other processes
  bool rebalanced = false;      ///< the regions were redrawn (on every process alike)
};

template <int D>
class PointExchange {
 public:
  virtual ~PointExchange() = default;
  PointExchange() = default;
  PointExchange(const PointExchange&) = delete;
  PointExchange& operator=(const PointExchange&) = delete;

  virtual int rank() const = 0;
  virtual int processes() const = 0;
  /// `owned`: this process's points (at the first call: every process's share of the run's
  /// points, any share). Returns in `owned` the points of this process's region, those that
  /// stayed first, in their order. Collective.
  virtual Migration migrate(TravellingPoints<D>& owned) = 0;
  /// Copies of the other processes' points within `radius` [m] of this process's region, with
  /// the same width of fields; `owned` as migrate left them (possibly reordered). Collective.
  virtual TravellingPoints<D> gather_ghosts(const TravellingPoints<D>& owned, double radius) = 0;
  /// The ghosts' values of a field whose owned values are `owned` (`width` doubles a point, in
  /// the order of the owned points of the last gather_ghosts); in the order of its ghosts.
  /// Collective.
  virtual std::vector<double> refresh(std::span<const double> owned, int width) const = 0;
  /// In place, over every process: the largest / the sum of each entry. Collective.
  virtual void max(std::span<double> values) const = 0;
  virtual void sum(std::span<double> values) const = 0;
  virtual void sum(std::span<std::int64_t> values) const = 0;
  /// The sum of `value` over the processes of lower rank (0 on the first). Collective.
  virtual std::int64_t sum_before(std::int64_t value) const = 0;
  /// Every process's `owned` on process 0, in id order; empty on the others. Collective.
  virtual TravellingPoints<D> gather(const TravellingPoints<D>& owned) const = 0;
  /// Whether x is in this process's region (after the last migrate): each x in exactly one
  /// process's region. Safe to call from several threads.
  virtual bool owns(const Vec<D>& x) const = 0;
};

}  // namespace hm::ldd
