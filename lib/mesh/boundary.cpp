#include "mesh/boundary.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <map>
#include <unordered_map>

#include "core/errors.hpp"
#include "core/text.hpp"

namespace hm::mesh {
namespace {

// Faces of a tet10 as outward tri6 (corners a,b,c, then mid-edges ab, bc, ca), for a
// right-handed tet; gmsh edges: 4:e01 5:e12 6:e20 7:e03 8:e23 9:e13.
constexpr std::array<std::array<int, 6>, 4> tet10_faces{{
    {0, 2, 1, 6, 5, 4},  // opposite node 3
    {0, 1, 3, 4, 9, 7},  // opposite node 2
    {1, 2, 3, 5, 8, 9},  // opposite node 0
    {0, 3, 2, 7, 8, 6},  // opposite node 1
}};
// Edges of a counter-clockwise tri6 as line3 (a, b, mid) with the cell on the left.
constexpr std::array<std::array<int, 3>, 3> tri6_edges{{{0, 1, 3}, {1, 2, 4}, {2, 0, 5}}};

double corner_jacobian(const StructureMesh& m, Index c) {
  auto x = [&](int k) -> Eigen::VectorXd { return m.nodes.row(m.cells(c, k)).transpose(); };
  if (m.dim == 2) {
    const Eigen::Vector2d a = x(1) - x(0), b = x(2) - x(0);
    return a.x() * b.y() - a.y() * b.x();
  }
  const Eigen::Vector3d a = x(1) - x(0), b = x(2) - x(0), d = x(3) - x(0);
  return a.cross(b).dot(d);
}

void flip_cell(StructureMesh& m, Index c) {
  auto swap = [&](int i, int j) { std::swap(m.cells(c, i), m.cells(c, j)); };
  if (m.dim == 2) {  // corners 1↔2, then e01↔e20; e12 stays
    swap(1, 2);
    swap(3, 5);
  } else {  // corners 1↔2: e01↔e20, e13↔e23; e12, e03 stay
    swap(1, 2);
    swap(4, 6);
    swap(8, 9);
  }
}

template <std::size_t N>
std::vector<Index> facet_nodes(const StructureMesh& m, Index c, const std::array<int, N>& local) {
  std::vector<Index> nodes(N);
  for (std::size_t k = 0; k < N; ++k) nodes[k] = m.cells(c, local[k]);
  return nodes;
}

struct ArrayHash {
  std::size_t operator()(const std::array<Index, 3>& a) const {
    std::size_t h = 0;
    for (Index v : a) h = h * 1000003u ^ std::hash<Index>{}(v);
    return h;
  }
};

}  // namespace

std::array<Index, 3> facet_key(std::span<const Index> facet_nodes, int dim) {
  std::array<Index, 3> key{facet_nodes[0], facet_nodes[1], dim == 3 ? facet_nodes[2] : Index{-1}};
  // Explicit compare-and-swap: std::sort on a sub-range trips g++ 12's -Warray-bounds.
  auto order = [&](int i, int j) {
    if (key[i] > key[j]) std::swap(key[i], key[j]);
  };
  order(0, 1);
  if (dim == 3) {
    order(1, 2);
    order(0, 1);
  }
  return key;
}

Index orient_cells_positively(StructureMesh& mesh) {
  Index flipped = 0;
  for (Index c = 0; c < mesh.cells.rows(); ++c)
    if (corner_jacobian(mesh, c) < 0) {
      flip_cell(mesh, c);
      ++flipped;
    }
  return flipped;
}

void build_boundary_facets(StructureMesh& mesh) {
  std::vector<std::vector<Index>> candidates;
  for (Index c = 0; c < mesh.cells.rows(); ++c) {
    if (mesh.dim == 2)
      for (const auto& e : tri6_edges) candidates.push_back(facet_nodes(mesh, c, e));
    else
      for (const auto& f : tet10_faces) candidates.push_back(facet_nodes(mesh, c, f));
  }
  std::unordered_map<std::array<Index, 3>, int, ArrayHash> uses;
  for (const auto& f : candidates) ++uses[facet_key(f, mesh.dim)];
  std::vector<const std::vector<Index>*> boundary;
  for (const auto& f : candidates) {
    const int n = uses[facet_key(f, mesh.dim)];
    HM_ASSERT(n <= 2, "a facet is shared by {} cells: the mesh is not conforming", n);
    if (n == 1) boundary.push_back(&f);
  }
  mesh.facets.resize(static_cast<Index>(boundary.size()), mesh.nodes_per_facet());
  for (std::size_t i = 0; i < boundary.size(); ++i)
    for (int k = 0; k < mesh.nodes_per_facet(); ++k)
      mesh.facets(static_cast<Index>(i), k) = (*boundary[i])[static_cast<std::size_t>(k)];
  mesh.facet_groups.clear();
}

namespace {

/// Linear cells (local indices into a facet) for each split. 2-D segments are reversed with
/// respect to the facet so that their left side (the SurfaceMesh normal) faces out.
std::vector<std::vector<int>> linear_pieces(int dim, SurfaceSplit split) {
  if (dim == 2)
    return split == SurfaceSplit::corners ? std::vector<std::vector<int>>{{1, 0}}
                                          : std::vector<std::vector<int>>{{2, 0}, {1, 2}};
  return split == SurfaceSplit::corners
             ? std::vector<std::vector<int>>{{0, 1, 2}}
             : std::vector<std::vector<int>>{{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
}

}  // namespace

BoundarySurface extract_boundary_surface(const StructureMesh& mesh, SurfaceSplit split,
                                         std::span<const Index> facets) {
  std::vector<Index> all;
  if (facets.empty()) {
    all.resize(static_cast<std::size_t>(mesh.facets.rows()));
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Index>(i);
    facets = all;
  }
  const auto pieces = linear_pieces(mesh.dim, split);
  BoundarySurface out;
  std::map<Index, Index> vertex_of_node;
  auto vertex = [&](Index node) {
    auto [it, inserted] = vertex_of_node.emplace(node, static_cast<Index>(out.volume_node.size()));
    if (inserted) out.volume_node.push_back(node);
    return it->second;
  };
  std::vector<Index> cells;
  for (Index f : facets)
    for (const auto& piece : pieces)
      for (int local : piece) cells.push_back(vertex(mesh.facets(f, local)));
  out.surface.dim = mesh.dim;
  out.surface.cells =
      Eigen::Map<IndexMatrix>(cells.data(), static_cast<Index>(cells.size()) / mesh.dim, mesh.dim);
  out.surface.vertices.resize(static_cast<Index>(out.volume_node.size()), mesh.dim);
  for (std::size_t v = 0; v < out.volume_node.size(); ++v)
    out.surface.vertices.row(static_cast<Index>(v)) = mesh.nodes.row(out.volume_node[v]);
  return out;
}

BoundarySurface extract_boundary_surface(const StructureMesh& mesh, SurfaceSplit split,
                                         const std::string& facet_group) {
  const auto it = mesh.facet_groups.find(facet_group);
  if (it == mesh.facet_groups.end() || it->second.empty()) {
    std::vector<std::string> names;
    for (const auto& [name, f] : mesh.facet_groups) names.push_back(name);
    input_error(
        "boundary group '{}' does not exist or has no facets; facet groups of this mesh: "
        "[{}]",
        facet_group, join(names, ", "));
  }
  return extract_boundary_surface(mesh, split, it->second);
}

}  // namespace hm::mesh
