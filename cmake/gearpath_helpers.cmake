# Build helpers. Each core module is one static library made of every .cc in its folder, and
# its tests are one GoogleTest executable made of every *_test.cc in the mirrored tests folder,
# so adding a file never needs a CMake edit.

# gearpath_module(NAME DEPS ...): library `gearpath_<NAME>` from the *.cc in this folder.
function(gearpath_module name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  if(sources)
    add_library(gearpath_${name} STATIC ${sources})
    target_include_directories(gearpath_${name} PUBLIC ${PROJECT_SOURCE_DIR})
    target_link_libraries(gearpath_${name} PUBLIC ${ARG_DEPS} PRIVATE gearpath_warnings)
    # GCC's -O2 vectorises only loops whose trip count is a known multiple of the vector length
    # ("very cheap"); the per-block kernels (docs/performance.md) are written for the vectoriser,
    # so the core libraries use the -O3 cost model at every optimisation level. It changes which
    # loops are vectorised, not results: without -ffast-math no floating-point sum is reordered.
    # -fno-math-errno: no core code reads errno after a math call, and with errno to set GCC
    # keeps every sqrt a scalar call; vsqrtpd rounds exactly as sqrtsd (IEEE), so the
    # magnitudes' loops vectorise with the same bits.
    target_compile_options(gearpath_${name} PRIVATE
      $<$<AND:$<CXX_COMPILER_ID:GNU>,$<NOT:$<CONFIG:Debug>>>:-fvect-cost-model=dynamic>
      -fno-math-errno)
    set_target_properties(gearpath_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  else()
    add_library(gearpath_${name} INTERFACE)
    target_include_directories(gearpath_${name} INTERFACE ${PROJECT_SOURCE_DIR})
    target_link_libraries(gearpath_${name} INTERFACE ${ARG_DEPS})
  endif()
endfunction()

# gearpath_module_tests(NAME DEPS ... [TIMEOUT s] [EXCLUDE gtest-patterns]): executable
# `test_<NAME>` from the *_test.cc in this folder, registered with ctest test by test. TIMEOUT is
# the per-test watchdog, so a hang fails fast instead of stalling CI. EXCLUDE (gtest filter
# syntax, ':'-separated) keeps tests out of the registration that another ctest entry runs.
# gearpath_test_pch(<target>): the headers every test parses (GoogleTest, Eigen, nlohmann-json,
# fmt: about 5 s of a 2-core CI machine per translation unit at -O2) precompiled once per test
# executable instead of in each of its ~150 sources. Tests only: the daemon's and the tools' own
# sources include what they use and nothing is forced on them.
function(gearpath_test_pch target)
  target_precompile_headers(${target} PRIVATE <gtest/gtest.h> <Eigen/Dense> <nlohmann/json.hpp>
                            <fmt/format.h> <string> <vector>)
endfunction()

function(gearpath_module_tests name)
  cmake_parse_arguments(ARG "" "TIMEOUT;EXCLUDE" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_test.cc)
  if(NOT sources)
    return()
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 120)
  endif()
  add_executable(test_${name} ${sources})
  target_include_directories(test_${name} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(test_${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main
                                             gearpath_warnings)
  target_compile_definitions(test_${name} PRIVATE
    GEARPATH_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data")
  gearpath_test_pch(test_${name})
  set(filter "")
  if(ARG_EXCLUDE)
    set(filter TEST_FILTER "-${ARG_EXCLUDE}")
  endif()
  gtest_discover_tests(test_${name} DISCOVERY_TIMEOUT 60 ${filter}
                       PROPERTIES TIMEOUT ${ARG_TIMEOUT}
                       WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
endfunction()

# gearpath_numpy_python(<var>): sets <var> (in the caller's scope) to a python3 that can import
# numpy, or to "" when there is none. /usr/bin/python3 first: Debian's interpreter has numpy
# once python3-numpy is installed (tools/install-deps.sh), while the first python3 on PATH may
# be another one without it. Cached in GEARPATH_NUMPY_PYTHON once found.
function(gearpath_numpy_python out)
  if(NOT GEARPATH_NUMPY_PYTHON)  # an earlier miss is looked for again
    set(found "")
    find_program(GEARPATH_PYTHON3_ON_PATH python3)
    foreach(candidate /usr/bin/python3 ${GEARPATH_PYTHON3_ON_PATH})
      if(NOT found AND EXISTS "${candidate}")
        execute_process(COMMAND "${candidate}" -c "import numpy" RESULT_VARIABLE numpy_missing
                        OUTPUT_QUIET ERROR_QUIET)
        if(numpy_missing EQUAL 0)
          set(found "${candidate}")
        endif()
      endif()
    endforeach()
    set(GEARPATH_NUMPY_PYTHON "${found}" CACHE INTERNAL "python3 with numpy, for the tests")
  endif()
  set(${out} "${GEARPATH_NUMPY_PYTHON}" PARENT_SCOPE)
endfunction()
