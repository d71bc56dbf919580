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
find_library(GMSH_LIBRARY gmsh)
if(GMSH_INCLUDE_DIR AND GMSH_LIBRARY)
  set(GMSH_FOUND TRUE)
endif()
hm_require(GMSH_FOUND libgmsh-dev "gmsh C++ API")
if(NOT TARGET gmsh::gmsh)
  add_library(gmsh::gmsh UNKNOWN IMPORTED)
  set_target_properties(gmsh::gmsh PROPERTIES IMPORTED_LOCATION "${GMSH_LIBRARY}"
                                              INTERFACE_INCLUDE_DIRECTORIES "${GMSH_INCLUDE_DIR}")
endif()

# CHOLMOD (SuiteSparse 5.12) has no CMake config and no .pc either.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY cholmod)
if(CHOLMOD_INCLUDE_DIR AND CHOLMOD_LIBRARY)
  set(CHOLMOD_FOUND TRUE)
endif()
hm_require(CHOLMOD_FOUND libsuitesparse-dev "SuiteSparse CHOLMOD")
if(NOT TARGET SuiteSparse::CHOLMOD)
  add_library(SuiteSparse::CHOLMOD UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::CHOLMOD PROPERTIES IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
                                                      INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}")
endif()

# UMFPACK (the same SuiteSparse package): the sparse LU of large unsymmetric Newton matrices.
find_library(UMFPACK_LIBRARY umfpack)
if(CHOLMOD_INCLUDE_DIR AND UMFPACK_LIBRARY)
  set(UMFPACK_FOUND TRUE)
endif()
hm_require(UMFPACK_FOUND libsuitesparse-dev "SuiteSparse UMFPACK")
if(NOT TARGET SuiteSparse::UMFPACK)
  add_library(SuiteSparse::UMFPACK UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::UMFPACK PROPERTIES IMPORTED_LOCATION "${UMFPACK_LIBRARY}"
                                                      INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}")
endif()

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
