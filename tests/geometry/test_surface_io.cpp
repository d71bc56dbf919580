#include <array>
#include <cstdint>
#include <fstream>

#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/surface_checks.hpp"
#include "geometry/surface_io.hpp"
#include "surfaces.hpp"

namespace hm::geometry {
namespace {

using hm::test::box_surface;

TEST(SurfaceIo, StlRoundTripMergesCornersOfTheBox) {
  const auto dir = hm::test::scratch_dir();
  // Dyadic sizes: exactly representable in the float assimp reads STL into.
  const auto box = box_surface({0.25, 0.0, -0.5}, {0.5, 0.25, 0.125});
  write_stl_ascii(box, dir / "box.stl");
  const auto read = read_surface_file(dir / "box.stl");
  EXPECT_EQ(read.vertices.rows(), 8);  // 36 STL vertices merged to the 8 corners
  EXPECT_EQ(read.cells.rows(), 12);
  EXPECT_DOUBLE_EQ(enclosed_volume(read), 0.5 * 0.25 * 0.125);
  const BoundingBox bb = bounding_box(read.vertices);
  EXPECT_EQ(bb.min, Eigen::Vector3d(0.25, 0.0, -0.5));
  EXPECT_EQ(bb.max, Eigen::Vector3d(0.75, 0.25, -0.375));
}

TEST(SurfaceIo, ObjQuadsAreTriangulatedAndVerticesMergedAcrossObjects) {
  const auto dir = hm::test::scratch_dir();
  // Two objects (two assimp meshes) sharing the square's diagonal vertices by coordinates only.
  std::ofstream(dir / "two.obj")
      << "o a\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n"
         "o b\nv 0 0 0\nv 1 1 0\nv 0 1 0\nv -1 1 0\nv -1 0 0\nf 4 5 6 7 8\n";
  const auto read = read_surface_file(dir / "two.obj");
  EXPECT_EQ(read.cells.rows(), 1 + 3);     // a triangle + a pentagon as 3 triangles
  EXPECT_EQ(read.vertices.rows(), 3 + 3);  // (0,0,0) and (1,1,0) shared
}

TEST(SurfaceIo, MissingFileNamesIt) {
  const auto message =
      hm::test::input_error_message([] { read_surface_file("/no/such/part.stl"); });
  EXPECT_NE(message.find("'/no/such/part.stl'"), std::string::npos) << message;
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
}

TEST(SurfaceIo, UnreadableFileGivesAssimpReason) {
  const auto dir = hm::test::scratch_dir();
  std::ofstream(dir / "junk.stl") << "this is not an STL file\n";
  const auto message = hm::test::input_error_message([&] { read_surface_file(dir / "junk.stl"); });
  EXPECT_NE(message.find("junk.stl"), std::string::npos) << message;
}

// Found by fuzzing (tests/fuzz/regressions/surface): assimp 5.2 loops for ever on a PLY header
// with a misspelt line; the header is checked first. A good PLY still reads.
TEST(SurfaceIo, MalformedPlyHeaderIsRefusedNotHung) {
  const auto dir = hm::test::scratch_dir();
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\n";
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
  std::ofstream(dir / "good.ply") << head
                                  << "element face 4\nproperty list uchar int vertex_indices\n"
                                     "end_header\n"
                                  << body;
  EXPECT_EQ(read_surface_file(dir / "good.ply").cells.rows(), 4);
  std::ofstream(dir / "bad.ply") << head << "elemen 1 0\n" << body;
  const auto message = hm::test::input_error_message([&] { read_surface_file(dir / "bad.ply"); });
  EXPECT_NE(message.find("bad.ply', line 7: 'elemen 1 0' is not a PLY header line"),
            std::string::npos)
      << message;
  std::ofstream(dir / "open.ply") << head << "element face 4\n";
  EXPECT_NE(hm::test::input_error_message([&] {
              read_surface_file(dir / "open.ply");
            }).find("has no end_header line"),
            std::string::npos);
}

// ASCII coordinates are read in double precision (assimp read them as floats: 0.2545 became
// 0.25450000166893005); binary STL is single precision by its format.
TEST(SurfaceIo, AsciiStlKeepsDoublePrecisionAndBinaryStlReadsFloats) {
  const auto dir = hm::test::scratch_dir();
  std::ofstream(dir / "tri.stl") << "solid t\n facet normal 0 0 1\n  outer loop\n"
                                    "   vertex 0.2545 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n"
                                    "  endloop\n endfacet\nendsolid t\n";
  EXPECT_EQ(read_surface_file(dir / "tri.stl").vertices(0, 0), 0.2545);
  {
    std::ofstream out(dir / "tri_binary.stl", std::ios::binary);
    out << std::string(80, ' ');
    const std::uint32_t count = 1;
    out.write(reinterpret_cast<const char*>(&count), 4);
    const std::array<float, 12> record{0, 0, 1, 0.2545f, 0, 0, 1, 0, 0, 0, 1, 0};
    out.write(reinterpret_cast<const char*>(record.data()), 48);
    out.write("\0\0", 2);
  }
  const auto binary = read_surface_file(dir / "tri_binary.stl");
  EXPECT_EQ(binary.cells.rows(), 1);
  EXPECT_EQ(binary.vertices(0, 0), static_cast<double>(0.2545f));
  // A facet with two vertices: refused with the line.
  std::ofstream(dir / "short.stl") << "solid t\n facet normal 0 0 1\n  outer loop\n"
                                      "   vertex 0 0 0\n   vertex 1 0 0\n  endloop\n";
  EXPECT_NE(hm::test::input_error_message([&] {
              read_surface_file(dir / "short.stl");
            }).find("short.stl', line 6: 'endloop' where an ASCII STL has three vertices"),
            std::string::npos);
}

// OBJ: negative (relative) indices and i/t/n corners; a corner past the vertices is refused.
TEST(SurfaceIo, ObjRelativeIndicesAndBadCorners) {
  const auto dir = hm::test::scratch_dir();
  std::ofstream(dir / "rel.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf -3//1 -2//1 -1//1\n";
  EXPECT_EQ(read_surface_file(dir / "rel.obj").cells.rows(), 1);
  std::ofstream(dir / "bad.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";
  EXPECT_NE(hm::test::input_error_message([&] {
              read_surface_file(dir / "bad.obj");
            }).find("a face refers to vertex 9 (counting from 1), the file has 3 vertices"),
            std::string::npos);
}

TEST(BoundingBox, ExtentReportNamesAxesAndMetres) {
  mesh::Coordinates p(2, 2);
  p << 0.0, 0.0, 0.005, 0.079;
  const auto text = describe(bounding_box(p));
  EXPECT_NE(text.find("x [0, 0.005]"), std::string::npos) << text;
  EXPECT_NE(text.find("y [0, 0.079]"), std::string::npos) << text;
  EXPECT_NE(text.find(" m"), std::string::npos) << text;
}

TEST(BoundingBox, MillimetresReadAsMetresAreFlagged) {
  mesh::Coordinates gate(2, 2);
  gate << 0.0, 0.0, 0.005, 0.079;
  EXPECT_FALSE(report_extent(bounding_box(gate), "gate in m"));
  gate *= 1000.0;  // 5 × 79 "m": fine by the bounds, it is the tank that would give it away
  EXPECT_FALSE(report_extent(bounding_box(gate), "gate in mm"));
  mesh::Coordinates tank(2, 3);
  tank << 0.0, 0.0, 0.0, 1610.0, 600.0, 150.0;  // a 1.61 m tank drawn in mm
  EXPECT_TRUE(report_extent(bounding_box(tank), "tank in mm"));
  tank /= 1e7;  // 0.16 mm across: below the 1 mm bound
  EXPECT_TRUE(report_extent(bounding_box(tank), "tank in micrometres"));
}

}  // namespace
}  // namespace hm::geometry
