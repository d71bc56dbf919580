#include "geometry/surface_io.hpp"

#include <Eigen/Geometry>
#include <array>
#include <fstream>
#include <map>
#include <vector>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <assimp/Importer.hpp>

#include "core/errors.hpp"
#include "geometry/surface_formats.hpp"

namespace hm::geometry {
namespace {

using mesh::Index;
using Point = std::array<double, 3>;

const aiScene* import_scene(Assimp::Importer& importer, const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path))
    input_error("geometry file '{}' does not exist (or is not a regular file)", path.string());
  const aiScene* scene =
      importer.ReadFile(path.string(), aiProcess_JoinIdenticalVertices | aiProcess_Triangulate |
                                           aiProcess_PreTransformVertices);
  if (scene == nullptr || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0)
    input_error(
        "geometry file '{}' could not be read by assimp: {} (accepted: STL, OBJ, PLY and "
        "the other formats assimp reads)",
        path.string(), importer.GetErrorString());
  return scene;
}

struct Soup {
  std::vector<Point> vertices;
  std::vector<std::array<Index, 3>> triangles;
  Index skipped = 0;
};

void append_mesh(const aiMesh& m, Soup& soup) {
  const auto offset = static_cast<Index>(soup.vertices.size());
  for (unsigned v = 0; v < m.mNumVertices; ++v)
    soup.vertices.push_back({m.mVertices[v].x, m.mVertices[v].y, m.mVertices[v].z});
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    const aiFace& face = m.mFaces[f];
    if (face.mNumIndices != 3) {
      ++soup.skipped;
      continue;
    }
    soup.triangles.push_back(
        {offset + face.mIndices[0], offset + face.mIndices[1], offset + face.mIndices[2]});
  }
}

mesh::SurfaceMesh to_surface(const Soup& soup) {
  mesh::SurfaceMesh s;
  s.dim = 3;
  s.vertices.resize(static_cast<Index>(soup.vertices.size()), 3);
  for (std::size_t i = 0; i < soup.vertices.size(); ++i)
    for (int k = 0; k < 3; ++k) s.vertices(static_cast<Index>(i), k) = soup.vertices[i][k];
  s.cells.resize(static_cast<Index>(soup.triangles.size()), 3);
  for (std::size_t i = 0; i < soup.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) s.cells(static_cast<Index>(i), k) = soup.triangles[i][k];
  return s;
}

/// Refuses a triangle without area (two corners at one point, or three on a line): it has no
/// normal, so no fluid side, and would put wall nodes with an undefined normal on the wall.
/// Tolerance: area below 1e-12 of the square of the surface's bounding-box diagonal.
void check_no_degenerate_triangles(const mesh::SurfaceMesh& surface,
                                   const std::filesystem::path& path) {
  if (surface.cells.cols() != 3 || surface.vertices.cols() != 3) return;
  const Eigen::Vector3d lower = surface.vertices.colwise().minCoeff().transpose();
  const Eigen::Vector3d upper = surface.vertices.colwise().maxCoeff().transpose();
  const double least_area = 1e-12 * (upper - lower).squaredNorm();
  for (Index c = 0; c < surface.cells.rows(); ++c) {
    const auto corner = [&](int k) -> Eigen::Vector3d {
      return surface.vertices.row(surface.cells(c, k)).transpose();
    };
    const double area = 0.5 * (corner(1) - corner(0)).cross(corner(2) - corner(0)).norm();
    if (!(area > least_area))
      input_error(
          "geometry file '{}': triangle {} (in file order) is degenerate, corners ({}), ({}), "
          "({}), area {:.3g} m²: it has no normal, so no fluid side. Expected triangles with an "
          "area; remove zero-area faces and merge duplicate vertices (e.g. MeshLab's \"Remove "
          "Zero Area Faces\")",
          path.string(), c + 1, fmt::join(corner(0), ", "), fmt::join(corner(1), ", "),
          fmt::join(corner(2), ", "), area);
  }
}

}  // namespace

mesh::SurfaceMesh read_surface_file(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path))
    input_error("geometry file '{}' does not exist (or is not a regular file)", path.string());
  if (std::optional<SurfaceFile> known = read_known_surface_format(path)) {
    if (known->skipped > 0)
      spdlog::warn("geometry file '{}': skipped {} faces that are points or lines", path.string(),
                   known->skipped);
    if (known->surface.cells.rows() == 0)
      input_error("geometry file '{}' holds no triangle; expected a triangulated surface",
                  path.string());
    merge_identical_vertices(known->surface);
    check_no_degenerate_triangles(known->surface, path);
    return std::move(known->surface);
  }
  Assimp::Importer importer;
  const aiScene* scene = import_scene(importer, path);
  Soup soup;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) append_mesh(*scene->mMeshes[i], soup);
  if (soup.skipped > 0)
    spdlog::warn("geometry file '{}': skipped {} faces that are points or lines", path.string(),
                 soup.skipped);
  if (soup.triangles.empty())
    input_error(
        "geometry file '{}' holds no triangle ({} meshes read); expected a closed "
        "triangulated surface",
        path.string(), scene->mNumMeshes);
  mesh::SurfaceMesh surface = to_surface(soup);
  merge_identical_vertices(surface);
  check_no_degenerate_triangles(surface, path);
  return surface;
}

void merge_identical_vertices(mesh::SurfaceMesh& surface) {
  std::map<std::vector<double>, Index> first_index;
  std::vector<Index> new_index(static_cast<std::size_t>(surface.vertices.rows()));
  std::vector<Index> kept;
  for (Index i = 0; i < surface.vertices.rows(); ++i) {
    std::vector<double> key(surface.vertices.row(i).data(),
                            surface.vertices.row(i).data() + surface.vertices.cols());
    auto [it, inserted] = first_index.emplace(std::move(key), static_cast<Index>(kept.size()));
    if (inserted) kept.push_back(i);
    new_index[static_cast<std::size_t>(i)] = it->second;
  }
  mesh::Coordinates merged(static_cast<Index>(kept.size()), surface.vertices.cols());
  for (std::size_t j = 0; j < kept.size(); ++j)
    merged.row(static_cast<Index>(j)) = surface.vertices.row(kept[j]);
  surface.vertices = std::move(merged);
  for (Index c = 0; c < surface.cells.rows(); ++c)
    for (Index k = 0; k < surface.cells.cols(); ++k)
      surface.cells(c, k) = new_index[static_cast<std::size_t>(surface.cells(c, k))];
}

void write_stl_ascii(const mesh::SurfaceMesh& surface, const std::filesystem::path& path,
                     std::string_view solid_name) {
  HM_ASSERT(surface.dim == 3 && surface.cells.cols() == 3, "STL needs a 3-D triangle surface");
  std::ofstream out(path);
  if (!out) input_error("cannot write STL file '{}'", path.string());
  out << fmt::format("solid {}\n", solid_name);
  for (Index c = 0; c < surface.cells.rows(); ++c) {
    const Eigen::Vector3d a = surface.vertices.row(surface.cells(c, 0)).transpose();
    const Eigen::Vector3d b = surface.vertices.row(surface.cells(c, 1)).transpose();
    const Eigen::Vector3d d = surface.vertices.row(surface.cells(c, 2)).transpose();
    Eigen::Vector3d n = (b - a).cross(d - a);
    if (n.norm() > 0) n.normalize();
    out << fmt::format("  facet normal {:.17g} {:.17g} {:.17g}\n    outer loop\n", n.x(), n.y(),
                       n.z());
    for (const auto& p : {a, b, d})
      out << fmt::format("      vertex {:.17g} {:.17g} {:.17g}\n", p.x(), p.y(), p.z());
    out << "    endloop\n  endfacet\n";
  }
  out << fmt::format("endsolid {}\n", solid_name);
  if (!out) input_error("writing STL file '{}' failed", path.string());
}

}  // namespace hm::geometry
