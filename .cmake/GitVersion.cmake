# Generates ${PROJECT_BINARY_DIR}/generated/hm_version.cpp on every build, rewriting it only when
# the version differs (WriteVersion.cmake: the git hash, a hash of uncommitted code changes, or of
# the code files of a source archive), so artefacts name the exact tool.
set(HM_VERSION_CPP ${PROJECT_BINARY_DIR}/generated/hm_version.cpp)
add_custom_target(hm_git_version
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DOUT=${HM_VERSION_CPP}
          -DPROJECT_VERSION=${PROJECT_VERSION} -P ${PROJECT_SOURCE_DIR}/.cmake/WriteVersion.cmake
  BYPRODUCTS ${HM_VERSION_CPP}
  COMMENT "hydromodal version stamp")
