#pragma once
// Shape quality of a structure mesh. gmsh 4.8 has no getElementQualities, so the measure is our
// own: the normalised radius ratio of each cell's corner simplex,
//   triangle: q = 2 r_in / R_circ,  tetrahedron: q = 3 r_in / R_circ,
// 1 for the equilateral simplex, → 0 for needles, caps and slivers (a flat tet with four
// well-spaced corners has q ≈ 0 although its edge ratios look fine).
#include <string>
#include <string_view>

#include "geometry/bounding_box.hpp"
#include "mesh/types.hpp"

namespace hm::mesh {

struct MeshQuality {
  int dim = 3;
  Index cells = 0;
  Index nodes = 0;
  double min_quality = 0.0;
  double mean_quality = 0.0;
  Index worst_cell = -1;
  double sliver_threshold = 0.0;
  Index slivers = 0;     ///< cells with quality below sliver_threshold
  double measure = 0.0;  ///< total area [m²] (2-D) or volume [m³] (3-D) of the corner simplices
  geometry::BoundingBox box;
};

/// Radius-ratio quality of one cell (see above) from its corner nodes.
double cell_quality(const StructureMesh& mesh, Index cell);

/// Area (2-D) or volume (3-D) of one cell's corner simplex; exact for straight-sided cells.
double cell_measure(const StructureMesh& mesh, Index cell);

MeshQuality assess_quality(const StructureMesh& mesh, double sliver_threshold);

/// Logs the quality summary (info) and the extent; a warning when there are slivers.
void report_quality(const MeshQuality& quality, std::string_view source);

}  // namespace hm::mesh
