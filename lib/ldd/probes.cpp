#include "ldd/probes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>

#include <Eigen/Geometry>

#include "core/errors.hpp"
#include "ldd/free_surface.hpp"

namespace hm::ldd {
namespace {

/// A fluid point that carries the flow: every type but isolated (a lone droplet is ballistic).
template <int D>
bool is_connected_fluid(const PointSet<D>& points, Index i) {
  return points.kind[i] == PointKind::fluid && points.type[i] != PointType::isolated;
}

/// A wall node with a pressure: type wall (Neumann) or surface (contact line), not inactive.
template <int D>
bool is_active_wall_node(const PointSet<D>& points, Index i) {
  return points.kind[i] == PointKind::wall &&
         (points.type[i] == PointType::wall || points.type[i] == PointType::surface);
}

/// Wall node j stands for the fluid on its side only: x behind it (the other side of a thin
/// wall) does not see it. A probe exactly on the wall does.
template <int D>
bool facing_away(const PointSet<D>& points, Index j, const Vec<D>& x, double radius) {
  return points.wall_normal[j].dot(x - points.position[j]) < -1e-9 * radius;
}

template <int D>
bool blocked_by_a_wall(std::span<const WallMesh<D>> walls, const Vec<D>& a, const Vec<D>& b) {
  for (const auto& w : walls)
    if (w.crosses(a, b)) return true;
  return false;
}

/// Distance [m] from r to the vertical line through x (the last axis is vertical).
template <int D>
double horizontal_distance(const Vec<D>& r, const Vec<D>& x) {
  return (r - x).template head<D - 1>().norm();
}

// ---- wall node lookup
// ----------------------------------------------------------------------------

/// The active wall nodes of one body in cells of size `cell`, sorted by cell (lexicographic, the
/// first axis slowest) and by index within a cell: a query visits the 3^D cells around a point in
/// a fixed order, so sums over the nodes it finds do not depend on how a cell is looked up. Cells
/// are found in O(1) from a dense table over the nodes' bounding box of cells where that table
/// is at most kDenseCellsPerEntry times the entries (wall nodes on the faces of a tank), else by
/// binary search on cell keys.
template <int D>
class WallNodeGrid {
 public:
  using Cell = std::array<std::int64_t, D>;

  WallNodeGrid(const PointSet<D>& points, int body, double cell)
      : WallNodeGrid(points, cell, [&](Index i) {
          return is_active_wall_node(points, i) && points.host[i].body == body;
        }) {}

  /// The points i with keep(i) (e.g. the connected fluid points for the wall shear).
  template <typename Keep>
  WallNodeGrid(const PointSet<D>& points, double cell, Keep&& keep) : cell_(cell) {
    std::vector<std::pair<Cell, Index>> entries;
    for (Index i = 0; i < points.size(); ++i)
      if (keep(i)) entries.emplace_back(cell_of(points.position[i]), i);
    std::sort(entries.begin(), entries.end());
    index_cells(entries);
  }

  /// Calls visit(j) for every node j whose cell is within one cell of x's.
  template <typename Visit>
  void for_each_near(const Vec<D>& x, Visit&& visit) const {
    any_cell_around<D>(cell_of(x), [&](const Cell& c) {
      const auto [first, last] = nodes_in(c);
      for (auto s = first; s < last; ++s) visit(node_[s]);
      return false;
    });
  }

  /// Whether a node lies in a cell that meets the box [lo, hi] grown by one cell on each side
  /// (every node within `cell` of the box does).
  bool any_near_box(const Vec<D>& lo, const Vec<D>& hi) const {
    if (node_.empty()) return false;
    Cell from = cell_of(lo), to = cell_of(hi), c;
    for (int a = 0; a < D; ++a) {
      from[a] = std::max(from[a] - 1, low_[a]);
      to[a] = std::min(to[a] + 1, low_[a] + dims_[a] - 1);
      if (from[a] > to[a]) return false;
    }
    c = from;
    while (true) {
      const auto [first, last] = nodes_in(c);
      if (first < last) return true;
      int a = D - 1;
      while (a >= 0 && ++c[a] > to[a]) {
        c[a] = from[a];
        --a;
      }
      if (a < 0) return false;
    }
  }

 private:
  static constexpr std::int64_t kDenseCellsPerEntry = 64;

  Cell cell_of(const Vec<D>& x) const {
    Cell c;
    for (int a = 0; a < D; ++a) c[a] = static_cast<std::int64_t>(std::floor(x[a] / cell_));
    return c;
  }

  /// Row-major number of a cell of the bounding box (the last axis fastest: the sort order).
  std::int64_t key(const Cell& c) const {
    std::int64_t k = 0;
    for (int a = 0; a < D; ++a) k = k * dims_[a] + (c[a] - low_[a]);
    return k;
  }

  bool in_box(const Cell& c) const {
    for (int a = 0; a < D; ++a)
      if (c[a] < low_[a] || c[a] >= low_[a] + dims_[a]) return false;
    return true;
  }

  void index_cells(const std::vector<std::pair<Cell, Index>>& entries) {
    node_.reserve(entries.size());
    for (const auto& e : entries) node_.push_back(e.second);
    if (entries.empty()) return;
    low_ = entries.front().first;
    Cell high = low_;
    for (const auto& e : entries)
      for (int a = 0; a < D; ++a) {
        low_[a] = std::min(low_[a], e.first[a]);
        high[a] = std::max(high[a], e.first[a]);
      }
    double cells = 1.0;
    for (int a = 0; a < D; ++a) {
      dims_[a] = high[a] - low_[a] + 1;
      cells *= static_cast<double>(dims_[a]);
    }
    if (cells > 4e18)
      numerical_error(
          "wall loads: the points span {} cells of {} m; points have left the "
          "domain (a run diverged?)",
          cells, cell_);
    key_.reserve(entries.size());
    for (const auto& e : entries) key_.push_back(key(e.first));
    const double dense_limit = static_cast<double>(kDenseCellsPerEntry) *
                               static_cast<double>(std::max<std::size_t>(entries.size(), 1024));
    if (cells > dense_limit) return;
    // start_[k] .. start_[k + 1]: the nodes of cell k.
    start_.assign(static_cast<std::size_t>(cells) + 1, 0);
    for (std::int64_t k : key_) ++start_[static_cast<std::size_t>(k) + 1];
    std::partial_sum(start_.begin(), start_.end(), start_.begin());
  }

  /// The range [first, last) of node_ in cell c.
  std::pair<std::size_t, std::size_t> nodes_in(const Cell& c) const {
    if (node_.empty() || !in_box(c)) return {0, 0};
    const std::int64_t k = key(c);
    if (!start_.empty())
      return {start_[static_cast<std::size_t>(k)], start_[static_cast<std::size_t>(k) + 1]};
    const auto range = std::equal_range(key_.begin(), key_.end(), k);
    return {static_cast<std::size_t>(range.first - key_.begin()),
            static_cast<std::size_t>(range.second - key_.begin())};
  }

  double cell_;
  Cell low_{}, dims_{};
  std::vector<Index> node_;         // sorted by cell, then index
  std::vector<std::int64_t> key_;   // cell key of each node_
  std::vector<std::size_t> start_;  // dense table (may be empty)
};

/// Shepard pressure at x from the nodes of `grid` within dx whose normal is within 60° of
/// `side`; `weight` receives Σ W (0: dry).
template <int D>
double shepard_wall_pressure(const PointSet<D>& points, std::span<const double> pressure,
                             const WallNodeGrid<D>& grid, const Vec<D>& x, const Vec<D>& side,
                             double dx, double& weight) {
  constexpr double min_alignment = 0.5;  // cos 60°
  double sum_w = 0.0, sum_wp = 0.0;
  grid.for_each_near(x, [&](Index j) {
    if (points.wall_normal[j].dot(side) < min_alignment) return;
    const double r = (points.position[j] - x).norm();
    if (r >= dx) return;
    const double w = wendland_c2(r / dx);
    sum_w += w;
    sum_wp += w * pressure[j];
  });
  weight = sum_w;
  return sum_w > 0.0 ? sum_wp / sum_w : 0.0;
}

// ---- quadrature on an element -------------------------------------------------------------------

template <int D>
struct QuadraturePoint {
  Vec<D> barycentric;
  double measure;  ///< length (2-D) or area (3-D) of the cell [m or m²]
};

/// Midpoints of k equal pieces of a segment, k = ⌈length / (dx/2)⌉.
std::vector<QuadraturePoint<2>> element_quadrature(const std::array<Vec<2>, 2>& x, double dx) {
  const double length = (x[1] - x[0]).norm();
  const int k = std::max(1, static_cast<int>(std::ceil(length / (0.5 * dx) - 1e-9)));
  std::vector<QuadraturePoint<2>> q;
  q.reserve(k);
  for (int s = 0; s < k; ++s) {
    const double t = (s + 0.5) / k;
    q.push_back({Vec<2>(1.0 - t, t), length / k});
  }
  return q;
}

/// Centroids of the k² triangles of the regular k-subdivision of a triangle, k = ⌈longest
/// edge / (dx/2)⌉; every sub-triangle has area A/k².
std::vector<QuadraturePoint<3>> element_quadrature(const std::array<Vec<3>, 3>& x, double dx) {
  const double area = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]).norm();
  const double edge = std::max({(x[1] - x[0]).norm(), (x[2] - x[1]).norm(), (x[0] - x[2]).norm()});
  const int k = std::max(1, static_cast<int>(std::ceil(edge / (0.5 * dx) - 1e-9)));
  const double piece = area / (double(k) * k);
  std::vector<QuadraturePoint<3>> q;
  q.reserve(static_cast<std::size_t>(k) * k);
  auto add = [&](double b1, double b2) { q.push_back({Vec<3>(1.0 - b1 - b2, b1, b2), piece}); };
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j) {
      add((3.0 * i + 1.0) / (3.0 * k), (3.0 * j + 1.0) / (3.0 * k));  // pointing up
      if (i + j <= k - 2) add((3.0 * i + 2.0) / (3.0 * k), (3.0 * j + 2.0) / (3.0 * k));  // down
    }
  return q;
}

/// One element's share of the loads: force on each of its vertices, and its wetted measure.
template <int D>
struct ElementLoad {
  ElementLoad() { vertex_force.fill(Vec<D>::Zero()); }
  std::array<Vec<D>, D> vertex_force;
  double wetted = 0.0;
};

/// One element's share of a load whose traction at a quadrature point x (barycentrics b) on the
/// side with normal `side` is traction(b, x, side, weight); weight > 0 marks the point wet. Only
/// the quadrature points `counted` (empty: all).
template <int D, typename Traction>
ElementLoad<D> element_load(const WallMesh<D>& wall, Index e, double dx,
                            const QuadraturePoints<D>& counted, Traction&& traction) {
  const auto& cell = wall.element(e);
  std::array<Vec<D>, D> x;
  for (int k = 0; k < D; ++k) x[k] = wall.vertices()[cell[k]];
  const Vec<D> n = wall.normal_at(e, Vec<D>::Constant(1.0 / D));
  ElementLoad<D> load;
  load.vertex_force.fill(Vec<D>::Zero());
  const int sides = wall.thin() ? 2 : 1;
  for (const auto& q : element_quadrature(x, dx)) {
    Vec<D> xq = Vec<D>::Zero();
    for (int k = 0; k < D; ++k) xq += q.barycentric[k] * x[k];
    if (counted && !counted(xq)) continue;
    Vec<D> t = Vec<D>::Zero();
    for (int s = 0; s < sides; ++s) {
      double weight = 0.0;
      t += traction(q.barycentric, xq, s == 0 ? n : Vec<D>(-n), weight);
      if (weight > 0.0) load.wetted += q.measure;
    }
    for (int k = 0; k < D; ++k) load.vertex_force[k] += (q.measure * q.barycentric[k]) * t;
  }
  return load;
}

/// Whether any node of `grid` (cells of size ≥ the Shepard radius) may reach element e: else
/// every quadrature point of it is dry and its load is zero.
template <int D>
bool element_near_nodes(const WallMesh<D>& wall, Index e, const WallNodeGrid<D>& grid) {
  const auto& cell = wall.element(e);
  Vec<D> lo = wall.vertices()[cell[0]], hi = lo;
  for (int k = 1; k < D; ++k) {
    lo = lo.cwiseMin(wall.vertices()[cell[k]]);
    hi = hi.cwiseMax(wall.vertices()[cell[k]]);
  }
  return grid.any_near_box(lo, hi);
}

/// Wall shear traction at x (wall velocity U, side normal n) from the fluid points of `fluid`
/// (a grid of cell 2.5 dx) in front of it (wall_viscous_loads); `weight` receives Σ W (0: dry).
template <int D>
Vec<D> shepard_wall_shear(const PointSet<D>& points, const WallNodeGrid<D>& fluid, const Vec<D>& x,
                          const Vec<D>& U, const Vec<D>& n, double dx, double mu, double& weight) {
  double sum_w = 0.0;
  Vec<D> sum = Vec<D>::Zero();
  fluid.for_each_near(x, [&](Index j) {
    const Vec<D> r = points.position[j] - x;
    const double d = r.dot(n);
    if (d < 0.25 * dx || d > 2.0 * dx || (r - d * n).norm() >= dx) return;
    const double w = wendland_c2(r.norm() / (2.0 * dx));
    Vec<D> du = points.velocity[j] - U;
    du -= du.dot(n) * n;
    sum_w += w;
    sum += (w / d) * du;
  });
  weight = sum_w;
  return sum_w > 0.0 ? Vec<D>(mu * sum / sum_w) : Vec<D>::Zero();
}

/// Sums per-element loads in element order (deterministic: Σ vertex_force == total bit for bit).
template <int D>
WallLoads<D> assemble_loads(const WallMesh<D>& wall,
                            const std::vector<ElementLoad<D>>& per_element) {
  const Index elements = wall.element_count();
  WallLoads<D> loads;
  loads.vertex_force.assign(wall.vertices().size(), Vec<D>::Zero());
  loads.element_force.assign(static_cast<std::size_t>(elements), Vec<D>::Zero());
  for (Index e = 0; e < elements; ++e) {
    for (int k = 0; k < D; ++k) {
      loads.vertex_force[wall.element(e)[k]] += per_element[e].vertex_force[k];
      loads.element_force[e] += per_element[e].vertex_force[k];
    }
    loads.wetted += per_element[e].wetted;
  }
  for (const auto& f : loads.vertex_force) loads.total += f;
  return loads;
}

}  // namespace

// ---- probes -------------------------------------------------------------------------------------

template <int D>
double probe_pressure(const PointSet<D>& points, std::span<const WallMesh<D>> walls,
                      const Vec<D>& x, double radius, double dx, bool* wet) {
  HM_ASSERT(radius > 0.0 && dx > 0.0, "probe_pressure: radius {} and dx {} must be > 0", radius,
            dx);
  const Index n = points.size();
  double sum_w = 0.0, sum_wp = 0.0;
#pragma omp parallel for reduction(+ : sum_w, sum_wp) schedule(static)
  for (Index j = 0; j < n; ++j) {
    if (!is_connected_fluid(points, j) && !is_active_wall_node(points, j)) continue;
    const double r = (points.position[j] - x).norm();
    if (r >= radius) continue;
    if (points.kind[j] == PointKind::wall && facing_away(points, j, x, radius)) continue;
    if (blocked_by_a_wall<D>(walls, x, points.position[j])) continue;
    const double w = wendland_c2(r / radius);
    sum_w += w;
    sum_wp += w * points.pressure[j];
  }
  constexpr double wet_fraction = 0.1;
  const bool is_wet = sum_w > 0.0 && sum_w >= wet_fraction * lattice_number_density<D>(dx, radius);
  if (wet) *wet = is_wet;
  return is_wet ? sum_wp / sum_w : 0.0;
}

template <int D>
double probe_elevation(const PointSet<D>& points, const Vec<D>& x, double dx, bool* wet) {
  HM_ASSERT(dx > 0.0, "probe_elevation: dx {} must be > 0", dx);
  std::vector<double> heights;
  for (Index i = 0; i < points.size(); ++i)
    if (is_connected_fluid(points, i) && horizontal_distance<D>(points.position[i], x) <= dx)
      heights.push_back(points.position[i][D - 1]);
  if (wet) *wet = !heights.empty();
  if (heights.empty()) return 0.0;
  std::sort(heights.begin(), heights.end());
  constexpr double max_gap = 2.0;  // [dx]: a larger vertical gap is air under spray or a jet
  std::size_t top = 0;
  while (top + 1 < heights.size() && heights[top + 1] - heights[top] <= max_gap * dx) ++top;
  return heights[top] + 0.5 * dx;
}

template <int D>
double probe_front(const PointSet<D>& points, const Vec<D>& direction, double band_low,
                   double band_high, double dx, bool* found) {
  const double length = direction.norm();
  HM_ASSERT(length > 0.0, "probe_front: the direction must not be zero");
  const Vec<D> d = direction / length;
  const Index n = points.size();
  double front = -std::numeric_limits<double>::infinity();
#pragma omp parallel for reduction(max : front) schedule(static)
  for (Index i = 0; i < n; ++i) {
    if (!is_connected_fluid(points, i)) continue;
    const double z = points.position[i][D - 1];
    if (z < band_low || z > band_high) continue;
    front = std::max(front, d.dot(points.position[i]));
  }
  const bool any = std::isfinite(front);
  if (found) *found = any;
  return any ? front + 0.5 * dx : 0.0;
}

template <int D>
WallLoads<D> wall_pressure_loads(const PointSet<D>& points, const WallMesh<D>& wall, int body,
                                 double dx, std::span<const double> pressure,
                                 const QuadraturePoints<D>& counted) {
  HM_ASSERT(dx > 0.0, "wall_pressure_loads: dx {} must be > 0", dx);
  if (pressure.empty()) pressure = points.pressure;
  HM_ASSERT(pressure.size() == points.pressure.size(),
            "wall_pressure_loads: {} pressures for {} points", pressure.size(),
            points.pressure.size());
  const WallNodeGrid<D> grid(points, body, dx);
  const Index elements = wall.element_count();
  std::vector<ElementLoad<D>> per_element(static_cast<std::size_t>(elements));
#pragma omp parallel for schedule(dynamic, 16)
  for (Index e = 0; e < elements; ++e) {
    if (!element_near_nodes(wall, e, grid)) {  // dry (the ceiling of a tank): no load
      per_element[e] = ElementLoad<D>{};
      continue;
    }
    per_element[e] = element_load(
        wall, e, dx, counted,
        [&](const Vec<D>&, const Vec<D>& x, const Vec<D>& side, double& weight) {
          // The fluid pushes the wall away from itself: −p n, n into the fluid.
          return Vec<D>(-shepard_wall_pressure(points, pressure, grid, x, side, dx, weight) * side);
        });
  }
  return assemble_loads(wall, per_element);
}

template <int D>
WallLoads<D> wall_viscous_loads(const PointSet<D>& points, const WallMesh<D>& wall, double dx,
                                double dynamic_viscosity, const QuadraturePoints<D>& counted) {
  HM_ASSERT(dx > 0.0 && dynamic_viscosity >= 0.0,
            "wall_viscous_loads: dx {} must be > 0 and mu {} >= 0", dx, dynamic_viscosity);
  // Cells of 2.5 dx hold every point within the 2 dx × dx box in front of a quadrature point.
  const WallNodeGrid<D> fluid(points, 2.5 * dx,
                              [&](Index i) { return is_connected_fluid(points, i); });
  const Index elements = wall.element_count();
  std::vector<ElementLoad<D>> per_element(static_cast<std::size_t>(elements));
#pragma omp parallel for schedule(dynamic, 16)
  for (Index e = 0; e < elements; ++e) {
    if (!element_near_nodes(wall, e, fluid)) {
      per_element[e] = ElementLoad<D>{};
      continue;
    }
    per_element[e] =
        element_load(wall, e, dx, counted,
                     [&](const Vec<D>& b, const Vec<D>& x, const Vec<D>& side, double& weight) {
                       return shepard_wall_shear(points, fluid, x, wall.velocity_at(e, b), side, dx,
                                                 dynamic_viscosity, weight);
                     });
  }
  return assemble_loads(wall, per_element);
}

template double probe_pressure<2>(const PointSet<2>&, std::span<const WallMesh<2>>, const Vec<2>&,
                                  double, double, bool*);
template double probe_pressure<3>(const PointSet<3>&, std::span<const WallMesh<3>>, const Vec<3>&,
                                  double, double, bool*);
template double probe_elevation<2>(const PointSet<2>&, const Vec<2>&, double, bool*);
template double probe_elevation<3>(const PointSet<3>&, const Vec<3>&, double, bool*);
template double probe_front<2>(const PointSet<2>&, const Vec<2>&, double, double, double, bool*);
template double probe_front<3>(const PointSet<3>&, const Vec<3>&, double, double, double, bool*);
template WallLoads<2> wall_viscous_loads<2>(const PointSet<2>&, const WallMesh<2>&, double, double,
                                            const QuadraturePoints<2>&);
template WallLoads<3> wall_viscous_loads<3>(const PointSet<3>&, const WallMesh<3>&, double, double,
                                            const QuadraturePoints<3>&);
template WallLoads<2> wall_pressure_loads<2>(const PointSet<2>&, const WallMesh<2>&, int, double,
                                             std::span<const double>, const QuadraturePoints<2>&);
template WallLoads<3> wall_pressure_loads<3>(const PointSet<3>&, const WallMesh<3>&, int, double,
                                             std::span<const double>, const QuadraturePoints<3>&);

}  // namespace hm::ldd
