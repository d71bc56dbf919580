#include <fstream>

#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "geometry/surface_io.hpp"
#include "mesh/gmsh_session.hpp"
#include "mesh/quality.hpp"
#include "mesh/structure_mesher.hpp"
#include "mesh_checks.hpp"
#include "surfaces.hpp"

namespace hm::mesh {
namespace {

using hm::test::input_error_message;

const std::filesystem::path data_dir = std::filesystem::path(HM_SOURCE_DIR) / "data" / "geometry";

MeshOptions options(int dim, double size) {
  MeshOptions o;
  o.dim = dim;
  o.size = size;
  return o;
}

std::vector<Index> all_facets(const StructureMesh& m) {
  std::vector<Index> f(static_cast<std::size_t>(m.facets.rows()));
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = static_cast<Index>(i);
  return f;
}

/// The quadratic-mesh invariants every structure mesh must satisfy, with its exact measure.
void expect_valid(const StructureMesh& m, double measure, double boundary_measure) {
  const double scale = geometry::bounding_box(m.nodes).diagonal();
  EXPECT_EQ(m.cells.cols(), m.nodes_per_cell());
  EXPECT_EQ(m.facets.cols(), m.nodes_per_facet());
  EXPECT_GT(hm::test::min_corner_jacobian(m), 0.0);
  // Straight edges: mid-edge nodes at the midpoints up to the round-off of gmsh evaluating the
  // geometry's parametrisation (a wrong node order would be off by ~h, 1e10 times more).
  EXPECT_LT(hm::test::max_midnode_offset(m), 1e-13 * scale);
  EXPECT_NEAR(assess_quality(m, 0.1).measure, measure, 1e-12 * measure);
  EXPECT_NEAR(hm::test::divergence_measure(m), measure, 1e-12 * measure);
  EXPECT_NEAR(hm::test::facet_measure(m, all_facets(m)), boundary_measure,
              1e-12 * boundary_measure);
}

TEST(StructureMesher, ElasticGateRectangleAsTri6WithFaceGroups) {
  const double w = 0.005, h = 0.079;
  const auto m = mesh_rectangle({{0.0, 0.0}, {w, h}}, options(2, 0.001));
  EXPECT_EQ(m.dim, 2);
  EXPECT_EQ(m.nodes.cols(), 2);
  expect_valid(m, w * h, 2 * (w + h));
  for (const char* g : {"xmin", "xmax", "ymin", "ymax"})
    ASSERT_EQ(m.facet_groups.count(g), 1u) << g;
  EXPECT_NEAR(hm::test::facet_measure(m, m.facet_groups.at("ymax")), w, 1e-15);
  EXPECT_NEAR(hm::test::facet_measure(m, m.facet_groups.at("xmin")), h, 1e-15);
  for (Index n : m.node_groups.at("ymax")) EXPECT_EQ(m.nodes(n, 1), h);
  // Size 1 mm across 5 mm: at least 5 edges across, so ≥ 11 nodes on the clamped edge.
  EXPECT_GE(m.node_groups.at("ymax").size(), 11u);
}

TEST(StructureMesher, PlateBoxAsTet10WithFaceGroups) {
  const Eigen::Vector3d o(0.1, -0.2, 0.0), s(0.079, 0.005, 0.03);
  const auto m = mesh_box({o, s}, options(3, 0.004));
  expect_valid(m, s.prod(), 2 * (s.x() * s.y() + s.y() * s.z() + s.z() * s.x()));
  EXPECT_NEAR(hm::test::facet_measure(m, m.facet_groups.at("xmin")), s.y() * s.z(),
              1e-12 * s.y() * s.z());
  for (Index n : m.node_groups.at("zmax")) EXPECT_EQ(m.nodes(n, 2), s.z());
  // Every boundary node with x = x0 is in xmin, and only those.
  std::set<Index> on_plane;
  for (Index f = 0; f < m.facets.rows(); ++f)
    for (Index k = 0; k < 6; ++k)
      if (m.nodes(m.facets(f, k), 0) == o.x()) on_plane.insert(m.facets(f, k));
  EXPECT_EQ(std::vector<Index>(on_plane.begin(), on_plane.end()), m.node_groups.at("xmin"));
}

TEST(StructureMesher, GeoScriptPhysicalGroups2d) {
  const auto m = mesh_geo_file(data_dir / "gate_2d.geo", options(2, 0.002));
  expect_valid(m, 0.005 * 0.079, 2 * (0.005 + 0.079));
  EXPECT_NEAR(hm::test::facet_measure(m, m.facet_groups.at("clamped")), 0.005, 1e-15);
  EXPECT_NEAR(hm::test::facet_measure(m, m.facet_groups.at("wetted")), 2 * 0.079, 1e-15);
  for (Index n : m.node_groups.at("clamped")) EXPECT_DOUBLE_EQ(m.nodes(n, 1), 0.079);
  EXPECT_EQ(static_cast<Index>(m.node_groups.at("gate").size()), m.node_count());
}

TEST(StructureMesher, GeoScriptPhysicalGroups3dWithScriptSizes) {
  MeshOptions o = options(3, 0.0);  // keep the script's lc = 4 mm
  o.required_groups = {"clamped", "wetted", "plate"};
  const auto m = mesh_geo_file(data_dir / "plate_3d.geo", o);
  expect_valid(m, 0.079 * 0.005 * 0.03, 2 * (0.079 * 0.005 + 0.005 * 0.03 + 0.03 * 0.079));
  EXPECT_NEAR(hm::test::facet_measure(m, m.facet_groups.at("clamped")), 0.005 * 0.03, 1e-17);
  EXPECT_NEAR(hm::test::facet_measure(m, m.facet_groups.at("wetted")), 0.079 * 0.03, 1e-16);
  for (Index n : m.node_groups.at("clamped")) EXPECT_EQ(m.nodes(n, 0), 0.0);
  for (Index n : m.node_groups.at("wetted")) EXPECT_EQ(m.nodes(n, 1), 0.0);
}

TEST(StructureMesher, CurvedBoundaryGetsMidEdgeNodesOnTheCurve) {
  // A disk of radius 0.1 m: with Mesh.SecondOrderLinear = 0 the boundary mid-edge nodes lie on
  // the circle (straight-edge midpoints would be inside by R(1 − cos(h/2R)) ≈ 3e-4 m here).
  const auto dir = hm::test::scratch_dir();
  std::ofstream(dir / "disk.geo") << "SetFactory(\"OpenCASCADE\");\nDisk(1) = {0, 0, 0, 0.1};\n"
                                     "Physical Curve(\"rim\") = {1};\n";
  const auto m = mesh_geo_file(dir / "disk.geo", options(2, 0.02));
  double worst = 0.0;
  for (Index f : m.facet_groups.at("rim"))
    worst = std::max(worst, std::abs(m.nodes.row(m.facets(f, 2)).norm() - 0.1));
  EXPECT_LT(worst, 1e-12);
  EXPECT_GT(hm::test::min_corner_jacobian(m), 0.0);
  EXPECT_EQ(m.facet_groups.at("rim").size(), static_cast<std::size_t>(m.facets.rows()));
}

TEST(StructureMesher, MissingGroupListsTheAvailableOnes) {
  MeshOptions o = options(3, 0.01);
  o.required_groups = {"clamp"};
  const auto message = input_error_message([&] { mesh_geo_file(data_dir / "plate_3d.geo", o); });
  EXPECT_NE(message.find("plate_3d.geo"), std::string::npos) << message;
  EXPECT_NE(message.find("group 'clamp' does not exist"), std::string::npos) << message;
  EXPECT_NE(message.find("available groups: [clamped, plate, wetted]"), std::string::npos)
      << message;
  EXPECT_NE(message.find("did you mean 'clamped'"), std::string::npos) << message;
}

TEST(StructureMesher, BoxGroupOnCadFile) {
  MeshOptions o = options(3, 0.005);
  o.box_groups = {{"clamped", {0, 0, 0}, {0, 0.005, 0.03}},
                  {"wetted", {0, 0, 0}, {0.079, 0, 0.03}}};
  o.required_groups = {"clamped", "wetted"};
  const auto m = mesh_cad_file(data_dir / "plate.step", o);
  expect_valid(m, 0.079 * 0.005 * 0.03, 2 * (0.079 * 0.005 + 0.005 * 0.03 + 0.03 * 0.079));
  EXPECT_NEAR(hm::test::facet_measure(m, m.facet_groups.at("clamped")), 0.005 * 0.03,
              1e-12 * 1.5e-4);
  EXPECT_NEAR(hm::test::facet_measure(m, m.facet_groups.at("wetted")), 0.079 * 0.03,
              1e-12 * 2.4e-3);
}

TEST(StructureMesher, EmptyBoxGroupGivesTheModelExtent) {
  MeshOptions o = options(3, 0.01);
  o.box_groups = {{"clamped", {1, 1, 1}, {2, 2, 2}}};
  const auto message = input_error_message([&] { mesh_cad_file(data_dir / "plate.step", o); });
  EXPECT_NE(message.find("group 'clamped' (box [(1, 1, 1), (2, 2, 2)]) contains no boundary node"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("x [0, 0.079]"), std::string::npos) << message;
}

TEST(StructureMesher, StlBoxBecomesATet10Volume) {
  const auto m = mesh_geometry_file(data_dir / "box_0.5x0.25x0.125.stl", options(3, 0.05));
  expect_valid(m, 0.5 * 0.25 * 0.125, 2 * (0.5 * 0.25 + 0.25 * 0.125 + 0.125 * 0.5));
  const auto box = geometry::bounding_box(m.nodes);
  EXPECT_EQ(box.min, Eigen::Vector3d(0.25, 0, 0));
  EXPECT_EQ(box.max, Eigen::Vector3d(0.75, 0.25, 0.125));
  // The surface was remeshed to the requested size: far more than the 12 input triangles.
  EXPECT_GT(m.facets.rows(), 200);
}

TEST(StructureMesher, StlInMillimetresWithItsLengthScaleIsTheMetreMesh) {
  // The same box written in millimetres, read with length_scale 0.001: the metre box.
  const auto dir = hm::test::scratch_dir();
  auto box = geometry::read_surface_file(data_dir / "box_0.5x0.25x0.125.stl");
  box.vertices *= 1000.0;
  geometry::write_stl_ascii(box, dir / "box_mm.stl");
  MeshOptions o = options(3, 0.05);
  o.length_scale = 0.001;
  const auto m = mesh_surface_file(dir / "box_mm.stl", o);
  expect_valid(m, 0.5 * 0.25 * 0.125, 2 * (0.5 * 0.25 + 0.25 * 0.125 + 0.125 * 0.5));
  const auto extent = geometry::bounding_box(m.nodes);
  EXPECT_NEAR((extent.min - Eigen::Vector3d(0.25, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((extent.max - Eigen::Vector3d(0.75, 0.25, 0.125)).norm(), 0.0, 1e-12);
}

TEST(StructureMesher, StlInMillimetresReadAsMetresIsRefusedBeforeMeshing) {
  // Read as metres, the box is 500 × 250 × 125 m: about 5.0 · 15.6e6 / 0.05³ = 6e11 tet10, far
  // beyond any machine's memory in fsi-modes. Refused with the estimate and the unit hint.
  const auto dir = hm::test::scratch_dir();
  auto box = geometry::read_surface_file(data_dir / "box_0.5x0.25x0.125.stl");
  box.vertices *= 1000.0;
  geometry::write_stl_ascii(box, dir / "box_mm.stl");
  const auto message =
      input_error_message([&] { mesh_surface_file(dir / "box_mm.stl", options(3, 0.05)); });
  EXPECT_NE(message.find("box_mm.stl: mesh size 0.05 m (structure.mesh.size) gives about 6.25e+11 "
                         "tet10 cells for a solid of 1.562e+07 m³ spanning 500 × 250 × 125 m"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("structure.geometry.length_unit = \"mm\""), std::string::npos) << message;
}

TEST(StructureMesher, CadFileIsScaledByItsLengthScale) {
  MeshOptions o = options(3, 0.01);
  o.length_scale = 2.0;  // as if plate.step were in units of 2 m
  const auto m = mesh_cad_file(data_dir / "plate.step", o);
  const double a = 2 * 0.079, b = 2 * 0.005, c = 2 * 0.03;
  expect_valid(m, a * b * c, 2 * (a * b + b * c + c * a));
}

TEST(StructureMesher, GeoScriptRefusesALengthScale) {
  MeshOptions o = options(2, 0.01);
  o.length_scale = 0.001;
  const auto message = input_error_message([&] { mesh_geo_file(data_dir / "gate_2d.geo", o); });
  EXPECT_NE(message.find("gate_2d.geo': its lengths are metres; a length scale of 0.001 cannot "
                         "apply"),
            std::string::npos)
      << message;
}

TEST(StructureMesher, InwardStlIsReorientedBeforeMeshing) {
  const auto dir = hm::test::scratch_dir();
  auto box = hm::test::box_surface({0, 0, 0}, {0.5, 0.5, 0.25});
  geometry::write_stl_ascii(box, dir / "outward.stl");
  for (Index c = 0; c < box.cells.rows(); ++c) std::swap(box.cells(c, 1), box.cells(c, 2));
  geometry::write_stl_ascii(box, dir / "inward.stl");
  const auto m = mesh_surface_file(dir / "inward.stl", options(3, 0.1));
  expect_valid(m, 0.0625, 2 * (0.25 + 0.125 + 0.125));
}

TEST(StructureMesher, BadSurfacesAreRejectedBeforeMeshing) {
  const auto dir = hm::test::scratch_dir();
  auto box = hm::test::box_surface({0, 0, 0}, {1, 1, 1});
  auto open = box;
  open.cells.conservativeResize(10, 3);  // a whole face missing
  geometry::write_stl_ascii(open, dir / "open.stl");
  auto message = input_error_message([&] { mesh_surface_file(dir / "open.stl", options(3, 0.2)); });
  EXPECT_NE(message.find("open.stl' is not closed: 4 border edges"), std::string::npos) << message;

  const auto crossing =
      hm::test::combined(box, hm::test::box_surface({0.5, 0.25, 0.25}, {1, 0.5, 0.5}));
  geometry::write_stl_ascii(crossing, dir / "crossing.stl");
  message = input_error_message([&] { mesh_surface_file(dir / "crossing.stl", options(3, 0.2)); });
  EXPECT_NE(message.find("crossing.stl' intersects itself"), std::string::npos) << message;
}

TEST(StructureMesher, FileErrorsNameTheFile) {
  auto message =
      input_error_message([] { mesh_geometry_file("/nowhere/gate.geo", options(2, 0.001)); });
  EXPECT_NE(message.find("'/nowhere/gate.geo' does not exist"), std::string::npos) << message;
  message = input_error_message([] { mesh_geometry_file("/nowhere/gate.xyz", options(2, 0.001)); });
  EXPECT_NE(message.find("extension '.xyz' is not supported"), std::string::npos) << message;
  message = input_error_message([] { mesh_cad_file("/nowhere/part.step", options(3, 0.001)); });
  EXPECT_NE(message.find("'/nowhere/part.step' does not exist"), std::string::npos) << message;
}

TEST(StructureMesher, ScriptErrorIsAnInputErrorAndGmshIsLeftClosed) {
  const auto dir = hm::test::scratch_dir();
  std::ofstream(dir / "broken.geo") << "Point(1) = {0, 0, 0, 1;\n";
  const auto message =
      input_error_message([&] { mesh_geo_file(dir / "broken.geo", options(2, 0.1)); });
  EXPECT_NE(message.find("broken.geo"), std::string::npos) << message;
  EXPECT_NE(message.find("syntax error"), std::string::npos) << message;
  // The session was closed by the exception: a new one opens, and meshing works.
  EXPECT_NO_THROW(mesh_rectangle({{0, 0}, {1, 1}}, options(2, 0.5)));
}

TEST(StructureMesher, DimensionMismatchIsExplained) {
  const auto message =
      input_error_message([&] { mesh_geo_file(data_dir / "gate_2d.geo", options(3, 0.01)); });
  EXPECT_NE(message.find("the geometry is 2-D"), std::string::npos) << message;
  EXPECT_NE(message.find("a 3-D structure mesh was asked for"), std::string::npos) << message;
}

TEST(StructureMesher, OptionsAreValidated) {
  auto message = input_error_message([] { mesh_box({}, options(3, 0.0)); });
  EXPECT_NE(message.find("mesh size 0 m is not positive"), std::string::npos) << message;
  MeshOptions o = options(3, 0.5);
  o.order = 1;
  message = input_error_message([&] { mesh_box({}, o); });
  EXPECT_NE(message.find("element order 1 is not supported"), std::string::npos) << message;
  message = input_error_message([] { mesh_box({{0, 0, 0}, {1, -1, 1}}, options(3, 0.5)); });
  EXPECT_NE(message.find("box: every side length must be positive"), std::string::npos) << message;
  o = options(3, 0.5);
  o.group_sizes = {{"clampd", 0.1}};
  message = input_error_message([&] { mesh_box({}, o); });
  EXPECT_NE(message.find("group 'clampd'"), std::string::npos) << message;
  EXPECT_NE(message.find("xmin"), std::string::npos) << message;
}

TEST(StructureMesher, GroupSizeRefinesNearTheGroup) {
  MeshOptions o = options(2, 0.01);
  const auto coarse = mesh_rectangle({{0, 0}, {0.1, 0.1}}, o);
  o.group_sizes = {{"ymin", 0.001}};
  const auto fine = mesh_rectangle({{0, 0}, {0.1, 0.1}}, o);
  const double coarse_edge = hm::test::facet_measure(coarse, coarse.facet_groups.at("ymin")) /
                             static_cast<double>(coarse.facet_groups.at("ymin").size());
  const double fine_edge = hm::test::facet_measure(fine, fine.facet_groups.at("ymin")) /
                           static_cast<double>(fine.facet_groups.at("ymin").size());
  EXPECT_NEAR(coarse_edge, 0.01, 0.001);
  EXPECT_NEAR(fine_edge, 0.001, 0.0001);
  EXPECT_NEAR(hm::test::facet_measure(fine, fine.facet_groups.at("ymax")) /
                  static_cast<double>(fine.facet_groups.at("ymax").size()),
              0.01, 0.001);  // the far edge keeps the global size
}

TEST(GmshSession, OnlyOneAtATime) {
  GmshSession first;
  EXPECT_THROW(GmshSession second, InternalError);
}

}  // namespace
}  // namespace hm::mesh
