# Unity ("jumbo") builds (build time only): a batch of source files compiled as one translation unit.
# Each test file and each CLI file includes gtest or CLI11 plus Eigen, fmt and nlohmann json: parsing
# them was most of a file's time (docs/benchmarks.md "Build and test time"). The library's Eigen-heavy
# files instantiate the same decompositions, each once per translation unit.
#
# The test suite and the CLI: batches by default (MACHDYN_UNITY). The library: batches only with
# MACHDYN_UNITY_LIBRARY, which `make test` sets for its two trees (build/test, build/asan). The release
# tree (`make demo`, `make bench`) compiles the library file by file, so that the benchmarks' code does
# not depend on which files share a batch (MACHDYN_BENCH refuses the option) and an edit recompiles one
# file. Library files do not use MACHDYN_UNITY_ID: no two of them define one name in an anonymous
# namespace (a constant or helper two files share lives in one header, src/common/constants.hpp,
# src/io/number_text.hpp ...), so every batching compiles the same functions.
#
# Test files keep their helpers apart with `namespace MACHDYN_UNITY_ID { ... }` where they would write
# `namespace { ... }`: CMake defines MACHDYN_UNITY_ID to a name unique per file inside a batch; outside
# a unity build it is empty, which leaves the anonymous namespace.
option(MACHDYN_UNITY "Compile the test suite and the CLI in batches (faster builds)" ON)
set(MACHDYN_UNITY_BATCH 8 CACHE STRING "source files per translation unit of a unity build (the CLI)")
# The test suite in batches of 16: two batches of 8 took 134 s of CPU under clang with ASan and UBSan,
# the same 16 files as one 117 s (GCC at -O1: 58 against 53 s); fewer batches parse gtest, Eigen and
# json fewer times (docs/benchmarks.md "Build and test time").
set(MACHDYN_UNITY_TEST_BATCH 16 CACHE STRING "test files per translation unit of a unity build")

# machdyn_unity(TARGET [BATCH]): a unity build of TARGET when MACHDYN_UNITY is on, BATCH files per
# translation unit (MACHDYN_UNITY_BATCH by default).
function(machdyn_unity target)
  set(batch ${MACHDYN_UNITY_BATCH})
  if(ARGC GREATER 1)
    set(batch ${ARGV1})
  endif()
  if(MACHDYN_UNITY)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${batch}
                                               UNITY_BUILD_UNIQUE_ID MACHDYN_UNITY_ID)
    # GCC 12 at -O3 reports -Wrestrict inside std::string's operator+(const char*, string&&) when enough
    # code is inlined around it (a false positive, GCC bug 105651); which batch meets it depends on the
    # batch's other files, so the warning is off for these targets rather than worked around per line.
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      target_compile_options(${target} PRIVATE -Wno-restrict)
    endif()
  else()
    target_compile_definitions(${target} PRIVATE MACHDYN_UNITY_ID=)
  endif()
endfunction()

option(MACHDYN_UNITY_LIBRARY "Compile the library in batches too (make test's trees; not with MACHDYN_BENCH)" OFF)
set(MACHDYN_UNITY_LIBRARY_BATCH 16 CACHE STRING "library source files per translation unit (MACHDYN_UNITY_LIBRARY)")

# machdyn_unity_library(TARGET): a unity build of the library TARGET when MACHDYN_UNITY_LIBRARY is on.
function(machdyn_unity_library target)
  if(NOT MACHDYN_UNITY_LIBRARY)
    return()
  endif()
  if(MACHDYN_BENCH)
    message(FATAL_ERROR "MACHDYN_UNITY_LIBRARY=ON with MACHDYN_BENCH=ON: the benchmarks measure the library "
                        "compiled file by file; configure the benchmark tree without MACHDYN_UNITY_LIBRARY")
  endif()
  set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${MACHDYN_UNITY_LIBRARY_BATCH})
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wno-restrict)  # GCC bug 105651, as above
  endif()
endfunction()
