# Finds every dependency from Debian packages. A missing one stops configure with the
# name of the Debian package that provides it.
include_guard(GLOBAL)

# The Debian packages, from the one list of them (packages.txt: one a line, '#' comments).
file(STRINGS ${PROJECT_SOURCE_DIR}/packages.txt BOXSIM_APT_PACKAGES REGEX "^[^#]")
list(JOIN BOXSIM_APT_PACKAGES " " BOXSIM_APT_PACKAGES)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/packages.txt)

macro(boxsim_require_package name debian_package)
  find_package(${name} ${ARGN} QUIET)
  if(NOT ${name}_FOUND)
    message(FATAL_ERROR
      "boxsim: dependency '${name}' was not found.\n"
      "Install it with:  apt-get install -y ${debian_package}\n"
      "(all dependencies at once: apt-get install -y ${BOXSIM_APT_PACKAGES})")
  endif()
endmacro()

macro(boxsim_require_program var program debian_package)
  find_program(${var} ${program})
  if(NOT ${var})
    message(FATAL_ERROR
      "boxsim: program '${program}' was not found.\n"
      "Install it with:  apt-get install -y ${debian_package}\n"
      "(all dependencies at once: apt-get install -y ${BOXSIM_APT_PACKAGES})")
  endif()
endmacro()

boxsim_require_package(Eigen3 libeigen3-dev 3.3 NO_MODULE)
boxsim_require_package(GSL libgsl-dev)
boxsim_require_package(GLPK libglpk-dev)
boxsim_require_package(nlohmann_json nlohmann-json3-dev 3.2)
boxsim_require_package(CLI11 libcli11-dev)
if(BOXSIM_BUILD_TESTS)
  boxsim_require_package(Catch2 catch2 2)
endif()
if(BOXSIM_BUILD_FIGURES)
  boxsim_require_program(GNUPLOT_EXECUTABLE gnuplot gnuplot-nox)
endif()
if(BOXSIM_BUILD_DOCS)
  boxsim_require_program(DOXYGEN_EXECUTABLE doxygen doxygen)
endif()

# Google Benchmark is optional: without it there is no 'bench' target and nothing else changes.
if(BOXSIM_BUILD_BENCH)
  find_package(benchmark QUIET)
  if(NOT benchmark_FOUND)
    message(STATUS
      "boxsim: Google Benchmark not found, so no 'bench' target. "
      "Install it with:  apt-get install -y libbenchmark-dev")
    set(BOXSIM_BUILD_BENCH OFF)
  endif()
endif()
