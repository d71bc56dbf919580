#pragma once
// The PETSc backends of the linear-solver seam (boomeramg, gamg). In a build without PETSc
// petsc_available() is false and make_petsc_solver() is never called. PETSc (and MPI, as a
// one-rank singleton when the process was not started by mpirun) is initialised on the first
// PETSc solver made and finalised at exit; its signal handlers are not installed, so the stages'
// own interrupt handling stays in charge.
#include <memory>

#include "linsolve/linear_solver.hpp"

namespace hm::linsolve {

bool petsc_available();
std::unique_ptr<LinearSolver> make_petsc_solver(Method method, const Settings& settings);

}  // namespace hm::linsolve
