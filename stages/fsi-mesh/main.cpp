// fsi-mesh SCENE -o mesh.h5 — meshes the structure of a scene (gmsh; quadratic elements).
#include "driver/mesh_stage.hpp"
#include "io/scene.hpp"
#include "stage_main.hpp"

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = "fsi-mesh",
      .summary =
          "Mesh the structure of a scene: tri6 (2-D) or tet10 (3-D) with named groups, its "
          "boundary surface and quality, written to a hydromodal.mesh artefact (+ .xdmf).",
  };
  return hm::stages::run_stage(argc, argv, info, [](const hm::stages::StageArgs& args) {
    const hm::io::Scene scene = hm::io::Scene::load(args.positional);
    spdlog::info("fsi-mesh: resolved parameters of {}:\n{}", args.positional,
                 scene.parameters_for("fsi-mesh"));
    if (args.validate) {
      hm::driver::validate_mesh_scene(scene);
      spdlog::info("fsi-mesh: {} is valid for this stage", args.positional);
      return;
    }
    if (args.output.empty()) throw hm::UsageError("fsi-mesh: -o/--output FILE is required");
    hm::driver::run_mesh_stage(scene, args.output);
  });
}
