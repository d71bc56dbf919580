#pragma once
// HDF5 artefacts: the only way stages talk to each other. A writer knows its schema and refuses
// datasets the schema does not declare; it stamps provenance (schema, stage, tool version, time,
// resolved parameters, input hashes) and writes atomically. A reader checks schema name and
// version and the presence and shape of required datasets before anything is read, and names the
// file and the dataset in every error.
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "io/atomic_file.hpp"
#include "io/schema.hpp"

namespace hm::io {

using MatrixRM = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using IndexMatrixRM = Eigen::Matrix<std::int64_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using Dims = std::vector<std::uint64_t>;

/// One input of a stage: its role ("scene", "mesh", "geometry", ...), path and content hash.
struct InputRecord {
  std::string role;
  std::string path;
  std::string sha256;
};
/// Hashes the file at `path` (InputError if unreadable).
InputRecord input_record(std::string role, const std::filesystem::path& path);

struct Provenance {
  std::string schema;
  int schema_version = 0;
  std::string stage;
  std::string tool_version;
  std::string created_utc;
  std::string parameters;  ///< canonical TOML of the resolved parameters
  std::string parameters_sha256;
  std::string status;
  std::vector<InputRecord> inputs;
};

class Hdf5File;  // RAII handle, defined in artefact.cpp

class ArtefactWriter {
 public:
  ArtefactWriter(const std::filesystem::path& output, const SchemaSpec& schema, std::string stage,
                 std::string parameters, std::vector<InputRecord> inputs);
  ~ArtefactWriter();
  ArtefactWriter(const ArtefactWriter&) = delete;
  ArtefactWriter& operator=(const ArtefactWriter&) = delete;

  /// Writes a float64 dataset of the given dims (row-major data, product of dims values).
  void write(const std::string& path, const double* data, const Dims& dims);
  void write(const std::string& path, const std::int64_t* data, const Dims& dims);
  void write(const std::string& path, const MatrixRM& matrix);
  void write(const std::string& path, const IndexMatrixRM& matrix);
  void write(const std::string& path, const std::vector<double>& values);
  void write(const std::string& path, const std::vector<std::int64_t>& values);
  void write_vector(const std::string& path, const Eigen::VectorXd& values);  ///< 1-D

  /// Extra root attributes (solver statistics, invariants). "status" defaults to "ok".
  void set_attribute(const std::string& name, const std::string& value);
  void set_attribute(const std::string& name, double value);
  void set_attribute(const std::string& name, std::int64_t value);

  /// Checks every required dataset was written, closes the file and moves it into place.
  void commit();

 private:
  const DatasetSpec& declared(const std::string& path, DType type, const Dims& dims);
  SchemaSpec schema_;  // a copy: callers may pass a temporary
  AtomicOutput output_;
  std::unique_ptr<Hdf5File> file_;
  std::map<std::string, std::uint64_t> extents_;  // symbol → extent, for shape consistency
  std::vector<std::string> written_;
};

/// Reads an artefact after checking schema name, version, required datasets and their shapes.
class ArtefactReader {
 public:
  ArtefactReader(const std::filesystem::path& path, const SchemaSpec& expected);
  ~ArtefactReader();
  ArtefactReader(ArtefactReader&&) noexcept;

  const Provenance& provenance() const { return provenance_; }
  const std::filesystem::path& path() const { return path_; }
  /// Extent of a symbolic dimension ("n_nodes", "dim", ...) as found in this file.
  std::uint64_t extent(const std::string& symbol) const;
  bool has(const std::string& dataset) const;
  /// Children names of a group (e.g. the node groups), sorted.
  std::vector<std::string> children(const std::string& group) const;

  MatrixRM read_matrix(const std::string& dataset) const;             ///< 1-D read as a column
  IndexMatrixRM read_indices(const std::string& dataset) const;       ///< 1-D read as a column
  std::vector<double> read_values(const std::string& dataset) const;  ///< any rank, flattened
  Eigen::VectorXd read_vector(const std::string& dataset) const;      ///< any rank, flattened
  /// A dataset stacked along its first axis ([n, ...], e.g. [mode][vertex][c]) as a matrix with
  /// one column per leading index, each the flattened rest.
  Eigen::MatrixXd read_columns(const std::string& dataset) const;
  std::vector<std::int64_t> read_index_values(const std::string& dataset) const;
  Dims dims(const std::string& dataset) const;
  std::optional<std::string> string_attribute(const std::string& name) const;
  std::optional<double> number_attribute(const std::string& name) const;

 private:
  std::filesystem::path path_;
  std::unique_ptr<Hdf5File> file_;
  Provenance provenance_;
  std::map<std::string, std::uint64_t> extents_;
};

/// What fsi-inspect shows of any artefact.
struct DatasetSummary {
  std::string path;
  std::string dtype;
  Dims dims;
  std::string unit;
  std::string description;
  std::vector<double> values;  ///< numeric datasets with at most `max_values` entries
};
struct RootAttribute {
  std::string name;
  std::string text;  ///< strings verbatim, numbers formatted
  std::optional<double> number;
  bool integer = false;  ///< stored as an integer type
};
struct ArtefactSummary {
  Provenance provenance;
  std::vector<RootAttribute> attributes;  ///< every root attribute
  std::vector<DatasetSummary> datasets;
};
/// Reads any artefact (validating it against its own schema when known). InputError when the file
/// is missing, not HDF5, truncated, has no schema attribute or fails its schema's checks.
ArtefactSummary summarise(const std::filesystem::path& path, std::size_t max_values = 1000);

/// The provenance of any artefact (no schema checks); InputError when it is not one.
Provenance read_artefact_provenance(const std::filesystem::path& path);

/// Why `output` would not be what a stage run now would write: "" when it is up to date, else
/// the reason. Up to date means: it is an artefact of `stage`, written by this tool version, with
/// the same canonical parameters, and every recorded input (except the scene file itself, whose
/// relevant content the parameters already capture) still has the recorded SHA-256 content hash;
/// `inputs` (role → path, e.g. "mesh" → mesh.h5) must be the recorded paths. File timestamps play
/// no part: touching an input changes nothing, editing one byte does.
std::string staleness(const std::filesystem::path& output, const std::string& stage,
                      const std::string& parameters,
                      const std::map<std::string, std::string>& inputs);

/// UTC now as ISO 8601 ("2026-11-22T01:48:28Z").
std::string utc_now_iso8601();

}  // namespace hm::io
