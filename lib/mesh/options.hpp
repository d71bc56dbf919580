#pragma once
// What the structure and wall meshers are asked for: the geometry primitives a scene can describe
// directly, named groups given as bounding boxes, and the meshing options. Lengths in metres.
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace hm::mesh {

/// 2-D rectangle in the xy plane: [origin, origin + size].
struct RectangleShape {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  Eigen::Vector2d size = Eigen::Vector2d::Ones();
};

/// 3-D axis-aligned box (the scene's `box` and `plate`): [origin, origin + size].
struct BoxShape {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d size = Eigen::Vector3d::Ones();
};

/// A named group selected by an axis-aligned box [min, max] (in 2-D z is ignored): every boundary
/// facet whose nodes all lie inside, and every boundary node inside. The box is grown by
/// 1e-6 × the model's bounding-box diagonal, so a flat box (min.x == max.x) selects a face.
struct BoxGroup {
  std::string name;
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
};

/// Relative tolerance of box groups (times the bounding-box diagonal of the model).
inline constexpr double box_group_tolerance = 1e-6;

struct MeshOptions {
  int dim = 3;        ///< 2: tri6 cells in the xy plane; 3: tet10 cells
  double size = 0.0;  ///< target element size [m] (gmsh Mesh.MeshSizeMax); required > 0 except
                      ///< for .geo scripts, which may set their own sizes
  /// Smaller target sizes [m] near named groups (a physical group of a .geo script, a box group,
  /// or a primitive's face name). Set on the group's geometry points; gmsh grades the size away
  /// from them. A size above `size` has no effect (the global size caps it).
  std::map<std::string, double> group_sizes;
  std::vector<BoxGroup> box_groups;          ///< groups defined by boxes, for any source
  std::vector<std::string> required_groups;  ///< names that must exist and be non-empty
  int order = 2;                             ///< element order; only 2 (tri6 / tet10) is supported
  int threads = 1;                           ///< gmsh General.NumThreads
  bool verbose = false;                      ///< gmsh messages on the terminal
  double sliver_threshold = 0.1;  ///< cells with radius-ratio quality below this are slivers
  /// Metres per length unit of a geometry file (CAD, STL/OBJ/PLY): 0.001 for a file in
  /// millimetres. A .geo script is in metres (1 only).
  double length_scale = 1.0;
};

/// Fluid walls: a linear surface (triangles in 3-D, segments in 2-D) as the fluid sees it.
/// Normal convention of SurfaceMesh cells (see types.hpp): 3-D triangle (a,b,c) has normal
/// (b−a)×(c−a); 2-D segment (a,b) has normal ẑ×(b−a) (its left side). Walls of primitives point
/// into the primitive's interior (the fluid).
struct WallOptions {
  int dim = 3;
  double size = 0.0;  ///< target edge length [m], > 0
  /// Which faces of a primitive (xmin, xmax, ymin, ymax, zmin, zmax), or which physical groups of a
  /// .geo script; empty = all.
  std::vector<std::string> faces;
  bool flip_normals =
      false;  ///< reverse every cell (for a .geo or an open STL given the other way)
  int threads = 1;
  bool verbose = false;
  /// Metres per length unit of a triangle file (STL, OBJ, PLY); a .geo script is in metres.
  double length_scale = 1.0;
  std::string length_unit_key = "length_unit";  ///< the scene key of the unit, for messages
};

}  // namespace hm::mesh
