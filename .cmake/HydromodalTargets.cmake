# Common compile settings for every hydromodal target.

add_library(hm_warnings INTERFACE)
target_compile_options(hm_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                             -Wno-psabi -Wno-missing-field-initializers)
if(HM_WERROR)
  target_compile_options(hm_warnings INTERFACE -Werror)
endif()
if(HM_ASSERTIONS)
  target_compile_definitions(hm_warnings INTERFACE HM_ENABLE_ASSERTIONS=1)
endif()

# hm_add_library(<name> SOURCES ... [DEPS ...]) — a library of lib/<folder>, linked as hm::<name>.
function(hm_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(hm_${name} STATIC ${ARG_SOURCES})
  add_library(hm::${name} ALIAS hm_${name})
  target_include_directories(hm_${name} PUBLIC ${PROJECT_SOURCE_DIR}/lib)
  target_link_libraries(hm_${name} PUBLIC ${ARG_DEPS} PRIVATE hm_warnings ${ARG_PRIVATE_DEPS})
endfunction()

# hm_add_stage(<exe-name> SOURCES ... DEPS ...) — one stage executable.
function(hm_add_stage name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE hm_warnings ${ARG_DEPS})
endfunction()

# hm_add_test(<name> SOURCES ... DEPS ... [LABELS ...]) — one GoogleTest binary, every case in ctest.
# Each case runs on 2 OpenMP threads (the parallel loops are exercised) whose idle threads sleep
# instead of spinning: with ctest -j2 two such cases share the 2 cores, and libgomp's spinning
# threads then took the cases 5-8x their time alone (a 14.7 s case took 82 s beside a 17.5 s
# one, which took 84 s; with OMP_WAIT_POLICY=PASSIVE 15.8 and 33.0 s).
function(hm_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE hm_warnings GTest::gtest_main ${ARG_DEPS})
  target_compile_definitions(${name} PRIVATE HM_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                             HM_BINARY_DIR="${PROJECT_BINARY_DIR}")
  gtest_discover_tests(${name} DISCOVERY_MODE PRE_TEST
                       PROPERTIES LABELS "${ARG_LABELS}" ENVIRONMENT "OMP_NUM_THREADS=2"
                                  ENVIRONMENT_MODIFICATION "OMP_WAIT_POLICY=set:PASSIVE")
endfunction()
