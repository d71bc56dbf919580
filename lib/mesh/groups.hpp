#pragma once
// Named groups of a structure mesh that do not come from gmsh physical groups: boxes from the
// scene, and the face names of primitives.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/options.hpp"
#include "mesh/types.hpp"

namespace hm::mesh {

/// xmin, xmax, ymin, ymax (and zmin, zmax in 3-D): the faces (edges in 2-D) of a primitive, as
/// flat box groups.
std::vector<BoxGroup> primitive_face_groups(const RectangleShape& rectangle);
std::vector<BoxGroup> primitive_face_groups(const BoxShape& box);

/// Adds each box group to node_groups (boundary nodes inside the box) and facet_groups (boundary
/// facets with every node inside). InputError when a name already exists or a box selects no
/// boundary node (the message gives the box and the model's extent).
void apply_box_groups(StructureMesh& mesh, std::span<const BoxGroup> groups,
                      std::string_view source);

/// Every group name of the mesh (node and facet groups), sorted, without repeats.
std::vector<std::string> group_names(const StructureMesh& mesh);

/// InputError naming the first requested group that is missing or empty, with the available ones.
void require_groups(const StructureMesh& mesh, std::span<const std::string> names,
                    std::string_view source);

}  // namespace hm::mesh
