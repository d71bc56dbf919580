#pragma once
// Free-surface detection (spec §1.8 with the §0.2 recipe), run after compute_operators:
//  1. candidates: n_i/n_0 < β_n, or ô_i > τ_o, or λ_min(M_i) < λ_c, where n_i, o_i and ô_i are
//     summed over FLUID neighbours only [CHOICE]: wall nodes are the wall, and the dry nodes
//     above a free surface would turn o_i of the surface points near a side wall downwards
//     (first 3-D hydrostatic run: 30 % of the top layer missed). Next to a wall every point is
//     a candidate; the cone test rejects it;
//  2. geometric confirmation: outward normal ν_i = −o_i/|o_i|, then its components into the
//     walls of the neighbouring wall nodes are removed [CHOICE] (a deficit towards a wall is the
//     wall; this also settles tank corners, §0.2 item 9, and the top corners of a column, where
//     ν points 55° off the vertical into the corner edge). If less than 0.3 of ν is left the
//     point is covered by walls; otherwise it is SURFACE when no neighbour covers the 45° cone
//     around the remaining direction. A fluid neighbour covers when it lies inside the
//     cone. A wall node j covers only when ν_i points into its wall (ν_i·n_j < −cos 45°) and the
//     ray from r_i along ν_i meets that wall's plane within h (this also keeps tank corners
//     covered, §0.2 item 9);
//  3. hysteresis: a point SURFACE before keeps the candidate test with thresholds tightened by
//     20 % (β' = 1 − 0.8(1 − β_n), τ' = 0.8 τ_o), so it leaves the surface only when clearly
//     inside; the cone test is applied as usual [CHOICE];
//  4. wall nodes at the contact line (D5): the outward normal projected on the wall tangent; if
//     its length is ≥ 0.3 and no neighbour covers the cone around it, the node is Dirichlet.
//     The cone is 85°, not 45° [CHOICE]: a node half a spacing below the surface of a lattice has
//     its nearest fluid neighbour at exactly 45°, so a 45° cone made it Dirichlet or not by
//     round-off (2.8 % hydrostatic error in 3-D); with 85° a node is Dirichlet only when no fluid
//     lies beyond it along the tangent (above the surface, ahead of a surge front). When
//     deactivate_wall_nodes_beyond_fluid ran first (the default of the tests), those nodes are
//     already inactive and item 4 finds none.
// Fluid points with fewer than N_min neighbours become ISOLATED.
#include <vector>

#include "ldd/operators.hpp"

namespace hm::ldd {

struct FreeSurfaceOptions {
  double reference_density = 0.0;  ///< n_0 = Σ W of a full lattice stencil (> 0, required)
  double beta_n = 0.90;
  double tau_o = 0.20;
  double lambda_c = 0.05;
  double cone_degrees = 45.0;       ///< half-angle of the cone of fluid points
  double wall_cone_degrees = 85.0;  ///< half-angle of the cone of wall nodes (item 4)
  double hysteresis = 0.8;
  double min_wall_tangent = 0.3;  ///< |tangential part of ν| below this: wall node covered
  /// Fluid neighbours cover a cone only within this distance, × h (0.8 h = 2 dx at h = 2.5 dx).
  double cover_reach = 0.8;
};

struct FreeSurfaceReport {
  Index candidates = 0;    ///< fluid points passing stage 1
  Index surface = 0;       ///< fluid points marked SURFACE
  Index contact_line = 0;  ///< wall nodes marked SURFACE
  Index isolated = 0;
  /// Each decided point's fluid-only number density Σ W(|r_ij|/h) over its fluid neighbours
  /// (0 at inactive nodes): the sparse-point test reads it instead of summing it again.
  std::vector<double> fluid_density;
};

/// n_0: Σ W(|r|/h) over the points of a square/cubic lattice of spacing dx within h of a point.
template <int D>
double lattice_number_density(double dx, double h);

/// Wall nodes beyond the fluid become PointType::inactive and their pairs are removed [CHOICE]:
/// the nodes item 4 would make Dirichlet (no fluid beyond them along the wall — above a free
/// surface, ahead of a surge front). Run it after deactivate_dry_wall_nodes and before
/// compute_operators. Dirichlet p = 0 at such a node sits up to a spacing above the top fluid
/// layer, where the hydrostatic field is −ρg dx/2, not 0: that was an O(dx/H) error at the
/// surface (3-D, 10 layers: 0.67 % of ρgH). Without them the contact line is carried by the
/// fluid surface points next to the wall. Returns the number of nodes deactivated. Only the
/// points [0, owned) are decided (all with owned < 0), and their pairs removed or left to the
/// caller, as in deactivate_dry_wall_nodes.
template <int D>
Index deactivate_wall_nodes_beyond_fluid(PointSet<D>& points, Neighbours& neighbours,
                                         const FreeSurfaceOptions& options, Index owned = -1,
                                         InactivePairs pairs = InactivePairs::removed);

/// Sets points.type of every fluid point (interior / surface / isolated) and of active wall
/// nodes (wall / surface), using the previous types for the hysteresis. Only the points
/// [0, owned) are decided (all with owned < 0): a ghost's neighbourhood ends at the halo's
/// edge, where it would pass for free surface, and its owner decides for it.
template <int D>
FreeSurfaceReport detect_free_surface(PointSet<D>& points, const Neighbours& neighbours,
                                      const Operators<D>& ops, const FreeSurfaceOptions& options,
                                      Index owned = -1);

}  // namespace hm::ldd
