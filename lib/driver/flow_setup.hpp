#pragma once
// The flow of a scene, ready to run: solver options from [fluid], [time], [solver]; the walls of
// mesh.h5 with their prescribed motions ([[wall]] motion keys); the fluid points seeded in every
// [[fluid.region]]; the probes ([[probe]]). Checks what the keys alone cannot (keys required by
// a motion, probe names and walls, regions and probes inside the walls), naming the scene key.
#include <string>
#include <utility>
#include <vector>

#include "coupling/probes.hpp"
#include "coupling/run.hpp"
#include "io/artefact.hpp"
#include "io/scene.hpp"
#include "ldd/flow.hpp"
#include "mesh/types.hpp"

namespace hm::driver {

/// The wall name of the structure's mapped surface in a coupled scene.
inline constexpr const char* structure_wall_name = "structure";

template <int D>
struct FlowSetup {
  ldd::FlowOptions<D> options;
  std::vector<std::string> wall_names;        ///< scene [[wall]] order
  std::vector<ldd::WallMesh<D>> walls;        ///< at their t = 0 state (moving ones placed)
  std::vector<coupling::WallMotion> motions;  ///< parallel to walls
  std::vector<ldd::Vec<D>> fluid, velocity;   ///< seeded points [m] and initial velocity [m/s]
  coupling::TimeControl time;
  std::vector<coupling::Probe<D>> probes;
  std::vector<std::filesystem::path> motion_tables;  ///< CSV files read (provenance inputs)
  int structure_wall = -1;  ///< index of the structure's wall (coupled scenes), else −1
};

/// Whether the scene describes a flow (it has a [fluid] section).
bool is_flow_scene(const io::Scene& scene);

/// Every check of the flow part of a scene that needs no mesh (for --validate): [time] and a
/// [[fluid.region]] present, the keys each wall motion requires (and its CSV table readable),
/// probe names ([A-Za-z0-9_]+, unique), each probe's kind-specific keys, a force probe's wall
/// among the [[wall]] names. InputError naming the key (file:line: key).
void validate_flow_scene(const io::Scene& scene);

/// The fluid regions and the probes against the scene's [[wall]]s, meshed here (for --validate:
/// the walls of a structure are not known without its artefacts): InputError for a fluid region
/// reaching outside a closed container wall or lying inside a closed obstacle (flip_normals), and
/// for a pressure or elevation probe inside a solid, outside a container or on a thin wall,
/// naming the probe, its position and the nearest point on the fluid side (see flow_setup).
void validate_flow_geometry(const io::Scene& scene);

/// Builds the flow from the scene and the wall surfaces (name → surface, at least the scene's
/// [[wall]] names). Runs validate_flow_scene first. InputError (naming the scene key) for a
/// fluid region outside the walls, a probe position outside the walls' bounding box.
/// `structure`: the structure's surface in a coupled scene (mapped.h5's target surface), added
/// after the [[wall]]s as the wall structure_wall_name, fixed here (its modes move it), before
/// the fluid is seeded. A pressure or elevation probe within 0.05 dx of a wall's face (either
/// side) measures on the face from the fluid side: it is placed 0.001 dx in front of it, so that
/// a probe given on an STL face read in single precision does not sit inside the solid. Deeper
/// behind a face, or on a thin wall, it is an InputError naming the nearest fluid side.
template <int D>
FlowSetup<D> flow_setup(const io::Scene& scene,
                        const std::vector<std::pair<std::string, mesh::SurfaceMesh>>& surfaces,
                        const mesh::SurfaceMesh* structure = nullptr);

/// As above with the walls of a hydromodal.mesh artefact (/walls/<name>).
template <int D>
FlowSetup<D> flow_setup(const io::Scene& scene, const io::ArtefactReader& mesh_artefact,
                        const mesh::SurfaceMesh* structure = nullptr);

/// The [[wall]]s of the scene meshed here, as fsi-mesh would write them to mesh.h5 (same
/// lib/mesh functions and keys): for rigid-only scenes, which fsi-mesh does not take (it needs a
/// [structure]). The surface files of kind = "file" walls are appended to `files`.
std::vector<std::pair<std::string, mesh::SurfaceMesh>> scene_wall_surfaces(
    const io::Scene& scene, std::vector<std::filesystem::path>* files = nullptr);

/// The default gravity: −9.81 m/s² along the last axis.
template <int D>
ldd::Vec<D> default_gravity();

}  // namespace hm::driver
