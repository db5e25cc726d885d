# Unity ("jumbo") builds of the test suite and the CLI (build time only; the library is left alone so
# that its code generation, and with it the benchmarks, does not depend on which files share a batch).
# Each test file and each CLI file includes gtest or CLI11 plus Eigen, fmt and nlohmann json: parsing
# them was most of a file's time (docs/benchmarks.md "Build and test time"), so MACHDYN_UNITY_BATCH
# files are compiled as one translation unit.
#
# Test files keep their helpers apart with `namespace MACHDYN_UNITY_ID { ... }` where they would write
# `namespace { ... }`: CMake defines MACHDYN_UNITY_ID to a name unique per file inside a batch; outside
# a unity build it is empty, which leaves the anonymous namespace.
option(MACHDYN_UNITY "Compile the test suite and the CLI in batches (faster builds)" ON)
set(MACHDYN_UNITY_BATCH 8 CACHE STRING "source files per translation unit of a unity build")

# machdyn_unity(TARGET): a unity build of TARGET when MACHDYN_UNITY is on.
function(machdyn_unity target)
  if(MACHDYN_UNITY)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${MACHDYN_UNITY_BATCH}
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
