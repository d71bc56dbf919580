#include "ldd/free_surface.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Eigenvalues>

#include "core/errors.hpp"

namespace hm::ldd {
namespace {

/// Whether a neighbour of i covers the cone of half-angle acos(cos_cone) around `dir`.
template <int D>
bool cone_covered(const PointSet<D>& pts, const Neighbours& nb, Index i, const Vec<D>& dir,
                  double cos_cone, double cover_reach) {
  const Vec<D>& xi = pts.position[i];
  const double cover_reach2 = cover_reach * cover_reach;
  for (Index j : nb.of(i)) {
    const Vec<D> r = pts.position[j] - xi;
    if (pts.kind[j] == PointKind::fluid) {
      // Only fluid within cover_reach covers: a droplet of spray up to h ahead of a surge front
      // made the tip an interior point, whose one-sided row then ran away (Lobovsky dam break
      // at H/80: 200 m/s along the floor) [CHOICE].
      if (r.dot(dir) > r.norm() * cos_cone && r.squaredNorm() < cover_reach2) return true;
      continue;
    }
    const Vec<D>& n = pts.wall_normal[j];
    const double facing = dir.dot(n);
    if (facing >= -cos_cone) continue;   // the direction does not point into that wall
    const double s = r.dot(n) / facing;  // distance along dir to the wall's plane
    if (s > -1e-9 * nb.radius && s < nb.radius) return true;
  }
  return false;
}

}  // namespace

template <int D>
double lattice_number_density(double dx, double h) {
  const int m = static_cast<int>(std::ceil(h / dx));
  double n0 = 0.0;
  Eigen::Matrix<int, D, 1> k = Eigen::Matrix<int, D, 1>::Constant(-m);
  while (true) {
    const double r = k.template cast<double>().norm() * dx;
    if (r > 0.0) n0 += wendland_c2(r / h);
    int a = 0;
    while (a < D && ++k[a] > m) k[a++] = -m;
    if (a == D) break;
  }
  return n0;
}

/// The outward normal ν with its components into the walls next to point i removed: a fluid
/// deficit towards a wall is the wall, not a free surface (two passes, for corners).
template <int D>
Vec<D> off_the_walls(const PointSet<D>& pts, const Neighbours& nb, Index i, Vec<D> nu) {
  for (int pass = 0; pass < 2; ++pass)
    for (Index j : nb.of(i)) {
      if (pts.kind[j] != PointKind::wall) continue;
      const double into = nu.dot(pts.wall_normal[j]);
      if (into < 0.0) nu -= into * pts.wall_normal[j];
    }
  return nu;
}

/// Number density, offset vector and Σ W|r| over the FLUID neighbours of i only: wall nodes stand
/// for the wall, not for fluid, and dry nodes above a free surface would otherwise turn the
/// offset of the surface points near a wall downwards.
template <int D>
struct FluidMoments {
  double density = 0.0, moment = 0.0;
  Vec<D> offset = Vec<D>::Zero();
  Mat<D> second = Mat<D>::Zero();  ///< Σ W r ⊗ r
};

template <int D>
FluidMoments<D> fluid_moments(const PointSet<D>& pts, const Neighbours& nb, Index i) {
  FluidMoments<D> m;
  for (Index j : nb.of(i)) {
    if (pts.kind[j] != PointKind::fluid) continue;
    const Vec<D> r = pts.position[j] - pts.position[i];
    const double d = r.norm(), w = wendland_c2(d / nb.radius);
    m.density += w;
    m.moment += w * d;
    m.offset += w * r;
    m.second.noalias() += w * r * r.transpose();
  }
  return m;
}

/// A fluid sheet or filament: the fluid neighbours alone span fewer than D directions
/// (λ_min of D·A/tr A below λ_c). Returns the direction across it (the eigenvector of λ_min),
/// or zero when the fluid stencil is not degenerate.
template <int D>
Vec<D> across_a_sheet(const FluidMoments<D>& m, double lambda_c) {
  const double trace = m.second.trace();
  if (trace <= 0.0) return Vec<D>::Zero();
  const Mat<D> normalised = m.second * (D / trace);
  // The closed form's smallest eigenvalue first (most stencils are not sheets); the direction
  // from the iterative solver, accurate also where eigenvalues are close.
  Eigen::SelfAdjointEigenSolver<Mat<D>> eigen;
  eigen.computeDirect(normalised, Eigen::EigenvaluesOnly);
  if (eigen.eigenvalues()[0] >= lambda_c) return Vec<D>::Zero();
  eigen.compute(normalised);
  if (eigen.eigenvalues()[0] >= lambda_c) return Vec<D>::Zero();
  return eigen.eigenvectors().col(0);
}

/// Item 4: wall node i lies beyond the fluid along the wall — the outward direction of its fluid
/// neighbours (offset `offset`), projected on the wall tangent, has length ≥ min_wall_tangent
/// and no neighbour covers the cone of half-angle acos(cos_wall_cone) around it.
template <int D>
bool beyond_the_fluid(const PointSet<D>& pts, const Neighbours& nb, Index i, const Vec<D>& offset,
                      const FreeSurfaceOptions& opt, double cos_wall_cone) {
  const double on = offset.norm();
  if (on == 0.0) return false;
  const Vec<D>& nw = pts.wall_normal[i];
  const Vec<D> nu = -offset / on;
  const Vec<D> tangent = nu - nu.dot(nw) * nw;
  return tangent.norm() >= opt.min_wall_tangent &&
         !cone_covered<D>(pts, nb, i, tangent.normalized(), cos_wall_cone,
                          opt.cover_reach * nb.radius);
}

template <int D>
Index deactivate_wall_nodes_beyond_fluid(PointSet<D>& pts, Neighbours& nb,
                                         const FreeSurfaceOptions& opt, Index owned,
                                         InactivePairs pairs) {
  const double cos_wall_cone = std::cos(opt.wall_cone_degrees * std::numbers::pi / 180.0);
  const Index n = pts.size();
  HM_ASSERT(nb.points() == n, "neighbour lists of {} points for {} points", nb.points(), n);
  // Decide for every node first, then remove: the test reads fluid neighbours only (and wall
  // nodes of other walls, which it does not change), so the order does not matter.
  // Only [0, owned) are decided (all with owned < 0); ghosts' owners decide for them.
  const Index decided = owned < 0 ? n : owned;
  std::vector<char> dry(static_cast<std::size_t>(n), 0);
  Index count = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : count)
  for (Index i = 0; i < decided; ++i) {
    if (pts.kind[i] != PointKind::wall || pts.type[i] == PointType::inactive) continue;
    const auto m = fluid_moments<D>(pts, nb, i);
    if (beyond_the_fluid<D>(pts, nb, i, m.offset, opt, cos_wall_cone)) {
      dry[i] = 1;
      ++count;
    }
  }
  if (count == 0) return 0;
  for (Index i = 0; i < n; ++i)
    if (dry[i]) pts.type[i] = PointType::inactive;
  if (pairs == InactivePairs::removed)
    remove_pairs(nb, [&](Index i, Index j) { return dry[i] || dry[j]; });
  return count;
}

template <int D>
FreeSurfaceReport detect_free_surface(PointSet<D>& pts, const Neighbours& nb,
                                      const Operators<D>& ops, const FreeSurfaceOptions& opt,
                                      Index owned) {
  HM_ASSERT(opt.reference_density > 0.0, "free surface: reference number density {} must be > 0",
            opt.reference_density);
  const double cos_cone = std::cos(opt.cone_degrees * std::numbers::pi / 180.0);
  const double cos_wall_cone = std::cos(opt.wall_cone_degrees * std::numbers::pi / 180.0);
  const Index n = owned < 0 ? pts.size() : owned;
  FreeSurfaceReport rep;
  rep.fluid_density.assign(static_cast<std::size_t>(n), 0.0);
  Index candidates = 0, surface = 0, contact = 0, isolated = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : candidates, surface, contact, isolated)
  for (Index i = 0; i < n; ++i) {
    const PointType before = pts.type[i];
    if (before == PointType::inactive) continue;
    const auto m = fluid_moments<D>(pts, nb, i);
    rep.fluid_density[i] = m.density;
    const double on = m.offset.norm();
    if (pts.kind[i] == PointKind::wall) {
      PointType t = PointType::wall;
      if (beyond_the_fluid<D>(pts, nb, i, m.offset, opt, cos_wall_cone)) {
        t = PointType::surface;
        ++contact;
      }
      pts.type[i] = t;
      continue;
    }
    if (ops.isolated(i)) {
      pts.type[i] = PointType::isolated;
      ++isolated;
      continue;
    }
    const bool was = before == PointType::surface;
    const double beta = was ? 1.0 - opt.hysteresis * (1.0 - opt.beta_n) : opt.beta_n;
    const double tau = was ? opt.hysteresis * opt.tau_o : opt.tau_o;
    const double ratio = m.moment > 0.0 ? on / m.moment : 1.0;
    const bool candidate =
        m.density < beta * opt.reference_density || ratio > tau || ops.lambda_min[i] < opt.lambda_c;
    PointType t = PointType::interior;
    const Vec<D> sheet = across_a_sheet<D>(m, opt.lambda_c);
    if (candidate || sheet.squaredNorm() > 0.0) {
      ++candidates;
      // A degenerate stencil with a vanishing offset (a symmetric filament) is a surface too.
      bool open = ops.lambda_min[i] < opt.lambda_c;
      auto open_towards = [&](const Vec<D>& outward) {
        const Vec<D> nu = off_the_walls<D>(pts, nb, i, outward);
        return nu.norm() >= opt.min_wall_tangent &&
               !cone_covered<D>(pts, nb, i, nu.normalized(), cos_cone, opt.cover_reach * nb.radius);
      };
      if (on > 0.0) open = open_towards(-m.offset / on);
      // A sheet one point thick (a run-up jet along a wall) is open on both faces, whatever its
      // offset says; the wall nodes beside it made the whole stencil look regular, and a
      // filament 2 dx from the K&O right wall at L/80 kept interior rows until it blew up.
      if (!open && sheet.squaredNorm() > 0.0) open = open_towards(sheet) || open_towards(-sheet);
      if (open) {
        t = PointType::surface;
        ++surface;
      }
    }
    pts.type[i] = t;
  }
  rep.candidates = candidates;
  rep.surface = surface;
  rep.contact_line = contact;
  rep.isolated = isolated;
  return rep;
}

template Index deactivate_wall_nodes_beyond_fluid<2>(PointSet<2>&, Neighbours&,
                                                     const FreeSurfaceOptions&, Index,
                                                     InactivePairs);
template Index deactivate_wall_nodes_beyond_fluid<3>(PointSet<3>&, Neighbours&,
                                                     const FreeSurfaceOptions&, Index,
                                                     InactivePairs);
template double lattice_number_density<2>(double, double);
template double lattice_number_density<3>(double, double);
template FreeSurfaceReport detect_free_surface<2>(PointSet<2>&, const Neighbours&,
                                                  const Operators<2>&, const FreeSurfaceOptions&,
                                                  Index);
template FreeSurfaceReport detect_free_surface<3>(PointSet<3>&, const Neighbours&,
                                                  const Operators<3>&, const FreeSurfaceOptions&,
                                                  Index);

}  // namespace hm::ldd
