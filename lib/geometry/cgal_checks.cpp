#include "geometry/cgal_checks.hpp"

#include <algorithm>
#include <array>
#include <iterator>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include "core/errors.hpp"

namespace hm::geometry::cgal {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using CgalMesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

/// A Surface_mesh whose face i is cells.row(i) (Surface_mesh numbers faces in insertion order),
/// built from the referenced vertices only: CGAL's orientation and component walks assume every
/// vertex has a halfedge, and an OBJ or PLY may list vertices no face uses. `original[v]` is our
/// index of CGAL vertex v.
struct CgalSurface {
  CgalMesh mesh;
  std::vector<mesh::Index> original;
};

CgalSurface to_cgal(const mesh::SurfaceMesh& surface) {
  HM_ASSERT(surface.dim == 3 && surface.cells.cols() == 3, "CGAL checks need 3-D triangles");
  constexpr std::size_t unused = static_cast<std::size_t>(-1);
  std::vector<std::size_t> compact(static_cast<std::size_t>(surface.vertices.rows()), unused);
  CgalSurface result;
  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  triangles.reserve(static_cast<std::size_t>(surface.cells.rows()));
  for (mesh::Index c = 0; c < surface.cells.rows(); ++c) {
    std::array<std::size_t, 3> triangle{};
    for (int k = 0; k < 3; ++k) {
      const mesh::Index v = surface.cells(c, k);
      auto& slot = compact[static_cast<std::size_t>(v)];
      if (slot == unused) {
        slot = points.size();
        points.emplace_back(surface.vertices(v, 0), surface.vertices(v, 1), surface.vertices(v, 2));
        result.original.push_back(v);
      }
      triangle[static_cast<std::size_t>(k)] = slot;
    }
    triangles.push_back(triangle);
  }
  HM_ASSERT(PMP::is_polygon_soup_a_polygon_mesh(triangles),
            "surface is not an oriented manifold; run the topology checks first");
  PMP::polygon_soup_to_polygon_mesh(points, triangles, result.mesh);
  HM_ASSERT(static_cast<mesh::Index>(result.mesh.number_of_faces()) == surface.cells.rows(),
            "CGAL dropped faces");
  return result;
}

/// Our vertex indices of CGAL face f, in CGAL's cyclic order.
std::array<mesh::Index, 3> face_vertices(const CgalSurface& m, CgalMesh::Face_index f) {
  std::array<mesh::Index, 3> v{};
  int k = 0;
  for (auto vd : CGAL::vertices_around_face(m.mesh.halfedge(f), m.mesh))
    v[k++] = m.original[static_cast<std::size_t>(vd)];
  return v;
}

}  // namespace

std::vector<std::pair<mesh::Index, mesh::Index>> self_intersecting_faces(
    const mesh::SurfaceMesh& surface) {
  const CgalSurface m = to_cgal(surface);
  std::vector<std::pair<CgalMesh::Face_index, CgalMesh::Face_index>> pairs;
  PMP::self_intersections(CGAL::faces(m.mesh), m.mesh, std::back_inserter(pairs));
  std::vector<std::pair<mesh::Index, mesh::Index>> result;
  result.reserve(pairs.size());
  for (const auto& [a, b] : pairs)
    result.emplace_back(std::min<mesh::Index>(a, b), std::max<mesh::Index>(a, b));
  std::sort(result.begin(), result.end());
  return result;
}

bool is_outward_oriented(const mesh::SurfaceMesh& surface) {
  return PMP::is_outward_oriented(to_cgal(surface).mesh);
}

mesh::Index orient_to_bound_a_volume(mesh::SurfaceMesh& surface) {
  CgalSurface m = to_cgal(surface);
  PMP::orient_to_bound_a_volume(m.mesh);
  mesh::Index flipped = 0;
  for (auto f : m.mesh.faces()) {
    const auto c = static_cast<mesh::Index>(f);
    const auto v = face_vertices(m, f);
    // Same cyclic order as before, or reversed?
    bool same = false;
    for (int r = 0; r < 3; ++r)
      same = same || (v[0] == surface.cells(c, r) && v[1] == surface.cells(c, (r + 1) % 3) &&
                      v[2] == surface.cells(c, (r + 2) % 3));
    if (!same) {
      std::swap(surface.cells(c, 1), surface.cells(c, 2));
      ++flipped;
    }
  }
  return flipped;
}

}  // namespace hm::geometry::cgal
