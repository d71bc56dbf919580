#pragma once
// Measurements taken from the LDD point set at output times: pressure probes, free-surface
// elevation gauges, the surge front, and the pressure loads on a wall mesh (consistent nodal
// forces, spec §3.1, reused by the structure coupling). All functions only read the point set;
// they are brute force over the points (a few probes per output time) or use a cell grid (loads).
// Gravity is along the last axis (y in 2-D, z in 3-D); "height" is that coordinate, in scene
// coordinates. SI units: m, Pa (gauge), N (3-D) or N/m per unit width (2-D).
#include <functional>
#include <span>
#include <vector>

#include "ldd/walls.hpp"

namespace hm::ldd {

/// Pressure [Pa] at x: the Wendland-weighted average W(|r_j − x|/radius) of p over the fluid
/// points (every type but isolated) and the active wall nodes (type wall or surface) within
/// `radius` [m] of x, leaving out points j for which the segment x → r_j crosses any of `walls`
/// (a probe does not see through a wall) and wall nodes whose normal points away from x (the
/// nodes of the far side of a thin wall; place a probe on a thin wall a little off it, on the
/// side it measures). It is a smoothed value: where the sphere is one-sided
/// (at a floor) it is biased by ∇p times the offset of the weighted centroid, O(radius·ρg).
/// Wet/dry: the probe is dry — returns 0 and *wet = false — when the weight sum is below 0.1 of
/// that of a full lattice of spacing dx [m] within radius (lattice_number_density). A probe on a
/// wall sees half a sphere of fluid (and the wall nodes): about 0.5 of it, wet.
template <int D>
double probe_pressure(const PointSet<D>& points, std::span<const WallMesh<D>> walls,
                      const Vec<D>& x, double radius, double dx, bool* wet = nullptr);

/// Free-surface elevation [m] at the horizontal position of x (2-D: x; 3-D: x and y), absolute
/// height in scene coordinates. The fluid points (not isolated) within horizontal distance ≤ dx
/// of the vertical gauge line are sorted by height; the column is followed up from its lowest
/// point while the vertical gap to the next point is ≤ 2 dx, so spray and a plunging jet above an
/// air gap are not counted. Returns the column top + dx/2: a point stands for a cell of height
/// dx, so a lattice of layers at (k + ½)dx filled to depth H gives exactly H. With no fluid on
/// the gauge line the gauge is dry: returns 0 and *wet = false.
template <int D>
double probe_elevation(const PointSet<D>& points, const Vec<D>& x, double dx, bool* wet = nullptr);

/// Surge front [m]: max of direction·r over the fluid points (not isolated) whose height is in
/// [band_low, band_high], plus dx/2 (the half cell a point stands for). `direction` is
/// normalised here (it must not be zero). With no point in the band: returns 0, *found = false.
template <int D>
double probe_front(const PointSet<D>& points, const Vec<D>& direction, double band_low,
                   double band_high, double dx, bool* found = nullptr);

/// Pressure loads on one wall mesh, in the mesh's vertex and element order.
template <int D>
struct WallLoads {
  /// Consistent nodal forces, one per vertex [N in 3-D; N/m per unit width in 2-D].
  std::vector<Vec<D>> vertex_force;
  /// Force on each element (the sum of its share of the nodal forces) [N or N/m].
  std::vector<Vec<D>> element_force;
  Vec<D> total = Vec<D>::Zero();  ///< Σ vertex_force [N or N/m]
  /// Wall area [m²] (2-D: length [m]) whose quadrature cells found a wall node: both sides of a
  /// thin wall count.
  double wetted = 0.0;
};

/// Which quadrature points of a wall's loads count (by position [m]); called from several threads.
template <int D>
using QuadraturePoints = std::function<bool(const Vec<D>&)>;

/// Pressure loads of the fluid on `wall` (body index `body` of the wall nodes in `points`), spec
/// §3.1 with the sampled wall nodes (CHOICE-B). Each element is cut into quadrature cells of size
/// ≤ dx/2 (a segment into k equal pieces, a triangle into its regular k-subdivision, one point
/// at each piece's centre); the pressure at a quadrature point is the Shepard average
/// (weights W(r/dx)) of the active wall nodes of this body within dx [m] whose normal is within
/// 60° of the side's normal [CHOICE: a box corner's other face and the back of a thin plate are
/// other surfaces], 0 when there is none (dry). The traction −p n (n into the fluid: the fluid
/// pushes the wall away from itself) is spread to the element's vertices with the linear shape
/// functions (the quadrature point's barycentrics), so Σ vertex_force = total exactly. A thin
/// wall is loaded on both sides: nodes with normal along +n give −p⁺n, along −n give +p⁻n.
/// `pressure`: one value per point instead of points.pressure (empty: points.pressure), e.g. the
/// added-mass response FlowSolver::acceleration_pressure. `counted`: the quadrature points to
/// load from (empty: all) — a process of a distributed flow those of its own region, whose
/// nodes within dx it holds (owned or ghosts); the processes' loads then add up to the whole.
template <int D>
WallLoads<D> wall_pressure_loads(const PointSet<D>& points, const WallMesh<D>& wall, int body,
                                 double dx, std::span<const double> pressure = {},
                                 const QuadraturePoints<D>& counted = {});

/// Viscous (no-slip shear) loads of the fluid on `wall`, on the quadrature of
/// wall_pressure_loads. At a quadrature point x_q with wall velocity U_q and normal n (into the
/// fluid; both sides of a thin wall) the traction is the wall shear
///   τ_w = μ ∂u_t/∂n ≈ μ·Σ_j W_j (u_j − U_q)_t / d_j / Σ_j W_j,
/// over the connected fluid points j in front of it (normal distance d_j = n·(x_j − x_q) in
/// [dx/4, 2dx], lateral distance below dx, weights W(r/2dx)): the one-sided first-order
/// gradient, exact for a linear profile, first order for a curved one. (·)_t removes the normal
/// part; the normal viscous stress 2μ ∂u_n/∂n vanishes at a no-slip wall (∂u_n/∂n = −∇_t·u_t =
/// 0) and is left out. `dynamic_viscosity` μ = ρν [Pa·s]. Dry quadrature points carry none.
/// `counted` as for wall_pressure_loads (the points within 2.3 dx of a quadrature point).
template <int D>
WallLoads<D> wall_viscous_loads(const PointSet<D>& points, const WallMesh<D>& wall, double dx,
                                double dynamic_viscosity, const QuadraturePoints<D>& counted = {});

}  // namespace hm::ldd
