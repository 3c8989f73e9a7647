# The 'docs' target: Doxygen HTML of the sources, the README (main page), one page per
# chapters/<technique>/README.md and the pages in docs/, into ${CMAKE_BINARY_DIR}/docs/html.
# Doxygen warnings fail the target (WARN_AS_ERROR in the Doxyfile).
#
# This file is both the module the top CMakeLists includes and, run with `cmake -P`, the
# script the target executes at build time. The script
#   1. lists the inputs that exist now (README.md and the chapter pages are optional, so a
#      tree without them still builds its documentation),
#   2. writes the "Thesis cross-references" page (every \thesis{...} citation in the inputs,
#      by section, with the files citing it) and the concordance of the pseudocode
#      (cmake/BoxsimConcordance.cmake: every line of Appendix A with the code implementing it
#      and the places citing it, and the check that every line is implemented),
#   3. writes a Doxyfile that includes the one in the source root and sets the output
#      directory, the inputs and Graphviz, and runs Doxygen on it.
# Doing this at build time rather than configure time keeps the pages and the input list in
# step with the sources without re-running CMake.
#
# The citations are collected here rather than by Doxygen's \xrefitem because an \xrefitem is
# a paragraph of its own: inside a sentence it would cut the sentence in two and carry its
# end into the cross-reference list. The aliases therefore render inline as a link to these
# pages: \thesis{...} to the thesis cross-references, \alg{...} to the concordance.

if(NOT CMAKE_SCRIPT_MODE_FILE)
  include_guard(GLOBAL)
  find_program(BOXSIM_DOT_EXECUTABLE dot)
  if(NOT BOXSIM_DOT_EXECUTABLE)
    message(STATUS "boxsim: Graphviz 'dot' not found; the docs will have no diagrams "
                   "(apt-get install -y graphviz)")
  endif()
  add_custom_target(docs
    COMMAND ${CMAKE_COMMAND}
            -DBOXSIM_SOURCE_DIR=${PROJECT_SOURCE_DIR}
            -DBOXSIM_DOCS_DIR=${CMAKE_BINARY_DIR}/docs
            -DBOXSIM_VERSION=${PROJECT_VERSION}
            -DDOXYGEN_EXECUTABLE=${DOXYGEN_EXECUTABLE}
            -DBOXSIM_DOT_EXECUTABLE=${BOXSIM_DOT_EXECUTABLE}
            -P ${CMAKE_CURRENT_LIST_FILE}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    COMMENT "Doxygen: ${CMAKE_BINARY_DIR}/docs/html/index.html"
    VERBATIM)
  return()
endif()

cmake_minimum_required(VERSION 3.25)

# Sets `out` to the lines of `file`, one list element per line, with the characters that
# CMake lists treat specially (; [ ] \) replaced by placeholders; see boxsimRestore().
function(boxsimReadLines file out)
  file(READ "${file}" content)
  string(REPLACE "\\" "<bs>" content "${content}")
  string(REPLACE ";" "<sc>" content "${content}")
  string(REPLACE "[" "<lb>" content "${content}")
  string(REPLACE "]" "<rb>" content "${content}")
  string(REPLACE "\n" ";" content "${content}")
  set(${out} "${content}" PARENT_SCOPE)
endfunction()

function(boxsimRestore text out)
  string(REPLACE "<sc>" ";" text "${text}")
  string(REPLACE "<lb>" "[" text "${text}")
  string(REPLACE "<rb>" "]" text "${text}")
  string(REPLACE "<bs>" "\\" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# Records every \thesis{...} of `file` (path relative to the source root) in the
# caller's variables: <kind>_labels (the cited sections) and <kind>_<md5 of label>_at (the
# "file|line" places citing it). Markdown code spans and fenced blocks are skipped: they show
# the commands rather than use them.
macro(boxsimScanCitations file)
  boxsimReadLines("${BOXSIM_SOURCE_DIR}/${file}" lines)
  set(lineNumber 0)
  set(inFence FALSE)
  foreach(line IN LISTS lines)
    math(EXPR lineNumber "${lineNumber} + 1")
    if("${file}" MATCHES "\\.md$")
      if(line MATCHES "^[ \t]*(```|~~~)")
        if(inFence)
          set(inFence FALSE)
        else()
          set(inFence TRUE)
        endif()
        continue()
      endif()
      if(inFence)
        continue()
      endif()
      string(REGEX REPLACE "`[^`]*`" "" line "${line}")
    endif()
    # An escaped backslash (\\thesis) shows the command instead of citing.
    string(REPLACE "<bs><bs>" "<escaped>" line "${line}")
    if(NOT line MATCHES "<bs>thesis{")
      continue()
    endif()
    string(REGEX MATCHALL "<bs>thesis{[^}]*}" citations "${line}")
    foreach(citation IN LISTS citations)
      set(kind thesis)
      string(REGEX REPLACE "^<bs>thesis{([^}]*)}$" "\\1" label "${citation}")
      string(STRIP "${label}" label)
      boxsimRestore("${label}" label)
      string(MD5 key "${label}")
      if(NOT DEFINED ${kind}_${key}_at)
        list(APPEND ${kind}_labels "${label}")
      endif()
      list(APPEND ${kind}_${key}_at "${file}|${lineNumber}")
    endforeach()
  endforeach()
endmacro()

# Writes the cross-reference page of one kind of citation to `path`; `column` heads the column
# of cited sections.
function(boxsimWriteCitationPage kind anchor title what column path)
  set(page "# ${title} {#${anchor}}\n\n")
  string(APPEND page "Every place the documentation cites ${what} with "
                     "<code>\\\\${kind}{...}</code>, by section, and the files that cite it "
                     "(with the line numbers).\n"
                     "Generated by the `docs` target (cmake/BoxsimDocs.cmake); not to be edited.\n\n")
  set(labels ${${kind}_labels})
  if(NOT labels)
    string(APPEND page "No citations yet.\n")
    file(WRITE "${path}" "${page}")
    return()
  endif()
  list(SORT labels COMPARE NATURAL)
  string(APPEND page "| ${column} | Cited in |\n|:--|:--|\n")
  foreach(label IN LISTS labels)
    string(MD5 key "${label}")
    # Group the places by file, keeping the files in scan order and the lines ascending.
    set(files "")
    foreach(place IN LISTS ${kind}_${key}_at)
      string(REGEX REPLACE "\\|[0-9]+$" "" file "${place}")
      string(REGEX REPLACE "^.*\\|" "" line "${place}")
      string(MD5 fileKey "${file}")
      if(NOT DEFINED lines_${fileKey})
        list(APPEND files "${file}")
      endif()
      list(APPEND lines_${fileKey} "${line}")
    endforeach()
    set(where "")
    foreach(file IN LISTS files)
      string(MD5 fileKey "${file}")
      list(JOIN lines_${fileKey} ", " lineList)
      unset(lines_${fileKey})
      # Pages and files with a \file comment have a documentation page to link to; other
      # files are only named.
      string(REGEX REPLACE "^src/" "" shown "${file}")
      list(FIND documentedFiles "${file}" documented)
      if(file STREQUAL "README.md")
        set(entry "\\ref index \"README.md\"")
      elseif(documented GREATER -1 OR file MATCHES "\\.md$")
        set(entry "\\ref ${shown} \"${shown}\"")
      else()
        set(entry "`${shown}`")
      endif()
      string(FIND "${lineList}" "," several)
      if(several GREATER -1)
        string(APPEND entry " (lines ${lineList})")
      else()
        string(APPEND entry " (line ${lineList})")
      endif()
      if(where)
        string(APPEND where ", ${entry}")
      else()
        set(where "${entry}")
      endif()
    endforeach()
    string(REPLACE "|" "\\|" shownLabel "${label}")
    string(APPEND page "| ${shownLabel} | ${where} |\n")
  endforeach()
  file(WRITE "${path}" "${page}")
endfunction()

foreach(required BOXSIM_SOURCE_DIR BOXSIM_DOCS_DIR DOXYGEN_EXECUTABLE)
  if(NOT ${required})
    message(FATAL_ERROR "boxsim docs: ${required} is not set")
  endif()
endforeach()

# 1. The inputs that exist, as absolute paths: Doxygen matches USE_MDFILE_AS_MAINPAGE against
# the path an input was given by, and a bare README.md would make every chapter README a
# second main page.
set(inputs "${BOXSIM_SOURCE_DIR}/src")
set(mainPage "")
if(EXISTS "${BOXSIM_SOURCE_DIR}/README.md")
  set(mainPage "${BOXSIM_SOURCE_DIR}/README.md")
  list(APPEND inputs "${mainPage}")
endif()
file(GLOB chapterPages RELATIVE "${BOXSIM_SOURCE_DIR}" "${BOXSIM_SOURCE_DIR}/chapters/*/README.md")
list(SORT chapterPages)
foreach(page IN LISTS chapterPages)
  list(APPEND inputs "${BOXSIM_SOURCE_DIR}/${page}")
endforeach()
if(IS_DIRECTORY "${BOXSIM_SOURCE_DIR}/docs")
  list(APPEND inputs "${BOXSIM_SOURCE_DIR}/docs")
endif()

# 2. The citation pages.
file(GLOB_RECURSE scanned RELATIVE "${BOXSIM_SOURCE_DIR}"
     "${BOXSIM_SOURCE_DIR}/src/*.hpp" "${BOXSIM_SOURCE_DIR}/src/*.cpp"
     "${BOXSIM_SOURCE_DIR}/docs/*.md")
list(APPEND scanned ${chapterPages})
if(mainPage)
  list(APPEND scanned README.md)
endif()
list(SORT scanned)
set(thesis_labels "")
set(documentedFiles "")
foreach(file IN LISTS scanned)
  file(READ "${BOXSIM_SOURCE_DIR}/${file}" content)
  if(content MATCHES "(///|//!|/\\*\\*|/\\*!)[ \t]*(\\\\|@)file")
    list(APPEND documentedFiles "${file}")
  endif()
  if(content MATCHES "\\\\thesis{")
    boxsimScanCitations("${file}")
  endif()
endforeach()
set(pagesDir "${BOXSIM_DOCS_DIR}/pages")
file(MAKE_DIRECTORY "${pagesDir}")
boxsimWriteCitationPage(thesis thesis_xrefs "Thesis cross-references" "Egan's thesis" "Thesis"
                        "${pagesDir}/thesis_xrefs.md")
include("${CMAKE_CURRENT_LIST_DIR}/BoxsimConcordance.cmake")
concordancePage("${pagesDir}/concordance.md")
list(APPEND inputs "${pagesDir}")

# 3. The Doxyfile of this build, then Doxygen. A .cpp file without a \file comment is left
# out: Doxygen would point the links of the functions it defines to a page it never writes.
set(quotedInputs "")
foreach(input IN LISTS inputs)
  string(APPEND quotedInputs " \"${input}\"")
endforeach()
set(quotedExcludes "")
foreach(file IN LISTS scanned)
  list(FIND documentedFiles "${file}" documented)
  if(file MATCHES "\\.cpp$" AND documented EQUAL -1)
    string(APPEND quotedExcludes " \"${BOXSIM_SOURCE_DIR}/${file}\"")
  endif()
endforeach()
set(haveDot NO)
set(dotPath "")
if(BOXSIM_DOT_EXECUTABLE AND EXISTS "${BOXSIM_DOT_EXECUTABLE}")
  set(haveDot YES)
  get_filename_component(dotPath "${BOXSIM_DOT_EXECUTABLE}" DIRECTORY)
endif()
set(config "${BOXSIM_DOCS_DIR}/Doxyfile")
file(WRITE "${config}"
     "# Generated by cmake/BoxsimDocs.cmake for this build tree.\n"
     "@INCLUDE = \"${BOXSIM_SOURCE_DIR}/Doxyfile\"\n"
     "PROJECT_NUMBER = \"${BOXSIM_VERSION}\"\n"
     "OUTPUT_DIRECTORY = \"${BOXSIM_DOCS_DIR}\"\n"
     "INPUT =${quotedInputs}\n"
     "EXCLUDE =${quotedExcludes}\n"
     "USE_MDFILE_AS_MAINPAGE = \"${mainPage}\"\n"
     "HAVE_DOT = ${haveDot}\n"
     "DOT_PATH = \"${dotPath}\"\n")
# Pages of removed sources would otherwise linger in the output.
file(REMOVE_RECURSE "${BOXSIM_DOCS_DIR}/html")
execute_process(COMMAND "${DOXYGEN_EXECUTABLE}" "${config}"
                WORKING_DIRECTORY "${BOXSIM_SOURCE_DIR}"
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "boxsim docs: Doxygen failed (status ${status}); every warning above is "
                      "an error (WARN_AS_ERROR = FAIL_ON_WARNINGS in the Doxyfile)")
endif()
