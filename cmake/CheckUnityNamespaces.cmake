# cmake -DROOT=<source dir> -P CheckUnityNamespaces.cmake: fails, naming the files, when a test file
# opens an anonymous namespace at the start of a line. Test files are compiled in batches
# (cmake/Unity.cmake), where the helpers of two files would meet; they use namespace MACHDYN_UNITY_ID.
file(GLOB_RECURSE _tests ${ROOT}/tests/*_test.cpp)
set(_bad "")
foreach(f ${_tests})
  file(STRINGS ${f} _lines REGEX "^namespace {")
  if(_lines)
    file(RELATIVE_PATH _rel ${ROOT} ${f})
    string(APPEND _bad "  ${_rel}\n")
  endif()
endforeach()
if(_bad)
  message(FATAL_ERROR "test files with `namespace {` (write `namespace MACHDYN_UNITY_ID {`, docs/design.md):\n${_bad}")
endif()
