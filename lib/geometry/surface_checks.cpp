#include "geometry/surface_checks.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <deque>
#include <map>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/errors.hpp"
#include "geometry/cgal_checks.hpp"

namespace hm::geometry {
namespace {

using mesh::Index;

Eigen::Vector3d vertex(const mesh::SurfaceMesh& s, Index v) {
  return s.vertices.row(v).transpose();
}

std::string point_text(const Eigen::Vector3d& p) {
  return fmt::format("({:.9g}, {:.9g}, {:.9g})", p.x(), p.y(), p.z());
}

std::string triangle_text(const mesh::SurfaceMesh& s, Index c) {
  return fmt::format("triangle {} [{} {} {}]", c, point_text(vertex(s, s.cells(c, 0))),
                     point_text(vertex(s, s.cells(c, 1))), point_text(vertex(s, s.cells(c, 2))));
}

bool is_degenerate(const mesh::SurfaceMesh& s, Index c) {
  const Index i = s.cells(c, 0), j = s.cells(c, 1), k = s.cells(c, 2);
  if (i == j || j == k || k == i) return true;
  const Eigen::Vector3d a = vertex(s, i), b = vertex(s, j), d = vertex(s, k);
  const double longest =
      std::max({(b - a).squaredNorm(), (d - b).squaredNorm(), (a - d).squaredNorm()});
  return (b - a).cross(d - a).norm() <= degenerate_tolerance * longest;
}

void reject_degenerate(const mesh::SurfaceMesh& s, std::string_view source) {
  std::vector<Index> bad;
  for (Index c = 0; c < s.cells.rows(); ++c)
    if (is_degenerate(s, c)) bad.push_back(c);
  if (!bad.empty())
    input_error(
        "surface '{}': {} of {} triangles are degenerate (zero area: coincident or "
        "collinear vertices); first: {}. Repair the mesh (e.g. remove zero-area facets).",
        source, bad.size(), s.cells.rows(), triangle_text(s, bad.front()));
}

/// One use of an undirected edge by a triangle: which triangle, and whether the triangle runs
/// along it from the smaller to the larger vertex index.
struct EdgeUse {
  Index triangle;
  bool ascending;
};
using EdgeMap = std::map<std::pair<Index, Index>, std::vector<EdgeUse>>;

EdgeMap edge_uses(const mesh::SurfaceMesh& s) {
  EdgeMap edges;
  for (Index c = 0; c < s.cells.rows(); ++c)
    for (int k = 0; k < 3; ++k) {
      const Index a = s.cells(c, k), b = s.cells(c, (k + 1) % 3);
      edges[{std::min(a, b), std::max(a, b)}].push_back({c, a < b});
    }
  return edges;
}

void reject_open_or_non_manifold(const mesh::SurfaceMesh& s, const EdgeMap& edges,
                                 std::string_view source) {
  Index border = 0, non_manifold = 0;
  const std::pair<Index, Index>*first_border = nullptr, *first_non_manifold = nullptr;
  for (const auto& [edge, uses] : edges) {
    if (uses.size() == 1 && border++ == 0) first_border = &edge;
    if (uses.size() > 2 && non_manifold++ == 0) first_non_manifold = &edge;
  }
  if (border > 0)
    input_error(
        "surface '{}' is not closed: {} border edges (holes) of {} edges; first border "
        "edge {} – {}. A structure surface must bound a volume.",
        source, border, edges.size(), point_text(vertex(s, first_border->first)),
        point_text(vertex(s, first_border->second)));
  if (non_manifold > 0)
    input_error(
        "surface '{}' is not a manifold: {} edges are shared by more than two triangles; "
        "first {} – {}",
        source, non_manifold, point_text(vertex(s, first_non_manifold->first)),
        point_text(vertex(s, first_non_manifold->second)));
}

/// Neighbours across each edge, with whether the pair currently agrees in orientation
/// (a shared edge traversed in opposite directions).
struct Neighbour {
  Index triangle;
  bool consistent;
};

std::vector<std::vector<Neighbour>> neighbours(const mesh::SurfaceMesh& s, const EdgeMap& edges) {
  std::vector<std::vector<Neighbour>> adjacent(static_cast<std::size_t>(s.cells.rows()));
  for (const auto& [edge, uses] : edges) {
    const EdgeUse& u = uses[0];
    const EdgeUse& w = uses[1];
    const bool consistent = u.ascending != w.ascending;
    adjacent[static_cast<std::size_t>(u.triangle)].push_back({w.triangle, consistent});
    adjacent[static_cast<std::size_t>(w.triangle)].push_back({u.triangle, consistent});
  }
  return adjacent;
}

/// Breadth-first walk over each shell deciding which triangles to flip so that every shared edge
/// is traversed in opposite directions. Returns {flipped count, shell count}.
std::pair<Index, Index> make_consistent(mesh::SurfaceMesh& s, const EdgeMap& edges,
                                        std::string_view source) {
  const auto adjacent = neighbours(s, edges);
  const auto n = static_cast<std::size_t>(s.cells.rows());
  std::vector<int> flip(n, -1);  // -1 unvisited, 0 keep, 1 flip
  Index shells = 0;
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (flip[seed] >= 0) continue;
    ++shells;
    flip[seed] = 0;
    std::deque<std::size_t> queue{seed};
    while (!queue.empty()) {
      const std::size_t t = queue.front();
      queue.pop_front();
      for (const Neighbour& nb : adjacent[t]) {
        const auto u = static_cast<std::size_t>(nb.triangle);
        const int wanted = nb.consistent ? flip[t] : 1 - flip[t];
        if (flip[u] < 0) {
          flip[u] = wanted;
          queue.push_back(u);
        } else if (flip[u] != wanted) {
          input_error(
              "surface '{}' cannot be oriented consistently (non-orientable shell); "
              "conflict between {} and {}",
              source, triangle_text(s, static_cast<Index>(t)), triangle_text(s, nb.triangle));
        }
      }
    }
  }
  Index flipped = 0;
  for (std::size_t t = 0; t < n; ++t)
    if (flip[t] == 1) {
      std::swap(s.cells(static_cast<Index>(t), 1), s.cells(static_cast<Index>(t), 2));
      ++flipped;
    }
  return {flipped, shells};
}

void reject_self_intersections(const mesh::SurfaceMesh& s, std::string_view source) {
  const auto pairs = cgal::self_intersecting_faces(s);
  if (!pairs.empty())
    input_error(
        "surface '{}' intersects itself: {} pairs of intersecting triangles; first pair: "
        "{} and {}",
        source, pairs.size(), triangle_text(s, pairs.front().first),
        triangle_text(s, pairs.front().second));
}

double longest_edge(const mesh::SurfaceMesh& s) {
  double longest = 0.0;
  for (Index c = 0; c < s.cells.rows(); ++c)
    for (int k = 0; k < 3; ++k)
      longest =
          std::max(longest, (vertex(s, s.cells(c, k)) - vertex(s, s.cells(c, (k + 1) % 3))).norm());
  return longest;
}

mesh::SurfaceMesh split_in_four(const mesh::SurfaceMesh& s) {
  std::vector<Eigen::Vector3d> points;
  for (Index v = 0; v < s.vertices.rows(); ++v) points.push_back(vertex(s, v));
  std::map<std::pair<Index, Index>, Index> midpoint;
  auto mid = [&](Index a, Index b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto [it, inserted] = midpoint.emplace(key, static_cast<Index>(points.size()));
    if (inserted) points.push_back(0.5 * (vertex(s, a) + vertex(s, b)));
    return it->second;
  };
  mesh::SurfaceMesh out;
  out.dim = 3;
  out.cells.resize(4 * s.cells.rows(), 3);
  for (Index c = 0; c < s.cells.rows(); ++c) {
    const Index a = s.cells(c, 0), b = s.cells(c, 1), d = s.cells(c, 2);
    const Index ab = mid(a, b), bd = mid(b, d), da = mid(d, a);
    out.cells.row(4 * c) << a, ab, da;
    out.cells.row(4 * c + 1) << ab, b, bd;
    out.cells.row(4 * c + 2) << da, bd, d;
    out.cells.row(4 * c + 3) << ab, bd, da;
  }
  out.vertices.resize(static_cast<Index>(points.size()), 3);
  for (std::size_t v = 0; v < points.size(); ++v)
    out.vertices.row(static_cast<Index>(v)) = points[v].transpose();
  return out;
}

}  // namespace

Index count_border_edges(const mesh::SurfaceMesh& surface) {
  Index border = 0;
  for (const auto& [edge, uses] : edge_uses(surface))
    if (uses.size() == 1) ++border;
  return border;
}

/// Each segment (a, b) becomes (a, m), (m, b); original vertices keep their indices.
mesh::SurfaceMesh split_segments_in_two(const mesh::SurfaceMesh& s) {
  mesh::SurfaceMesh out;
  out.dim = 2;
  const Index n = s.vertices.rows(), cells = s.cells.rows();
  out.vertices.resize(n + cells, 2);
  out.vertices.topRows(n) = s.vertices;
  out.cells.resize(2 * cells, 2);
  for (Index c = 0; c < cells; ++c) {
    const Index a = s.cells(c, 0), b = s.cells(c, 1), m = n + c;
    out.vertices.row(m) = 0.5 * (s.vertices.row(a) + s.vertices.row(b));
    out.cells.row(2 * c) << a, m;
    out.cells.row(2 * c + 1) << m, b;
  }
  return out;
}

double longest_segment(const mesh::SurfaceMesh& s) {
  double longest = 0.0;
  for (Index c = 0; c < s.cells.rows(); ++c)
    longest =
        std::max(longest, (s.vertices.row(s.cells(c, 0)) - s.vertices.row(s.cells(c, 1))).norm());
  return longest;
}

mesh::SurfaceMesh refine_uniformly(const mesh::SurfaceMesh& surface, double max_edge) {
  HM_ASSERT(max_edge > 0.0, "refine_uniformly needs a positive size");
  mesh::SurfaceMesh out = surface;
  if (surface.dim == 2) {
    while (out.cells.rows() > 0 && longest_segment(out) > max_edge)
      out = split_segments_in_two(out);
    return out;
  }
  while (out.cells.rows() > 0 && longest_edge(out) > max_edge) out = split_in_four(out);
  return out;
}

double refined_cell_count(const mesh::SurfaceMesh& surface, double max_edge) {
  HM_ASSERT(max_edge > 0.0, "refined_cell_count needs a positive size");
  if (surface.cells.rows() == 0) return 0.0;
  double longest = surface.dim == 2 ? longest_segment(surface) : longest_edge(surface);
  double cells = static_cast<double>(surface.cells.rows());
  while (longest > max_edge) {
    longest *= 0.5;
    cells *= surface.dim == 2 ? 2.0 : 4.0;
  }
  return cells;
}

void reverse_cells(mesh::SurfaceMesh& surface) {
  for (Index c = 0; c < surface.cells.rows(); ++c)
    std::swap(surface.cells(c, 0), surface.cells(c, 1));
}

double enclosed_volume(const mesh::SurfaceMesh& surface) {
  double six_v = 0.0;
  for (Index c = 0; c < surface.cells.rows(); ++c)
    six_v +=
        vertex(surface, surface.cells(c, 0))
            .dot(vertex(surface, surface.cells(c, 1)).cross(vertex(surface, surface.cells(c, 2))));
  return six_v / 6.0;
}

SurfaceCheckReport check_closed_surface(mesh::SurfaceMesh& surface, std::string_view source) {
  if (surface.dim != 3 || surface.cells.cols() != 3 || surface.cells.rows() == 0)
    input_error("surface '{}' is not a non-empty 3-D triangle surface", source);
  SurfaceCheckReport report;
  report.vertices = surface.vertices.rows();
  report.triangles = surface.cells.rows();
  report.box = bounding_box(surface.vertices);
  reject_degenerate(surface, source);
  const EdgeMap edges = edge_uses(surface);
  reject_open_or_non_manifold(surface, edges, source);
  std::tie(report.flipped_for_consistency, report.components) =
      make_consistent(surface, edges, source);
  if (report.flipped_for_consistency > 0)
    spdlog::warn(
        "surface '{}': {} of {} triangles were oriented against their neighbours and "
        "have been flipped",
        source, report.flipped_for_consistency, report.triangles);
  reject_self_intersections(surface, source);
  report.flipped_outward = cgal::orient_to_bound_a_volume(surface);
  if (report.flipped_outward > 0)
    spdlog::info("surface '{}': reoriented {} triangles so that the normals point out of the solid",
                 source, report.flipped_outward);
  report.enclosed_volume = enclosed_volume(surface);
  return report;
}

}  // namespace hm::geometry
