# The layer rule of src/boxsim, checked at build time (cmake -P, run by src/CMakeLists.txt
# before a layer's library is compiled):
#
#   core → collision → techniques → io → cli
#
# a file may include boxsim headers of its own layer and of the layers below it, never of a
# layer above. Linking alone cannot enforce this: an upward include of a header that declares
# only inline code or types links fine. So every `#include "boxsim/..."` of every file of the
# layer is read, and the build stops naming each file, the include and the rule.
#
# Arguments (-D): LAYER (core, collision, techniques or io), SOURCE_DIR (src/boxsim),
# STAMP (written when the layer passes), FILES (the layer's files, ';'-separated).
cmake_minimum_required(VERSION 3.25)

set(layers core collision techniques io cli)

# The layer of a path relative to src/boxsim ("core/world.hpp", "techniques.cpp").
function(boxsim_layer_of path out)
  string(REGEX MATCH "^[a-z_]+/" dir "${path}")
  string(REGEX REPLACE "/$" "" dir "${dir}")
  if(dir STREQUAL "core" OR dir STREQUAL "collision" OR dir STREQUAL "io" OR dir STREQUAL "cli")
    set(${out} ${dir} PARENT_SCOPE)
  else()
    # The technique directories and techniques.hpp/.cpp at the top of src/boxsim.
    set(${out} techniques PARENT_SCOPE)
  endif()
endfunction()

list(FIND layers "${LAYER}" own_rank)
if(own_rank LESS 0)
  message(FATAL_ERROR "BoxsimLayerCheck: unknown layer '${LAYER}'")
endif()
set(violations "")
foreach(file IN LISTS FILES)
  file(RELATIVE_PATH rel "${SOURCE_DIR}" "${file}")
  file(STRINGS "${file}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<]boxsim/")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[\"<]boxsim/([^\">]+)[\">].*$" "\\1"
           included "${line}")
    boxsim_layer_of("${included}" included_layer)
    list(FIND layers "${included_layer}" included_rank)
    if(included_rank GREATER own_rank)
      string(APPEND violations
             "  src/boxsim/${rel}: #include \"boxsim/${included}\": layer '${LAYER}' includes "
             "layer '${included_layer}', which is above it\n")
    endif()
  endforeach()
endforeach()
if(violations)
  message(FATAL_ERROR
          "boxsim layer rule broken (core → collision → techniques → io → cli: a file includes "
          "only its own layer and those below):\n${violations}"
          "Move the piece the include needs down to the including layer (or lower).")
endif()
file(WRITE "${STAMP}" "")
