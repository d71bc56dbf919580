#include "ldd/snapshots.hpp"

#include <hdf5.h>

#include <fstream>
#include <set>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"

namespace hm::ldd {
namespace {

// ---- HDF5 (C API), the few calls a snapshot needs
// ------------------------------------------------

class H5Handle {
 public:
  H5Handle(hid_t id, herr_t (*closer)(hid_t)) : id_(id), close_(closer) {}
  ~H5Handle() {
    if (id_ >= 0) close_(id_);
  }
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Closes now; false when HDF5 reports an error (data not flushed).
  bool close() {
    const herr_t status = id_ >= 0 ? close_(id_) : 0;
    id_ = -1;
    return status >= 0;
  }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

void write_string_attribute(hid_t object, const char* name, const std::string& value) {
  H5Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), value.size() + 1);
  H5Tset_strpad(type.get(), H5T_STR_NULLTERM);
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  H5Handle attribute(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                     H5Aclose);
  HM_ASSERT(attribute.valid(), "cannot create attribute {}", name);
  H5Awrite(attribute.get(), type.get(), value.c_str());
}

void write_time_attribute(hid_t object, double t) {
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  H5Handle attribute(
      H5Acreate2(object, "time", H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  HM_ASSERT(attribute.valid(), "cannot create attribute time");
  H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, &t);
  write_string_attribute(object, "time_unit", "s");
}

/// Writes a dataset (intermediate groups created) with a "unit" attribute ("" for none).
void write_dataset(hid_t file, const std::filesystem::path& where, const std::string& path,
                   hid_t memtype, hid_t filetype, const void* data,
                   const std::vector<hsize_t>& dims, const std::string& unit) {
  H5Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
  H5Handle link_props(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(link_props.get(), 1);
  H5Handle dataset(H5Dcreate2(file, path.c_str(), filetype, space.get(), link_props.get(),
                              H5P_DEFAULT, H5P_DEFAULT),
                   H5Dclose);
  if (!dataset.valid())
    input_error("cannot create dataset '{}' in snapshot '{}'", path, where.string());
  hsize_t count = 1;
  for (auto d : dims) count *= d;
  if (count > 0 && H5Dwrite(dataset.get(), memtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    input_error("cannot write dataset '{}' of snapshot '{}' (disk full?)", path, where.string());
  if (!unit.empty()) write_string_attribute(dataset.get(), "unit", unit);
}

/// n × 3 row-major copy of D-vectors, zero beyond D.
template <int D>
std::vector<double> as_xyz(std::span<const Vec<D>> v) {
  std::vector<double> out(3 * v.size(), 0.0);
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int a = 0; a < D; ++a) out[3 * i + a] = v[i][a];
  return out;
}

template <typename Enum>
std::vector<std::uint8_t> as_bytes(const std::vector<Enum>& v) {
  std::vector<std::uint8_t> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = static_cast<std::uint8_t>(v[i]);
  return out;
}

template <int D>
void write_points(hid_t file, const std::filesystem::path& where, const PointSet<D>& points) {
  const hsize_t n = points.position.size();
  const auto x = as_xyz<D>(points.position), u = as_xyz<D>(points.velocity);
  const auto type = as_bytes(points.type), kind = as_bytes(points.kind);
  write_dataset(file, where, "/points/position", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, x.data(),
                {n, 3}, "m");
  write_dataset(file, where, "/points/velocity", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, u.data(),
                {n, 3}, "m/s");
  write_dataset(file, where, "/points/pressure", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE,
                points.pressure.data(), {n}, "Pa");
  write_dataset(file, where, "/points/type", H5T_NATIVE_UINT8, H5T_STD_U8LE, type.data(), {n}, "");
  write_dataset(file, where, "/points/kind", H5T_NATIVE_UINT8, H5T_STD_U8LE, kind.data(), {n}, "");
}

template <int D>
void write_wall(hid_t file, const std::filesystem::path& where, const WallMesh<D>& wall,
                const std::string& name) {
  const auto x = as_xyz<D>(wall.vertices());
  std::vector<std::int64_t> cells(static_cast<std::size_t>(wall.element_count()) * D);
  for (Index e = 0; e < wall.element_count(); ++e)
    for (int k = 0; k < D; ++k) cells[static_cast<std::size_t>(e) * D + k] = wall.element(e)[k];
  const std::string group = "/walls/" + name;
  write_dataset(file, where, group + "/vertices", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, x.data(),
                {wall.vertices().size(), 3}, "m");
  write_dataset(file, where, group + "/cells", H5T_NATIVE_INT64, H5T_STD_I64LE, cells.data(),
                {static_cast<hsize_t>(wall.element_count()), static_cast<hsize_t>(D)}, "");
}

template <int D>
void write_wall_fields(hid_t file, const std::filesystem::path& where, const WallMesh<D>& wall,
                       const std::string& name, const WallFields<D>& fields) {
  const std::string group = "/walls/" + name;
  const hsize_t n = wall.vertices().size();
  if (!fields.displacement.empty()) {
    HM_ASSERT(fields.displacement.size() == n, "wall '{}': {} displacements for {} vertices", name,
              fields.displacement.size(), n);
    const auto u = as_xyz<D>(fields.displacement);
    write_dataset(file, where, group + "/displacement", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, u.data(),
                  {n, 3}, "m");
  }
  if (!fields.pressure.empty()) {
    HM_ASSERT(fields.pressure.size() == n, "wall '{}': {} pressures for {} vertices", name,
              fields.pressure.size(), n);
    write_dataset(file, where, group + "/pressure", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE,
                  fields.pressure.data(), {n}, "Pa");
  }
}

// ---- XDMF
// -----------------------------------------------------------------------------------------

std::string xml_escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string hdf_item(const std::string& file, const std::string& dataset, const std::string& dims,
                     const char* number_type, int precision) {
  return fmt::format(
      "<DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"{}\" Format=\"HDF\">{}:{}"
      "</DataItem>",
      dims, number_type, precision, xml_escaped(file), xml_escaped(dataset));
}

std::string attribute_xml(const char* name, bool vector, const std::string& item) {
  return fmt::format(
      "        <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Node\">{}</Attribute>\n", name,
      vector ? "Vector" : "Scalar", item);
}

void validate_wall_names(std::span<const std::string> names, std::size_t walls,
                         const std::filesystem::path& folder) {
  if (names.size() != walls)
    input_error("snapshots in '{}': {} wall names for {} walls", folder.string(), names.size(),
                walls);
  std::set<std::string> seen;
  for (const auto& name : names) {
    if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos)
      input_error("snapshots in '{}': wall name '{}' cannot name an HDF5 group (non-empty, no '/')",
                  folder.string(), name);
    if (!seen.insert(name).second)
      input_error("snapshots in '{}': two walls are named '{}'; names must be unique",
                  folder.string(), name);
  }
}

}  // namespace

template <int D>
SnapshotWriter<D>::SnapshotWriter(std::filesystem::path folder, std::string stem)
    : folder_(std::move(folder)), stem_(std::move(stem)) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors are reported as exceptions
  std::error_code ec;
  std::filesystem::create_directories(folder_, ec);
  if (!std::filesystem::is_directory(folder_))
    input_error("cannot create the snapshot folder '{}'", folder_.string());
}

template <int D>
std::filesystem::path SnapshotWriter<D>::xdmf_path() const {
  return folder_ / (stem_ + ".xdmf");
}

template <int D>
std::filesystem::path SnapshotWriter<D>::write(double t, const PointSet<D>& points,
                                               std::span<const WallMesh<D>> walls,
                                               std::span<const std::string> wall_names,
                                               std::span<const WallFields<D>> fields) {
  HM_ASSERT(fields.empty() || fields.size() == walls.size(), "{} wall fields for {} walls",
            fields.size(), walls.size());
  validate_wall_names(wall_names, walls.size(), folder_);
  Entry entry;
  entry.file = fmt::format("{}_{:06d}.h5", stem_, entries_.size());
  entry.time = t;
  entry.points = points.position.size();
  const std::filesystem::path path = folder_ / entry.file;
  io::AtomicOutput output(path);
  {
    H5Handle file(H5Fcreate(output.temp_path().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                  H5Fclose);
    if (!file.valid()) input_error("cannot create the snapshot '{}'", path.string());
    write_time_attribute(file.get(), t);
    write_points<D>(file.get(), path, points);
    for (std::size_t w = 0; w < walls.size(); ++w) {
      write_wall<D>(file.get(), path, walls[w], wall_names[w]);
      if (!fields.empty())
        write_wall_fields<D>(file.get(), path, walls[w], wall_names[w], fields[w]);
      entry.wall_displacement.push_back(!fields.empty() && !fields[w].displacement.empty());
      entry.wall_pressure.push_back(!fields.empty() && !fields[w].pressure.empty());
      entry.walls.push_back(wall_names[w]);
      entry.wall_vertices.push_back(walls[w].vertices().size());
      entry.wall_cells.push_back(static_cast<std::uint64_t>(walls[w].element_count()));
    }
    if (!file.close()) input_error("cannot finish the snapshot '{}' (disk full?)", path.string());
  }
  output.commit();
  entries_.push_back(std::move(entry));
  write_index();
  return path;
}

template <int D>
void SnapshotWriter<D>::resume(std::size_t count, std::span<const WallMesh<D>> walls,
                               std::span<const std::string> wall_names,
                               std::span<const WallFields<D>> fields) {
  validate_wall_names(wall_names, walls.size(), folder_);
  entries_.clear();
  for (std::size_t k = 0; k < count; ++k) {
    Entry entry;
    entry.file = fmt::format("{}_{:06d}.h5", stem_, k);
    const std::filesystem::path path = folder_ / entry.file;
    H5Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    if (!file.valid())
      input_error("cannot resume the snapshots: '{}' is missing or unreadable", path.string());
    H5Handle time(H5Aopen(file.get(), "time", H5P_DEFAULT), H5Aclose);
    H5Handle points(H5Dopen2(file.get(), "/points/position", H5P_DEFAULT), H5Dclose);
    if (!time.valid() || !points.valid() || H5Aread(time.get(), H5T_NATIVE_DOUBLE, &entry.time) < 0)
      input_error("cannot resume the snapshots: '{}' has no time or points", path.string());
    H5Handle space(H5Dget_space(points.get()), H5Sclose);
    hsize_t dims[2] = {0, 0};
    H5Sget_simple_extent_dims(space.get(), dims, nullptr);
    entry.points = dims[0];
    for (std::size_t w = 0; w < walls.size(); ++w) {
      entry.wall_displacement.push_back(!fields.empty() && !fields[w].displacement.empty());
      entry.wall_pressure.push_back(!fields.empty() && !fields[w].pressure.empty());
      entry.walls.push_back(wall_names[w]);
      entry.wall_vertices.push_back(walls[w].vertices().size());
      entry.wall_cells.push_back(static_cast<std::uint64_t>(walls[w].element_count()));
    }
    entries_.push_back(std::move(entry));
  }
}

template <int D>
void SnapshotWriter<D>::write_index() const {
  std::string xml =
      "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      "<Xdmf Version=\"2.0\">\n  <Domain>\n";
  xml += fmt::format("    <Grid Name=\"{}\" GridType=\"Collection\" CollectionType=\"Temporal\">\n",
                     xml_escaped(stem_));
  for (const auto& e : entries_) {
    xml += fmt::format(
        "    <Grid Name=\"{}\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
        "      <Time Value=\"{}\"/>\n",
        xml_escaped(e.file), e.time);
    // Polyvertex without a connectivity item: XDMF readers (vtkxdmf2 XdmfTopology::Update)
    // generate the default 0..n−1, one vertex cell per point.
    if (e.points > 0) {
      const std::string n = std::to_string(e.points), n3 = n + " 3";
      xml += fmt::format(
          "      <Grid Name=\"points\" GridType=\"Uniform\">\n"
          "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" "
          "NodesPerElement=\"1\"/>\n"
          "        <Geometry GeometryType=\"XYZ\">{}</Geometry>\n",
          n, hdf_item(e.file, "/points/position", n3, "Float", 8));
      xml += attribute_xml("velocity", true, hdf_item(e.file, "/points/velocity", n3, "Float", 8));
      xml += attribute_xml("pressure", false, hdf_item(e.file, "/points/pressure", n, "Float", 8));
      xml += attribute_xml("type", false, hdf_item(e.file, "/points/type", n, "UChar", 1));
      xml += attribute_xml("kind", false, hdf_item(e.file, "/points/kind", n, "UChar", 1));
      xml += "      </Grid>\n";
    }
    for (std::size_t w = 0; w < e.walls.size(); ++w) {
      if (e.wall_cells[w] == 0) continue;
      const std::string group = "/walls/" + e.walls[w];
      xml += fmt::format(
          "      <Grid Name=\"{}\" GridType=\"Uniform\">\n"
          "        <Topology TopologyType=\"{}\" NumberOfElements=\"{}\" NodesPerElement=\"{}\">"
          "{}</Topology>\n"
          "        <Geometry GeometryType=\"XYZ\">{}</Geometry>\n",
          xml_escaped(e.walls[w]), D == 2 ? "Polyline" : "Triangle", e.wall_cells[w], D,
          hdf_item(e.file, group + "/cells", fmt::format("{} {}", e.wall_cells[w], D), "Int", 8),
          hdf_item(e.file, group + "/vertices", fmt::format("{} 3", e.wall_vertices[w]), "Float",
                   8));
      const std::string m = std::to_string(e.wall_vertices[w]);
      if (e.wall_displacement[w])
        xml += attribute_xml("displacement", true,
                             hdf_item(e.file, group + "/displacement", m + " 3", "Float", 8));
      if (e.wall_pressure[w])
        xml +=
            attribute_xml("pressure", false, hdf_item(e.file, group + "/pressure", m, "Float", 8));
      xml += "      </Grid>\n";
    }
    xml += "    </Grid>\n";
  }
  xml += "    </Grid>\n  </Domain>\n</Xdmf>\n";
  io::AtomicOutput output(xdmf_path());
  {
    std::ofstream out(output.temp_path());
    out << xml;
    out.close();
    if (!out) input_error("cannot write the snapshot index '{}'", xdmf_path().string());
  }
  output.commit();
}

template class SnapshotWriter<2>;
template class SnapshotWriter<3>;

}  // namespace hm::ldd
