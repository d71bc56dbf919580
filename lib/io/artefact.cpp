#include "io/artefact.hpp"

#include <hdf5.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <numeric>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/version.hpp"
#include "io/hash.hpp"
#include "io/seal.hpp"

namespace hm::io {

// ---- RAII handles -------------------------------------------------------------------------------

namespace {

void silence_hdf5_errors() {
  static const bool done = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = -1; }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

Handle dataspace(const Dims& dims) {
  std::vector<hsize_t> extents(dims.begin(), dims.end());
  return {H5Screate_simple(static_cast<int>(extents.size()), extents.data(), nullptr), H5Sclose};
}

Handle string_type(std::size_t length) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), std::max<std::size_t>(length, 1));
  H5Tset_strpad(type.get(), H5T_STR_NULLTERM);
  return type;
}

void write_string_attribute(hid_t object, const std::string& name, const std::string& value) {
  Handle type = string_type(value.size() + 1);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
  Handle attribute(
      H5Acreate2(object, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
  HM_ASSERT(attribute.valid(), "cannot create attribute {}", name);
  H5Awrite(attribute.get(), type.get(), value.c_str());
}

template <typename T>
void write_number_attribute(hid_t object, const std::string& name, T value, hid_t memtype) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
  Handle attribute(H5Acreate2(object, name.c_str(), memtype, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose);
  HM_ASSERT(attribute.valid(), "cannot create attribute {}", name);
  H5Awrite(attribute.get(), memtype, &value);
}

std::optional<std::string> read_string_attribute(hid_t object, const std::string& name) {
  if (H5Aexists(object, name.c_str()) <= 0) return std::nullopt;
  Handle attribute(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose);
  Handle type(H5Aget_type(attribute.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING) return std::nullopt;
  if (H5Tis_variable_str(type.get()) > 0) {
    char* text = nullptr;
    Handle memtype(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(memtype.get(), H5T_VARIABLE);
    if (H5Aread(attribute.get(), memtype.get(), &text) < 0 || !text) return std::nullopt;
    std::string out(text);
    H5free_memory(text);
    return out;
  }
  const std::size_t size = H5Tget_size(type.get());
  std::string buffer(size + 1, '\0');
  Handle memtype = string_type(size + 1);
  if (H5Aread(attribute.get(), memtype.get(), buffer.data()) < 0) return std::nullopt;
  buffer.resize(std::strlen(buffer.c_str()));
  return buffer;
}

std::optional<double> read_number_attribute(hid_t object, const std::string& name) {
  if (H5Aexists(object, name.c_str()) <= 0) return std::nullopt;
  Handle attribute(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose);
  Handle type(H5Aget_type(attribute.get()), H5Tclose);
  const H5T_class_t type_class = H5Tget_class(type.get());
  if (type_class != H5T_FLOAT && type_class != H5T_INTEGER) return std::nullopt;
  double value = 0;
  if (H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value) < 0) return std::nullopt;
  return value;
}

/// The names of the attributes on `object` of `file`; an iteration HDF5 cannot finish (a corrupt
/// attribute table) is an InputError, not a shorter list.
std::vector<std::string> attribute_names(hid_t object, const std::filesystem::path& file) {
  std::vector<std::string> names;
  const herr_t walked = H5Aiterate2(
      object, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
        static_cast<std::vector<std::string>*>(data)->emplace_back(name);
        return 0;
      },
      &names);
  if (walked < 0)
    input_error("'{}': its attributes cannot be listed (corrupt file?)", file.string());
  return names;
}

/// Every dataset in `file`, absolute paths, sorted; a walk HDF5 cannot finish (a corrupt object
/// header or group table) is an InputError, not a partial list.
std::vector<std::string> dataset_paths(hid_t root, const std::filesystem::path& file) {
  std::vector<std::string> paths;
  const herr_t walked = H5Ovisit(
      root, H5_INDEX_NAME, H5_ITER_INC,
      [](hid_t, const char* name, const H5O_info_t* info, void* data) -> herr_t {
        // Appended, not "/" + name: GCC 12 at -O3 warns (-Wrestrict, a false positive) on an
        // operator+ that inserts into a temporary; dims_text formats for the same reason.
        if (info->type == H5O_TYPE_DATASET)
          static_cast<std::vector<std::string>*>(data)->push_back(std::string("/").append(name));
        return 0;
      },
      &paths);
  if (walked < 0)
    input_error("'{}': its groups and datasets cannot be walked (corrupt file?)", file.string());
  std::sort(paths.begin(), paths.end());
  return paths;
}

Dims dataset_dims(hid_t dataset) {
  Handle space(H5Dget_space(dataset), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> extents(std::max(rank, 0));
  H5Sget_simple_extent_dims(space.get(), extents.data(), nullptr);
  return Dims(extents.begin(), extents.end());
}

std::optional<DType> dataset_dtype(hid_t dataset) {
  Handle type(H5Dget_type(dataset), H5Tclose);
  switch (H5Tget_class(type.get())) {
    case H5T_FLOAT:
      return DType::f64;
    case H5T_INTEGER:
      return DType::i64;
    case H5T_STRING:
      return DType::str;
    default:
      return std::nullopt;
  }
}

std::string dims_text(const Dims& dims) {
  std::vector<std::string> parts;
  for (auto d : dims) parts.push_back(std::to_string(d));
  return fmt::format("[{}]", fmt::join(parts, " × "));
}

std::uint64_t product(const Dims& dims) {
  return std::accumulate(dims.begin(), dims.end(), std::uint64_t{1}, std::multiplies<>());
}

/// Checks `dims` against the symbolic shape of `spec`, recording new symbols in `extents`.
/// Returns "" when consistent, else a description of the mismatch.
std::string check_shape(const DatasetSpec& spec, const Dims& dims,
                        std::map<std::string, std::uint64_t>& extents) {
  if (dims.size() != spec.shape.size())
    return fmt::format("has rank {} {}, expected rank {} [{}]", dims.size(), dims_text(dims),
                       spec.shape.size(), fmt::join(spec.shape, " × "));
  for (std::size_t i = 0; i < dims.size(); ++i) {
    const std::string& symbol = spec.shape[i];
    if (symbol == "*") continue;
    if (std::isdigit(static_cast<unsigned char>(symbol[0]))) {
      if (dims[i] != std::stoull(symbol))
        return fmt::format("has extent {} in dimension {}, expected {}", dims[i], i, symbol);
      continue;
    }
    const auto [it, inserted] = extents.emplace(symbol, dims[i]);
    if (!inserted && it->second != dims[i])
      return fmt::format("has {} = {} in dimension {}, but another dataset of the file has {} = {}",
                         symbol, dims[i], i, symbol, it->second);
  }
  return "";
}

}  // namespace

class Hdf5File : public Handle {
 public:
  explicit Hdf5File(hid_t id) : Handle(id, H5Fclose) {}
};

InputRecord input_record(std::string role, const std::filesystem::path& path) {
  return {std::move(role), path.string(), sha256_file(path)};
}

std::string utc_now_iso8601() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buffer;
}

// ---- writer -------------------------------------------------------------------------------------

ArtefactWriter::ArtefactWriter(const std::filesystem::path& output, const SchemaSpec& schema,
                               std::string stage, std::string parameters,
                               std::vector<InputRecord> inputs)
    : schema_(schema), output_(output) {
  silence_hdf5_errors();
  const Handle create_props(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
  H5Pset_userblock(create_props.get(), seal_block_size);  // the seal's place (seal.hpp)
  file_ = std::make_unique<Hdf5File>(
      H5Fcreate(output_.temp_path().c_str(), H5F_ACC_TRUNC, create_props.get(), H5P_DEFAULT));
  if (!file_->valid())
    input_error("cannot create '{}' (for '{}')", output_.temp_path().string(), output.string());
  const hid_t root = file_->get();
  write_string_attribute(root, attr::schema, schema.name);
  write_number_attribute<std::int64_t>(root, attr::schema_version, schema.version,
                                       H5T_NATIVE_INT64);
  write_string_attribute(root, attr::stage, stage);
  write_string_attribute(root, attr::tool_version, std::string(tool_version()));
  write_string_attribute(root, attr::created_utc, utc_now_iso8601());
  write_string_attribute(root, attr::parameters_sha256, sha256_text(parameters));
  write_string_attribute(root, attr::parameters, parameters);
  write_string_attribute(root, attr::status, "ok");
  for (const auto& input : inputs) {
    const std::string prefix = std::string(attr::input_prefix) + input.role + ":";
    write_string_attribute(root, prefix + "path", input.path);
    write_string_attribute(root, prefix + "sha256", input.sha256);
  }
}

ArtefactWriter::~ArtefactWriter() = default;

const DatasetSpec& ArtefactWriter::declared(const std::string& path, DType type, const Dims& dims) {
  const DatasetSpec* spec = schema_.find(path);
  HM_ASSERT(spec, "dataset '{}' is not declared in schema {}", path, schema_.name);
  HM_ASSERT(spec->type == type, "dataset '{}' declared {} but written as {}", path,
            dtype_name(spec->type), dtype_name(type));
  const std::string mismatch = check_shape(*spec, dims, extents_);
  HM_ASSERT(mismatch.empty(), "dataset '{}' of {} {}", path, schema_.name, mismatch);
  return *spec;
}

namespace {
void write_dataset(hid_t file, const std::string& path, hid_t memtype, hid_t filetype,
                   const void* data, const Dims& dims, const DatasetSpec& spec) {
  Handle space = dataspace(dims);
  Handle link_props(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(link_props.get(), 1);
  Handle create_props(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  const std::uint64_t count = product(dims);
  if (count >= 4096 && !dims.empty()) {  // compress large arrays: chunk by outermost rows
    std::vector<hsize_t> chunk(dims.begin(), dims.end());
    chunk[0] = std::max<hsize_t>(
        1, std::min<hsize_t>(dims[0], (1u << 16) / std::max<std::uint64_t>(1, count / dims[0])));
    H5Pset_chunk(create_props.get(), static_cast<int>(chunk.size()), chunk.data());
    H5Pset_shuffle(create_props.get());
    H5Pset_deflate(create_props.get(), 4);
  }
  Handle dataset(H5Dcreate2(file, path.c_str(), filetype, space.get(), link_props.get(),
                            create_props.get(), H5P_DEFAULT),
                 H5Dclose);
  HM_ASSERT(dataset.valid(), "cannot create dataset {}", path);
  if (count > 0 && H5Dwrite(dataset.get(), memtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    input_error("cannot write dataset '{}' (disk full or file system error?)", path);
  write_string_attribute(dataset.get(), attr::unit, spec.unit);
  write_string_attribute(dataset.get(), attr::description, spec.doc);
}
}  // namespace

void ArtefactWriter::write(const std::string& path, const double* data, const Dims& dims) {
  const DatasetSpec& spec = declared(path, DType::f64, dims);
  for (std::uint64_t i = 0; i < product(dims); ++i)
    if (!std::isfinite(data[i]) && !(spec.missing_values && std::isnan(data[i])))
      numerical_error(
          "refusing to write a non-finite value ({}) into dataset '{}' at flat index {}", data[i],
          path, i);
  write_dataset(file_->get(), path, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, data, dims, spec);
  written_.push_back(path);
}

void ArtefactWriter::write(const std::string& path, const std::int64_t* data, const Dims& dims) {
  const DatasetSpec& spec = declared(path, DType::i64, dims);
  write_dataset(file_->get(), path, H5T_NATIVE_INT64, H5T_STD_I64LE, data, dims, spec);
  written_.push_back(path);
}

void ArtefactWriter::write(const std::string& path, const MatrixRM& m) {
  write(path, m.data(),
        Dims{static_cast<std::uint64_t>(m.rows()), static_cast<std::uint64_t>(m.cols())});
}
void ArtefactWriter::write(const std::string& path, const IndexMatrixRM& m) {
  write(path, m.data(),
        Dims{static_cast<std::uint64_t>(m.rows()), static_cast<std::uint64_t>(m.cols())});
}
void ArtefactWriter::write(const std::string& path, const std::vector<double>& v) {
  write(path, v.data(), Dims{v.size()});
}
void ArtefactWriter::write(const std::string& path, const std::vector<std::int64_t>& v) {
  write(path, v.data(), Dims{v.size()});
}
void ArtefactWriter::write_vector(const std::string& path, const Eigen::VectorXd& v) {
  write(path, v.data(), Dims{static_cast<std::uint64_t>(v.size())});
}

void ArtefactWriter::set_attribute(const std::string& name, const std::string& value) {
  write_string_attribute(file_->get(), name, value);
}
void ArtefactWriter::set_attribute(const std::string& name, double value) {
  write_number_attribute(file_->get(), name, value, H5T_NATIVE_DOUBLE);
}
void ArtefactWriter::set_attribute(const std::string& name, std::int64_t value) {
  write_number_attribute(file_->get(), name, value, H5T_NATIVE_INT64);
}

void ArtefactWriter::commit() {
  for (const auto& spec : schema_.datasets) {
    if (!spec.required) continue;
    const bool found = std::any_of(written_.begin(), written_.end(),
                                   [&](const std::string& p) { return schema_.find(p) == &spec; });
    HM_ASSERT(found, "required dataset '{}' of {} was not written", spec.path, schema_.name);
  }
  H5Fflush(file_->get(), H5F_SCOPE_GLOBAL);
  file_.reset();  // close before sealing and the rename
  write_seal(output_.temp_path());
  output_.commit();
}

// ---- reader -------------------------------------------------------------------------------------

namespace {

std::unique_ptr<Hdf5File> open_artefact_file(const std::filesystem::path& path) {
  silence_hdf5_errors();
  if (!std::filesystem::exists(path)) input_error("'{}': no such file", path.string());
  if (!std::filesystem::is_regular_file(path))
    input_error("'{}' is not a regular file", path.string());
  check_seal(path);  // before HDF5 parses a byte of it
  auto file = std::make_unique<Hdf5File>(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  if (!file->valid())
    input_error("'{}' cannot be opened as HDF5: the file is truncated or corrupt", path.string());
  return file;
}

Provenance read_provenance(hid_t root, const std::filesystem::path& path) {
  Provenance p;
  const auto schema = read_string_attribute(root, attr::schema);
  if (!schema)
    input_error("'{}' has no root attribute '{}': it is not a hydromodal artefact", path.string(),
                attr::schema);
  p.schema = *schema;
  p.schema_version =
      static_cast<int>(read_number_attribute(root, attr::schema_version).value_or(0));
  p.stage = read_string_attribute(root, attr::stage).value_or("");
  p.tool_version = read_string_attribute(root, attr::tool_version).value_or("");
  p.created_utc = read_string_attribute(root, attr::created_utc).value_or("");
  p.parameters = read_string_attribute(root, attr::parameters).value_or("");
  p.parameters_sha256 = read_string_attribute(root, attr::parameters_sha256).value_or("");
  p.status = read_string_attribute(root, attr::status).value_or("");
  const std::string prefix = attr::input_prefix;
  for (const auto& name : attribute_names(root, path)) {
    if (name.rfind(prefix, 0) != 0 || !name.ends_with(":path")) continue;
    const std::string role = name.substr(prefix.size(), name.size() - prefix.size() - 5);
    p.inputs.push_back({role, read_string_attribute(root, name).value_or(""),
                        read_string_attribute(root, prefix + role + ":sha256").value_or("")});
  }
  return p;
}

/// Checks required datasets, types and shapes; returns the symbol extents.
std::map<std::string, std::uint64_t> validate_datasets(hid_t root, const SchemaSpec& schema,
                                                       const std::filesystem::path& path) {
  std::map<std::string, std::uint64_t> extents;
  const std::vector<std::string> present = dataset_paths(root, path);
  for (const auto& spec : schema.datasets) {
    const bool found = std::any_of(present.begin(), present.end(),
                                   [&](const std::string& p) { return schema.find(p) == &spec; });
    if (spec.required && !found)
      input_error(
          "'{}' ({} v{}) lacks the required dataset '{}' ({}); the file is incomplete or "
          "was not written by this tool version",
          path.string(), schema.name, schema.version, spec.path, spec.doc);
  }
  for (const auto& dataset_path : present) {
    const DatasetSpec* spec = schema.find(dataset_path);
    if (!spec) continue;  // extra datasets are allowed (forward compatibility)
    Handle dataset(H5Dopen2(root, dataset_path.c_str(), H5P_DEFAULT), H5Dclose);
    if (!dataset.valid())
      input_error("'{}': dataset '{}' cannot be opened (corrupt file?)", path.string(),
                  dataset_path);
    const auto type = dataset_dtype(dataset.get());
    if (type != spec->type)
      input_error("'{}': dataset '{}' has type {}, expected {}", path.string(), dataset_path,
                  type ? dtype_name(*type) : "unsupported", dtype_name(spec->type));
    const std::string mismatch = check_shape(*spec, dataset_dims(dataset.get()), extents);
    if (!mismatch.empty())
      input_error("'{}': dataset '{}' {}", path.string(), dataset_path, mismatch);
  }
  return extents;
}

}  // namespace

ArtefactReader::ArtefactReader(const std::filesystem::path& path, const SchemaSpec& expected)
    : path_(path), file_(open_artefact_file(path)) {
  provenance_ = read_provenance(file_->get(), path);
  if (provenance_.schema != expected.name)
    input_error("'{}' is a '{}' artefact, but a '{}' artefact is expected here (written by {})",
                path.string(), provenance_.schema, expected.name,
                provenance_.stage.empty() ? "an unknown stage" : provenance_.stage);
  if (!expected.reads(provenance_.schema_version))
    input_error(
        "'{}' has {} schema version {}, but this tool reads {}; rerun the stage "
        "'{}' to regenerate it",
        path.string(), expected.name, provenance_.schema_version, expected.readable_versions(),
        provenance_.stage);
  extents_ = validate_datasets(file_->get(), expected, path);
}

ArtefactReader::~ArtefactReader() = default;
ArtefactReader::ArtefactReader(ArtefactReader&&) noexcept = default;

std::uint64_t ArtefactReader::extent(const std::string& symbol) const {
  const auto it = extents_.find(symbol);
  HM_ASSERT(it != extents_.end(), "no extent '{}' in {}", symbol, path_.string());
  return it->second;
}

bool ArtefactReader::has(const std::string& dataset) const {
  return H5Lexists(file_->get(), dataset.c_str(), H5P_DEFAULT) > 0 &&
         H5Oexists_by_name(file_->get(), dataset.c_str(), H5P_DEFAULT) > 0;
}

std::vector<std::string> ArtefactReader::children(const std::string& group) const {
  std::vector<std::string> names;
  if (H5Lexists(file_->get(), group.c_str(), H5P_DEFAULT) <= 0) return names;
  H5Literate_by_name(
      file_->get(), group.c_str(), H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
        static_cast<std::vector<std::string>*>(data)->emplace_back(name);
        return 0;
      },
      &names, H5P_DEFAULT);
  return names;
}

Dims ArtefactReader::dims(const std::string& dataset) const {
  Handle handle(H5Dopen2(file_->get(), dataset.c_str(), H5P_DEFAULT), H5Dclose);
  if (!handle.valid()) input_error("'{}' has no dataset '{}'", path_.string(), dataset);
  return dataset_dims(handle.get());
}

namespace {
template <typename T>
std::vector<T> read_all(hid_t file, const std::filesystem::path& path, const std::string& dataset,
                        hid_t memtype) {
  Handle handle(H5Dopen2(file, dataset.c_str(), H5P_DEFAULT), H5Dclose);
  if (!handle.valid()) input_error("'{}' has no dataset '{}'", path.string(), dataset);
  std::vector<T> values(product(dataset_dims(handle.get())));
  if (!values.empty() &&
      H5Dread(handle.get(), memtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    input_error("'{}': dataset '{}' cannot be read (truncated or corrupt file)", path.string(),
                dataset);
  return values;
}
}  // namespace

std::vector<double> ArtefactReader::read_values(const std::string& dataset) const {
  return read_all<double>(file_->get(), path_, dataset, H5T_NATIVE_DOUBLE);
}
Eigen::VectorXd ArtefactReader::read_vector(const std::string& dataset) const {
  const std::vector<double> values = read_values(dataset);
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}
Eigen::MatrixXd ArtefactReader::read_columns(const std::string& dataset) const {
  const Dims d = dims(dataset);
  const std::vector<double> values = read_values(dataset);
  const auto columns = static_cast<Eigen::Index>(d.empty() ? 0 : d.front());
  const Eigen::Index rows = columns > 0 ? static_cast<Eigen::Index>(values.size()) / columns : 0;
  return Eigen::Map<const Eigen::MatrixXd>(values.data(), rows, columns);
}
std::vector<std::int64_t> ArtefactReader::read_index_values(const std::string& dataset) const {
  return read_all<std::int64_t>(file_->get(), path_, dataset, H5T_NATIVE_INT64);
}

MatrixRM ArtefactReader::read_matrix(const std::string& dataset) const {
  const Dims d = dims(dataset);
  const auto rows = static_cast<Eigen::Index>(d.empty() ? 1 : d[0]);
  const auto values = read_values(dataset);
  const auto cols = rows ? static_cast<Eigen::Index>(values.size()) / rows : 0;
  return Eigen::Map<const MatrixRM>(values.data(), rows, cols);
}

IndexMatrixRM ArtefactReader::read_indices(const std::string& dataset) const {
  const Dims d = dims(dataset);
  const auto rows = static_cast<Eigen::Index>(d.empty() ? 1 : d[0]);
  const auto values = read_index_values(dataset);
  const auto cols = rows ? static_cast<Eigen::Index>(values.size()) / rows : 0;
  return Eigen::Map<const IndexMatrixRM>(values.data(), rows, cols);
}

std::optional<std::string> ArtefactReader::string_attribute(const std::string& name) const {
  return read_string_attribute(file_->get(), name);
}
std::optional<double> ArtefactReader::number_attribute(const std::string& name) const {
  return read_number_attribute(file_->get(), name);
}

// ---- staleness ---------------------------------------------------------------------------------

Provenance read_artefact_provenance(const std::filesystem::path& path) {
  const auto file = open_artefact_file(path);
  return read_provenance(file->get(), path);
}

std::string staleness(const std::filesystem::path& output, const std::string& stage,
                      const std::string& parameters,
                      const std::map<std::string, std::string>& inputs) {
  if (!std::filesystem::exists(output)) return "it does not exist";
  Provenance p;
  try {
    p = read_artefact_provenance(output);
  } catch (const InputError& e) {
    return fmt::format("it is not a readable artefact ({})", e.what());
  }
  if (p.stage != stage) return fmt::format("it was written by {}, not {}", p.stage, stage);
  if (p.status != "ok") return fmt::format("its status is '{}'", p.status);
  if (p.tool_version != tool_version())
    return fmt::format("the tool changed ({} → {})", p.tool_version, tool_version());
  if (p.parameters_sha256 != sha256_text(parameters)) return "the scene parameters changed";
  for (const auto& input : inputs) {
    const auto recorded = std::find_if(p.inputs.begin(), p.inputs.end(),
                                       [&](const InputRecord& r) { return r.role == input.first; });
    if (recorded == p.inputs.end() || recorded->path != input.second)
      return fmt::format("input '{}' is now '{}'", input.first, input.second);
  }
  for (const auto& input : p.inputs) {
    if (input.role == "scene") continue;
    std::error_code ec;
    if (!std::filesystem::exists(input.path, ec))
      return fmt::format("input '{}' is gone", input.path);
    if (sha256_file(input.path) != input.sha256)
      return fmt::format("the content of input '{}' ({}) changed", input.role, input.path);
  }
  return "";
}

// ---- summary ------------------------------------------------------------------------------------

ArtefactSummary summarise(const std::filesystem::path& path, std::size_t max_values) {
  auto file = open_artefact_file(path);
  ArtefactSummary summary;
  summary.provenance = read_provenance(file->get(), path);
  if (const SchemaSpec* spec = find_schema(summary.provenance.schema)) {
    if (!spec->reads(summary.provenance.schema_version))
      input_error("'{}' has {} schema version {}, this tool knows {}", path.string(), spec->name,
                  summary.provenance.schema_version, spec->readable_versions());
    validate_datasets(file->get(), *spec, path);
  }
  for (const auto& name : attribute_names(file->get(), path)) {
    RootAttribute a{name, read_string_attribute(file->get(), name).value_or(""),
                    read_number_attribute(file->get(), name)};
    if (a.number) {
      Handle attribute(H5Aopen(file->get(), name.c_str(), H5P_DEFAULT), H5Aclose);
      Handle type(H5Aget_type(attribute.get()), H5Tclose);
      a.integer = H5Tget_class(type.get()) == H5T_INTEGER;
      a.text = a.integer ? fmt::format("{}", static_cast<std::int64_t>(*a.number))
                         : fmt::format("{}", *a.number);
    }
    summary.attributes.push_back(std::move(a));
  }
  for (const auto& dataset_path : dataset_paths(file->get(), path)) {
    Handle dataset(H5Dopen2(file->get(), dataset_path.c_str(), H5P_DEFAULT), H5Dclose);
    if (!dataset.valid())
      input_error("'{}': dataset '{}' cannot be opened (corrupt file?)", path.string(),
                  dataset_path);
    DatasetSummary d;
    d.path = dataset_path;
    const auto type = dataset_dtype(dataset.get());
    d.dtype = type ? std::string(dtype_name(*type)) : "other";
    d.dims = dataset_dims(dataset.get());
    d.unit = read_string_attribute(dataset.get(), attr::unit).value_or("");
    d.description = read_string_attribute(dataset.get(), attr::description).value_or("");
    if (type && *type != DType::str && product(d.dims) <= max_values) {
      d.values.resize(product(d.dims));
      if (!d.values.empty() && H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL,
                                       H5P_DEFAULT, d.values.data()) < 0)
        input_error("'{}': dataset '{}' cannot be read (truncated or corrupt file)", path.string(),
                    dataset_path);
    }
    summary.datasets.push_back(std::move(d));
  }
  return summary;
}

}  // namespace hm::io
