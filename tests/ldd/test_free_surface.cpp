// Free-surface detection on a disk, a sphere and a water column.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "clouds.hpp"
#include "tank.hpp"

namespace hm::ldd {
namespace {

/// Points of a (jittered) lattice within radius R: every point within dx/2 (jittered: 0.4 dx) of
/// the rim must be SURFACE; points deeper than 2 dx that are SURFACE are false positives
/// (≤ 0.5 %). Why 0.4 dx with a 0.2 dx jitter: two points are ≥ 0.6 dx apart, so a neighbour
/// inside the 45° cone lies ≥ 0.42 dx further out — beyond the rim for a point that deep; a
/// point at depth 0.45 dx can be legitimately shadowed by a neighbour at the rim.
template <int D>
void check_ball(double jitter, int cells) {
  const double dx = 2.0 / cells, R = 0.9;
  PointSet<D> pts;
  for (const auto& x : test::lattice<D>(Vec<D>::Constant(-1), Vec<D>::Constant(1), dx, jitter, 9))
    if (x.norm() <= R) pts.add_fluid(x);
  const double h = 2.5 * dx;
  const auto nb = find_neighbours<D>(pts.position, h);
  const auto ops = compute_operators<D>(pts.position, nb);
  FreeSurfaceOptions fs;
  fs.reference_density = lattice_number_density<D>(dx, h);
  detect_free_surface<D>(pts, nb, ops, fs);
  Index outer = 0, missed = 0, inside = 0, false_pos = 0;
  for (Index i = 0; i < pts.size(); ++i) {
    const double depth = R - pts.position[i].norm();
    const bool surface = pts.type[i] == PointType::surface;
    if (depth < (jitter > 0.0 ? 0.4 : 0.5) * dx) {
      ++outer;
      missed += surface ? 0 : 1;
    } else if (depth > 2.0 * dx) {
      ++inside;
      false_pos += surface ? 1 : 0;
    }
  }
  std::printf("D=%d jitter %.1f: %d outer, %d missed; %d inside, %d false positives\n", D, jitter,
              outer, missed, inside, false_pos);
  EXPECT_EQ(missed, 0);
  EXPECT_LE(false_pos, 0.005 * inside);
}

TEST(LddFreeSurface, Disk) {
  check_ball<2>(0.0, 80);
  check_ball<2>(0.2, 80);
}
TEST(LddFreeSurface, Sphere) {
  check_ball<3>(0.0, 30);
  check_ball<3>(0.2, 30);
}

TEST(LddFreeSurface, JitteredWaterColumn2D) {
  const auto c = test::water_column<2>(Vec<2>(0.5, 0.4), 0.3, 0.01, 0.05, Preconditioner::ilu, 0.2);
  double top = -1;
  for (Index i = 0; i < c.points.size(); ++i)
    if (c.points.kind[i] == PointKind::fluid) top = std::max(top, c.points.position[i].y());
  Index outer = 0, missed = 0, inside = 0, false_pos = 0;
  for (Index i = 0; i < c.points.size(); ++i) {
    if (c.points.kind[i] != PointKind::fluid) continue;
    const double y = c.points.position[i].y();
    const bool surface = c.points.type[i] == PointType::surface;
    // The top layer (0.3 − dx/2 ± 0.2 dx) must be found; deeper than 2 dx nothing may be.
    if (y > 0.3 - 0.75 * c.dx) {
      ++outer;
      missed += surface ? 0 : 1;
    } else if (y < 0.3 - 2.0 * c.dx) {
      ++inside;
      false_pos += surface ? 1 : 0;
    }
  }
  std::printf("column: %d outer, %d missed; %d inside, %d false positives\n", outer, missed, inside,
              false_pos);
  EXPECT_EQ(missed, 0);
  EXPECT_LE(false_pos, 0.005 * inside);
}

// A run-up jet: a vertical filament of fluid one point thick, 1.5 dx from a wall (wall nodes at
// spacing dx, normal −x, towards the filament), points ≈ 0.6 dx apart along it. Every point of the
// filament is SURFACE: the wall nodes make the whole stencil regular (λ_min of all neighbours
// well above λ_c) and the number density is above n0, so only the fluid-only moment tells.
TEST(LddFreeSurface, FilamentBesideAWall) {
  const double dx = 0.01, h = 2.5 * dx;
  PointSet<2> pts;
  for (int k = 0; k <= 50; ++k)  // unevenly spaced: the offset along the filament is not zero
    pts.add_fluid(Vec<2>(0.0, (0.6 * k + 0.15 * std::sin(1.7 * k)) * dx));
  for (double y = -0.05; y <= 0.35; y += dx)
    pts.add_wall_node(Vec<2>(1.5 * dx, y), Vec<2>(-1, 0), WallHost<2>{});
  const auto nb = find_neighbours<2>(pts.position, h);
  const auto ops = compute_operators<2>(pts.position, nb);
  FreeSurfaceOptions fs;
  fs.reference_density = lattice_number_density<2>(dx, h);
  detect_free_surface<2>(pts, nb, ops, fs);
  Index filament = 0, missed = 0;
  double lambda = 1.0;
  for (Index i = 0; i < pts.size(); ++i) {
    if (pts.kind[i] != PointKind::fluid) continue;
    ++filament;
    missed += pts.type[i] == PointType::surface ? 0 : 1;
    const double y = pts.position[i].y();
    if (y > h && y < 0.29 - h) lambda = std::min(lambda, ops.lambda_min[i]);  // away from its ends
  }
  std::printf(
      "filament: %d points, %d not surface; smallest λ_min with the wall nodes %.3f (away from the "
      "ends)\n",
      filament, missed, lambda);
  EXPECT_GT(lambda, fs.lambda_c);  // the whole stencil is not degenerate
  EXPECT_EQ(missed, 0);
}

}  // namespace
}  // namespace hm::ldd
