#include "parallel/decomposition.hpp"

#include <algorithm>
#include <cfloat>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <numeric>
#include <stdexcept>

#include <fmt/format.h>
#include <mpi.h>
#include <zoltan.h>

namespace hm::parallel {
namespace {

void finalize_mpi() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

/// MPI (and Zoltan on it) once per process. MPI started here is finalised at exit; one that
/// PETSc started is PETSc's to finalise.
void ensure_started() {
  static std::once_flag once;
  std::call_once(once, [] {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) {
      MPI_Init(nullptr, nullptr);
      std::atexit(finalize_mpi);
    }
    float version = 0.0f;
    if (Zoltan_Initialize(0, nullptr, &version) != ZOLTAN_OK)
      throw std::runtime_error("Zoltan_Initialize failed");
  });
}

void check(int code, const char* call) {
  if (code == ZOLTAN_OK || code == ZOLTAN_WARN) return;
  throw std::runtime_error(fmt::format("{} failed (Zoltan error {})", call, code));
}

// Zoltan's query functions: the points of a PointBlock<D> (passed as `data`), each with a
// two-word global id (its 64-bit id) and its index as local id.
template <int D>
int count_points(void* data, int* error) {
  *error = ZOLTAN_OK;
  return static_cast<int>(static_cast<const PointBlock<D>*>(data)->size());
}

template <int D>
void list_points(void* data, int, int, ZOLTAN_ID_PTR global, ZOLTAN_ID_PTR local,
                 int weight_dimension, float* weights, int* error) {
  const auto& points = *static_cast<const PointBlock<D>*>(data);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (weight_dimension > 0)
      weights[i] = points.weight.size() == points.size() ? points.weight[i] : 1.0f;
    const auto id = static_cast<std::uint64_t>(points.id[i]);
    global[2 * i] = static_cast<ZOLTAN_ID_TYPE>(id & 0xffffffffu);
    global[2 * i + 1] = static_cast<ZOLTAN_ID_TYPE>(id >> 32);
    local[i] = static_cast<ZOLTAN_ID_TYPE>(i);
  }
  *error = ZOLTAN_OK;
}

/// Points bound for other processes, grouped by destination as MPI_Alltoallv sends them: an id
/// and D + width doubles (position, fields) a point.
template <int D>
class Outbox {
 public:
  /// Room for counts[q] points to process q.
  Outbox(std::vector<int> counts, int width)
      : counts_(std::move(counts)), starts_(counts_.size(), 0), width_(width) {
    std::exclusive_scan(counts_.begin(), counts_.end(), starts_.begin(), 0);
    cursor_ = starts_;
    const auto total = static_cast<std::size_t>(std::accumulate(counts_.begin(), counts_.end(), 0));
    ids_.resize(total);
    values_.resize(total * static_cast<std::size_t>(per_point()));
  }

  int size() const { return static_cast<int>(ids_.size()); }

  void pack(int process, const Eigen::Matrix<double, D, 1>& x, std::int64_t id,
            const double* fields) {
    const auto slot = static_cast<std::size_t>(cursor_[static_cast<std::size_t>(process)]++);
    ids_[slot] = id;
    double* v = &values_[slot * static_cast<std::size_t>(per_point())];
    for (int a = 0; a < D; ++a) v[a] = x[a];
    std::copy_n(fields, width_, v + D);
  }

  /// Sends each process what was packed for it and appends what the others sent to `into`, by
  /// sending rank and in the sender's order. Collective. Returns the number of points received.
  int deliver(PointBlock<D>& into) const {
    std::vector<int> receive_counts(counts_.size(), 0), receive_starts(counts_.size(), 0);
    MPI_Alltoall(counts_.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    std::exclusive_scan(receive_counts.begin(), receive_counts.end(), receive_starts.begin(), 0);
    const int received = std::accumulate(receive_counts.begin(), receive_counts.end(), 0);
    std::vector<std::int64_t> ids(static_cast<std::size_t>(received));
    MPI_Alltoallv(ids_.data(), counts_.data(), starts_.data(), MPI_INT64_T, ids.data(),
                  receive_counts.data(), receive_starts.data(), MPI_INT64_T, MPI_COMM_WORLD);
    const auto scaled = [this](std::vector<int> v) {
      for (int& x : v) x *= per_point();
      return v;
    };
    std::vector<double> values(static_cast<std::size_t>(received) * per_point());
    MPI_Alltoallv(values_.data(), scaled(counts_).data(), scaled(starts_).data(), MPI_DOUBLE,
                  values.data(), scaled(receive_counts).data(), scaled(receive_starts).data(),
                  MPI_DOUBLE, MPI_COMM_WORLD);
    const std::size_t held = into.size() + static_cast<std::size_t>(received);
    into.position.reserve(held);
    into.id.reserve(held);
    into.fields.reserve(held * static_cast<std::size_t>(width_));
    for (int r = 0; r < received; ++r) {
      const double* v = &values[static_cast<std::size_t>(r) * per_point()];
      Eigen::Matrix<double, D, 1> x;
      for (int a = 0; a < D; ++a) x[a] = v[a];
      into.add(x, ids[static_cast<std::size_t>(r)], v + D);
    }
    return received;
  }

 private:
  int per_point() const { return D + width_; }

  std::vector<int> counts_, starts_, cursor_;
  int width_;
  std::vector<std::int64_t> ids_;
  std::vector<double> values_;
};

/// Sends each point i with owner[i] ≠ rank to that process; the others stay where they are, in
/// their order (moved up over the ones sent, not copied), and those received follow by
/// sending rank, in the sender's order — exchange()'s result for one destination a point.
/// Weights are not carried. `report` counts the points sent away and received.
template <int D>
void send_to_owners(PointBlock<D>& points, const std::vector<int>& owner, int rank, int count,
                    MigrationReport& report) {
  const auto width = static_cast<std::size_t>(points.width);
  std::vector<int> leaving(static_cast<std::size_t>(count), 0);
  for (int p : owner)
    if (p != rank) ++leaving[static_cast<std::size_t>(p)];
  Outbox<D> outbox(std::move(leaving), points.width);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double* f = points.fields.data() + i * width;
    if (owner[i] != rank) {
      outbox.pack(owner[i], points.position[i], points.id[i], f);
    } else if (kept++ != i) {  // moves up to slot kept − 1 (< i: already read)
      points.position[kept - 1] = points.position[i];
      points.id[kept - 1] = points.id[i];
      std::copy_n(f, width, points.fields.data() + (kept - 1) * width);
    }
  }
  points.position.resize(kept);
  points.id.resize(kept);
  points.fields.resize(kept * width);
  points.weight.clear();
  report.sent = outbox.size();
  report.received = outbox.deliver(points);
  report.owned = static_cast<long>(points.size());
}

template <int D>
int dimension(void*, int* error) {
  *error = ZOLTAN_OK;
  return D;
}

template <int D>
void coordinates(void* data, int, int, int count, ZOLTAN_ID_PTR, ZOLTAN_ID_PTR local, int,
                 double* out, int* error) {
  const auto& points = *static_cast<const PointBlock<D>*>(data);
  for (int k = 0; k < count; ++k)
    for (int a = 0; a < D; ++a) out[D * k + a] = points.position[local[k]][a];
  *error = ZOLTAN_OK;
}

/// Sends point i to every process in destinations[i] (its own rank: kept) and returns what this
/// process then holds: the kept points in their order, then those received, by sending rank
/// and in the sender's order. `report` counts the points sent away and received.
template <int D>
PointBlock<D> exchange(const PointBlock<D>& points,
                       const std::vector<std::vector<int>>& destinations, int rank, int count,
                       MigrationReport& report) {
  std::vector<int> counts(static_cast<std::size_t>(count), 0);
  for (const auto& to : destinations)
    for (int p : to) ++counts[static_cast<std::size_t>(p)];
  const auto staying = static_cast<std::size_t>(counts[static_cast<std::size_t>(rank)]);
  counts[static_cast<std::size_t>(rank)] = 0;
  Outbox<D> outbox(std::move(counts), points.width);
  PointBlock<D> out;
  out.width = points.width;
  out.position.reserve(staying);
  out.id.reserve(staying);
  out.fields.reserve(staying * static_cast<std::size_t>(points.width));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double* f = points.fields.data() + i * static_cast<std::size_t>(points.width);
    for (int p : destinations[i]) {
      if (p == rank)
        out.add(points.position[i], points.id[i], f);
      else
        outbox.pack(p, points.position[i], points.id[i], f);
    }
  }
  report.sent = outbox.size();
  report.received = outbox.deliver(out);
  report.owned = static_cast<long>(out.size());
  return out;
}

}  // namespace

Processes processes() {
  ensure_started();
  Processes p;
  MPI_Comm_rank(MPI_COMM_WORLD, &p.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &p.count);
  return p;
}

bool started_by_mpirun() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
    if (std::getenv(variable) != nullptr) return true;
  return false;
}

void abort_run(const std::string& what, int exit_code) {
  const Processes p = processes();
  std::fprintf(stderr, "hydromodal: process %d of %d failed: %s\n", p.rank, p.count, what.c_str());
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, exit_code);
  std::_Exit(exit_code);  // MPI_Abort does not return; this is for the compiler
}

template <int D>
PointBlock<D> gather_on_first(const PointBlock<D>& points) {
  const Processes p = processes();
  const int mine = static_cast<int>(points.size());
  std::vector<int> counts(static_cast<std::size_t>(p.count), 0);
  MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  // Ids, then positions and fields as one record of D + width doubles a point.
  const int per_point = D + points.width;
  std::vector<int> starts(counts.size(), 0), value_counts(counts.size()),
      value_starts(counts.size());
  std::exclusive_scan(counts.begin(), counts.end(), starts.begin(), 0);
  for (std::size_t r = 0; r < counts.size(); ++r) {
    value_counts[r] = counts[r] * per_point;
    value_starts[r] = starts[r] * per_point;
  }
  const int total = p.rank == 0 ? starts.back() + counts.back() : 0;
  std::vector<std::int64_t> ids(static_cast<std::size_t>(total));
  MPI_Gatherv(points.id.data(), mine, MPI_INT64_T, ids.data(), counts.data(), starts.data(),
              MPI_INT64_T, 0, MPI_COMM_WORLD);
  std::vector<double> records(points.size() * static_cast<std::size_t>(per_point));
  for (std::size_t i = 0; i < points.size(); ++i) {
    double* v = &records[i * static_cast<std::size_t>(per_point)];
    for (int a = 0; a < D; ++a) v[a] = points.position[i][a];
    for (int k = 0; k < points.width; ++k) v[D + k] = points.fields[i * points.width + k];
  }
  std::vector<double> all(static_cast<std::size_t>(total) * per_point);
  MPI_Gatherv(records.data(), mine * per_point, MPI_DOUBLE, all.data(), value_counts.data(),
              value_starts.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  PointBlock<D> out;
  out.width = points.width;
  std::vector<std::size_t> order(static_cast<std::size_t>(total));
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
  for (std::size_t k : order) {
    const double* v = &all[k * static_cast<std::size_t>(per_point)];
    Eigen::Matrix<double, D, 1> x;
    for (int a = 0; a < D; ++a) x[a] = v[a];
    out.add(x, ids[k], v + D);
  }
  return out;
}

template <int D>
struct Decomposition<D>::Zoltan {
  Zoltan_Struct* zz = nullptr;
  Processes processes;
  ~Zoltan() {
    if (zz != nullptr) Zoltan_Destroy(&zz);
  }
};

template <int D>
Decomposition<D>::Decomposition(PointBlock<D>& points) : zoltan_(std::make_unique<Zoltan>()) {
  zoltan_->processes = processes();
  zoltan_->zz = Zoltan_Create(MPI_COMM_WORLD);
  if (zoltan_->zz == nullptr) throw std::runtime_error("Zoltan_Create failed");
  Zoltan_Struct* zz = zoltan_->zz;
  // Recursive coordinate bisection with its cuts kept (for owner_of and the ghosts' boxes),
  // each cut midway between the points on its two sides, each point weighing its weight; the
  // points are then sent by region (balance), so Zoltan returns no lists.
  for (const auto& [name, value] : {std::pair{"DEBUG_LEVEL", "0"},
                                    {"LB_METHOD", "RCB"},
                                    {"KEEP_CUTS", "1"},
                                    {"RETURN_LISTS", "NONE"},
                                    {"NUM_GID_ENTRIES", "2"},
                                    {"NUM_LID_ENTRIES", "1"},
                                    {"OBJ_WEIGHT_DIM", "1"},
                                    {"RCB_RECTILINEAR_BLOCKS", "0"},
                                    {"AVERAGE_CUTS", "1"},
                                    {"IMBALANCE_TOL", "1.01"}})
    check(Zoltan_Set_Param(zz, name, value), "Zoltan_Set_Param");
  balance(points);
}

template <int D>
Decomposition<D>::~Decomposition() = default;

template <int D>
MigrationReport Decomposition<D>::balance(PointBlock<D>& points) {
  Zoltan_Struct* zz = zoltan_->zz;
  check(Zoltan_Set_Num_Obj_Fn(zz, count_points<D>, &points), "Zoltan_Set_Num_Obj_Fn");
  check(Zoltan_Set_Obj_List_Fn(zz, list_points<D>, &points), "Zoltan_Set_Obj_List_Fn");
  check(Zoltan_Set_Num_Geom_Fn(zz, dimension<D>, &points), "Zoltan_Set_Num_Geom_Fn");
  check(Zoltan_Set_Geom_Multi_Fn(zz, coordinates<D>, &points), "Zoltan_Set_Geom_Multi_Fn");
  // The cuts only: which point goes where is owner_of's (below), so no lists are built.
  int changes = 0, gid_entries = 0, lid_entries = 0, imports = 0, exports = 0;
  ZOLTAN_ID_PTR import_global = nullptr, import_local = nullptr, export_global = nullptr,
                export_local = nullptr;
  int *import_procs = nullptr, *import_parts = nullptr, *export_procs = nullptr,
      *export_parts = nullptr;
  check(Zoltan_LB_Partition(zz, &changes, &gid_entries, &lid_entries, &imports, &import_global,
                            &import_local, &import_procs, &import_parts, &exports, &export_global,
                            &export_local, &export_procs, &export_parts),
        "Zoltan_LB_Partition");
  Zoltan_LB_Free_Part(&import_global, &import_local, &import_procs, &import_parts);
  Zoltan_LB_Free_Part(&export_global, &export_local, &export_procs, &export_parts);
  keep_own_region();
  // Not Zoltan's lists, which may send points lying on a cut (a lattice row) to either side for
  // balance: the regions decide, so that a point is always in its owner's region.
  return migrate(points);
}

template <int D>
void Decomposition<D>::keep_own_region() {
  // Zoltan's point and box queries are asked for every point (migration, ghosts, the wall
  // loads' and the volume monitor's filters); most points are well inside their region, which
  // the box answers at once.
  const int rank = zoltan_->processes.rank;
  region_known_ = false;
  int dimensions = 0;
  double lo[3], hi[3];
  check(Zoltan_RCB_Box(zoltan_->zz, rank, &dimensions, &lo[0], &lo[1], &lo[2], &hi[0], &hi[1],
                       &hi[2]),
        "Zoltan_RCB_Box");
  if (zoltan_->processes.count == 1) {  // everywhere (Zoltan's box is then a point)
    region_lo_.setConstant(-DBL_MAX);
    region_hi_.setConstant(DBL_MAX);
    region_known_ = true;
    return;
  }
  if (dimensions != D) return;
  // Part `rank` is this process's (Zoltan's default: one part a process): asked at a point
  // inside the box.
  double inside[3] = {0.0, 0.0, 0.0};
  for (int a = 0; a < D; ++a) {
    if (!(lo[a] < hi[a])) return;
    region_lo_[a] = lo[a];
    region_hi_[a] = hi[a];
    const bool bounded_below = lo[a] > -DBL_MAX, bounded_above = hi[a] < DBL_MAX;
    inside[a] = bounded_below && bounded_above ? 0.5 * (lo[a] + hi[a])
                : bounded_below                ? lo[a] + 1.0
                : bounded_above                ? hi[a] - 1.0
                                               : 0.0;
  }
  int process = -1, part = -1;
  check(Zoltan_LB_Point_PP_Assign(zoltan_->zz, inside, &process, &part),
        "Zoltan_LB_Point_PP_Assign");
  region_known_ = process == rank && part == rank;
}

template <int D>
bool Decomposition<D>::box_strictly_inside(const Eigen::Matrix<double, D, 1>& x, double r) const {
  if (!region_known_) return false;
  for (int a = 0; a < D; ++a)
    if (!(x[a] - r > region_lo_[a] && x[a] + r < region_hi_[a])) return false;
  return true;
}

template <int D>
std::optional<bool> Decomposition<D>::in_own_region(const Eigen::Matrix<double, D, 1>& x) const {
  if (!region_known_) return std::nullopt;
  if (box_strictly_inside(x, 0.0)) return true;
  for (int a = 0; a < D; ++a)
    if (x[a] < region_lo_[a] || x[a] > region_hi_[a]) return false;
  return std::nullopt;
}

template <int D>
int Decomposition<D>::owner_of(const Eigen::Matrix<double, D, 1>& x) const {
  if (box_strictly_inside(x, 0.0)) return zoltan_->processes.rank;
  double coordinates[3] = {0.0, 0.0, 0.0};
  for (int a = 0; a < D; ++a) coordinates[a] = x[a];
  int process = -1, part = -1;
  check(Zoltan_LB_Point_PP_Assign(zoltan_->zz, coordinates, &process, &part),
        "Zoltan_LB_Point_PP_Assign");
  return process;
}

template <int D>
MigrationReport Decomposition<D>::migrate(PointBlock<D>& points) {
  std::vector<int> owner(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) owner[i] = owner_of(points.position[i]);
  MigrationReport report;
  send_to_owners(points, owner, zoltan_->processes.rank, zoltan_->processes.count, report);
  return report;
}

template <int D>
PointBlock<D> Decomposition<D>::ghosts(const PointBlock<D>& points, double radius) const {
  return halo(points, radius).ghosts_;
}

/// The processes a halo sends to and receives from, in ascending rank order (the order of its
/// send buffer and of its ghosts), with the points each, as an MPI distributed graph.
struct NeighbourGraph {
  MPI_Comm comm = MPI_COMM_NULL;
  std::vector<int> send_counts, receive_counts;  ///< points, per destination / source

  /// From the points this process sends to each process of the run (a collective call: the
  /// counts it receives come from the others).
  explicit NeighbourGraph(const std::vector<int>& send_to) {
    std::vector<int> receive_from(send_to.size(), 0);
    MPI_Alltoall(send_to.data(), 1, MPI_INT, receive_from.data(), 1, MPI_INT, MPI_COMM_WORLD);
    std::vector<int> destinations, sources;
    for (std::size_t q = 0; q < send_to.size(); ++q) {
      if (send_to[q] > 0) {
        destinations.push_back(static_cast<int>(q));
        send_counts.push_back(send_to[q]);
      }
      if (receive_from[q] > 0) {
        sources.push_back(static_cast<int>(q));
        receive_counts.push_back(receive_from[q]);
      }
    }
    MPI_Dist_graph_create_adjacent(MPI_COMM_WORLD, static_cast<int>(sources.size()), sources.data(),
                                   MPI_UNWEIGHTED, static_cast<int>(destinations.size()),
                                   destinations.data(), MPI_UNWEIGHTED, MPI_INFO_NULL,
                                   /*reorder=*/0, &comm);
  }
  ~NeighbourGraph() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized && comm != MPI_COMM_NULL) MPI_Comm_free(&comm);
  }
  NeighbourGraph(const NeighbourGraph&) = delete;
  NeighbourGraph& operator=(const NeighbourGraph&) = delete;
};

template <int D>
Halo<D> Decomposition<D>::halo(const PointBlock<D>& points, double radius) const {
  const int rank = zoltan_->processes.rank, count = zoltan_->processes.count;
  std::vector<int> procs(static_cast<std::size_t>(count)), parts(static_cast<std::size_t>(count));
  std::vector<std::vector<int>> destinations(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (box_strictly_inside(points.position[i], radius)) continue;  // reaches no other region
    double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {0.0, 0.0, 0.0};
    for (int a = 0; a < D; ++a) {
      lo[a] = points.position[i][a] - radius;
      hi[a] = points.position[i][a] + radius;
    }
    int process_count = 0, part_count = 0;
    check(Zoltan_LB_Box_PP_Assign(zoltan_->zz, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2],
                                  procs.data(), &process_count, parts.data(), &part_count),
          "Zoltan_LB_Box_PP_Assign");
    for (int k = 0; k < process_count; ++k)
      if (procs[static_cast<std::size_t>(k)] != rank)
        destinations[i].push_back(procs[static_cast<std::size_t>(k)]);
  }
  Halo<D> halo;
  MigrationReport report;
  halo.ghosts_ = exchange(points, destinations, rank, count, report);
  std::vector<int> send_counts(static_cast<std::size_t>(count), 0);
  for (const auto& to : destinations)
    for (int q : to) ++send_counts[static_cast<std::size_t>(q)];
  std::vector<int> start(static_cast<std::size_t>(count), 0);
  std::exclusive_scan(send_counts.begin(), send_counts.end(), start.begin(), 0);
  halo.send_points_.resize(static_cast<std::size_t>(report.sent));
  for (std::size_t i = 0; i < points.size(); ++i)  // in exchange()'s order
    for (int q : destinations[i])
      halo.send_points_[static_cast<std::size_t>(start[q]++)] = static_cast<int>(i);
  halo.graph_ = std::make_shared<const NeighbourGraph>(send_counts);
  return halo;
}

template <int D>
std::vector<double> Halo<D>::refresh(std::span<const double> owned_fields, int width) const {
  std::vector<double> send(send_points_.size() * static_cast<std::size_t>(width));
  for (std::size_t k = 0; k < send_points_.size(); ++k)
    for (int f = 0; f < width; ++f)
      send[k * width + f] = owned_fields[static_cast<std::size_t>(send_points_[k]) * width + f];
  auto scaled = [width](const std::vector<int>& counts, std::vector<int>& starts) {
    std::vector<int> v(counts);
    for (int& x : v) x *= width;
    starts.assign(v.size(), 0);
    std::exclusive_scan(v.begin(), v.end(), starts.begin(), 0);
    return v;
  };
  std::vector<int> send_starts, receive_starts;
  const auto send_counts = scaled(graph_->send_counts, send_starts);
  const auto receive_counts = scaled(graph_->receive_counts, receive_starts);
  std::vector<double> received(ghosts_.size() * static_cast<std::size_t>(width));
  MPI_Neighbor_alltoallv(send.data(), send_counts.data(), send_starts.data(), MPI_DOUBLE,
                         received.data(), receive_counts.data(), receive_starts.data(), MPI_DOUBLE,
                         graph_->comm);
  return received;
}

template <int D>
double Decomposition<D>::imbalance(const PointBlock<D>& points) const {
  double mine = static_cast<double>(points.size());
  if (points.weight.size() == points.size())
    mine = std::accumulate(points.weight.begin(), points.weight.end(), 0.0);
  double largest = 0, total = 0;
  MPI_Allreduce(&mine, &largest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(&mine, &total, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  const double mean = total / zoltan_->processes.count;
  return mean > 0.0 ? largest / mean : 1.0;
}

template PointBlock<2> gather_on_first<2>(const PointBlock<2>&);
template PointBlock<3> gather_on_first<3>(const PointBlock<3>&);
template class Halo<2>;
template class Halo<3>;
template class Decomposition<2>;
template class Decomposition<3>;

}  // namespace hm::parallel
