#include "mesh/structured.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.hpp"

namespace hm::mesh {
namespace {

using LatticePoint = std::array<Index, 3>;  // half-cell lattice coordinates (z = 0 in 2-D)

constexpr std::array<std::pair<int, int>, 3> kTri6Edges{{{0, 1}, {1, 2}, {2, 0}}};
constexpr std::array<std::pair<int, int>, 6> kTet10Edges{
    {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}}};
constexpr std::array<const char*, 6> kSideNames{"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};

/// The (2n+1)-points-per-axis lattice of a structured quadratic mesh.
struct Lattice {
  int dim;
  LatticePoint points;  // points per axis

  Index id(const LatticePoint& p) const { return p[0] + points[0] * (p[1] + points[1] * p[2]); }
  Index size() const { return points[0] * points[1] * points[2]; }
};

LatticePoint midpoint(const LatticePoint& a, const LatticePoint& b) {
  return {(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2};
}

LatticePoint offset(LatticePoint p, int axis, Index by) {
  p[axis] += by;
  return p;
}

Eigen::Vector3d as_vector(const LatticePoint& p) {
  return {static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2])};
}

/// Corners followed by the mid-edge nodes, in gmsh order, as node indices.
template <std::size_t NEdges>
std::vector<Index> quadratic_nodes(const Lattice& lattice, const std::vector<LatticePoint>& corners,
                                   const std::array<std::pair<int, int>, NEdges>& edges) {
  std::vector<Index> nodes;
  for (const auto& c : corners) nodes.push_back(lattice.id(c));
  for (const auto& [a, b] : edges) nodes.push_back(lattice.id(midpoint(corners[a], corners[b])));
  return nodes;
}

void append_row(IndexMatrix& m, Index row, const std::vector<Index>& values) {
  for (std::size_t c = 0; c < values.size(); ++c) m(row, static_cast<Index>(c)) = values[c];
}

void validate_extent(const char* what, double length, int cells) {
  if (!(length > 0.0)) input_error("structured mesh: length {} = {} m; must be > 0", what, length);
  if (cells < 1) input_error("structured mesh: cell count {} = {}; must be ≥ 1", what, cells);
}

Coordinates lattice_coordinates(const Lattice& lattice, const Eigen::Vector3d& spacing,
                                const Eigen::Vector3d& origin) {
  Coordinates nodes(lattice.size(), lattice.dim);
  for (Index k = 0; k < lattice.points[2]; ++k)
    for (Index j = 0; j < lattice.points[1]; ++j)
      for (Index i = 0; i < lattice.points[0]; ++i) {
        const Index id = lattice.id({i, j, k});
        const Eigen::Vector3d x = origin + spacing.cwiseProduct(as_vector({i, j, k}));
        for (int d = 0; d < lattice.dim; ++d) nodes(id, d) = x[d];
      }
  return nodes;
}

/// Node groups: every lattice node on each side of the domain, sorted.
void add_side_node_groups(const Lattice& lattice, StructureMesh& mesh) {
  for (Index n = 0; n < lattice.size(); ++n) {
    const LatticePoint p{n % lattice.points[0], (n / lattice.points[0]) % lattice.points[1],
                         n / (lattice.points[0] * lattice.points[1])};
    for (int axis = 0; axis < lattice.dim; ++axis) {
      if (p[axis] == 0) mesh.node_groups[kSideNames[2 * axis]].push_back(n);
      if (p[axis] == lattice.points[axis] - 1)
        mesh.node_groups[kSideNames[2 * axis + 1]].push_back(n);
    }
  }
}

/// Boundary squares (3-D) or segments (2-D) of one side: corner lists of each cell face.
/// The corner order makes the facet normal point along `outward`.
std::vector<std::vector<LatticePoint>> side_facets(const Lattice& lattice, int axis, bool high) {
  const Index plane = high ? lattice.points[axis] - 1 : 0;
  const Eigen::Vector3d outward = Eigen::Vector3d::Unit(axis) * (high ? 1.0 : -1.0);
  std::vector<int> tangential;
  for (int a = 0; a < lattice.dim; ++a)
    if (a != axis) tangential.push_back(a);
  std::vector<std::vector<LatticePoint>> facets;
  const int t0 = tangential[0];
  const Index cells0 = (lattice.points[t0] - 1) / 2;
  const Index cells1 = lattice.dim == 3 ? (lattice.points[tangential[1]] - 1) / 2 : 1;
  for (Index v = 0; v < cells1; ++v)
    for (Index u = 0; u < cells0; ++u) {
      LatticePoint base{0, 0, 0};
      base[axis] = plane;
      base[t0] = 2 * u;
      if (lattice.dim == 2) {
        std::vector<LatticePoint> seg{base, offset(base, t0, 2)};
        const Eigen::Vector3d t = as_vector(seg[1]) - as_vector(seg[0]);
        if (Eigen::Vector3d(t.y(), -t.x(), 0.0).dot(outward) < 0) std::swap(seg[0], seg[1]);
        facets.push_back(seg);
        continue;
      }
      const int t1 = tangential[1];
      base[t1] = 2 * v;
      const LatticePoint p00 = base, p10 = offset(base, t0, 2), p01 = offset(base, t1, 2);
      const LatticePoint p11 = offset(p10, t1, 2);
      for (std::vector<LatticePoint> tri :
           {std::vector{p00, p10, p11}, std::vector{p00, p11, p01}}) {
        const Eigen::Vector3d n =
            (as_vector(tri[1]) - as_vector(tri[0])).cross(as_vector(tri[2]) - as_vector(tri[0]));
        if (n.dot(outward) < 0) std::swap(tri[1], tri[2]);
        facets.push_back(tri);
      }
    }
  return facets;
}

void add_boundary_facets(const Lattice& lattice, StructureMesh& mesh) {
  std::vector<std::vector<Index>> rows;
  for (int axis = 0; axis < lattice.dim; ++axis)
    for (bool high : {false, true})
      for (const auto& corners : side_facets(lattice, axis, high)) {
        mesh.facet_groups[kSideNames[2 * axis + (high ? 1 : 0)]].push_back(
            static_cast<Index>(rows.size()));
        if (lattice.dim == 2)
          rows.push_back(
              quadratic_nodes(lattice, corners, std::array<std::pair<int, int>, 1>{{{0, 1}}}));
        else
          rows.push_back(quadratic_nodes(lattice, corners, kTri6Edges));
      }
  mesh.facets.resize(static_cast<Index>(rows.size()), mesh.nodes_per_facet());
  for (std::size_t r = 0; r < rows.size(); ++r)
    append_row(mesh.facets, static_cast<Index>(r), rows[r]);
}

/// The two triangles of a rectangle cell, counter-clockwise.
std::vector<std::vector<LatticePoint>> rectangle_cell_triangles(const LatticePoint& base) {
  const LatticePoint p00 = base, p10 = offset(base, 0, 2), p01 = offset(base, 1, 2);
  const LatticePoint p11 = offset(p10, 1, 2);
  return {{p00, p10, p11}, {p00, p11, p01}};
}

/// The six Kuhn tetrahedra of a box cell: paths 000 → 111 along the axes in every order,
/// reordered to positive volume.
std::vector<std::vector<LatticePoint>> box_cell_tetrahedra(const LatticePoint& base) {
  std::array<int, 3> order{0, 1, 2};
  std::vector<std::vector<LatticePoint>> tets;
  do {
    std::vector<LatticePoint> tet{base};
    for (int axis : order) tet.push_back(offset(tet.back(), axis, 2));
    const Eigen::Vector3d x0 = as_vector(tet[0]);
    const double volume6 =
        (as_vector(tet[1]) - x0).cross(as_vector(tet[2]) - x0).dot(as_vector(tet[3]) - x0);
    if (volume6 < 0) std::swap(tet[1], tet[2]);
    tets.push_back(tet);
  } while (std::next_permutation(order.begin(), order.end()));
  return tets;
}

}  // namespace

StructureMesh structured_rectangle(double lx, double ly, int nx, int ny, Eigen::Vector2d origin) {
  validate_extent("lx", lx, nx);
  validate_extent("ly", ly, ny);
  const Lattice lattice{2, {2 * nx + 1, 2 * ny + 1, 1}};
  StructureMesh mesh;
  mesh.dim = 2;
  mesh.nodes = lattice_coordinates(lattice, {lx / (2.0 * nx), ly / (2.0 * ny), 0.0},
                                   {origin.x(), origin.y(), 0.0});
  mesh.cells.resize(2 * Index{nx} * ny, 6);
  Index row = 0;
  for (Index j = 0; j < ny; ++j)
    for (Index i = 0; i < nx; ++i)
      for (const auto& tri : rectangle_cell_triangles({2 * i, 2 * j, 0}))
        append_row(mesh.cells, row++, quadratic_nodes(lattice, tri, kTri6Edges));
  add_side_node_groups(lattice, mesh);
  add_boundary_facets(lattice, mesh);
  return mesh;
}

StructureMesh structured_box(double lx, double ly, double lz, int nx, int ny, int nz,
                             Eigen::Vector3d origin) {
  validate_extent("lx", lx, nx);
  validate_extent("ly", ly, ny);
  validate_extent("lz", lz, nz);
  const Lattice lattice{3, {2 * nx + 1, 2 * ny + 1, 2 * nz + 1}};
  StructureMesh mesh;
  mesh.dim = 3;
  mesh.nodes =
      lattice_coordinates(lattice, {lx / (2.0 * nx), ly / (2.0 * ny), lz / (2.0 * nz)}, origin);
  mesh.cells.resize(6 * Index{nx} * ny * nz, 10);
  Index row = 0;
  for (Index k = 0; k < nz; ++k)
    for (Index j = 0; j < ny; ++j)
      for (Index i = 0; i < nx; ++i)
        for (const auto& tet : box_cell_tetrahedra({2 * i, 2 * j, 2 * k}))
          append_row(mesh.cells, row++, quadratic_nodes(lattice, tet, kTet10Edges));
  add_side_node_groups(lattice, mesh);
  add_boundary_facets(lattice, mesh);
  return mesh;
}

}  // namespace hm::mesh
