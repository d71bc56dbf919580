// fsi-mesh SCENE -o mesh.h5 — meshes the structure (and the fluid walls) of a scene with gmsh.
#include "driver/mesh_stage.hpp"
#include "stage_main.hpp"

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = "fsi-mesh",
      .summary =
          "Mesh the structure of a scene: tri6 (2-D) or tet10 (3-D) with named groups, its "
          "boundary surface and quality, and the fluid walls, written to a hydromodal.mesh "
          "artefact (+ .xdmf).",
  };
  return hm::stages::run_scene_stage(
      argc, argv, info,
      {.validate = hm::driver::validate_mesh_scene,
       .run = [](const hm::io::Scene& scene, const auto&, const std::string& output) {
         hm::driver::run_mesh_stage(scene, output);
       }});
}
