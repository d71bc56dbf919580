#pragma once
// The decomposition of a run's points over processes (MPI): each process owns the points in its
// region of space; regions come from Zoltan's recursive coordinate bisection (RCB, the cuts kept
// so that any position can be assigned to its region). Three operations, every one collective:
//  * balance: new regions holding equal shares of all the points, and each point sent to the
//    process that now owns it (when the load drifts);
//  * migrate: each point that moved out of its process's region sent to the region's owner,
//    with the regions unchanged (every step);
//  * ghosts: copies of the points within a radius of another process's region, sent to it (the
//    neighbours a process needs of points it does not own); the Halo keeps who sends what to
//    whom, so that fields computed later in a step reach the ghosts again without a search.
// A point travels with its global id and `width` doubles of fields (velocity, pressure, ...);
// nothing is lost or duplicated (MigrationReport counts what moved). Positions in metres.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ldd/exchange.hpp"

namespace hm::parallel {

/// The processes of the run (MPI_COMM_WORLD; one when not started by mpirun). Initialises MPI
/// (a one-process singleton without mpirun) on first use and finalises it at exit unless
/// something else (PETSc) started it.
struct Processes {
  int rank = 0;   ///< this process's
  int count = 1;  ///< in the run
};
Processes processes();

/// Whether this process was started by mpirun (OpenMPI's or a PMI launcher's environment), so
/// that a stage run without it never touches MPI.
bool started_by_mpirun();

/// Ends the whole run from one process: writes "hydromodal: process R of N failed: <what>" to
/// stderr and aborts every process of the run with `exit_code` (MPI_Abort), so that the others,
/// waiting in a collective call for this one, do not hang. For a failure that only some
/// processes see (an exception on one rank); never returns.
[[noreturn]] void abort_run(const std::string& what, int exit_code);

/// This process's points: positions, global ids and `width` doubles of fields per point (the
/// flow's travelling points, ldd/exchange.hpp).
template <int D>
using PointBlock = ldd::TravellingPoints<D>;

/// Every process's points on process 0, ordered by id (ids, positions, fields), for output
/// written once; an empty block on the others. Collective.
template <int D>
PointBlock<D> gather_on_first(const PointBlock<D>& points);

struct MigrationReport {
  long sent = 0;      ///< points this process sent away
  long received = 0;  ///< points it received
  long owned = 0;     ///< points it owns afterwards
};

/// The processes one halo exchanges with (an MPI distributed-graph communicator; defined where
/// MPI is).
struct NeighbourGraph;

/// The ghost exchange as it was built: the ghosts a process received, and which of its owned
/// points it sent to which process. Valid while no point changes process (within a step). A
/// refresh talks to those processes alone (MPI_Neighbor_alltoallv on their graph): its cost
/// does not grow with the number of processes of the run.
template <int D>
class Halo {
 public:
  /// The ghosts received (ids, positions and the fields of the build), by sending process.
  const PointBlock<D>& ghosts() const { return ghosts_; }
  /// Sends the owned points' `owned_fields` (`width` doubles a point, in the order of the
  /// points the halo was built on) again; returns the ghosts' (`width` a ghost, ghost order).
  /// Collective.
  std::vector<double> refresh(std::span<const double> owned_fields, int width) const;
  /// Ghost points sent and received by this process (for the cost model).
  long sent() const { return static_cast<long>(send_points_.size()); }
  long received() const { return static_cast<long>(ghosts_.size()); }

 private:
  template <int>
  friend class Decomposition;
  PointBlock<D> ghosts_;
  std::vector<int> send_points_;  ///< owned points, grouped by destination process
  std::shared_ptr<const NeighbourGraph> graph_;
};

template <int D>
class Decomposition {
 public:
  /// Regions for `points` (every process's, balanced by their weights: PointBlock::weight, 1
  /// each without), and the points sent to them.
  explicit Decomposition(PointBlock<D>& points);
  ~Decomposition();
  Decomposition(const Decomposition&) = delete;
  Decomposition& operator=(const Decomposition&) = delete;

  /// New regions of equal shares of the points (by weight), and the points sent to their owners.
  MigrationReport balance(PointBlock<D>& points);
  /// Each point outside this process's region sent to the owner of the region it is in.
  MigrationReport migrate(PointBlock<D>& points);
  /// The points of the other processes within `radius` [m] of this process's region (more
  /// precisely: whose box of half-width `radius` reaches it), as copies with their ids and
  /// fields, ordered by sending process and then by their order there.
  PointBlock<D> ghosts(const PointBlock<D>& points, double radius) const;
  /// The same exchange, kept (Halo::refresh sends fields along it again).
  Halo<D> halo(const PointBlock<D>& points, double radius) const;
  /// The process whose region holds x.
  int owner_of(const Eigen::Matrix<double, D, 1>& x) const;
  /// Whether x is in this process's region, answered from the region's box without Zoltan:
  /// true strictly inside, false strictly outside, nothing on its faces (ask owner_of). Safe
  /// to call from several threads.
  std::optional<bool> in_own_region(const Eigen::Matrix<double, D, 1>& x) const;
  /// The largest process's share against the mean (1 = even) over every process, by the points'
  /// weights where they have them, else by count.
  double imbalance(const PointBlock<D>& points) const;

 private:
  /// This process's region from the cuts (RCB: a box, unbounded on the outer sides), or
  /// none where Zoltan's parts are not the processes.
  void keep_own_region();
  /// Whether the box of half-width r around x lies strictly inside this process's region.
  bool box_strictly_inside(const Eigen::Matrix<double, D, 1>& x, double r) const;

  struct Zoltan;
  std::unique_ptr<Zoltan> zoltan_;
  bool region_known_ = false;
  Eigen::Matrix<double, D, 1> region_lo_, region_hi_;
};

}  // namespace hm::parallel
