// The point decomposition (parallel/decomposition.hpp), run by ctest as `mpirun -np N`,
// N = 1…4. A water column's lattice starts dealt out by id (every process spread over the whole
// column); after the decomposition, after moving every point, and after a rebalance: every id
// owned exactly once over the processes, each point in its owner's region, its fields with it,
// the shares even; the ghosts of each process are every other process's point within the
// radius of one of its own (checked against all points gathered), never one of its own.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <vector>

#include "dealt_points.hpp"
#include "parallel/decomposition.hpp"

namespace hm::parallel {
namespace {

using test::dealt_lattice;
using test::displacement;
using test::field;
using test::kWidth;
template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

/// Every process's points: (id, position), on every process.
template <int D>
std::vector<std::pair<std::int64_t, Vec<D>>> gather_all(const PointBlock<D>& block,
                                                        const Processes& p) {
  const int mine = static_cast<int>(block.size());
  std::vector<int> counts(static_cast<std::size_t>(p.count)), starts(counts.size(), 0);
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  std::exclusive_scan(counts.begin(), counts.end(), starts.begin(), 0);
  const int total = starts.back() + counts.back();
  std::vector<std::int64_t> ids(static_cast<std::size_t>(total));
  MPI_Allgatherv(block.id.data(), mine, MPI_INT64_T, ids.data(), counts.data(), starts.data(),
                 MPI_INT64_T, MPI_COMM_WORLD);
  std::vector<double> mine_x;
  for (const auto& x : block.position)
    for (int a = 0; a < D; ++a) mine_x.push_back(x[a]);
  for (auto* v : {&counts, &starts})
    for (int& c : *v) c *= D;
  std::vector<double> xs(static_cast<std::size_t>(total) * D);
  MPI_Allgatherv(mine_x.data(), mine * D, MPI_DOUBLE, xs.data(), counts.data(), starts.data(),
                 MPI_DOUBLE, MPI_COMM_WORLD);
  std::vector<std::pair<std::int64_t, Vec<D>>> all(static_cast<std::size_t>(total));
  for (int k = 0; k < total; ++k) {
    all[static_cast<std::size_t>(k)].first = ids[static_cast<std::size_t>(k)];
    for (int a = 0; a < D; ++a)
      all[static_cast<std::size_t>(k)].second[a] = xs[static_cast<std::size_t>(k) * D + a];
  }
  return all;
}

/// Every id of 0 … total−1 owned exactly once, each point in its owner's region, its fields
/// with it.
template <int D>
void expect_owned_once(const Decomposition<D>& d, const PointBlock<D>& block, std::int64_t total,
                       const Processes& p, const char* when) {
  auto all = gather_all(block, p);
  ASSERT_EQ(static_cast<std::int64_t>(all.size()), total) << when;
  std::vector<std::int64_t> ids;
  for (const auto& [id, x] : all) ids.push_back(id);
  std::sort(ids.begin(), ids.end());
  for (std::int64_t k = 0; k < total; ++k)
    ASSERT_EQ(ids[static_cast<std::size_t>(k)], k) << when << ": id " << k << " lost or doubled";
  int misplaced = 0, wrong_fields = 0;
  for (std::size_t i = 0; i < block.size(); ++i) {
    misplaced += d.owner_of(block.position[i]) != p.rank;
    for (int k = 0; k < kWidth; ++k)
      wrong_fields +=
          block.fields[i * kWidth + static_cast<std::size_t>(k)] != field(block.id[i], k);
  }
  EXPECT_EQ(misplaced, 0) << when;
  EXPECT_EQ(wrong_fields, 0) << when;
}

/// The ghosts are exactly the other processes' points within `radius` of one of this
/// process's points — or more (those near its region), but never one of its own.
template <int D>
void expect_complete_ghosts(const PointBlock<D>& block, const PointBlock<D>& ghosts, double radius,
                            const Processes& p) {
  const std::set<std::int64_t> own(block.id.begin(), block.id.end());
  const std::set<std::int64_t> ghost(ghosts.id.begin(), ghosts.id.end());
  EXPECT_EQ(ghost.size(), ghosts.size()) << "a ghost received twice";
  for (std::int64_t id : ghosts.id) ASSERT_FALSE(own.count(id)) << "own point " << id;
  for (std::size_t g = 0; g < ghosts.size(); ++g)
    for (int k = 0; k < kWidth; ++k)
      ASSERT_EQ(ghosts.fields[g * kWidth + static_cast<std::size_t>(k)], field(ghosts.id[g], k));
  int missing = 0;
  for (const auto& [id, x] : gather_all(block, p)) {
    if (own.count(id) || ghost.count(id)) continue;
    for (const auto& y : block.position)
      if ((x - y).norm() < radius) {
        ++missing;
        break;
      }
  }
  EXPECT_EQ(missing, 0) << "neighbours of own points that are not ghosts";
}

/// Every position (the points of every process, a far-away one, and the midpoints between the
/// points) is in exactly one process's region, whether its box answers (in_own_region) or
/// Zoltan does (owner_of), and the two agree where both answer.
template <int D>
void expect_regions_partition_space(const Decomposition<D>& d, const PointBlock<D>& block,
                                    const Processes& p, const char* when) {
  std::vector<Vec<D>> positions;
  for (const auto& [id, x] : gather_all(block, p)) positions.push_back(x);
  const std::size_t points = positions.size();
  for (std::size_t k = 0; k + 1 < points; k += 7)
    positions.push_back(0.5 * (positions[k] + positions[k + 1]));
  positions.push_back(Vec<D>::Constant(1e3));
  positions.push_back(Vec<D>::Constant(-1e3));
  std::vector<int> claims(positions.size(), 0);
  int disagreements = 0;
  for (std::size_t k = 0; k < positions.size(); ++k) {
    const bool zoltan = d.owner_of(positions[k]) == p.rank;
    const auto box = d.in_own_region(positions[k]);
    disagreements += box.has_value() && *box != zoltan;
    claims[k] = box.value_or(zoltan) ? 1 : 0;
  }
  MPI_Allreduce(MPI_IN_PLACE, claims.data(), static_cast<int>(claims.size()), MPI_INT, MPI_SUM,
                MPI_COMM_WORLD);
  EXPECT_EQ(disagreements, 0) << when;
  EXPECT_EQ(std::count(claims.begin(), claims.end(), 1), static_cast<long>(claims.size()))
      << when << ": positions in no region or in several";
}

template <int D>
void run_decomposition(double dx) {
  const Processes p = processes();
  PointBlock<D> block = dealt_lattice<D>(dx, p);
  long local = static_cast<long>(block.size()), total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);

  Decomposition<D> d(block);
  expect_owned_once(d, block, total, p, "after the decomposition");
  expect_regions_partition_space(d, block, p, "after the decomposition");
  EXPECT_LE(d.imbalance(block), 1.02);

  // Every point moves up to 2 dx (more than a step does): the few that left are migrated.
  for (std::size_t i = 0; i < block.size(); ++i)
    block.position[i] += displacement<D>(block.id[i], 2 * dx);
  const auto moved = d.migrate(block);
  expect_owned_once(d, block, total, p, "after migration");
  long sent = moved.sent, all_sent = 0;
  MPI_Allreduce(&sent, &all_sent, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (p.count > 1) {
    EXPECT_GT(all_sent, 0);
  }
  EXPECT_LT(all_sent, total / 4) << "only points near the cuts move";

  const double radius = 2.1 * dx;
  expect_complete_ghosts(block, d.ghosts(block, radius), radius, p);

  // Gathered on process 0 for output: every point once, by id, with its fields.
  const auto gathered = gather_on_first(block);
  auto everywhere = gather_all(block, p);  // (id, position) of every point, by id below
  std::sort(everywhere.begin(), everywhere.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  if (p.rank == 0) {
    ASSERT_EQ(static_cast<long>(gathered.size()), total);
    int wrong = 0;
    for (std::size_t k = 0; k < gathered.size(); ++k) {
      wrong += gathered.id[k] != static_cast<std::int64_t>(k);
      wrong += gathered.position[k] != everywhere[k].second;
      for (int f = 0; f < kWidth; ++f)
        wrong +=
            gathered.fields[k * kWidth + static_cast<std::size_t>(f)] != field(gathered.id[k], f);
    }
    EXPECT_EQ(wrong, 0);
  } else {
    EXPECT_EQ(gathered.size(), 0u);
  }

  // The halo sends fields computed later (a pressure, a velocity: functions of the id here)
  // to the same ghosts again.
  const auto halo = d.halo(block, radius);
  EXPECT_EQ(halo.ghosts().id, d.ghosts(block, radius).id);
  std::vector<double> later;
  for (std::int64_t id : block.id) later.insert(later.end(), {-1.0 * id, 0.5 * id});
  const auto refreshed = halo.refresh(later, 2);
  ASSERT_EQ(refreshed.size(), 2 * halo.ghosts().size());
  int stale = 0;
  for (std::size_t g = 0; g < halo.ghosts().size(); ++g) {
    const auto id = static_cast<double>(halo.ghosts().id[g]);
    stale += refreshed[2 * g] != -id || refreshed[2 * g + 1] != 0.5 * id;
  }
  EXPECT_EQ(stale, 0);

  // The column collapses to the right half of the tank: the load drifts; rebalance.
  for (auto& x : block.position) x[0] = 0.6 + 0.5 * x[0];
  d.migrate(block);
  const double drifted = d.imbalance(block);
  if (p.count > 1) {
    EXPECT_GT(drifted, 1.3);
  }
  d.balance(block);
  expect_owned_once(d, block, total, p, "after the rebalance");
  expect_regions_partition_space(d, block, p, "after the rebalance");
  EXPECT_LE(d.imbalance(block), 1.02);
  expect_complete_ghosts(block, d.ghosts(block, radius), radius, p);
}

TEST(Decomposition, TwoDimensionalColumn) {
  run_decomposition<2>(0.006);
}

TEST(Decomposition, ThreeDimensionalColumn) {
  run_decomposition<3>(0.02);
}

}  // namespace
}  // namespace hm::parallel
