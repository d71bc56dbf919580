// Snapshots: one HDF5 file per call plus an XDMF temporal index rewritten each time; the data
// read back with the HDF5 C API matches the point set and the walls.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "../common/scratch.hpp"
#include "core/errors.hpp"
#include "ldd/snapshots.hpp"
#include "tank.hpp"

namespace fs = std::filesystem;

namespace hm::ldd {
namespace {

using hm::test::fresh_dir;
using hm::test::read_text;

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// Reads a whole dataset as `memtype` into a vector of T; dims returned in `dims`.
template <typename T>
std::vector<T> read_dataset(const fs::path& file, const std::string& name, hid_t memtype,
                            std::vector<hsize_t>& dims) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << file;
  const hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << name;
  const hid_t s = H5Dget_space(d);
  dims.assign(H5Sget_simple_extent_ndims(s), 0);
  H5Sget_simple_extent_dims(s, dims.data(), nullptr);
  hsize_t n = 1;
  for (auto k : dims) n *= k;
  std::vector<T> out(n);
  H5Dread(d, memtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
  H5Sclose(s);
  H5Dclose(d);
  H5Fclose(f);
  return out;
}

double read_time(const fs::path& file) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t a = H5Aopen(f, "time", H5P_DEFAULT);
  double t = -1;
  H5Aread(a, H5T_NATIVE_DOUBLE, &t);
  H5Aclose(a);
  H5Fclose(f);
  return t;
}

TEST(LddSnapshots, ThreeSnapshots2D) {
  const fs::path dir = fresh_dir("snapshots_2d") / "snapshots";
  std::vector<WallMesh<2>> walls;
  walls.push_back(test::box_tank<2>(Vec<2>(0.5, 0.4), 0.1));
  const std::vector<std::string> names = {"tank"};
  PointSet<2> pts;
  for (const auto& x : seed_box<2>({Vec<2>::Zero(), Vec<2>(0.1, 0.05)}, 0.01, walls))
    pts.add_fluid(x, Vec<2>(x.y(), -x.x()));
  add_wall_nodes<2>(pts, walls[0], 0, 0.05);
  pts.type[3] = PointType::surface;
  const std::vector<double> times = {0.0, 0.0125, 1.0 / 3.0};
  SnapshotWriter<2> writer(dir, "flow");
  std::vector<fs::path> files;
  for (std::size_t k = 0; k < times.size(); ++k) {
    for (Index i = 0; i < pts.size(); ++i) pts.pressure[i] = 1000.0 * k + i;
    files.push_back(writer.write(times[k], pts, walls, names));
  }
  EXPECT_EQ(writer.count(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(files[k], dir / fmt::format("flow_{:06d}.h5", k));
    ASSERT_TRUE(fs::exists(files[k]));
    EXPECT_EQ(read_time(files[k]), times[k]);
  }
  // Only the snapshots and the index: no temporary files left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 4);

  const std::string xml = read_text(writer.xdmf_path());
  EXPECT_EQ(writer.xdmf_path(), dir / "flow.xdmf");
  EXPECT_NE(xml.find("<Xdmf Version=\"2.0\">"), std::string::npos);
  EXPECT_EQ(occurrences(xml, "GridType=\"Collection\" CollectionType=\"Temporal\""), 1u);
  EXPECT_EQ(occurrences(xml, "<Time Value="), 3u);
  EXPECT_NE(xml.find("<Time Value=\"0\"/>"), std::string::npos);
  EXPECT_NE(xml.find("<Time Value=\"0.0125\"/>"), std::string::npos);
  EXPECT_NE(xml.find("<Time Value=\"0.3333333333333333\"/>"), std::string::npos);
  EXPECT_LT(xml.find("flow_000001.h5:/points/position"), xml.find("flow_000002.h5"));
  EXPECT_EQ(occurrences(xml, "TopologyType=\"Polyvertex\""), 3u);
  EXPECT_EQ(occurrences(xml, "TopologyType=\"Polyline\""), 3u);
  const std::string n = std::to_string(pts.size());
  EXPECT_NE(xml.find("NumberOfElements=\"" + n + "\""), std::string::npos);
  // Balanced elements: a crude well-formedness check of the nesting.
  EXPECT_EQ(occurrences(xml, "<Grid "), occurrences(xml, "</Grid>"));
  EXPECT_EQ(occurrences(xml, "<Attribute "), occurrences(xml, "</Attribute>"));
  EXPECT_EQ(occurrences(xml, "<DataItem "), occurrences(xml, "</DataItem>"));

  std::vector<hsize_t> dims;
  const auto x = read_dataset<double>(files[2], "/points/position", H5T_NATIVE_DOUBLE, dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{static_cast<hsize_t>(pts.size()), 3}));
  const auto u = read_dataset<double>(files[2], "/points/velocity", H5T_NATIVE_DOUBLE, dims);
  const auto p = read_dataset<double>(files[2], "/points/pressure", H5T_NATIVE_DOUBLE, dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{static_cast<hsize_t>(pts.size())}));
  const auto type = read_dataset<std::uint8_t>(files[2], "/points/type", H5T_NATIVE_UINT8, dims);
  const auto kind = read_dataset<std::uint8_t>(files[2], "/points/kind", H5T_NATIVE_UINT8, dims);
  for (Index i = 0; i < pts.size(); ++i) {
    ASSERT_EQ(x[3 * i], pts.position[i].x());
    ASSERT_EQ(x[3 * i + 1], pts.position[i].y());
    ASSERT_EQ(x[3 * i + 2], 0.0);
    ASSERT_EQ(u[3 * i], pts.velocity[i].x());
    ASSERT_EQ(u[3 * i + 1], pts.velocity[i].y());
    ASSERT_EQ(p[i], 2000.0 + i);
    ASSERT_EQ(type[i], static_cast<std::uint8_t>(pts.type[i]));
    ASSERT_EQ(kind[i], static_cast<std::uint8_t>(pts.kind[i]));
  }
  EXPECT_EQ(type[3], 1u);  // surface
  const auto p0 = read_dataset<double>(files[0], "/points/pressure", H5T_NATIVE_DOUBLE, dims);
  EXPECT_EQ(p0[5], 5.0);
  const auto v = read_dataset<double>(files[1], "/walls/tank/vertices", H5T_NATIVE_DOUBLE, dims);
  ASSERT_EQ(dims[0], walls[0].vertices().size());
  for (std::size_t i = 0; i < walls[0].vertices().size(); ++i)
    ASSERT_EQ(v[3 * i + 1], walls[0].vertices()[i].y());
  const auto cells =
      read_dataset<std::int64_t>(files[1], "/walls/tank/cells", H5T_NATIVE_INT64, dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{static_cast<hsize_t>(walls[0].element_count()), 2}));
  for (Index e = 0; e < walls[0].element_count(); ++e)
    ASSERT_EQ(cells[2 * e + 1], walls[0].element(e)[1]);
}

TEST(LddSnapshots, TrianglesIn3DAndBadWallNames) {
  const fs::path dir = fresh_dir("snapshots_3d");
  std::vector<WallMesh<3>> walls;
  walls.push_back(test::box_tank<3>(Vec<3>(0.2, 0.2, 0.2), 0.1));
  PointSet<3> pts;
  pts.add_fluid(Vec<3>(0.1, 0.1, 0.1));
  pts.pressure[0] = 42.0;
  SnapshotWriter<3> writer(dir, "flow3");
  const std::vector<std::string> names = {"box"};
  const auto file = writer.write(0.5, pts, walls, names);
  const std::string xml = read_text(writer.xdmf_path());
  EXPECT_EQ(occurrences(xml, "TopologyType=\"Triangle\""), 1u);
  EXPECT_NE(xml.find("flow3_000000.h5:/walls/box/cells"), std::string::npos);
  std::vector<hsize_t> dims;
  const auto x = read_dataset<double>(file, "/points/position", H5T_NATIVE_DOUBLE, dims);
  EXPECT_EQ(x, (std::vector<double>{0.1, 0.1, 0.1}));
  EXPECT_EQ(read_dataset<double>(file, "/points/pressure", H5T_NATIVE_DOUBLE, dims)[0], 42.0);

  auto message = [&](std::vector<std::string> bad) {
    try {
      writer.write(1.0, pts, walls, bad);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no InputError");
  };
  auto m = message({"a/b"});
  EXPECT_NE(m.find("wall name 'a/b' cannot name an HDF5 group"), std::string::npos) << m;
  m = message({});
  EXPECT_NE(m.find("0 wall names for 1 walls"), std::string::npos) << m;
  EXPECT_EQ(writer.count(), 1u);  // failed writes add nothing to the index
}

}  // namespace
}  // namespace hm::ldd
