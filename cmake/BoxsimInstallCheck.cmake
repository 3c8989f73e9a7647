# The ctest installed_package: installs the build BUILD_DIR into BUILD_DIR/install-check/prefix,
# builds examples/drop_die against the installed package in a build of its own, once through
# find_package(boxsim) and once through pkg-config, and runs both. Any step that fails stops
# the script with its output.
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DCXX=... -P BoxsimInstallCheck.cmake
cmake_minimum_required(VERSION 3.25)
set(work ${BUILD_DIR}/install-check)
set(prefix ${work}/prefix)
file(REMOVE_RECURSE ${work})

function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "installed package: ${what} failed (${status}):\n${out}")
  endif()
  message(STATUS "installed package: ${what}")
  set(output "${out}" PARENT_SCOPE)
endfunction()

step("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# find_package(boxsim CONFIG REQUIRED) in a separate build of examples/.
step("configure examples/ against the package"
     ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples -B ${work}/examples -DCMAKE_PREFIX_PATH=${prefix}
     -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release)
step("build drop_die" ${CMAKE_COMMAND} --build ${work}/examples --target drop_die)
step("run drop_die" ${work}/examples/drop_die)
if(NOT output MATCHES "asleep")
  message(FATAL_ERROR "installed package: drop_die built against the package printed\n${output}")
endif()

# pkg-config, with the installed boxsim.pc first on the search path.
find_program(PKG_CONFIG pkg-config REQUIRED)
file(GLOB_RECURSE pcFile ${prefix}/*/boxsim.pc)
get_filename_component(pcDir "${pcFile}" DIRECTORY)
set(ENV{PKG_CONFIG_PATH} "${pcDir}")
step("pkg-config boxsim" ${PKG_CONFIG} --cflags --libs boxsim)
string(STRIP "${output}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
step("compile drop_die with pkg-config's flags"
     ${CXX} -O2 ${SOURCE_DIR}/examples/drop_die.cpp -o ${work}/drop_die_pc ${flags})
step("run drop_die built with pkg-config" ${work}/drop_die_pc)
