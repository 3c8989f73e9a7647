# `cmake --install`: the headers, the four layer libraries, the command line, a CMake package
# and a pkg-config file, so that a program elsewhere builds against boxsim with
#
#   find_package(boxsim CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE boxsim::boxsim)
#
# or with `pkg-config --cflags --libs boxsim`. The package's targets are boxsim::core,
# boxsim::collision, boxsim::techniques, boxsim::io (one a layer, each linking the one below)
# and boxsim::boxsim, all of them. examples/ builds against either (docs/library.md).
include_guard(GLOBAL)
include(CMakePackageConfigHelpers)

set(BOXSIM_CMAKE_PACKAGE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/boxsim)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/boxsim/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/boxsim
        FILES_MATCHING PATTERN "*.hpp" PATTERN "cli" EXCLUDE
        # The scene reader's JSON helper is internal to io (and needs nlohmann-json's headers).
        PATTERN "scene_json.hpp" EXCLUDE)
install(TARGETS boxsim_core boxsim_collision boxsim_techniques boxsim_io boxsim_lib
        EXPORT boxsimTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS boxsim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT boxsimTargets NAMESPACE boxsim:: DESTINATION ${BOXSIM_CMAKE_PACKAGE_DIR})

# The techniques link OpenMP where it was found (src/CMakeLists.txt): a program linking them
# needs its runtime too.
if(BOXSIM_HAVE_OPENMP)
  set(BOXSIM_FIND_OPENMP "find_dependency(OpenMP COMPONENTS CXX)")
  set(BOXSIM_PC_OPENMP " -fopenmp")
else()
  set(BOXSIM_FIND_OPENMP "")
  set(BOXSIM_PC_OPENMP "")
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/boxsimConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/boxsimConfig.cmake
                              INSTALL_DESTINATION ${BOXSIM_CMAKE_PACKAGE_DIR})
# 0.y.z: a minor version may change the interface, so a program asks for the minor it was
# written against.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/boxsimConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/boxsimConfig.cmake
              ${PROJECT_BINARY_DIR}/boxsimConfigVersion.cmake ${PROJECT_SOURCE_DIR}/cmake/FindGLPK.cmake
        DESTINATION ${BOXSIM_CMAKE_PACKAGE_DIR})

# pkg-config: the libraries from the top layer down, as a static link needs them; the
# dependencies' own .pc files (eigen3, gsl, nlohmann_json) add their flags; GLPK has none, so
# -lglpk is named. The prefix is
# relative to the file, so `cmake --install --prefix` anywhere gives a working file.
file(RELATIVE_PATH BOXSIM_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" BOXSIM_PC_TO_PREFIX "${BOXSIM_PC_TO_PREFIX}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/boxsim.pc.in ${PROJECT_BINARY_DIR}/boxsim.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/boxsim.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
