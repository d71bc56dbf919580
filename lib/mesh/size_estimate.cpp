#include "mesh/size_estimate.hpp"

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/memory.hpp"

namespace hm::mesh {
namespace {

/// Cells per (measure / size^dim) gmsh 4.8's default algorithms give at Mesh.MeshSizeMax = size,
/// measured through fsi-mesh: a 0.5 m square at 10 / 5 / 2.5 mm: 5 832 / 23 238 / 92 558 tri6
/// (2.33 / 2.32 / 2.31); a box: 5.0 tet10 per V/h³.
constexpr double cells_per_measure_2d = 2.32;
constexpr double cells_per_measure_3d = 5.0;

/// fsi-modes' peak resident memory as a·cells^p, from measured runs (5 modes, /usr/bin/time):
///   3-D: 4 920 / 23 006 tet10 cells: 260 MB / 1.47 GB, the power law through both;
///   2-D (the gate's scene on a 0.5 m square): 5 832 / 23 238 / 92 558 tri6 cells: 84 / 289 /
///   1 001 MB; the per-cell memory of the largest (10.8 kB) taken as linear (the small runs
///   carry the process's fixed share; a sparse factor in 2-D grows as n log n, so not less).
constexpr double modes_a_3d = 18570.0, modes_p_3d = 1.123;
constexpr double modes_a_2d = 10820.0, modes_p_2d = 1.0;

/// A wall cell's share of fsi-mesh's peak while refining [bytes]: the refined copy (vertices
/// 12 B and cells 24 B a triangle), the level before it, the edge-midpoint map of the split
/// (about 1.5 edges a triangle, 64 B a map node) and the artefact's write buffer. An estimate
/// from the data structures, rounded up.
constexpr double bytes_per_wall_cell = 256.0;

/// Memory the stage may plan on: 90 % of what the machine has available (0 when unknown).
double usable_memory() {
  return 0.9 * available_memory();
}

std::string extent_text(const Eigen::Vector3d& extent, int dim) {
  return dim == 2 ? fmt::format("{:.4g} × {:.4g} m", extent.x(), extent.y())
                  : fmt::format("{:.4g} × {:.4g} × {:.4g} m", extent.x(), extent.y(), extent.z());
}

std::string unit_hint(bool from_file, std::string_view key) {
  if (!from_file) return "";
  return fmt::format(
      ". If the file's lengths are not metres (a CAD or STL export in millimetres), declare "
      "its unit: {} = \"mm\" (or \"cm\", \"in\", \"ft\")",
      key);
}

/// The largest element size (from `size` up, in 5 % steps) whose memory fits `have`.
template <class Memory>
double largest_size_that_fits(double size, double have, Memory memory_at) {
  double fit = size;
  while (memory_at(fit) > have && fit < 1e6 * size) fit *= 1.05;
  return fit;
}

}  // namespace

double estimated_structure_cells(int dim, double measure, double size) {
  return (dim == 2 ? cells_per_measure_2d : cells_per_measure_3d) * measure / std::pow(size, dim);
}

double estimated_modes_memory(int dim, double cells) {
  return dim == 2 ? modes_a_2d * std::pow(cells, modes_p_2d)
                  : modes_a_3d * std::pow(cells, modes_p_3d);
}

double estimated_wall_memory(double cells) {
  return bytes_per_wall_cell * cells;
}

void check_structure_estimate(int dim, double measure, double size, const Eigen::Vector3d& extent,
                              bool from_file, std::string_view source) {
  const double have = usable_memory();
  const double cells = estimated_structure_cells(dim, measure, size);
  const double need = estimated_modes_memory(dim, cells);
  if (have <= 0.0 || need <= have) return;
  const double fit = largest_size_that_fits(size, have, [&](double h) {
    return estimated_modes_memory(dim, estimated_structure_cells(dim, measure, h));
  });
  input_error(
      "{}: mesh size {} m (structure.mesh.size) gives about {:.3g} {} cells for a solid of "
      "{:.4g} {} spanning {}; fsi-modes would need about {:.3g} GiB and this machine has "
      "{:.3g} GiB available. The smallest size that fits is about {:.3g} m{}",
      source, size, cells, dim == 2 ? "tri6" : "tet10", measure, dim == 2 ? "m²" : "m³",
      extent_text(extent, dim), gibibytes(need), gibibytes(have / 0.9), fit,
      unit_hint(from_file, "structure.geometry.length_unit"));
}

void check_wall_estimate(int dim, double cells, double size, const Eigen::Vector3d& extent,
                         std::string_view unit_key, std::string_view source) {
  const double have = usable_memory();
  const double need = estimated_wall_memory(cells);
  if (have <= 0.0 || need <= have) return;
  // Cells grow as size^-(dim-1).
  const double fit = largest_size_that_fits(size, have, [&](double h) {
    return estimated_wall_memory(cells * std::pow(size / h, dim - 1));
  });
  input_error(
      "{}: mesh size {} m gives about {:.3g} wall {} spanning {}, which need about {:.3g} GiB; "
      "this machine has {:.3g} GiB available. The smallest mesh_size that fits is about {:.3g} "
      "m{}",
      source, size, cells, dim == 2 ? "segments" : "triangles", extent_text(extent, dim),
      gibibytes(need), gibibytes(have / 0.9), fit, unit_hint(!unit_key.empty(), unit_key));
}

}  // namespace hm::mesh
