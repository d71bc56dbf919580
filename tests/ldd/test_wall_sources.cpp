// Walls from where a run gets them (issue 5): (a) a 2-D tank meshed by fsi-mesh into mesh.h5 and
// read back by driver::read_wall; (b) a 3-D tank read from an STL file (assimp). In both cases a
// water column at rest gets one PPE solve, asserted against ρg(H − z) within 0.5 % of ρgH at
// every point below the top layer, as the hydrostatic tests on lib/mesh walls.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "../common/scratch.hpp"
#include "core/errors.hpp"
#include "driver/mesh_stage.hpp"
#include "driver/wall_io.hpp"
#include "geometry/surface_io.hpp"
#include "io/scene.hpp"
#include "io/schema.hpp"
#include "tank.hpp"

namespace fs = std::filesystem;

namespace hm::ldd {
namespace {

using hm::test::fresh_dir;

// A small clamped gate (the scene needs a structure) and a closed 0.5 × 0.4 m tank.
const char* scene_2d = R"([case]
name = "tank2d"
dimension = 2
[structure]
clamped = "ymax"
[structure.geometry]
kind = "rectangle"
origin = [0.2, 0.3]
size = [0.01, 0.05]
[structure.mesh]
size = 0.005
[structure.material]
youngs_modulus = 12e6
poisson_ratio = 0.4
density = 1100
[modes]
count = 2
[[wall]]
name = "tank"
kind = "rectangle"
origin = [0.0, 0.0]
size = [0.5, 0.4]
mesh_size = 0.05
)";

TEST(LddWallSources, TankFromMeshArtefact2D) {
  const fs::path dir = fresh_dir("mesh_h5");
  std::ofstream(dir / "scene.toml") << scene_2d;
  driver::run_mesh_stage(io::Scene::load(dir / "scene.toml"), dir / "mesh.h5");
  const io::ArtefactReader reader(dir / "mesh.h5", io::mesh_schema());
  EXPECT_EQ(driver::wall_names(reader), std::vector<std::string>{"tank"});
  const mesh::SurfaceMesh surface = driver::read_wall(reader, "tank");
  ASSERT_EQ(surface.dim, 2);
  EXPECT_EQ(surface.cells.rows(), 4 * 9);  // 0.5 m / 0.05 + 0.4 m / 0.05, twice
  WallMesh<2> tank(surface, "tank");
  EXPECT_EQ(tank.open_boundary_count(), 0);

  const auto c = test::water_column_in<2>(std::move(tank), Vec<2>(0.5, 0.4), 0.3, 0.01);
  ASSERT_TRUE(c.report.converged);
  const double err = test::hydrostatic_error<2>(c);
  std::printf("2-D tank from mesh.h5: %d unknowns, %d iterations, max error %.2e of rho g H\n",
              c.report.unknowns, c.report.iterations, err);
  EXPECT_LT(err, 0.005);
  fs::remove_all(dir);
}

TEST(LddWallSources, UnknownWallNamesThePresentOnes) {
  const fs::path dir = fresh_dir("mesh_h5_bad");
  std::ofstream(dir / "scene.toml") << scene_2d;
  driver::run_mesh_stage(io::Scene::load(dir / "scene.toml"), dir / "mesh.h5");
  const io::ArtefactReader reader(dir / "mesh.h5", io::mesh_schema());
  try {
    (void)driver::read_wall(reader, "basin");
    ADD_FAILURE() << "no InputError for an unknown wall";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("mesh.h5"), std::string::npos) << what;
    EXPECT_NE(what.find("'basin'"), std::string::npos) << what;
    EXPECT_NE(what.find("walls present: tank"), std::string::npos) << what;
  }
  fs::remove_all(dir);
}

TEST(LddWallSources, TankFromStlFile3D) {
  const fs::path dir = fresh_dir("stl");
  const Vec<3> size(0.15, 0.125, 0.3);
  mesh::WallOptions o;
  o.dim = 3;
  o.size = 0.1;
  const mesh::SurfaceMesh box = mesh::mesh_box_walls({Eigen::Vector3d::Zero(), size}, o);
  geometry::write_stl_ascii(box, dir / "tank.stl", "tank");
  const mesh::SurfaceMesh surface = geometry::read_surface_file(dir / "tank.stl");
  ASSERT_EQ(surface.cells.rows(), box.cells.rows());
  EXPECT_EQ(surface.vertices.rows(), box.vertices.rows());  // STL repeats them; merged on read
  WallMesh<3> tank(surface, "tank.stl");
  EXPECT_EQ(tank.open_boundary_count(), 0);

  const auto c = test::water_column_in<3>(std::move(tank), size, 0.2, 0.0125);
  ASSERT_TRUE(c.report.converged);
  const double err = test::hydrostatic_error<3>(c);
  std::printf("3-D tank from STL: %d unknowns, %d iterations, max error %.2e of rho g H\n",
              c.report.unknowns, c.report.iterations, err);
  EXPECT_LT(err, 0.005);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace hm::ldd
