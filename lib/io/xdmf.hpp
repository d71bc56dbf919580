#pragma once
// XDMF (v2) sidecars that make an HDF5 artefact openable in ParaView. The XML only references
// datasets of the artefact (no data is copied); it is written atomically next to it.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace hm::io {

struct XdmfField {
  std::string name;
  bool on_nodes = true;                     ///< Center="Node" (else "Cell")
  std::string dataset;                      ///< HDF5 path in the artefact
  std::vector<std::uint64_t> dataset_dims;  ///< full dims of `dataset`
  /// For one slice of a stacked dataset ([n, rows, cols]): the index along the first axis.
  std::int64_t slice = -1;
};

struct XdmfGrid {
  std::string name;
  int dim = 3;                ///< 2 → Geometry "XY", 3 → "XYZ"
  std::string topology;       ///< "Tri_6", "Tet_10", "Triangle", "Polyline", ...
  std::string cells_dataset;  ///< n_cells × nodes_per_cell, 0-based, XDMF node order
  std::uint64_t cells = 0, nodes_per_cell = 0;
  std::string nodes_dataset;  ///< n_nodes × dim [m]
  std::uint64_t nodes = 0;
  std::vector<XdmfField> fields;
};

/// Writes `xdmf_path` describing `grids` stored in `h5_path` (referenced by file name, so the
/// two files may be moved together).
void write_xdmf(const std::filesystem::path& xdmf_path, const std::filesystem::path& h5_path,
                const std::vector<XdmfGrid>& grids);

}  // namespace hm::io
