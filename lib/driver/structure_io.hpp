#pragma once
// The structure mesh in artefacts: written by fsi-mesh (hydromodal.mesh, under /structure) and
// copied by fsi-modes (hydromodal.modes, under /mesh) so that an archived mode set carries the
// mesh it was computed on.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fem/material.hpp"
#include "fem/reduced_stvk.hpp"
#include "io/artefact.hpp"
#include "io/scene.hpp"
#include "mesh/boundary.hpp"
#include "mesh/types.hpp"
#include "modal/modes.hpp"

namespace hm::driver {

/// Cells in VTK/XDMF node order (tet10: gmsh nodes 8 and 9 swapped; tri6 unchanged).
mesh::IndexMatrix cells_in_vtk_order(const mesh::StructureMesh& mesh);

/// Writes nodes, cells, facets, groups, the linear boundary surface and the cell quality.
void write_structure_mesh(io::ArtefactWriter& writer, const mesh::StructureMesh& mesh,
                          const mesh::BoundarySurface& surface, const Eigen::VectorXd& quality);

struct MeshArtefact {
  mesh::StructureMesh structure;
  mesh::BoundarySurface surface;
};
/// Reads the structure of a hydromodal.mesh artefact (checked against its schema).
MeshArtefact read_structure_mesh(const io::ArtefactReader& reader);

/// The mode set of a hydromodal.modes artefact, as far as modal superposition needs it: dim,
/// λ, ω, f, ζ and the shapes as full DOF vectors (n_nodes·dim × n_modes, DOF = dim·node + c).
modal::ModeSet read_mode_set(const io::ArtefactReader& reader);

/// The reduced model of a mode set computed with modes.derivatives (hydromodal.modes version 2:
/// /basis/vectors and /reduced/*), the tensors of structure.model = "nonlinear_modal"; nullopt
/// when the set has none. InputError naming the file when its parts do not fit each other.
std::optional<fem::ReducedStvk> read_reduced_model(const io::ArtefactReader& reader);

/// The linear material of the scene's [structure] (E, ν, ρ; 2-D section and thickness).
fem::ElasticModel elastic_model(const io::Scene& scene);

/// The clamped node groups of structure.clamped (none: a free-free body).
std::vector<std::string> clamped_groups(const io::Scene& scene);

/// XDMF sidecar of a mesh artefact: the structure with its quality field, and each wall.
void write_mesh_xdmf(const std::filesystem::path& h5_path, const mesh::StructureMesh& mesh,
                     const std::map<std::string, mesh::SurfaceMesh>& walls = {});

}  // namespace hm::driver
