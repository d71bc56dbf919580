#include "mesh/groups.hpp"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/text.hpp"
#include "geometry/bounding_box.hpp"

namespace hm::mesh {
namespace {

constexpr std::array<std::string_view, 3> axis_names{"x", "y", "z"};

std::vector<BoxGroup> face_groups(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int dim) {
  std::vector<BoxGroup> groups;
  for (int axis = 0; axis < dim; ++axis) {
    BoxGroup low{fmt::format("{}min", axis_names[axis]), lo, hi};
    low.max[axis] = lo[axis];
    BoxGroup high{fmt::format("{}max", axis_names[axis]), lo, hi};
    high.min[axis] = hi[axis];
    groups.push_back(low);
    groups.push_back(high);
  }
  return groups;
}

Eigen::Vector3d node_point(const StructureMesh& m, Index node) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  p.head(m.dim) = m.nodes.row(node).transpose();
  return p;
}

std::string box_text(const BoxGroup& g) {
  return fmt::format("[({:.6g}, {:.6g}, {:.6g}), ({:.6g}, {:.6g}, {:.6g})]", g.min.x(), g.min.y(),
                     g.min.z(), g.max.x(), g.max.y(), g.max.z());
}

}  // namespace

std::vector<BoxGroup> primitive_face_groups(const RectangleShape& r) {
  const Eigen::Vector3d lo(r.origin.x(), r.origin.y(), 0.0);
  const Eigen::Vector3d hi(r.origin.x() + r.size.x(), r.origin.y() + r.size.y(), 0.0);
  return face_groups(lo, hi, 2);
}

std::vector<BoxGroup> primitive_face_groups(const BoxShape& b) {
  return face_groups(b.origin, b.origin + b.size, 3);
}

void apply_box_groups(StructureMesh& mesh, std::span<const BoxGroup> groups,
                      std::string_view source) {
  geometry::BoundingBox model = geometry::bounding_box(mesh.nodes);
  const double tolerance = box_group_tolerance * model.diagonal();
  for (const BoxGroup& g : groups) {
    if (mesh.node_groups.count(g.name) > 0 || mesh.facet_groups.count(g.name) > 0)
      input_error("{}: group '{}' is defined twice (a box group has the name of an existing group)",
                  source, g.name);
    geometry::BoundingBox box{g.min, g.max};
    if (mesh.dim == 2) box.min.z() = box.max.z() = 0.0;
    auto inside = [&](Index node) { return box.contains(node_point(mesh, node), tolerance); };
    std::set<Index> nodes;
    std::vector<Index> facets;
    for (Index f = 0; f < mesh.facets.rows(); ++f) {
      bool all_inside = true;
      for (Index k = 0; k < mesh.facets.cols(); ++k) {
        const Index n = mesh.facets(f, k);
        if (inside(n))
          nodes.insert(n);
        else
          all_inside = false;
      }
      if (all_inside) facets.push_back(f);
    }
    if (nodes.empty())
      input_error("{}: group '{}' (box {}) contains no boundary node; the model spans {}", source,
                  g.name, box_text(g), geometry::describe(model));
    mesh.node_groups[g.name].assign(nodes.begin(), nodes.end());
    if (!facets.empty()) mesh.facet_groups[g.name] = std::move(facets);
  }
}

std::vector<std::string> group_names(const StructureMesh& mesh) {
  std::set<std::string> names;
  for (const auto& [name, nodes] : mesh.node_groups) names.insert(name);
  for (const auto& [name, facets] : mesh.facet_groups) names.insert(name);
  return {names.begin(), names.end()};
}

void require_groups(const StructureMesh& mesh, std::span<const std::string> names,
                    std::string_view source) {
  for (const std::string& name : names) {
    const auto it = mesh.node_groups.find(name);
    if (it != mesh.node_groups.end() && !it->second.empty()) continue;
    const auto available = group_names(mesh);
    const std::string hint = closest_match(name, available);
    input_error("{}: group '{}' {}; available groups: [{}]{}", source, name,
                it == mesh.node_groups.end() ? "does not exist" : "is empty", join(available, ", "),
                hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint));
  }
}

}  // namespace hm::mesh
