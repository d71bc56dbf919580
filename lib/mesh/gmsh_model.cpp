#include "mesh/gmsh_model.hpp"

#include <algorithm>

#include <gmsh.h>

#include "core/errors.hpp"

namespace hm::mesh::gmsh_model {

std::map<std::string, std::vector<DimTag>> physical_groups() {
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups);
  std::map<std::string, std::vector<DimTag>> named;
  for (const auto& [dim, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    if (name.empty()) name = std::to_string(tag);
    named[name].emplace_back(dim, tag);
  }
  return named;
}

std::vector<std::size_t> element_nodes(int type, int entity_tag) {
  std::vector<std::size_t> element_tags, node_tags;
  gmsh::model::mesh::getElementsByType(type, element_tags, node_tags, entity_tag);
  return node_tags;
}

Coordinates node_coordinates(const std::vector<std::size_t>& tags, int dim) {
  std::vector<std::size_t> all_tags;
  std::vector<double> xyz, uvw;
  gmsh::model::mesh::getNodes(all_tags, xyz, uvw, -1, -1, false, false);
  std::unordered_map<std::size_t, std::size_t> position;
  position.reserve(all_tags.size());
  for (std::size_t i = 0; i < all_tags.size(); ++i) position.emplace(all_tags[i], i);
  Coordinates out(static_cast<Index>(tags.size()), dim);
  for (std::size_t i = 0; i < tags.size(); ++i) {
    const auto it = position.find(tags[i]);
    HM_ASSERT(it != position.end(), "gmsh node {} has no coordinates", tags[i]);
    for (int k = 0; k < dim; ++k) out(static_cast<Index>(i), k) = xyz[3 * it->second + k];
  }
  return out;
}

Numbering number_nodes(const std::vector<std::size_t>& flat_tags) {
  Numbering n;
  for (std::size_t tag : flat_tags)
    if (n.index.emplace(tag, static_cast<Index>(n.tags.size())).second) n.tags.push_back(tag);
  return n;
}

std::vector<DimTag> points_of(const std::vector<DimTag>& entities) {
  std::vector<DimTag> points;
  for (const auto& e : entities)
    if (e.first == 0) points.push_back(e);
  std::vector<DimTag> higher;
  std::copy_if(entities.begin(), entities.end(), std::back_inserter(higher),
               [](const DimTag& e) { return e.first > 0; });
  if (!higher.empty()) {
    gmsh::vectorpair boundary;
    gmsh::model::getBoundary(higher, boundary, false, false, true);
    for (const auto& b : boundary)
      if (b.first == 0) points.push_back(b);
  }
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

std::vector<DimTag> entities_in_box(const double (&min)[3], const double (&max)[3],
                                    double tolerance, int below_dim) {
  std::vector<DimTag> found;
  for (int d = 0; d < below_dim; ++d) {
    gmsh::vectorpair in_box;
    gmsh::model::getEntitiesInBoundingBox(min[0] - tolerance, min[1] - tolerance,
                                          min[2] - tolerance, max[0] + tolerance,
                                          max[1] + tolerance, max[2] + tolerance, in_box, d);
    found.insert(found.end(), in_box.begin(), in_box.end());
  }
  return found;
}

}  // namespace hm::mesh::gmsh_model
