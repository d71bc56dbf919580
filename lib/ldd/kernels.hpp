#pragma once
// The flow step's per-point kernels: each computes what one phase of a step does at one point
// i from i's data and its neighbours' (never writing any point), and returns it; FlowSolver
// (ldd/flow.cpp) runs them through the point-loop driver (ldd/point_loop.hpp) and stores the
// results. Written as templates in the header, so that each inlines into its loop.
// SI units throughout: positions m, velocities m/s, pressure Pa, time s.
#include <algorithm>
#include <limits>
#include <optional>
#include <span>

#include "ldd/neighbours.hpp"
#include "ldd/operators.hpp"
#include "ldd/points.hpp"
#include "ldd/walls.hpp"

namespace hm::ldd::kernels {

/// What the kernels read: the points, their neighbour lists and operators.
template <int D>
struct Cloud {
  const PointSet<D>& points;
  const Neighbours& neighbours;
  const Operators<D>& ops;

  bool fluid(Index i) const { return points.kind[i] == PointKind::fluid; }
  PointType type(Index i) const { return points.type[i]; }
  const Vec<D>& x(Index i) const { return points.position[i]; }
};

// ---------------------------------------------------------------------------------------------
// Positions: PBD, shifting, wall clearance

struct PbdParameters {
  double distance = 0.0;       ///< d0: fluid pairs closer than this are pushed apart [m]
  double wall_distance = 0.0;  ///< the same against wall nodes (d0/2) [m]
  double relaxation = 1.0;     ///< of the summed correction
  double clamp = 0.0;          ///< the largest displacement of one iteration [m]
};

/// One position-based-dynamics iteration at fluid point i: the displacement that moves it
/// towards distance d0 from the fluid points and d0/2 from the wall nodes closer than that (a
/// wall node counting as the share of the wall it stands for), averaged over those pairs and
/// clamped. Nothing for wall nodes and for points with no such pair.
template <int D>
std::optional<Vec<D>> pbd_displacement(const Cloud<D>& c, Index i, const PbdParameters& p) {
  if (!c.fluid(i)) return std::nullopt;
  Vec<D> delta = Vec<D>::Zero();
  double count = 0.0;  // pairs, a wall node counting as the wall share it stands for
  // Most pairs are farther than d0: they are told apart on |r|² without the square root
  // (with a margin that leaves every pair near d0 to the exact test below).
  const double reach = std::max(p.distance, p.wall_distance) * (1.0 + 1e-9);
  const double reach2 = reach * reach;
  for (Index j : c.neighbours.of(i)) {
    const Vec<D> r = c.x(j) - c.x(i);
    if (r.squaredNorm() >= reach2) continue;
    const double d = r.norm();
    if (d <= 0.0) continue;
    const double w = c.ops.weight_of(j);
    if (c.fluid(j)) {
      if (d >= p.distance) continue;
      delta -= 0.5 * (p.distance - d) / d * r;
    } else {
      if (d >= p.wall_distance) continue;
      delta -= w * (p.wall_distance - d) / d * r;
    }
    count += w;
  }
  if (count == 0.0) return std::nullopt;
  delta *= p.relaxation / count;
  const double length = delta.norm();
  if (length > p.clamp) delta *= p.clamp / length;
  return delta;
}

/// ∇_i of the concentration C_i = n_i/n0 [1/m] with support radius h, lattice spacing dx and
/// lattice number density n0. Fluid neighbours count as they are; a wall node j stands for the
/// fluid mirrored behind the wall: the points of its lattice column at depths dx/2 and 3dx/2
/// below the node (deeper ones are beyond h of any fluid point at the clearance d0/2). For a
/// lattice beside a flat wall, the fluid and the mirrored columns form the full lattice, so the
/// gradient vanishes in every layer; counting fluid only made the first layer attract points
/// (its band held 44 % more points after the K&O dam break at L/20), counting the nodes as
/// points pushed the second layer away. `near_surface` is set when a fluid neighbour is on the
/// free surface or isolated.
template <int D>
Vec<D> concentration_gradient(const Cloud<D>& c, Index i, double h, double dx, double n0,
                              bool& near_surface) {
  const Vec<D>& xi = c.x(i);
  Vec<D> grad = Vec<D>::Zero();
  auto add = [&](const Vec<D>& xj, double weight = 1.0) {
    const Vec<D> r = xi - xj;
    const double d = r.norm();
    if (d > 0.0 && d < h) grad += (weight * wendland_c2_derivative(d / h) / (h * d)) * r;
  };
  for (Index j : c.neighbours.of(i)) {
    const Vec<D>& xj = c.x(j);
    if (c.fluid(j)) {
      add(xj);
      near_surface =
          near_surface || c.type(j) == PointType::surface || c.type(j) == PointType::isolated;
      continue;
    }
    const Vec<D>& n = c.points.wall_normal[j];
    if (n.dot(xi - xj) <= 0.0) continue;  // the node faces away (the far side of a thin wall)
    // A node sampled finer than dx stands for that share of a lattice column.
    add(xj - 0.5 * dx * n, c.ops.weight_of(j));
    add(xj - 1.5 * dx * n, c.ops.weight_of(j));
  }
  return grad / n0;
}

struct ShiftParameters {
  double coefficient = 0.0;  ///< A of D = A dx |u| Δt
  double dx = 0.0;           ///< lattice spacing [m]
  double dt = 0.0;           ///< the step [s]
  double max_shift = 0.0;    ///< the largest displacement [m]
  double h = 0.0;            ///< support radius [m]
  double n0 = 0.0;           ///< the lattice's number density
};

/// The Fickian shift of fluid point i down its concentration gradient, −A dx |u| Δt ∇C, clamped
/// to max_shift; zero for wall nodes, isolated points and points within h of the free surface
/// (their deficit is the missing air, not a void).
template <int D>
Vec<D> fickian_shift(const Cloud<D>& c, Index i, const ShiftParameters& p) {
  if (!c.fluid(i) || c.type(i) == PointType::isolated) return Vec<D>::Zero();
  bool near_surface = c.type(i) == PointType::surface;
  const Vec<D> grad = concentration_gradient(c, i, p.h, p.dx, p.n0, near_surface);
  if (near_surface) return Vec<D>::Zero();
  Vec<D> delta = -(p.coefficient * p.dx * c.points.velocity[i].norm() * p.dt) * grad;
  const double length = delta.norm();
  if (length > p.max_shift) delta *= p.max_shift / length;
  return delta;
}

/// A fluid point kept clear of the walls: where it ended, its velocity, a lower bound of its
/// distance to the nearest wall, and whether it was found behind a wall it did not cross.
template <int D>
struct Clearance {
  Vec<D> position;
  Vec<D> velocity;
  double nearest = std::numeric_limits<double>::infinity();  ///< [m]
  bool outside = false;
};

/// The point at x moving at u, put back to `clearance` in front of every wall it came closer
/// to than that, its velocity towards that wall removed. `start` is where it began the step
/// (null: unknown, taken to have come through every wall): a point behind a wall it neither
/// crossed nor was swept over by has left the domain over an open wall end and is `outside`.
template <int D>
Clearance<D> wall_clearance(std::span<const WallMesh<D>> walls, Vec<D> x, Vec<D> u,
                            const Vec<D>* start, double clearance) {
  // The point crossed the wall this step, or the wall swept over it (the walls are at t + Δt
  // before the step starts).
  auto came_through = [&](const WallMesh<D>& wall) {
    return start == nullptr || wall.crosses(*start, x) ||
           wall.closest(*start).signed_distance < 0.0;
  };
  Clearance<D> out;
  double nearest = std::numeric_limits<double>::infinity();
  // Two passes settle corners: leaving one wall may bring the point too close to another.
  for (int pass = 0; pass < 2; ++pass) {
    bool moved = false;
    nearest = std::numeric_limits<double>::infinity();
    for (const auto& wall : walls) {
      const auto c = wall.closest(x);
      // A thin wall is wetted on both sides: the side is the sign of the distance.
      const double side = wall.thin() && c.signed_distance < 0.0 ? -1.0 : 1.0;
      const double distance = side * c.signed_distance;
      const Vec<D> normal = side * c.normal;
      if (distance < 0.0 && !wall.thin() && !came_through(wall)) {
        // Behind a wall it did not cross this step: it left the domain over an open wall end
        // (the K&O run-up jet over the top of the right wall at L/80). Putting it back in
        // front teleported it into the fluid inside and the run blew up (t = 0.775 s).
        out.outside = true;
        nearest = std::min(nearest, -distance);
        continue;
      }
      if (distance < clearance) {
        x = c.point + clearance * normal;
        const Vec<D> relative = u - wall.velocity_at(c.element, c.barycentric);
        const double towards = relative.dot(normal);
        if (towards < 0.0) u -= towards * normal;
        moved = true;
        nearest = std::min(nearest, clearance);
      } else {
        nearest = std::min(nearest, distance);
      }
    }
    if (!moved) break;
  }
  out.position = x;
  out.velocity = u;
  out.nearest = nearest;
  return out;
}

// ---------------------------------------------------------------------------------------------
// Classification

/// Whether interior fluid point i is too sparse for a Laplacian row of its own: its number
/// density (fluid and wall, from the operators) below `total_limit`, or its fluid-only density
/// (Wendland C2 of support h) below `fluid_limit`.
inline bool is_sparse(double total_density, double fluid_density, double total_limit,
                      double fluid_limit) {
  return total_density < total_limit || fluid_density < fluid_limit;
}
/// The same, the fluid-only density summed here.
template <int D>
bool is_sparse(const Cloud<D>& c, Index i, double total_limit, double fluid_limit, double h) {
  if (c.ops.number_density[i] < total_limit) return true;
  double fluid_density = 0.0;
  for (Index j : c.neighbours.of(i))
    if (c.fluid(j)) fluid_density += wendland_c2((c.x(j) - c.x(i)).norm() / h);
  return is_sparse(c.ops.number_density[i], fluid_density, total_limit, fluid_limit);
}

// ---------------------------------------------------------------------------------------------
// Predictor, surface pressure, corrector, smoothing

/// ν ∇²u at point i from the operators' Laplacian weights [m/s²] (u: a velocity per point;
/// the wall nodes' is their wall's, no-slip). Zero at inactive nodes and isolated points.
template <int D>
Vec<D> viscous_acceleration(const Cloud<D>& c, Index i, std::span<const Vec<D>> u,
                            double viscosity) {
  if (c.type(i) == PointType::inactive || c.ops.isolated(i)) return Vec<D>::Zero();
  Vec<D> sum = Vec<D>::Zero();
  for (auto k = c.neighbours.offsets[i]; k < c.neighbours.offsets[i + 1]; ++k)
    sum += c.ops.laplacian[k] * (u[c.neighbours.indices[k]] - u[i]);
  return viscosity * sum;
}

/// u* at point i after Δt of gravity g and the viscous acceleration (none for isolated points:
/// ballistic); at a wall node u*_b = U^n + Δt(g + ν∇²u − A), U and A the wall's velocity and
/// acceleration: the velocity the Neumann row assumes (§0.2 item 5, D1).
template <int D>
Vec<D> predicted_velocity(const Cloud<D>& c, Index i, double dt, const Vec<D>& gravity,
                          const Vec<D>& viscous) {
  if (c.fluid(i)) {
    const bool ballistic = c.type(i) == PointType::isolated;
    return c.points.velocity[i] + dt * (gravity + (ballistic ? Vec<D>::Zero() : viscous));
  }
  return c.points.wall_velocity[i] + dt * (gravity + viscous - c.points.wall_acceleration[i]);
}

/// The Dirichlet pressure of free-surface point i [Pa]: a surface point stands for a cell of
/// size dx, so the free surface lies dx/2 beyond it along the outward normal ν (spec §5 item
/// 7), and p = 0 there gives p_i = −ρ (g·ν) dx/2 (the hydrostatic part; never negative: a
/// surface point is not in tension). ν is against the Wendland-weighted sum of r_ij over the
/// fluid neighbours. Nothing where that sum vanishes.
template <int D>
std::optional<double> surface_pressure(const Cloud<D>& c, Index i, double h, double dx,
                                       double density, const Vec<D>& gravity) {
  Vec<D> offset = Vec<D>::Zero();
  for (Index j : c.neighbours.of(i)) {
    if (!c.fluid(j)) continue;
    const Vec<D> r = c.x(j) - c.x(i);
    offset += wendland_c2(r.norm() / h) * r;
  }
  const double length = offset.norm();
  if (length <= 0.0) return std::nullopt;
  const Vec<D> outward = -offset / length;
  return std::max(0.0, -density * gravity.dot(outward) * (0.5 * dx));
}

/// u^{n+1} at point i: u* − (Δt/ρ)∇p at fluid points (`scale` = Δt/ρ), u* at isolated points
/// (ballistic), the wall's velocity at wall nodes.
template <int D>
Vec<D> corrected_velocity(const Cloud<D>& c, Index i, const Vec<D>& predicted, const Vec<D>& grad_p,
                          double scale) {
  if (!c.fluid(i)) return c.points.wall_velocity[i];
  if (c.type(i) == PointType::isolated || c.ops.isolated(i)) return predicted;
  return predicted - scale * grad_p;
}

/// The velocity smoothing's change at fluid point i: ε times the Wendland-weighted mean of
/// u_j − u_i over its fluid neighbours (no friction from the walls). Nothing for wall nodes,
/// isolated points and points without fluid neighbours.
template <int D>
std::optional<Vec<D>> smoothing_change(const Cloud<D>& c, Index i, double eps, double h) {
  if (!c.fluid(i) || c.type(i) == PointType::isolated) return std::nullopt;
  double weight = 0.0;
  Vec<D> sum = Vec<D>::Zero();
  for (Index j : c.neighbours.of(i)) {
    if (!c.fluid(j)) continue;  // no friction from the walls
    const double w = wendland_c2((c.x(j) - c.x(i)).norm() / h);
    weight += w;
    sum += w * (c.points.velocity[j] - c.points.velocity[i]);
  }
  if (!(weight > 0.0)) return std::nullopt;
  return ((eps / weight) * sum).eval();
}

}  // namespace hm::ldd::kernels
