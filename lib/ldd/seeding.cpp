#include "ldd/seeding.hpp"

#include <cmath>

#include <fmt/ranges.h>

#include "core/errors.hpp"

namespace hm::ldd {
namespace {

/// Points of the region closer than this fraction of dx/2 to a wall are still kept: the lattice
/// of a box that is the tank sits exactly dx/2 from the walls.
constexpr double clearance_tolerance = 1e-6;

template <int D>
std::string text(const Vec<D>& v) {
  return fmt::format("({:g})", fmt::join(v.data(), v.data() + D, ", "));
}

template <int D>
void check_spacing(const Box<D>& region, double dx, std::string_view what) {
  if (!(dx > 0.0) || !std::isfinite(dx))
    input_error("fluid spacing dx = {:g} m must be a positive number", dx);
  const double extent = (region.upper - region.lower).minCoeff();
  if (!(extent > 0.0))
    input_error("{} {}–{} is empty (smallest side {:g} m); give lower < upper on every axis", what,
                text<D>(region.lower), text<D>(region.upper), extent);
  if (extent < 4.0 * dx)
    input_error(
        "fluid spacing dx = {:g} m is too large for the {} {}–{}: its smallest side "
        "{:g} m holds fewer than 4 points; choose dx ≤ {:g} m",
        dx, what, text<D>(region.lower), text<D>(region.upper), extent, extent / 4.0);
}

template <int D>
std::vector<Vec<D>> lattice_points(const Box<D>& region, double dx,
                                   std::span<const WallMesh<D>> walls) {
  Eigen::Matrix<long, D, 1> n;
  for (int a = 0; a < D; ++a)
    n[a] = static_cast<long>(std::floor((region.upper[a] - region.lower[a]) / dx + 1e-9));
  const long total = n.prod();
  std::vector<Vec<D>> out;
  std::vector<char> keep(static_cast<std::size_t>(total), 0);
  std::vector<Vec<D>> all(static_cast<std::size_t>(total));
#pragma omp parallel for schedule(static)
  for (long k = 0; k < total; ++k) {
    long rem = k;
    Vec<D> p;
    for (int a = 0; a < D; ++a) {
      p[a] = region.lower[a] + (static_cast<double>(rem % n[a]) + 0.5) * dx;
      rem /= n[a];
    }
    bool ok = true;
    for (const auto& w : walls)
      ok = ok && w.closest(p).signed_distance >= 0.5 * dx * (1.0 - clearance_tolerance);
    all[static_cast<std::size_t>(k)] = p;
    keep[static_cast<std::size_t>(k)] = ok;
  }
  for (long k = 0; k < total; ++k)
    if (keep[static_cast<std::size_t>(k)]) out.push_back(all[static_cast<std::size_t>(k)]);
  return out;
}

}  // namespace

template <int D>
std::vector<Vec<D>> seed_box(const Box<D>& fluid, double dx, std::span<const WallMesh<D>> walls) {
  check_spacing<D>(fluid, dx, "fluid box");
  if (!walls.empty()) {
    Vec<D> lo = walls[0].lower(), hi = walls[0].upper();
    for (const auto& w : walls) {
      lo = lo.cwiseMin(w.lower());
      hi = hi.cwiseMax(w.upper());
    }
    const double tol = 1e-9 * (hi - lo).norm();
    if ((fluid.lower.array() < lo.array() - tol).any() ||
        (fluid.upper.array() > hi.array() + tol).any())
      input_error(
          "fluid box {}–{} is not inside the tank: the walls span {}–{}; move or shrink "
          "the fluid box",
          text<D>(fluid.lower), text<D>(fluid.upper), text<D>(lo), text<D>(hi));
  }
  auto points = lattice_points<D>(fluid, dx, walls);
  if (points.empty())
    input_error(
        "fluid box {}–{} at dx = {:g} m: no lattice point is dx/2 from the walls on their "
        "fluid side; check the wall normals (they must point into the fluid)",
        text<D>(fluid.lower), text<D>(fluid.upper), dx);
  return points;
}

template <int D>
std::vector<Vec<D>> seed_inside(const WallMesh<D>& container, double dx) {
  container.require_closed("seeding the fluid inside it");
  const Box<D> region{container.lower(), container.upper()};
  check_spacing<D>(region, dx, fmt::format("inside of wall '{}'", container.name()));
  auto points = lattice_points<D>(region, dx, std::span<const WallMesh<D>>(&container, 1));
  if (points.empty())
    input_error(
        "wall '{}' at dx = {:g} m: no lattice point lies inside, dx/2 from the surface; "
        "check that its normals point into the fluid",
        container.name(), dx);
  return points;
}

template std::vector<Vec<2>> seed_box<2>(const Box<2>&, double, std::span<const WallMesh<2>>);
template std::vector<Vec<3>> seed_box<3>(const Box<3>&, double, std::span<const WallMesh<3>>);
template std::vector<Vec<2>> seed_inside<2>(const WallMesh<2>&, double);
template std::vector<Vec<3>> seed_inside<3>(const WallMesh<3>&, double);

}  // namespace hm::ldd
