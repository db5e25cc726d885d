# Precompiled headers (build time only; no effect on the code): the heavy, stable third-party and
# standard headers are parsed once per target instead of once per source file. Only headers outside
# this project go in, so that editing a machdyn header does not rebuild a whole target through them.
# On by default for clang only (the sanitizer build of `make test`): clang loads its 34 MB header
# lazily and compiled each measured file 20-35 % faster; GCC 12 reads its whole 150-190 MB .gch into
# every file and was slower than no header at all (user+sys, docs/benchmarks.md "Build and test
# time"). MACHDYN_PCH=OFF also checks that every file includes what it uses.
# Off under ccache: clang is handed the header and its .pch by absolute paths inside the build tree
# (after -Xclang, which ccache's base_dir does not rewrite), so another checkout of the same sources
# (a fresh clone of `.ci/run`) missed the cache for every file; measured on two clones of one commit:
# 0 of 3 hits with the header, 2 of 2 without. A cache hit costs nothing, the header saves 20-35 %
# of a single file (4-11 % of a unity batch, whose headers are parsed once anyway). `make test` turns it
# on for its sanitizer tree (Makefile ASAN_PCH): its goal is a cold build.
if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang" AND NOT CMAKE_CXX_COMPILER_LAUNCHER MATCHES "ccache")
  set(_machdyn_pch_default ON)
else()
  set(_machdyn_pch_default OFF)
endif()
option(MACHDYN_PCH "Precompile the heavy third-party headers (faster clang builds)" ${_machdyn_pch_default})

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
