# Precompiled headers (build time only; no effect on the code): the heavy, stable third-party and
# standard headers are parsed once per target instead of once per source file. Measured in
# docs/benchmarks.md ("Build and test time"). Only headers outside this project go in, so that editing
# a machdyn header does not rebuild every file of a target through its precompiled header.
# MACHDYN_PCH=OFF builds without them (e.g. to check that every file includes what it uses).
option(MACHDYN_PCH "Precompile the heavy third-party headers (faster builds)" ON)

set(MACHDYN_PCH_HEADERS
  <algorithm> <array> <cmath> <cstdint> <filesystem> <fstream> <functional> <map> <memory>
  <optional> <sstream> <stdexcept> <string> <string_view> <vector>
  <Eigen/Core> <Eigen/SparseCore> <fmt/format.h> <nlohmann/json.hpp>)

# ccache caches files compiled with a precompiled header only when it may ignore __DATE__/__TIME__
# and the header's #defines (its manual, "Precompiled headers"); clang must also leave the timestamp
# out of the header (see machdyn_precompile). Ninja's dependency files still rebuild the header when
# any header in it changes.
if(MACHDYN_PCH AND CMAKE_CXX_COMPILER_LAUNCHER MATCHES "ccache")
  set(CMAKE_CXX_COMPILER_LAUNCHER ${CMAKE_COMMAND} -E env CCACHE_SLOPPINESS=pch_defines,time_macros
      ${CMAKE_CXX_COMPILER_LAUNCHER})
endif()

# machdyn_precompile(TARGET [EXTRA_HEADER...]): the common set plus the target's own heavy headers
# (gtest for the tests, CLI11 for the CLI).
function(machdyn_precompile target)
  if(MACHDYN_PCH)
    target_precompile_headers(${target} PRIVATE ${MACHDYN_PCH_HEADERS} ${ARGN})
    if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
      target_compile_options(${target} PRIVATE "SHELL:-Xclang -fno-pch-timestamp")
    endif()
  endif()
endfunction()
