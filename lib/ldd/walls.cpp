#include "ldd/walls.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>

#include <Eigen/Geometry>

#include "core/errors.hpp"

namespace hm::ldd {
namespace {

std::uint64_t edge_key(Index a, Index b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

template <int D>
double box_distance2(const Vec<D>& x, const Vec<D>& lo, const Vec<D>& hi) {
  return (lo - x).cwiseMax(x - hi).cwiseMax(0.0).squaredNorm();
}

/// Closest point on segment ab: barycentrics (1 − t, t), exact 0/1 at the ends.
Vec<2> closest_on_segment(const Vec<2>& x, const Vec<2>& a, const Vec<2>& b) {
  const Vec<2> ab = b - a;
  const double t = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return {1.0 - t, t};
}

/// Closest point on triangle abc (Ericson, Real-Time Collision Detection §5.1.5): barycentrics,
/// with exact zeros in the vertex and edge regions.
Vec<3> closest_on_triangle(const Vec<3>& p, const Vec<3>& a, const Vec<3>& b, const Vec<3>& c) {
  const Vec<3> ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vec<3> bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vec<3> cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

double cross2(const Vec<2>& a, const Vec<2>& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Segment pq passes from one side of the line ab to the other through the closed segment ab
/// (2-D; grazing an end of ab counts, so no pair slips under the foot of a baffle).
bool segments_cross(const Vec<2>& p, const Vec<2>& q, const Vec<2>& a, const Vec<2>& b) {
  const double d1 = cross2(b - a, p - a), d2 = cross2(b - a, q - a);
  const double d3 = cross2(q - p, a - p), d4 = cross2(q - p, b - p);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && d3 * d4 <= 0.0;
}

/// Segment pq crosses triangle abc strictly inside pq (Möller–Trumbore).
bool segment_crosses_triangle(const Vec<3>& p, const Vec<3>& q, const Vec<3>& a, const Vec<3>& b,
                              const Vec<3>& c) {
  const Vec<3> dir = q - p, e1 = b - a, e2 = c - a;
  const Vec<3> s1 = dir.cross(e2);
  const double det = e1.dot(s1);
  if (std::abs(det) < 1e-300) return false;
  const Vec<3> s = p - a;
  const double u = s.dot(s1) / det;
  if (u < 0 || u > 1) return false;
  const Vec<3> s2 = s.cross(e1);
  const double v = dir.dot(s2) / det;
  if (v < 0 || u + v > 1) return false;
  const double t = e2.dot(s2) / det;
  return t > 1e-9 && t < 1 - 1e-9;
}

}  // namespace

/// Bounding-volume hierarchy over the elements: nodes in pre-order (children after parents), so
/// a reverse sweep refits it.
template <int D>
struct WallMesh<D>::Tree {
  struct Node {
    Vec<D> lo = Vec<D>::Zero(), hi = Vec<D>::Zero();
    int left = -1, right = -1;  // children; leaf when left < 0
    int first = 0, count = 0;   // leaf: elements order[first, first + count)
  };
  std::vector<Node> nodes;
  std::vector<Index> order;

  void element_box(const WallMesh& w, Index e, Vec<D>& lo, Vec<D>& hi) const {
    lo = hi = w.x_[w.cells_[e][0]];
    for (int k = 1; k < D; ++k) {
      lo = lo.cwiseMin(w.x_[w.cells_[e][k]]);
      hi = hi.cwiseMax(w.x_[w.cells_[e][k]]);
    }
  }
  int build(const WallMesh& w, const std::vector<Vec<D>>& centre, int first, int count) {
    const int id = static_cast<int>(nodes.size());
    nodes.push_back({});
    nodes[id].first = first;
    nodes[id].count = count;
    if (count > 4) {
      Vec<D> lo = centre[order[first]], hi = lo;
      for (int k = first; k < first + count; ++k) {
        lo = lo.cwiseMin(centre[order[k]]);
        hi = hi.cwiseMax(centre[order[k]]);
      }
      int axis = 0;
      (hi - lo).maxCoeff(&axis);
      const int half = count / 2;
      std::nth_element(order.begin() + first, order.begin() + first + half,
                       order.begin() + first + count,
                       [&](Index a, Index b) { return centre[a][axis] < centre[b][axis]; });
      const int l = build(w, centre, first, half);
      const int r = build(w, centre, first + half, count - half);
      nodes[id].left = l;
      nodes[id].right = r;
    }
    return id;
  }
  void refit(const WallMesh& w) {
    for (auto n = nodes.rbegin(); n != nodes.rend(); ++n) {
      if (n->left < 0) {
        element_box(w, order[n->first], n->lo, n->hi);
        for (int k = n->first + 1; k < n->first + n->count; ++k) {
          Vec<D> lo, hi;
          element_box(w, order[k], lo, hi);
          n->lo = n->lo.cwiseMin(lo);
          n->hi = n->hi.cwiseMax(hi);
        }
      } else {
        n->lo = nodes[n->left].lo.cwiseMin(nodes[n->right].lo);
        n->hi = nodes[n->left].hi.cwiseMax(nodes[n->right].hi);
      }
    }
  }
  Tree(const WallMesh& w) {
    const Index n = w.element_count();
    order.resize(n);
    std::iota(order.begin(), order.end(), 0);
    std::vector<Vec<D>> centre(n);
    for (Index e = 0; e < n; ++e) {
      centre[e] = Vec<D>::Zero();
      for (int k = 0; k < D; ++k) centre[e] += w.x_[w.cells_[e][k]] / D;
    }
    if (n > 0) build(w, centre, 0, n);
    refit(w);
  }
};

template <int D>
WallMesh<D>::WallMesh(const mesh::SurfaceMesh& s, std::string name, bool thin)
    : name_(std::move(name)), thin_(thin) {
  if (s.dim != D || s.vertices.cols() != D || s.cells.cols() != D)
    input_error(
        "wall '{}': a {}-D surface mesh ({} columns of vertices, {} of cells) given to a "
        "{}-D flow; expected {} and {}",
        name_, s.dim, s.vertices.cols(), s.cells.cols(), D, D, D);
  if (s.cells.rows() == 0) input_error("wall '{}': the surface mesh has no elements", name_);
  x_.resize(static_cast<std::size_t>(s.vertices.rows()));
  for (Eigen::Index v = 0; v < s.vertices.rows(); ++v)
    x_[v] = s.vertices.row(v).transpose().template head<D>();
  v_.assign(x_.size(), Vec<D>::Zero());
  a_.assign(x_.size(), Vec<D>::Zero());
  cells_.resize(static_cast<std::size_t>(s.cells.rows()));
  for (Eigen::Index e = 0; e < s.cells.rows(); ++e)
    for (int k = 0; k < D; ++k) {
      const auto v = s.cells(e, k);
      if (v < 0 || v >= s.vertices.rows())
        input_error("wall '{}': element {} refers to vertex {}, but there are {} vertices", name_,
                    e, v, s.vertices.rows());
      cells_[e][k] = static_cast<Index>(v);
    }
  compute_normals();
  tree_ = std::make_unique<Tree>(*this);
}

template <int D>
WallMesh<D>::~WallMesh() = default;
template <int D>
WallMesh<D>::WallMesh(WallMesh&&) noexcept = default;
template <int D>
WallMesh<D>& WallMesh<D>::operator=(WallMesh&&) noexcept = default;

template <int D>
double WallMesh<D>::enclosed_measure() const {
  // Divergence theorem with the field x/D: Σ over elements of (x·n) |e| / D. A segment's normal is
  // its tangent turned left, a triangle's the right-hand cross product.
  double measure = 0.0;
  for (const auto& c : cells_) {
    if constexpr (D == 2) {
      measure += 0.5 * (x_[c[1]].x() * x_[c[0]].y() - x_[c[0]].x() * x_[c[1]].y());
    } else {
      measure += x_[c[0]].dot(x_[c[1]].cross(x_[c[2]])) / 6.0;
    }
  }
  return measure;
}

template <int D>
void WallMesh<D>::compute_normals() {
  const Index n = element_count();
  face_normal_.resize(n);
  vertex_normal_.assign(x_.size(), Vec<D>::Zero());
  std::map<std::uint64_t, Vec<D>> edges;
  for (Index e = 0; e < n; ++e) {
    const auto& c = cells_[e];
    if constexpr (D == 2) {
      const Vec<2> t = x_[c[1]] - x_[c[0]];
      face_normal_[e] = Vec<2>(-t.y(), t.x()).normalized();
      for (int k = 0; k < 2; ++k) vertex_normal_[c[k]] += face_normal_[e];
    } else {
      face_normal_[e] = (x_[c[1]] - x_[c[0]]).cross(x_[c[2]] - x_[c[0]]).normalized();
      for (int k = 0; k < 3; ++k) {
        const Vec<3> u = (x_[c[(k + 1) % 3]] - x_[c[k]]).normalized();
        const Vec<3> w = (x_[c[(k + 2) % 3]] - x_[c[k]]).normalized();
        const double angle = std::acos(std::clamp(u.dot(w), -1.0, 1.0));
        vertex_normal_[c[k]] += angle * face_normal_[e];
        const auto key = edge_key(c[k], c[(k + 1) % 3]);
        auto it = edges.try_emplace(key, Vec<D>::Zero()).first;
        it->second += face_normal_[e];
      }
    }
    if (!face_normal_[e].allFinite())
      input_error("wall '{}': element {} is degenerate (zero length or area)", name_, e);
  }
  for (auto& vn : vertex_normal_)
    if (vn.squaredNorm() > 0) vn.normalize();
  mark_open_features();
  edge_normal_.clear();
  for (auto& [k, en] : edges)
    edge_normal_.emplace_back(k, en.squaredNorm() > 0 ? en.normalized() : en);
}

/// How many elements use each boundary entity: vertices of segments (2-D), edges of triangles
/// (3-D, keyed by edge_key). A closed wall uses every one exactly twice.
template <int D>
std::map<std::uint64_t, int> boundary_uses(const std::vector<std::array<Index, D>>& cells) {
  std::map<std::uint64_t, int> uses;
  for (const auto& c : cells) {
    if constexpr (D == 2) {
      for (int k = 0; k < 2; ++k) ++uses[static_cast<std::uint64_t>(c[k])];
    } else {
      for (int k = 0; k < 3; ++k) ++uses[edge_key(c[k], c[(k + 1) % 3])];
    }
  }
  return uses;
}

template <int D>
void WallMesh<D>::mark_open_features() {
  // Open ends of the mesh: vertices used by one segment (2-D); edges used by one triangle and
  // their vertices (3-D).
  open_vertex_.assign(x_.size(), 0);
  open_edges_.clear();
  for (const auto& [key, uses] : boundary_uses<D>(cells_)) {
    if (uses != 1) continue;
    if constexpr (D == 2) {
      open_vertex_[static_cast<std::size_t>(key)] = 1;
    } else {
      open_edges_.push_back(key);
      open_vertex_[key >> 32] = open_vertex_[key & 0xffffffffu] = 1;
    }
  }
  std::sort(open_edges_.begin(), open_edges_.end());
}

template <int D>
bool WallMesh<D>::on_open_end(Index e, const Vec<D>& b) const {
  int zeros = 0, nonzero = -1;
  for (int k = 0; k < D; ++k) {
    if (b[k] == 0.0)
      ++zeros;
    else
      nonzero = k;
  }
  if (zeros == D - 1) return open_vertex_[cells_[e][nonzero]] != 0;
  if constexpr (D == 3) {
    if (zeros == 1) {
      int z = 0;
      while (b[z] != 0.0) ++z;
      const auto key = edge_key(cells_[e][(z + 1) % 3], cells_[e][(z + 2) % 3]);
      return std::binary_search(open_edges_.begin(), open_edges_.end(), key);
    }
  }
  return false;
}

template <int D>
Vec<D> WallMesh<D>::lower() const {
  return tree_->nodes.empty() ? Vec<D>::Zero() : tree_->nodes[0].lo;
}
template <int D>
Vec<D> WallMesh<D>::upper() const {
  return tree_->nodes.empty() ? Vec<D>::Zero() : tree_->nodes[0].hi;
}

template <int D>
void WallMesh<D>::move(std::span<const Vec<D>> x, std::span<const Vec<D>> v,
                       std::span<const Vec<D>> a) {
  HM_ASSERT(x.size() == x_.size(), "wall '{}': {} new positions for {} vertices", name_, x.size(),
            x_.size());
  x_.assign(x.begin(), x.end());
  if (v.empty())
    v_.assign(x_.size(), Vec<D>::Zero());
  else
    v_.assign(v.begin(), v.end());
  if (a.empty())
    a_.assign(x_.size(), Vec<D>::Zero());
  else
    a_.assign(a.begin(), a.end());
  compute_normals();
  tree_->refit(*this);
}

template <int D>
Vec<D> WallMesh<D>::point_at(Index e, const Vec<D>& b) const {
  Vec<D> p = Vec<D>::Zero();
  for (int k = 0; k < D; ++k) p += b[k] * x_[cells_[e][k]];
  return p;
}
template <int D>
Vec<D> WallMesh<D>::velocity_at(Index e, const Vec<D>& b) const {
  Vec<D> p = Vec<D>::Zero();
  for (int k = 0; k < D; ++k) p += b[k] * v_[cells_[e][k]];
  return p;
}
template <int D>
Vec<D> WallMesh<D>::acceleration_at(Index e, const Vec<D>& b) const {
  Vec<D> p = Vec<D>::Zero();
  for (int k = 0; k < D; ++k) p += b[k] * a_[cells_[e][k]];
  return p;
}

template <int D>
Vec<D> WallMesh<D>::normal_at(Index e, const Vec<D>& b) const {
  int zeros = 0, nonzero = -1;
  for (int k = 0; k < D; ++k) {
    if (b[k] == 0.0)
      ++zeros;
    else
      nonzero = k;
  }
  if (zeros == D - 1) return vertex_normal_[cells_[e][nonzero]];  // at a vertex
  if constexpr (D == 3) {
    if (zeros == 1) {  // on an edge: the vertices with non-zero weight
      int z = 0;
      while (b[z] != 0.0) ++z;
      const auto key = edge_key(cells_[e][(z + 1) % 3], cells_[e][(z + 2) % 3]);
      const auto it = std::lower_bound(edge_normal_.begin(), edge_normal_.end(), key,
                                       [](const auto& p, std::uint64_t k) { return p.first < k; });
      if (it != edge_normal_.end() && it->first == key) return it->second;
    }
  }
  return face_normal_[e];
}

template <int D>
ClosestPoint<D> WallMesh<D>::closest(const Vec<D>& x) const {
  ClosestPoint<D> best;
  double best2 = std::numeric_limits<double>::infinity();
  std::array<int, 64> stack{};
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const auto& node = tree_->nodes[stack[--top]];
    if (box_distance2<D>(x, node.lo, node.hi) >= best2) continue;
    if (node.left < 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        const Index e = tree_->order[k];
        const auto& c = cells_[e];
        Vec<D> b;
        if constexpr (D == 2)
          b = closest_on_segment(x, x_[c[0]], x_[c[1]]);
        else
          b = closest_on_triangle(x, x_[c[0]], x_[c[1]], x_[c[2]]);
        const Vec<D> p = point_at(e, b);
        const double d2 = (x - p).squaredNorm();
        if (d2 < best2) {
          best2 = d2;
          best.point = p;
          best.element = e;
          best.barycentric = b;
        }
      }
      continue;
    }
    const auto& l = tree_->nodes[node.left];
    const auto& r = tree_->nodes[node.right];
    const bool left_first = box_distance2<D>(x, l.lo, l.hi) < box_distance2<D>(x, r.lo, r.hi);
    stack[top++] = left_first ? node.right : node.left;  // the nearer child is popped first
    stack[top++] = left_first ? node.left : node.right;
  }
  best.normal = normal_at(best.element, best.barycentric);
  const double d = std::sqrt(best2);
  if (d > 0.0 && on_open_end(best.element, best.barycentric)) {
    // Beyond the open end of a wall (the top of a tank side, the tip of a baffle) there is no
    // inside: the distance is unsigned and the normal points at x. With the pseudo-normal, a
    // point going round the top of a tank wall was "inside" and teleported back across it
    // (the K&O run-up jet at L/40 blew up there).
    best.normal = (x - best.point) / d;
    best.signed_distance = d;
    return best;
  }
  best.signed_distance = (x - best.point).dot(best.normal) < 0.0 ? -d : d;
  return best;
}

template <int D>
bool WallMesh<D>::crosses(const Vec<D>& a, const Vec<D>& b) const {
  const Vec<D> lo = a.cwiseMin(b), hi = a.cwiseMax(b);
  std::array<int, 64> stack{};
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const auto& node = tree_->nodes[stack[--top]];
    if ((node.lo.array() > hi.array()).any() || (node.hi.array() < lo.array()).any()) continue;
    if (node.left >= 0) {
      stack[top++] = node.left;
      stack[top++] = node.right;
      continue;
    }
    for (int k = node.first; k < node.first + node.count; ++k) {
      const auto& c = cells_[tree_->order[k]];
      if constexpr (D == 2) {
        if (segments_cross(a, b, x_[c[0]], x_[c[1]])) return true;
      } else {
        if (segment_crosses_triangle(a, b, x_[c[0]], x_[c[1]], x_[c[2]])) return true;
      }
    }
  }
  return false;
}

template <int D>
Index WallMesh<D>::open_boundary_count() const {
  const auto uses = boundary_uses<D>(cells_);
  Index open = 0;
  for (const auto& [k, n] : uses) open += n != 2 ? 1 : 0;
  return open;
}

template <int D>
void WallMesh<D>::require_closed(std::string_view purpose) const {
  const auto uses = boundary_uses<D>(cells_);
  Index open = 0;
  Vec<D> where = Vec<D>::Zero();
  for (const auto& [k, n] : uses) {
    if (n == 2) continue;
    if (open++ == 0) where = D == 2 ? x_[k] : Vec<D>(0.5 * (x_[k >> 32] + x_[k & 0xffffffffu]));
  }
  if (open > 0)
    input_error(
        "wall '{}' must be a closed {} for {}, but it has {} open {} (the first at ({:g})); "
        "close the surface or give the fluid as a box",
        name_, D == 2 ? "curve" : "surface", purpose, open,
        D == 2 ? "ends (vertices not shared by two segments)"
               : "edges (not shared by two triangles)",
        fmt::join(where.data(), where.data() + D, ", "));
}

// ---- wall nodes ------------------------------------------------------------------------------

namespace {

template <int D>
double median_edge_length(const WallMesh<D>& wall) {
  std::vector<double> length;
  length.reserve(static_cast<std::size_t>(wall.element_count()) * D);
  for (Index e = 0; e < wall.element_count(); ++e) {
    const auto& c = wall.element(e);
    for (int k = 0; k < (D == 2 ? 1 : 3); ++k)
      length.push_back((wall.vertices()[c[k]] - wall.vertices()[c[(k + 1) % D]]).norm());
  }
  if (length.empty()) return 0.0;
  auto middle = length.begin() + static_cast<std::ptrdiff_t>(length.size() / 2);
  std::nth_element(length.begin(), middle, length.end());
  return *middle;
}

/// The sites (element, barycentric) farther than `spacing` from every site kept before them
/// whose normal is within 60° of theirs (a greedy Poisson-disk thinning, in site order).
template <int D>
std::vector<std::pair<Index, Vec<D>>> thinned_sites(
    const WallMesh<D>& wall, const std::vector<std::pair<Index, Vec<D>>>& sites, double spacing) {
  constexpr double min_alignment = 0.5;  // cos 60°
  using Cell = std::array<std::int64_t, D>;
  std::map<Cell, std::vector<std::pair<Vec<D>, Vec<D>>>> kept_in;  // cell → (position, normal)
  auto cell_of = [&](const Vec<D>& x) {
    Cell c;
    for (int a = 0; a < D; ++a) c[a] = static_cast<std::int64_t>(std::floor(x[a] / spacing));
    return c;
  };
  auto crowded = [&](const Vec<D>& x, const Vec<D>& n) {
    return any_cell_around<D>(cell_of(x), [&](const Cell& c) {
      const auto it = kept_in.find(c);
      if (it == kept_in.end()) return false;
      for (const auto& [y, m] : it->second)
        if ((y - x).norm() < spacing && m.dot(n) > min_alignment) return true;
      return false;
    });
  };
  std::vector<std::pair<Index, Vec<D>>> kept;
  for (const auto& [e, b] : sites) {
    const Vec<D> x = wall.point_at(e, b), n = wall.normal_at(e, b);
    if (crowded(x, n)) continue;
    kept_in[cell_of(x)].emplace_back(x, n);
    kept.emplace_back(e, b);
  }
  return kept;
}

}  // namespace

template <int D>
Index add_wall_nodes(PointSet<D>& points, const WallMesh<D>& wall, int body, double dx) {
  HM_ASSERT(dx > 0.0, "add_wall_nodes: dx {} must be > 0", dx);
  const Index first = points.size();
  std::vector<std::pair<Index, Vec<D>>> sites;  // (element, barycentric)
  std::vector<char> vertex_done(wall.vertices().size(), 0);
  auto add_vertex = [&](Index e, int k) {
    if (vertex_done[wall.element(e)[k]]) return;
    vertex_done[wall.element(e)[k]] = 1;
    Vec<D> b = Vec<D>::Zero();
    b[k] = 1.0;
    sites.emplace_back(e, b);
  };
  auto divisions = [&](Index a, Index b) {
    return std::max(
        1,
        static_cast<int>(std::ceil((wall.vertices()[a] - wall.vertices()[b]).norm() / dx - 1e-9)));
  };
  std::map<std::uint64_t, char> edge_done;
  for (Index e = 0; e < wall.element_count(); ++e) {
    const auto& c = wall.element(e);
    for (int k = 0; k < D; ++k) add_vertex(e, k);
    if constexpr (D == 2) {
      const int n = divisions(c[0], c[1]);
      for (int s = 1; s < n; ++s) sites.emplace_back(e, Vec<2>(1.0 - double(s) / n, double(s) / n));
    } else {
      int nmax = 1;
      for (int k = 0; k < 3; ++k) {
        const Index a = c[k], b = c[(k + 1) % 3];
        const int n = divisions(a, b);
        nmax = std::max(nmax, n);
        if (edge_done[edge_key(a, b)]++) continue;
        for (int s = 1; s < n; ++s) {
          Vec<3> bary = Vec<3>::Zero();
          bary[k] = 1.0 - double(s) / n;
          bary[(k + 1) % 3] = double(s) / n;
          sites.emplace_back(e, bary);
        }
      }
      for (int i = 1; i < nmax; ++i)
        for (int j = 1; i + j < nmax; ++j)
          sites.emplace_back(
              e, Vec<3>(double(i) / nmax, double(j) / nmax, double(nmax - i - j) / nmax));
    }
  }
  if (wall.thins_dense_nodes() && median_edge_length(wall) < 0.5 * dx)
    sites = thinned_sites(wall, sites, dx);
  for (const int side : wall.thin() ? std::vector<int>{1, -1} : std::vector<int>{1})
    for (const auto& [e, b] : sites)
      points.add_wall_node(wall.point_at(e, b), side * wall.normal_at(e, b), {body, e, b});
  for (Index i = first; i < points.size(); ++i) {
    points.wall_velocity[i] = points.velocity[i] =
        wall.velocity_at(points.host[i].element, points.host[i].barycentric);
    points.wall_acceleration[i] =
        wall.acceleration_at(points.host[i].element, points.host[i].barycentric);
  }
  return points.size() - first;
}

template <int D>
void update_wall_nodes(PointSet<D>& points, std::span<const WallMesh<D>> walls) {
  const Index n = points.size();
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    if (points.kind[i] != PointKind::wall) continue;
    const auto& h = points.host[i];
    const auto& w = walls[static_cast<std::size_t>(h.body)];
    const double side =
        points.wall_normal[i].dot(w.normal_at(h.element, h.barycentric)) < 0 ? -1 : 1;
    points.position[i] = w.point_at(h.element, h.barycentric);
    points.wall_normal[i] = side * w.normal_at(h.element, h.barycentric);
    points.wall_velocity[i] = points.velocity[i] = w.velocity_at(h.element, h.barycentric);
    points.wall_acceleration[i] = w.acceleration_at(h.element, h.barycentric);
  }
}

template <int D>
std::vector<double> wall_node_weights(const PointSet<D>& points, double radius, double dx) {
  HM_ASSERT(dx > 0.0 && radius > 0.0, "wall_node_weights: dx {} and radius {} must be > 0", dx,
            radius);
  const Index n = points.size();
  std::vector<Index> wall;  // local wall-node number -> point index
  std::vector<Vec<D>> position;
  for (Index i = 0; i < n; ++i)
    if (points.kind[i] == PointKind::wall) {
      wall.push_back(i);
      position.push_back(points.position[i]);
    }
  // An own search over the wall nodes alone: the operators' lists have lost the pairs cut
  // through walls and past a node's back (cut_pairs_through_thin_walls), so on a convex bend
  // they missed most of the node's own face and its weight came out 4–17× too large.
  const Neighbours nb = find_neighbours<D>(std::span<const Vec<D>>(position), radius);
  const double integral = D == 2 ? 2.0 * radius / 3.0 : std::numbers::pi * radius * radius / 7.0;
  const double cell = D == 2 ? dx : dx * dx;
  std::vector<double> w(static_cast<std::size_t>(n), 1.0);
  const auto count = static_cast<Index>(wall.size());
#pragma omp parallel for schedule(static)
  for (Index a = 0; a < count; ++a) {
    const Index i = wall[a];
    double sum = 1.0;  // W(0): the node itself
    for (Index b : nb.of(a)) {
      const Index j = wall[b];
      if (points.host[j].body != points.host[i].body ||
          points.wall_normal[j].dot(points.wall_normal[i]) < -0.5)
        continue;
      sum += wendland_c2((points.position[j] - points.position[i]).norm() / radius);
    }
    w[i] = integral / (cell * sum);
  }
  return w;
}

template <int D>
std::int64_t cut_pairs_through_thin_walls(Neighbours& nb, const PointSet<D>& points,
                                          std::span<const WallMesh<D>> walls) {
  const Index n = points.size();
  std::vector<int> thin;
  for (std::size_t w = 0; w < walls.size(); ++w)
    if (walls[w].thin() || walls[w].solid()) thin.push_back(static_cast<int>(w));
  // near[i] bit w: point i is within h of thin wall w. Only points within h of the wall's
  // bounding box can be (the closest-point query for every point of a 3-D tank was a tenth of
  // wedge_entry_3d's run).
  std::vector<std::uint32_t> near(static_cast<std::size_t>(n), 0);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i)
    for (std::size_t t = 0; t < thin.size() && t < 32; ++t) {
      const auto& wall = walls[thin[t]];
      const Vec<D>& x = points.position[i];
      const bool in_reach = (x.array() >= wall.lower().array() - nb.radius).all() &&
                            (x.array() <= wall.upper().array() + nb.radius).all();
      if (in_reach && std::abs(wall.closest(x).signed_distance) < nb.radius) near[i] |= 1u << t;
    }
  // Wall nodes of other walls inside a solid body, or on its surface facing into it (the floor
  // under a gate standing on it), are buried: they lose every pair. Left in, the floor nodes
  // under the elastic gate saw the fluid at the gate's foot through weak Neumann rows that
  // became p = 0 Dirichlet points — a drain that cut the column's hydrostatic pressure at
  // t = 0 to 85 % and the gate's added mass by a third.
  // Likewise a solid body's own nodes where it stands on another wall (the gate's foot on the
  // floor): their corner rows, with a pseudo-normal into the floor, were weak and became such
  // p = 0 points as well.
  std::vector<char> buried(static_cast<std::size_t>(n), 0);
  const auto facing_into = [&](Index i, const WallMesh<D>& other) {
    const auto c = other.closest(points.position[i]);
    const double tolerance = 1e-9 * (other.upper() - other.lower()).norm();
    return c.signed_distance < -tolerance ||
           (c.signed_distance <= tolerance && points.wall_normal[i].dot(c.normal) < -0.5);
  };
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    if (points.kind[i] != PointKind::wall) continue;
    const int own = points.host[i].body;
    for (std::size_t t = 0; t < thin.size() && t < 32; ++t)
      if (walls[thin[t]].solid() && own != thin[t] && (near[i] >> t & 1u) &&
          facing_into(i, walls[thin[t]]))
        buried[i] = 1;
    if (buried[i] || !walls[static_cast<std::size_t>(own)].solid()) continue;
    for (std::size_t w = 0; w < walls.size() && !buried[i]; ++w)
      if (static_cast<int>(w) != own && !walls[w].thin() && facing_into(i, walls[w])) buried[i] = 1;
  }
  // No wall node couples to a point behind it, whatever its wall: the other face of a block
  // thinner than h (the 5 mm wall above the elastic gate at h = 12.5 mm turned its fluid-side
  // rows weak, hence p = 0 Dirichlet), the far side of a thin wall, a point past a wall's end.
  auto behind_node = [&](Index i, Index j) {
    if (points.kind[i] != PointKind::wall) return false;
    return (points.position[j] - points.position[i]).dot(points.wall_normal[i]) < 0.0;
  };
  const auto before = nb.pairs();
  remove_pairs(nb, [&](Index i, Index j) {
    if (buried[i] || buried[j] || behind_node(i, j) || behind_node(j, i)) return true;
    const std::uint32_t both = near[i] & near[j];
    for (std::size_t t = 0; t < thin.size() && t < 32; ++t)
      if ((both >> t & 1u) && walls[thin[t]].crosses(points.position[i], points.position[j]))
        return true;
    return false;
  });
  return before - nb.pairs();
}

template class WallMesh<2>;
template class WallMesh<3>;
template Index add_wall_nodes<2>(PointSet<2>&, const WallMesh<2>&, int, double);
template Index add_wall_nodes<3>(PointSet<3>&, const WallMesh<3>&, int, double);
template void update_wall_nodes<2>(PointSet<2>&, std::span<const WallMesh<2>>);
template void update_wall_nodes<3>(PointSet<3>&, std::span<const WallMesh<3>>);
template std::vector<double> wall_node_weights<2>(const PointSet<2>&, double, double);
template std::vector<double> wall_node_weights<3>(const PointSet<3>&, double, double);
template std::int64_t cut_pairs_through_thin_walls<2>(Neighbours&, const PointSet<2>&,
                                                      std::span<const WallMesh<2>>);
template std::int64_t cut_pairs_through_thin_walls<3>(Neighbours&, const PointSet<3>&,
                                                      std::span<const WallMesh<3>>);

}  // namespace hm::ldd
