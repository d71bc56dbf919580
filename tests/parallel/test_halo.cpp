// Kernels over owned points with ghosts appended give the one-process values (run by ctest as
// `mpirun -np N`, N = 1…4). Every process runs the same 2-D dam break for 20 steps, then keeps
// the points (fluid points and wall nodes) of its region of a Decomposition and the ghosts
// within the support radius h of it; on those alone it builds neighbour lists and operators and
// runs the flow's kernels (ldd/kernels.hpp) over its owned points. Against the same kernels on
// every point in one piece: equal to round-off (the neighbours are summed in another order)
// at every owned point, and every point owned once; the same for the free surface (types
// equal), the PPE's sources and the slip velocity gradient.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "flow_points.hpp"
#include "ldd/free_surface.hpp"
#include "ldd/kernels.hpp"
#include "ldd/point_loop.hpp"
#include "ldd/ppe.hpp"
#include "parallel/decomposition.hpp"
#include "ppe_cases.hpp"

namespace hm::ldd {
namespace {

using test::append;
using test::dealt_points;
using test::refresh_types;

using Vec2 = Vec<2>;

/// What the kernels give at point i of `c`, as one vector of numbers.
std::vector<double> kernel_values(const kernels::Cloud<2>& c, Index i, double dx, double h,
                                  double n0) {
  std::vector<double> v;
  auto add = [&v](const Vec2& x) { v.insert(v.end(), {x.x(), x.y()}); };
  const kernels::PbdParameters pbd{
      .distance = 0.9 * dx, .wall_distance = 0.45 * dx, .relaxation = 1.0, .clamp = 0.1 * dx};
  add(kernels::pbd_displacement(c, i, pbd).value_or(Vec2::Zero()));
  bool near_surface = false;
  add(kernels::concentration_gradient(c, i, h, dx, n0, near_surface));
  v.push_back(near_surface);
  add(kernels::smoothing_change(c, i, 0.1, h).value_or(Vec2::Zero()));
  add(kernels::viscous_acceleration<2>(c, i, c.points.velocity, 1e-3));
  v.push_back(kernels::is_sparse(c, i, 0.9 * n0, 0.45 * n0, h));
  add(kernels::predicted_velocity<2>(c, i, 1e-3, Vec2(0.0, -9.81), Vec2::Zero()));
  v.push_back(c.ops.number_density[i]);
  return v;
}

TEST(Halo, KernelsOnOwnedPointsWithGhostsGiveTheOneProcessValues) {
  const auto p = parallel::processes();
  const double dx = 0.01;
  auto flow = test::dam_break<2>(dx, Preconditioner::automatic);
  for (int s = 0; s < 20; ++s) flow.step(flow.stable_dt(0.0).first);
  const PointSet<2>& all = flow.points();
  const double h = flow.support(), n0 = flow.reference_density();

  // One piece: every point's neighbours and operators.
  const Neighbours whole_nb = find_neighbours<2>(all.position, h);
  const Operators<2> whole_ops = compute_operators<2>(all.position, whole_nb);
  const kernels::Cloud<2> whole{all, whole_nb, whole_ops};

  // This process's region: owned points first, then the ghosts within h of it.
  auto owned = dealt_points(all, p);
  parallel::Decomposition<2> decomposition(owned);
  const auto halo = decomposition.halo(owned, h);
  const auto& ghosts = halo.ghosts();
  PointSet<2> local;
  std::vector<std::int64_t> ids;
  append(owned, local, ids);
  append(ghosts, local, ids);
  const auto owned_count = static_cast<Index>(owned.size());
  const Neighbours local_nb = find_neighbours<2>(local.position, h);
  const Operators<2> local_ops = compute_operators<2>(local.position, local_nb);
  const kernels::Cloud<2> mine{local, local_nb, local_ops};

  struct Differences {
    double largest = 0.0;  // relative to the value's scale
    long points = 0, lists_differ = 0;
    void merge(const Differences& o) {
      largest = std::max(largest, o.largest);
      points += o.points;
      lists_differ += o.lists_differ;
    }
  };
  const auto d = reduce_points(owned_count, Differences{}, [&](Index i, Differences& t) {
    const auto g = static_cast<Index>(ids[static_cast<std::size_t>(i)]);
    ++t.points;
    t.lists_differ += local_nb.count(i) != whole_nb.count(g);
    const auto a = kernel_values(mine, i, dx, h, n0), b = kernel_values(whole, g, dx, h, n0);
    for (std::size_t k = 0; k < a.size(); ++k)
      t.largest = std::max(t.largest, std::abs(a[k] - b[k]) / (std::abs(b[k]) + 1e-3));
  });
  long points = d.points, total = 0, lists_differ = 0;
  MPI_Allreduce(&points, &total, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(&d.lists_differ, &lists_differ, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  double largest = 0.0;
  MPI_Allreduce(&d.largest, &largest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  if (p.rank == 0)
    std::printf("%d processes: %ld points, largest relative difference %.3g, %zu ghosts here\n",
                p.count, total, largest, ghosts.size());
  EXPECT_EQ(total, all.size());
  EXPECT_EQ(lists_differ, 0);
  EXPECT_LT(largest, 1e-10);
  if (p.count > 1) {
    EXPECT_GT(ghosts.size(), 0u);
  }

  // The phases built on the operators: free surface (from the types the ghosts carried), the
  // PPE's sources from u* (the ghosts' velocities) and the slip velocity gradient.
  FreeSurfaceOptions surface = flow.options().free_surface;
  surface.reference_density = n0;
  PointSet<2> one = all;
  detect_free_surface<2>(one, whole_nb, whole_ops, surface);
  detect_free_surface<2>(local, local_nb, local_ops, surface);
  // The ghosts' types are their owners' (a ghost's own neighbourhood is cut off at the halo's
  // edge: there it would pass for free surface, and its neighbours' PPE sources would lose
  // their volume term — 12–72 % off at 2–4 processes before this refresh).
  refresh_types(halo, local, owned_count);
  PpeOptions<2> po;
  po.gravity = Vec2(0.0, -9.81);
  po.dt = 1e-3;
  po.dx = dx;
  po.reference_density = n0;
  const auto one_data = ppe_data<2>(one, whole_nb, whole_ops, one.velocity, {}, po);
  const auto local_data = ppe_data<2>(local, local_nb, local_ops, local.velocity, {}, po);
  const auto one_grad = slip_velocity_gradient<2>(one, whole_nb, whole_ops, one.velocity);
  const auto local_grad = slip_velocity_gradient<2>(local, local_nb, local_ops, local.velocity);
  long types_differ = 0;
  double data_difference = 0.0, data_scale = 0.0, grad_difference = 0.0, grad_scale = 0.0;
  for (Index i = 0; i < owned_count; ++i) {
    const auto g = static_cast<Index>(ids[static_cast<std::size_t>(i)]);
    types_differ += local.type[i] != one.type[g];
    for (const auto v : std::array{&PoissonData::source, &PoissonData::neumann}) {
      data_difference = std::max(data_difference, std::abs((local_data.*v)[i] - (one_data.*v)[g]));
      data_scale = std::max(data_scale, std::abs((one_data.*v)[g]));
    }
    grad_difference = std::max(grad_difference, (local_grad[i] - one_grad[g]).norm());
    grad_scale = std::max(grad_scale, one_grad[g].norm());
  }
  long all_types_differ = 0;
  double relative[2] = {data_difference / data_scale, grad_difference / grad_scale}, most[2] = {};
  MPI_Allreduce(&types_differ, &all_types_differ, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(relative, most, 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  if (p.rank == 0)
    std::printf(
        "free-surface types differ at %ld points; PPE sources within %.3g, ∇u within %.3g\n",
        all_types_differ, most[0], most[1]);
  EXPECT_EQ(all_types_differ, 0);
  EXPECT_LT(most[0], 1e-10);
  EXPECT_LT(most[1], 1e-10);
}

/// The flow's neighbour rebuild (FlowSolver::rebuild_neighbours) on points whose first `owned`
/// are owned and the rest ghosts (halo null: one piece): wet neighbours, pairs through walls
/// cut, the wall nodes' weights, dry nodes and nodes beyond the fluid inactive — each decided by
/// the owner, the ghosts' types and weights refreshed before the pairs go.
std::pair<Neighbours, std::vector<double>> rebuild(PointSet<2>& points, Index owned,
                                                   const parallel::Halo<2>* halo,
                                                   const FlowSolver<2>& flow) {
  const double h = flow.support();
  Neighbours nb = find_wet_neighbours<2>(points, h);
  cut_pairs_through_thin_walls<2>(nb, points, flow.walls());
  std::vector<double> weight = wall_node_weights<2>(points, h, flow.dx());
  if (halo != nullptr) {
    const auto ghost_weight =
        halo->refresh(std::vector<double>(weight.begin(), weight.begin() + owned), 1);
    std::copy(ghost_weight.begin(), ghost_weight.end(), weight.begin() + owned);
  }
  deactivate_dry_wall_nodes<2>(points, nb, owned);
  if (halo != nullptr) {
    refresh_types(*halo, points, owned);
    remove_pairs_with_inactive<2>(points, nb);
  }
  FreeSurfaceOptions surface = flow.options().free_surface;
  surface.reference_density = flow.reference_density();
  deactivate_wall_nodes_beyond_fluid<2>(points, nb, surface, owned);
  if (halo != nullptr) {
    refresh_types(*halo, points, owned);
    remove_pairs_with_inactive<2>(points, nb);
  }
  return {std::move(nb), std::move(weight)};
}

TEST(Halo, TheFlowsNeighbourRebuildOnOwnedPointsGivesTheOnePieceListsAndOperators) {
  const auto p = parallel::processes();
  const double dx = 0.01;
  auto flow = test::dam_break<2>(dx, Preconditioner::automatic);
  for (int s = 0; s < 20; ++s) flow.step(flow.stable_dt(0.0).first);
  const double h = flow.support(), n0 = flow.reference_density();
  const auto& options = flow.options().operators;

  PointSet<2> one = flow.points();
  const auto [whole_nb, whole_weight] = rebuild(one, one.size(), nullptr, flow);
  const auto whole_ops = compute_operators<2>(one.position, whole_nb, options, whole_weight);

  auto owned = dealt_points(flow.points(), p);
  parallel::Decomposition<2> decomposition(owned);
  const auto halo = decomposition.halo(owned, h);
  PointSet<2> local;
  std::vector<std::int64_t> ids;
  append(owned, local, ids);
  append(halo.ghosts(), local, ids);
  const auto n_owned = static_cast<Index>(owned.size());
  const auto [nb, weight] = rebuild(local, n_owned, &halo, flow);
  const auto ops = compute_operators<2>(local.position, nb, options, weight);

  long lists_differ = 0, types_differ = 0;
  double largest = 0.0;
  for (Index i = 0; i < n_owned; ++i) {
    const auto g = static_cast<Index>(ids[static_cast<std::size_t>(i)]);
    std::vector<Index> list;
    for (Index j : nb.of(i)) list.push_back(static_cast<Index>(ids[static_cast<std::size_t>(j)]));
    std::sort(list.begin(), list.end());
    const auto expected = whole_nb.of(g);
    lists_differ += !std::equal(list.begin(), list.end(), expected.begin(), expected.end());
    types_differ += local.type[i] != one.type[g];
    const auto a = kernel_values({local, nb, ops}, i, dx, h, n0);
    const auto b = kernel_values({one, whole_nb, whole_ops}, g, dx, h, n0);
    for (std::size_t k = 0; k < a.size(); ++k)
      largest = std::max(largest, std::abs(a[k] - b[k]) / (std::abs(b[k]) + 1e-3));
  }
  long counts[2] = {lists_differ, types_differ}, all_counts[2] = {};
  double all_largest = 0.0;
  MPI_Allreduce(counts, all_counts, 2, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(&largest, &all_largest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  if (p.rank == 0)
    std::printf("rebuild on %d processes: %ld lists and %ld types differ; kernels within %.3g\n",
                p.count, all_counts[0], all_counts[1], all_largest);
  EXPECT_EQ(all_counts[0], 0);
  EXPECT_EQ(all_counts[1], 0);
  EXPECT_LT(all_largest, 1e-10);
}

}  // namespace
}  // namespace hm::ldd
