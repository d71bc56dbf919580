// The structure stages in process: fsi-mesh → fsi-modes → fsi-map on small 2-D and 3-D cases,
// checking what crosses the artefacts (modes survive the round trip, the map of the structure's
// own surface is the identity, bad targets are refused with their reason).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "../common/scratch.hpp"
#include "core/errors.hpp"
#include "driver/map_stage.hpp"
#include "driver/mesh_stage.hpp"
#include "driver/modes_stage.hpp"
#include "geometry/surface_io.hpp"
#include "io/artefact.hpp"
#include "io/scene.hpp"

namespace fs = std::filesystem;
using namespace hm;

namespace {

using hm::test::fresh_dir;

io::Scene write_scene(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return io::Scene::load(path);
}

const char* gate = R"([case]
name = "gate"
dimension = 2
[structure]
clamped = "ymax"
[structure.geometry]
kind = "rectangle"
origin = [0.1, 0.0]
size = [0.005, 0.079]
[structure.mesh]
size = 0.0025
[structure.material]
youngs_modulus = 12e6
poisson_ratio = 0.4
density = 1100
[modes]
count = 4
)";

std::string plate(const std::string& map_section) {
  return std::string(R"([case]
name = "plate"
dimension = 3
[structure]
clamped = "xmin"
[structure.geometry]
kind = "box"
origin = [0.0, 0.0, 0.0]
size = [0.1, 0.02, 0.01]
[structure.mesh]
size = 0.005
[structure.material]
youngs_modulus = 2e11
poisson_ratio = 0.3
density = 7850
[modes]
count = 4
)") + map_section;
}

io::MatrixRM stacked(const io::ArtefactReader& r, const std::string& dataset) {
  const io::Dims d = r.dims(dataset);
  const std::vector<double> v = r.read_values(dataset);
  return Eigen::Map<const io::MatrixRM>(v.data(), static_cast<Eigen::Index>(d[0]),
                                        static_cast<Eigen::Index>(d[1] * d[2]));
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

}  // namespace

TEST(StructureChain, GateModesRoundTripAndIdentityMap) {
  const fs::path dir = fresh_dir("gate");
  const io::Scene scene = write_scene(dir / "scene.toml", gate);
  driver::run_mesh_stage(scene, dir / "mesh.h5");
  driver::run_modes_stage(scene, dir / "mesh.h5", dir / "modes.h5");
  driver::run_map_stage(scene, dir / "modes.h5", dir / "mapped.h5");
  const io::Scene refined =
      write_scene(dir / "refined.toml", std::string(gate) + "[map]\nmax_edge = 0.0002\n");
  driver::run_map_stage(refined, dir / "modes.h5", dir / "refined.h5");
  EXPECT_GT(io::ArtefactReader(dir / "refined.h5", io::mapped_modes_schema()).extent("n_target"),
            io::ArtefactReader(dir / "mapped.h5", io::mapped_modes_schema()).extent("n_target"));

  const io::ArtefactReader modes(dir / "modes.h5", io::modes_schema());
  EXPECT_EQ(modes.extent("n_modes"), 4u);
  const std::vector<double> f = modes.read_values(io::ds::frequencies_hz);
  EXPECT_NEAR(f[0], 14.75, 0.02 * 14.75) << "Euler–Bernoulli with E/(1 − nu^2)";
  for (double r : modes.read_values(io::ds::residual)) EXPECT_LE(r, 1e-8);
  for (double o : modes.read_values(io::ds::orthogonality_error)) EXPECT_LE(o, 1e-10);
  EXPECT_EQ(modes.provenance().inputs.size(), 2u);

  // The structure's own surface as target: the map must be the identity.
  const io::ArtefactReader mapped(dir / "mapped.h5", io::mapped_modes_schema());
  const io::MatrixRM on_surface = stacked(modes, io::ds::surface_shapes);
  const io::MatrixRM on_target = stacked(mapped, io::ds::mapped_shapes);
  ASSERT_EQ(on_surface.rows(), on_target.rows());
  ASSERT_EQ(on_surface.cols(), on_target.cols());
  EXPECT_LE((on_surface - on_target).cwiseAbs().maxCoeff(),
            1e-12 * on_surface.cwiseAbs().maxCoeff());
  EXPECT_EQ(mapped.read_values(io::ds::frequencies_hz), f);
}

TEST(StructureChain, PlateMapsOntoARefinedSurfaceAndRefusesBadTargets) {
  const fs::path dir = fresh_dir("plate");
  const io::Scene scene = write_scene(dir / "scene.toml", plate("[map]\nmax_edge = 0.002\n"));
  driver::run_mesh_stage(scene, dir / "mesh.h5");
  driver::run_modes_stage(scene, dir / "mesh.h5", dir / "modes.h5");
  driver::run_map_stage(scene, dir / "modes.h5", dir / "mapped.h5");
  const io::ArtefactReader mapped(dir / "mapped.h5", io::mapped_modes_schema());
  EXPECT_GT(mapped.extent("n_target"),
            io::ArtefactReader(dir / "modes.h5", io::modes_schema()).extent("n_surface_vertices"));
  // Refinement keeps the structure's surface vertices first: there the interpolant must return
  // the source values (RBF interpolation is exact at its centres).
  const io::ArtefactReader source(dir / "modes.h5", io::modes_schema());
  const io::MatrixRM on_surface = stacked(source, io::ds::surface_shapes);
  const io::MatrixRM on_target = stacked(mapped, io::ds::mapped_shapes);
  const Eigen::Index n = on_surface.cols();
  EXPECT_EQ(mapped.read_matrix(io::ds::target_vertices).topRows(n / 3),
            source.read_matrix(io::ds::modes_surface_vertices));
  EXPECT_LE((on_target.leftCols(n) - on_surface).cwiseAbs().maxCoeff(),
            1e-10 * on_surface.cwiseAbs().maxCoeff());

  // A target surface in millimetres, and one beside the plate.
  const io::ArtefactReader modes(dir / "modes.h5", io::modes_schema());
  mesh::SurfaceMesh surface;
  surface.dim = 3;
  surface.vertices = modes.read_matrix(io::ds::modes_surface_vertices);
  surface.cells = modes.read_indices(io::ds::modes_surface_cells);
  mesh::SurfaceMesh in_mm = surface;
  in_mm.vertices *= 1000.0;
  geometry::write_stl_ascii(in_mm, dir / "plate_mm.stl");
  mesh::SurfaceMesh beside = surface;
  beside.vertices.col(1).array() += 0.05;
  geometry::write_stl_ascii(beside, dir / "beside.stl");

  const io::Scene mm =
      write_scene(dir / "mm.toml", plate("[map]\ntarget = \"file\"\nfile = \"plate_mm.stl\"\n"));
  const std::string units =
      error_of([&] { driver::run_map_stage(mm, dir / "modes.h5", dir / "mm.h5"); });
  EXPECT_NE(units.find("units differ by ~1000? (mm vs m)"), std::string::npos) << units;
  EXPECT_FALSE(fs::exists(dir / "mm.h5"));

  const io::Scene far =
      write_scene(dir / "far.toml", plate("[map]\ntarget = \"file\"\nfile = \"beside.stl\"\n"));
  const std::string disjoint =
      error_of([&] { driver::run_map_stage(far, dir / "modes.h5", dir / "far.h5"); });
  EXPECT_NE(disjoint.find("target points lie farther than the support radius"), std::string::npos)
      << disjoint;
  EXPECT_FALSE(fs::exists(dir / "far.h5"));
}
