#pragma once
// Flow snapshots for ParaView: one HDF5 file per output time plus an XDMF (v2) index that is a
// temporal collection of all snapshots written so far.
//
// `<folder>/<stem>_<k:06>.h5` (k = 0, 1, ... in the order of write calls), root attribute
// `time` [s] (and `time_unit` = "s"), datasets (each with a `unit` attribute where it has one):
//   /points/position  n × 3 float64 [m]   (z = 0 in 2-D, so ParaView shows the plane)
//   /points/velocity  n × 3 float64 [m/s] (0 along z in 2-D)
//   /points/pressure  n     float64 [Pa], gauge
//   /points/type      n     uint8   PointType (0 interior, 1 surface, 2 wall, 3 isolated,
//                                   4 inactive)
//   /points/kind      n     uint8   PointKind (0 fluid, 1 wall node)
//   /walls/<name>/vertices  m × 3 float64 [m]
//   /walls/<name>/cells     c × D int64, 0-based (segments in 2-D, triangles in 3-D)
//   /walls/<name>/displacement, /walls/<name>/pressure   m × 3 [m], m [Pa], when given
// `<folder>/<stem>.xdmf`: GridType="Collection" CollectionType="Temporal", one spatial
// collection per snapshot holding the points (Polyvertex) and each wall (Polyline / Triangle).
//
// Kill-safety: each .h5 is written under a temporary name and renamed into place; the .xdmf is
// then rewritten the same way. A killed run leaves an index of every complete snapshot.
// The index lists the snapshots of this writer only: a new writer on the same folder starts again
// at k = 0 and overwrites, unless it resumes the earlier ones (a restart).
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "ldd/walls.hpp"

namespace hm::ldd {

/// Optional per-vertex fields of a wall in a snapshot (empty: not written): the displacement of
/// a flexible body from its reference shape [m] and the wall pressure [Pa].
template <int D>
struct WallFields {
  std::vector<Vec<D>> displacement;
  std::vector<double> pressure;
};

template <int D>
class SnapshotWriter {
 public:
  /// `folder` is created when missing; `stem` names the files ("flow" → flow_000000.h5,
  /// flow.xdmf).
  SnapshotWriter(std::filesystem::path folder, std::string stem);

  /// Writes snapshot k at time t [s]: the points and the walls, walls[i] named wall_names[i]
  /// (same length; names are unique HDF5 link names: no '/' or '.'-only names, InputError).
  /// Returns the path of the .h5 file. InputError when the files cannot be written.
  /// `fields`: empty, or one per wall (/walls/<name>/displacement, /walls/<name>/pressure).
  std::filesystem::path write(double t, const PointSet<D>& points,
                              std::span<const WallMesh<D>> walls,
                              std::span<const std::string> wall_names,
                              std::span<const WallFields<D>> fields = {});

  /// Takes over the first `count` snapshots already in the folder (a run restarted from a
  /// checkpoint): their times and point counts are read from the files, the walls are those
  /// given (the same scene). The next write is snapshot `count`. InputError when a file is
  /// missing or unreadable.
  void resume(std::size_t count, std::span<const WallMesh<D>> walls,
              std::span<const std::string> wall_names, std::span<const WallFields<D>> fields = {});

  std::filesystem::path xdmf_path() const;
  std::size_t count() const { return entries_.size(); }

 private:
  struct Entry {
    std::string file;  ///< .h5 file name, relative to the folder
    double time = 0.0;
    std::uint64_t points = 0;
    std::vector<std::string> walls;
    std::vector<std::uint64_t> wall_vertices, wall_cells;
    std::vector<char> wall_displacement, wall_pressure;  ///< per wall: field written
  };
  void write_index() const;
  std::filesystem::path folder_;
  std::string stem_;
  std::vector<Entry> entries_;
};

}  // namespace hm::ldd
