#pragma once
// Internal helpers over the gmsh model of an open GmshSession (not part of the public API).
#include <cstddef>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mesh/types.hpp"

namespace hm::mesh::gmsh_model {

using DimTag = std::pair<int, int>;

/// gmsh element type codes (MSH format constants).
inline constexpr int line2 = 1, tri3 = 2, line3 = 8, tri6 = 9, tet10 = 11;

/// Physical groups by name (an unnamed group is named by its number), each with its (dim, tag)s.
std::map<std::string, std::vector<DimTag>> physical_groups();

/// Flat node tags of all elements of `type` in one entity (tag −1: all entities of that type).
std::vector<std::size_t> element_nodes(int type, int entity_tag = -1);

/// Coordinates of the given node tags, in that order, as rows of an n × dim matrix.
Coordinates node_coordinates(const std::vector<std::size_t>& tags, int dim);

/// Distinct tags in first-appearance order, and tag → position.
struct Numbering {
  std::vector<std::size_t> tags;
  std::unordered_map<std::size_t, Index> index;
};
Numbering number_nodes(const std::vector<std::size_t>& flat_tags);

/// Geometry points on the closure of the entities (points of curves, surfaces, volumes).
std::vector<DimTag> points_of(const std::vector<DimTag>& entities);

/// Entities of dimension < model dimension inside a box grown by `tolerance` (OCC pads boxes by
/// its own tolerance, so `tolerance` must be ≥ 1e-6 m for OCC models).
std::vector<DimTag> entities_in_box(const double (&min)[3], const double (&max)[3],
                                    double tolerance, int below_dim);

}  // namespace hm::mesh::gmsh_model
