#pragma once
// Estimates made before meshing, so that a mesh that cannot be finished on this machine (a part
// meshed 1000 times too fine, a file in millimetres read as metres) is refused up front with the
// estimate and the size that fits, not killed hours later.
#include <string_view>

#include "mesh/types.hpp"

namespace hm::mesh {

/// Quadratic cells gmsh makes for a solid of `measure` (area [m²] in 2-D, volume [m³] in 3-D)
/// at element size `size` [m].
double estimated_structure_cells(int dim, double measure, double size);

/// Peak memory of fsi-modes [bytes] for a structure mesh of `cells` tri6 (2-D) / tet10 (3-D)
/// cells: assembly, the sparse factorisation ARPACK's shift-invert needs, and the modes.
double estimated_modes_memory(int dim, double cells);

/// Peak memory of fsi-mesh [bytes] for a wall of `cells` triangles (3-D) or segments (2-D).
double estimated_wall_memory(double cells);

/// Refuses (InputError naming `source`) a structure mesh of element size `size` [m] whose cell
/// estimate would not fit the memory fsi-modes has here; the message gives the cells, the bytes,
/// the memory available and the largest size that fits, and for a geometry file (`from_file`)
/// the unit hint. `extent` is the geometry's bounding-box size [m]. No-op when the memory
/// available is unknown.
void check_structure_estimate(int dim, double measure, double size, const Eigen::Vector3d& extent,
                              bool from_file, std::string_view source);

/// Refuses a wall that would have `cells` cells (see estimated_wall_memory) at edge length
/// `size` [m]; as check_structure_estimate, the hint naming `unit_key`.
void check_wall_estimate(int dim, double cells, double size, const Eigen::Vector3d& extent,
                         std::string_view unit_key, std::string_view source);

}  // namespace hm::mesh
