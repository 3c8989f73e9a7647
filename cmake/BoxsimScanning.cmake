# Reading the sources line by line, for the scripts that write the generated pages of the docs:
# cmake/BoxsimDocs.cmake (the thesis cross-references) and cmake/BoxsimConcordance.cmake (the
# concordance of the pseudocode and its check). Both include this file.

include_guard(GLOBAL)

# The characters CMake lists treat specially (\ ; [ ]), by their ASCII codes, and the
# placeholders that stand for them in the lines of boxsimReadLines().
set(boxsimSpecialCodes 92 59 91 93)
set(boxsimPlaceholders "<bs>" "<sc>" "<lb>" "<rb>")

# Sets `out` to the lines of `file`, one list element per line, with the special characters
# replaced by their placeholders; boxsimRestore() puts them back.
function(boxsimReadLines file out)
  file(READ "${file}" content)
  foreach(code placeholder IN ZIP_LISTS boxsimSpecialCodes boxsimPlaceholders)
    string(ASCII ${code} character)
    string(REPLACE "${character}" "${placeholder}" content "${content}")
  endforeach()
  string(REPLACE "\n" ";" content "${content}")
  set(${out} "${content}" PARENT_SCOPE)
endfunction()

function(boxsimRestore text out)
  foreach(code placeholder IN ZIP_LISTS boxsimSpecialCodes boxsimPlaceholders)
    string(ASCII ${code} character)
    string(REPLACE "${placeholder}" "${character}" text "${text}")
  endforeach()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# Sets `out` to the part of the Markdown line `line` (from boxsimReadLines) that uses commands
# and tags rather than showing them: nothing on a fence (``` or ~~~) or inside a fenced block,
# the line without its code spans elsewhere. `fenceVariable` names the caller's variable that
# carries the fence state from line to line (FALSE before the first line).
function(boxsimMarkdownText line fenceVariable out)
  if(line MATCHES "^[ \t]*(```|~~~)")
    if(${fenceVariable})
      set(${fenceVariable} FALSE PARENT_SCOPE)
    else()
      set(${fenceVariable} TRUE PARENT_SCOPE)
    endif()
    set(${out} "" PARENT_SCOPE)
  elseif(${fenceVariable})
    set(${out} "" PARENT_SCOPE)
  else()
    string(REGEX REPLACE "`[^`]*`" "" line "${line}")
    set(${out} "${line}" PARENT_SCOPE)
  endif()
endfunction()

# Groups `places` ("file|line" entries) by file: sets `filesOut` to the files, in the order of
# their first place, and `linesOut` to their lines, one entry "line,line,..." a file in the
# order given, without repeats.
function(boxsimPlacesByFile places filesOut linesOut)
  set(files "")
  foreach(place IN LISTS places)
    string(REGEX REPLACE "\\|[0-9]+$" "" file "${place}")
    string(REGEX REPLACE "^.*\\|" "" line "${place}")
    string(MD5 key "${file}")
    if(NOT DEFINED placeLines_${key})
      list(APPEND files "${file}")
    endif()
    list(APPEND placeLines_${key} "${line}")
  endforeach()
  set(lineLists "")
  foreach(file IN LISTS files)
    string(MD5 key "${file}")
    list(REMOVE_DUPLICATES placeLines_${key})
    list(JOIN placeLines_${key} "," lineList)
    list(APPEND lineLists "${lineList}")
  endforeach()
  set(${filesOut} "${files}" PARENT_SCOPE)
  set(${linesOut} "${lineLists}" PARENT_SCOPE)
endfunction()

# Appends `file` to the list variable `listVariable` when `content` (the file's text) has a
# Doxygen \file comment, that is when Doxygen makes a page of the file that a link can name.
function(boxsimNoteDocumented file content listVariable)
  if(content MATCHES "(///|//!|/\\*\\*|/\\*!)[ \t]*(\\\\|@)file")
    set(${listVariable} ${${listVariable}} "${file}" PARENT_SCOPE)
  endif()
endfunction()
