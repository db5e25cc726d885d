# Installing machdyn for other programs (issue 13):
#   cmake --install BUILD [--prefix P]  headers, libmachdyn.a, the CLI, the Python package and a CMake
#                                       package: find_package(machdyn) gives the target machdyn::machdyn
#   make package                        a Debian package of all of it (CPack DEB), with its Debian
#                                       dependencies declared (shared libraries found by dpkg-shlibdeps)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

target_compile_features(machdyn PUBLIC cxx_std_20)  # for the projects that link machdyn::machdyn
set(MACHDYN_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/machdyn)
install(TARGETS machdyn EXPORT machdynTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/include/machdyn DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT dev)
install(TARGETS machdyn_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT cli)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/examples/ DESTINATION ${CMAKE_INSTALL_DATADIR}/machdyn/examples COMPONENT cli
        FILES_MATCHING PATTERN "*.yaml" PATTERN "*.csv" PATTERN notebooks EXCLUDE)
# The documentation (the references docs/*.md with their figures, the README) in the Debian place,
# /usr/share/doc/machdyn.
install(DIRECTORY ${CMAKE_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT cli
        FILES_MATCHING PATTERN "*.md" PATTERN "*.png" PATTERN "*.svg")
install(FILES ${CMAKE_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT cli)
install(EXPORT machdynTargets NAMESPACE machdyn:: DESTINATION ${MACHDYN_CMAKE_DIR} COMPONENT dev)
set(MACHDYN_WITH_MPI ${MPI_CXX_FOUND})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/machdynConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/machdynConfig.cmake INSTALL_DESTINATION ${MACHDYN_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/machdynConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/machdynConfig.cmake ${CMAKE_BINARY_DIR}/machdynConfigVersion.cmake
        DESTINATION ${MACHDYN_CMAKE_DIR} COMPONENT dev)

# Debian package: one package with everything. Depends: the shared libraries the CLI and the Python
# module link (dpkg-shlibdeps), Python with numpy for the module. The headers' and CMake package's
# dependencies (Eigen, fmt, ...) are -dev packages a C++ user needs anyway: Recommends.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME machdyn)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Dynamics of machine drives: C++ library, CLI and Python module")
set(CPACK_PACKAGE_CONTACT "machdyn developers <machdyn@localhost>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3 (>= 3.11), python3 (<< 3.12), python3-numpy")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS
    "libeigen3-dev, libsundials-dev, libyaml-cpp-dev, libfmt-dev, nlohmann-json3-dev, python3-pandas, python3-matplotlib, gnuplot-nox")
set(CPACK_PACKAGE_DIRECTORY ${CMAKE_BINARY_DIR}/package)
include(CPack)

option(MACHDYN_PACKAGE_TESTS "Test cmake --install and the .deb (off in the sanitizer build)" ON)
if(MACHDYN_TESTS AND MACHDYN_PACKAGE_TESTS)
  # The installed CMake package builds an outside project; the .deb unpacks and its CLI runs.
  add_test(NAME package.find_package
           COMMAND bash ${CMAKE_SOURCE_DIR}/tests/package/find_package.sh ${CMAKE_BINARY_DIR} ${CMAKE_SOURCE_DIR})
  add_test(NAME package.deb
           COMMAND bash ${CMAKE_SOURCE_DIR}/tests/package/deb.sh ${CMAKE_BINARY_DIR} ${CMAKE_SOURCE_DIR})
  set_tests_properties(package.find_package package.deb PROPERTIES TIMEOUT 600 RESOURCE_LOCK machdyn_install)
endif()
