#pragma once
// fsi-modes: scene + mesh.h5 → modes.h5 (hydromodal.modes) + modes.xdmf.
#include <filesystem>

#include "io/scene.hpp"

namespace hm::driver {

/// Checks everything fsi-modes needs from the scene (for --validate).
void validate_modes_scene(const io::Scene& scene);

/// Assembles K and M on the mesh of `mesh_artefact`, extracts the requested modes, checks their
/// invariants and writes the artefact atomically. With modes.derivatives also the reduced model
/// of structure.model = "nonlinear_modal": the static modal derivatives of the modes, the
/// M-orthonormal basis of both and its Saint Venant–Kirchhoff tensors (fem/reduced_basis.hpp,
/// fem/reduced_stvk.hpp). NumericalError (exit 3) when the eigensolver
/// does not converge: the converged modes are then kept in "<output stem>.failed.h5" with the
/// status recorded, and nothing is written at `output`.
void run_modes_stage(const io::Scene& scene, const std::filesystem::path& mesh_artefact,
                     const std::filesystem::path& output);

}  // namespace hm::driver
