#pragma once
// Walls as surface meshes (spec §1.5): segments in 2-D, triangles in 3-D, normals into the fluid
// (mesh::SurfaceMesh convention: triangle (a,b,c) → (b−a)×(c−a); segment (a,b) → ẑ×(b−a)).
// An AABB tree (own, median split, refit in O(n) when the mesh moves) answers closest point,
// signed distance (sign from the angle-weighted pseudo-normal of the closest feature: face, edge
// or vertex; positive on the fluid side; unsigned beyond an open end of the mesh, where there is
// no inside) and segment crossing. Wall nodes (CHOICE-B, §0.2) are
// sampled on the elements at spacing ≤ FlowOptions::wall_node_spacing·dx and follow the mesh
// through their barycentrics.
#include <array>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ldd/neighbours.hpp"
#include "mesh/types.hpp"

namespace hm::ldd {

template <int D>
struct ClosestPoint {
  Vec<D> point = Vec<D>::Zero();        ///< closest point on the wall [m]
  Index element = -1;                   ///< element holding it
  Vec<D> barycentric = Vec<D>::Zero();  ///< in that element (exact zeros on edges/vertices)
  double signed_distance = 0.0;         ///< [m], > 0 on the fluid side
  Vec<D> normal = Vec<D>::Zero();       ///< pseudo-normal of the closest feature, unit
};

template <int D>
class WallMesh {
 public:
  /// `name` appears in error messages. A `thin` wall (baffle, gate) is wetted on both sides:
  /// neighbour pairs crossing it are cut and its nodes are sampled on both sides.
  WallMesh(const mesh::SurfaceMesh& surface, std::string name, bool thin = false);
  ~WallMesh();
  WallMesh(WallMesh&&) noexcept;
  WallMesh& operator=(WallMesh&&) noexcept;

  const std::string& name() const { return name_; }
  bool thin() const { return thin_; }
  /// A solid body the fluid flows around (a flexible gate, a plate): neighbour pairs crossing
  /// it are cut like those through a thin wall, so the two faces of a body thinner than the
  /// support h do not see each other's fluid.
  bool solid() const { return solid_; }
  void set_solid(bool solid) { solid_ = solid; }
  /// Whether this wall's nodes in tension (p < 0) are released (made Dirichlet p = 0) when the
  /// flow's release_wall_tension is on (the default). A flexible body keeps its tension: the
  /// release is a contact nonlinearity that breaks the coupling's sub-iterations.
  bool releases_tension() const { return releases_tension_; }
  void set_releases_tension(bool release) { releases_tension_ = release; }
  /// Whether add_wall_nodes thins the nodes of this wall to the node spacing where its mesh is
  /// finer than that (a detailed STL part): off by default; the scene's rigid walls turn it on.
  /// A flexible body's surface keeps a node at every vertex (its answers were validated so).
  bool thins_dense_nodes() const { return thins_dense_nodes_; }
  void set_thins_dense_nodes(bool thin_out) { thins_dense_nodes_ = thin_out; }
  Index element_count() const { return static_cast<Index>(cells_.size()); }
  const std::vector<Vec<D>>& vertices() const { return x_; }
  const std::array<Index, D>& element(Index e) const { return cells_[e]; }
  Vec<D> lower() const;  ///< bounding box [m]
  Vec<D> upper() const;

  /// New vertex positions [m], velocities [m/s] and accelerations [m/s²] (same count and order
  /// as the vertices; velocity/acceleration may be empty = zero); refits the tree.
  void move(std::span<const Vec<D>> x, std::span<const Vec<D>> v = {},
            std::span<const Vec<D>> a = {});

  Vec<D> vertex_velocity(Index v) const { return v_[static_cast<std::size_t>(v)]; }  ///< [m/s]
  Vec<D> vertex_acceleration(Index v) const { return a_[static_cast<std::size_t>(v)]; }
  Vec<D> point_at(Index e, const Vec<D>& barycentric) const;
  Vec<D> velocity_at(Index e, const Vec<D>& barycentric) const;
  Vec<D> acceleration_at(Index e, const Vec<D>& barycentric) const;
  /// Unit normal at a point of element e: the element's, or the pseudo-normal of the edge or
  /// vertex when barycentric coordinates are exactly zero.
  Vec<D> normal_at(Index e, const Vec<D>& barycentric) const;

  ClosestPoint<D> closest(const Vec<D>& x) const;
  /// Whether the open segment a→b crosses an element (touching at an end does not count).
  bool crosses(const Vec<D>& a, const Vec<D>& b) const;

  /// Signed volume (3-D) or area (2-D) the wall encloses [m³ or m²]: positive when its normals
  /// point out of it (the fluid outside: an obstacle), negative for a container. Meaningful for
  /// a closed wall only (open_boundary_count() == 0).
  double enclosed_measure() const;

  /// Open boundary of the mesh: edges used by one triangle (3-D) or vertices used by one
  /// segment (2-D), plus non-manifold ones. 0 for a closed surface.
  Index open_boundary_count() const;
  /// Throws InputError naming the wall, `purpose`, the count and a location of the first gap.
  void require_closed(std::string_view purpose) const;

 private:
  struct Tree;
  void compute_normals();
  void mark_open_features();
  bool on_open_end(Index e, const Vec<D>& barycentric) const;
  std::string name_;
  bool thin_ = false;
  bool solid_ = false;
  bool releases_tension_ = true;
  bool thins_dense_nodes_ = false;
  std::vector<Vec<D>> x_, v_, a_;
  std::vector<std::array<Index, D>> cells_;
  std::vector<Vec<D>> face_normal_, vertex_normal_;
  std::vector<std::pair<std::uint64_t, Vec<D>>> edge_normal_;  // 3-D: sorted by edge key
  std::vector<std::uint8_t> open_vertex_;                      // vertex on an open end
  std::vector<std::uint64_t> open_edges_;                      // 3-D: open edges, sorted
  std::unique_ptr<Tree> tree_;
};

/// Samples wall nodes on every element of `wall` at spacing ≤ `spacing` [m] (vertices and shared
/// edges once) and appends them to `points` with body index `body`; a thin wall gets a second set
/// with the opposite normal. Sets their velocity and acceleration from the wall. Returns the count.
/// A wall that thins_dense_nodes() and whose median edge is shorter than spacing/2 keeps, of
/// these sites in order, only those farther than `spacing` from every kept site whose normal is
/// within 60° of theirs (the two faces of a thin flange keep their own nodes): a detailed mesh
/// gives nodes at about the spacing, not one at every vertex (an STL bracket of 7 290 vertices
/// at 0.5 mm gave 11× the nodes of its area at dx = 2 mm, and the PPE 4 017 iterations).
template <int D>
Index add_wall_nodes(PointSet<D>& points, const WallMesh<D>& wall, int body, double spacing);

/// Moves every wall node to its host element's current position and sets its normal, velocity
/// and acceleration (walls[body] is the node's wall).
template <int D>
void update_wall_nodes(PointSet<D>& points, std::span<const WallMesh<D>> walls);

/// Quadrature weight ω per point for the operators (compute_operators): 1 for a fluid point; for
/// a wall node the wall measure it stands for in units of dx^(D−1), ω_i = ∫W dS / (dx^(D−1)
/// Σ_j W_ij) over the wall nodes j of its body not on its other side (i included, n_i·n_j ≥ −1/2:
/// the adjacent face at a corner or an edge counts, so the weight stays ≈ 1 there at spacing dx),
/// ∫W dS = 2h/3 (2-D) or πh²/7 (3-D), h = radius [m], the sum over every wall node within h
/// (its own search, not the operators' lists, which have lost the pairs cut through walls): ≈ 1 at
/// spacing dx, s/dx at spacing s < dx. Without it a wall sampled at dx/32 outweighed its fluid 20:1
/// in the moment matrix of its nodes, which then counted as degenerate (λ_min(M) < λ_c) and were
/// regularised; n·∇p of their Neumann rows came out at half its value and the added mass of a wall
/// at +80 %.
template <int D>
std::vector<double> wall_node_weights(const PointSet<D>& points, double radius, double dx);

/// Cuts neighbour pairs through walls (§1.5): pairs from any wall node to a point behind it
/// (r_ij·n_i < 0: the other face of a block or gate thinner than h); pairs whose segment crosses
/// a thin wall or a solid body, tested only when both points are within h of it; every pair of
/// a wall node buried in a solid body or facing into the wall a solid body stands on (the floor
/// under a gate and the gate's foot). Returns the number of directed pairs removed.
template <int D>
std::int64_t cut_pairs_through_thin_walls(Neighbours& neighbours, const PointSet<D>& points,
                                          std::span<const WallMesh<D>> walls);

}  // namespace hm::ldd
