# Every third-party library hydromodal uses, found from Debian 12 packages.
# A missing one stops configuration with the name of the Debian package that provides it;
# `.ci/install-deps` installs them all.

function(hm_require found_var debian_package what)
  if(NOT ${found_var})
    message(FATAL_ERROR
      "hydromodal: ${what} not found. Install the Debian package '${debian_package}' "
      "(or run: bash .ci/install-deps).")
  endif()
endfunction()

# An IMPORTED target for a library with neither a CMake config nor a .pc file: lib<library> found
# on the system, headers in `include_dir` (found by the caller); stops like hm_require if either
# is missing.
function(hm_import_library target library include_dir debian_package what)
  string(MAKE_C_IDENTIFIER "${target}" prefix)
  find_library(${prefix}_LIBRARY ${library})
  set(found FALSE)
  if(include_dir AND ${prefix}_LIBRARY)
    set(found TRUE)
  endif()
  hm_require(found "${debian_package}" "${what}")
  if(NOT TARGET ${target})
    add_library(${target} UNKNOWN IMPORTED)
    set_target_properties(${target} PROPERTIES IMPORTED_LOCATION "${${prefix}_LIBRARY}"
                                               INTERFACE_INCLUDE_DIRECTORIES "${include_dir}")
  endif()
endfunction()

find_package(Eigen3 3.3 QUIET NO_MODULE)
hm_require(Eigen3_FOUND libeigen3-dev "Eigen 3")

find_package(Spectra QUIET)
hm_require(Spectra_FOUND libspectra-dev "Spectra")

find_package(HDF5 QUIET COMPONENTS C)
hm_require(HDF5_FOUND libhdf5-dev "HDF5 (C library)")

find_package(tomlplusplus QUIET)
hm_require(tomlplusplus_FOUND libtomlplusplus-dev "toml++")

find_package(CLI11 QUIET)
hm_require(CLI11_FOUND libcli11-dev "CLI11")

find_package(fmt QUIET)
hm_require(fmt_FOUND libfmt-dev "fmt")

find_package(spdlog QUIET)
hm_require(spdlog_FOUND libspdlog-dev "spdlog")

find_package(nlohmann_json 3 QUIET)
hm_require(nlohmann_json_FOUND nlohmann-json3-dev "nlohmann-json")

find_package(nanoflann QUIET)
hm_require(nanoflann_FOUND libnanoflann-dev "nanoflann")

find_package(OpenSSL QUIET COMPONENTS Crypto)
hm_require(OPENSSL_FOUND libssl-dev "OpenSSL libcrypto (SHA-256 of inputs)")

find_package(OpenMP QUIET COMPONENTS CXX)
hm_require(OpenMP_CXX_FOUND g++ "OpenMP for C++")

find_package(assimp QUIET)
hm_require(assimp_FOUND libassimp-dev "assimp")

set(CGAL_DISABLE_GMP ON)
set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)
find_package(CGAL QUIET)
hm_require(CGAL_FOUND libcgal-dev "CGAL")

find_package(PkgConfig QUIET)
hm_require(PKG_CONFIG_FOUND pkg-config "pkg-config")
pkg_check_modules(ARPACK QUIET IMPORTED_TARGET arpack)
hm_require(ARPACK_FOUND libarpack2-dev "ARPACK-ng")

# gmsh 4.8 ships only gmsh.h and libgmsh.so (no CMake config, no .pc).
find_path(GMSH_INCLUDE_DIR gmsh.h)
hm_import_library(gmsh::gmsh gmsh "${GMSH_INCLUDE_DIR}" libgmsh-dev "gmsh C++ API")

# CHOLMOD (SuiteSparse 5.12) has no CMake config and no .pc either.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
hm_import_library(SuiteSparse::CHOLMOD cholmod "${CHOLMOD_INCLUDE_DIR}" libsuitesparse-dev
                  "SuiteSparse CHOLMOD")
# UMFPACK (the same package, headers beside CHOLMOD's): the sparse LU of large unsymmetric
# Newton matrices.
hm_import_library(SuiteSparse::UMFPACK umfpack "${CHOLMOD_INCLUDE_DIR}" libsuitesparse-dev
                  "SuiteSparse UMFPACK")

# BLAS (libblas-dev, which libsuitesparse-dev depends on; OpenBLAS replaces it at run time
# through update-alternatives): the dense symmetric rank-k updates of the reduced tensors.
find_package(BLAS QUIET)
hm_require(BLAS_FOUND libblas-dev "BLAS")

if(HM_BUILD_TESTS)
  find_package(GTest QUIET)
  hm_require(GTest_FOUND libgtest-dev "GoogleTest")
endif()
if(HM_BUILD_BENCHMARKS)
  find_package(benchmark QUIET)
  hm_require(benchmark_FOUND libbenchmark-dev "Google Benchmark")
endif()

# PETSc 3.18 (petsc-dev, built on OpenMPI, with hypre's BoomerAMG inside): the algebraic-
# multigrid backends of the linear-solver seam (lib/linsolve). Without it (or with HM_PETSC=OFF)
# the build has the native solvers only, and a scene asking for boomeramg or gamg is refused.
# petsc.h includes mpi.h, whose headers the .pc file does not name: MPI's C target adds them.
set(HM_WITH_PETSC FALSE)
if(HM_PETSC)
  pkg_check_modules(PETSC QUIET IMPORTED_TARGET petsc)
  find_package(MPI QUIET COMPONENTS C)
  if(PETSC_FOUND AND MPI_C_FOUND)
    set(HM_WITH_PETSC TRUE)
    message(STATUS "hydromodal: PETSc ${PETSC_VERSION} found: the boomeramg and gamg solvers are built")
  else()
    message(STATUS "hydromodal: PETSc not found (Debian: petsc-dev, openmpi-bin): "
                   "only the jacobi and ilu solvers are built")
  endif()
endif()

# Zoltan 13.2 (libtrilinos-zoltan-dev, already a dependency of petsc-dev): the decomposition of
# the points over MPI processes (lib/parallel: recursive coordinate bisection, point and box
# assignment for migration and ghosts). Built with PETSc's MPI; without either, no lib/parallel.
set(HM_WITH_ZOLTAN FALSE)
if(HM_WITH_PETSC)
  find_package(Zoltan CONFIG QUIET PATHS /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/Zoltan)
  if(Zoltan_FOUND AND TARGET trilinos_zoltan)
    set(HM_WITH_ZOLTAN TRUE)
    message(STATUS "hydromodal: Zoltan found: the point decomposition (lib/parallel) is built")
  else()
    message(STATUS "hydromodal: Zoltan not found (Debian: libtrilinos-zoltan-dev): "
                   "no point decomposition")
  endif()
endif()
