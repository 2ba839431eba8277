# Every citation of the method and protocol documents in the sources names a section those
# documents have. Run by CTest (tests/docs/CMakeLists.txt) or by hand:
#   cmake -DROOT=<source root> -P tests/docs/check_citations.cmake
# Optional: -DSCAN="runtime;kernels;..." replaces the scanned folders and files (relative to
# ROOT); -DDOCS_DIR=<dir> reads method.md and protocol.md from <dir> instead of ROOT/docs.
#
# A citation is the document's name, spaces and a section sign with a section number:
# "method.md" cites docs/method.md; "protocol" and "protocol.md" cite docs/protocol.md. A range
# (an en dash or a hyphen between two numbers with the same prefix: "4.3–4.4", "0–1") cites every
# section in it. On the same line, bare section numbers that follow a citation without a
# break in between ("(method.md §0 density MLP, §4.1 Psi)", "protocol §1/§4") cite the same
# document; a '.', '(' or ')' ends the run. A document name at the end of a line whose next
# line (after a comment marker or a string quote) starts with the section sign counts as one
# citation. Bare section numbers with no document named before them on their line are not
# checked (they may cite other documents, e.g. an RFC).
#
# A section resolves when its document has a markdown heading whose text starts with the
# section sign and that number, followed by a space or the end of the line ("## §4 SG-NLF",
# "### §4.2 Confidence-aware pose graph"): the convention stated at the top of both documents.
# Every unresolved citation is printed with the file and line that make it, and the script
# fails (FATAL_ERROR, exit status 1).
cmake_minimum_required(VERSION 3.20)

if(NOT DEFINED ROOT OR NOT IS_DIRECTORY "${ROOT}")
  message(FATAL_ERROR "check_citations: pass -DROOT=<source root> (got '${ROOT}')")
endif()
if(NOT DEFINED SCAN OR SCAN STREQUAL "")
  set(SCAN runtime kernels tests benchmarks scripts README.md)
endif()
if(NOT DEFINED DOCS_DIR OR DOCS_DIR STREQUAL "")
  set(DOCS_DIR "${ROOT}/docs")
endif()

# The sign and the en dash as UTF-8 bytes, so the patterns do not depend on this file's encoding
# being read as UTF-8 anywhere but in string literals.
string(ASCII 194 167 _sect)     # U+00A7 SECTION SIGN
string(ASCII 226 128 147 _dash)  # U+2013 EN DASH
set(_num "[0-9]+(\\.[0-9]+)*")
set(_sec "${_sect}${_num}((${_dash}|-)[0-9]+(\\.[0-9]+)*)?")
set(_name "(method\\.md|protocol\\.md|protocol)")
# Tokens of one line: a named citation, a bare section number, or a break.
set(_token "${_name} +${_sec}|${_sec}|[.()]")

# --- The sections each document defines. --------------------------------------------------
foreach(_doc method protocol)
  set(_defined_${_doc} "")
  set(_path "${DOCS_DIR}/${_doc}.md")
  if(EXISTS "${_path}")
    file(READ "${_path}" _text)
    string(REPLACE ";" "," _text "${_text}")
    string(REPLACE "\\" "/" _text "${_text}")
    string(REPLACE "[" "<" _text "${_text}")
    string(REPLACE "]" ">" _text "${_text}")
    string(REPLACE "\r" "" _text "${_text}")
    string(REPLACE "\n" ";" _heads "${_text}")
    foreach(_h IN LISTS _heads)
      if(_h MATCHES "^#+ +${_sect}(${_num})( |$)")
        list(APPEND _defined_${_doc} "${CMAKE_MATCH_1}")
      endif()
    endforeach()
  endif()
endforeach()

# Sections of a cited id ("4.2", or a range "4.3–4.4") into _out; an unusable range gives the
# empty list and sets _bad.
function(expand_section id out bad)
  set(${bad} "" PARENT_SCOPE)
  string(REPLACE "${_dash}" "-" id "${id}")
  if(NOT id MATCHES "-")
    set(${out} "${id}" PARENT_SCOPE)
    return()
  endif()
  string(REGEX MATCH "^[^-]+" _a "${id}")
  string(REGEX MATCH "[^-]+$" _b "${id}")
  string(REPLACE "." ";" _pa "${_a}")
  string(REPLACE "." ";" _pb "${_b}")
  list(LENGTH _pa _na)
  list(LENGTH _pb _nb)
  if(NOT _na EQUAL _nb)
    set(${out} "" PARENT_SCOPE)
    set(${bad} "the two ends of the range have different depths" PARENT_SCOPE)
    return()
  endif()
  math(EXPR _last "${_na} - 1")
  list(GET _pa ${_last} _lo)
  list(GET _pb ${_last} _hi)
  list(REMOVE_AT _pa ${_last})
  list(REMOVE_AT _pb ${_last})
  if(NOT "${_pa}" STREQUAL "${_pb}" OR _lo GREATER _hi)
    set(${out} "" PARENT_SCOPE)
    set(${bad} "not an ascending range within one section" PARENT_SCOPE)
    return()
  endif()
  string(REPLACE ";" "." _prefix "${_pa}")
  if(NOT _prefix STREQUAL "")
    string(APPEND _prefix ".")
  endif()
  set(_list "")
  foreach(_k RANGE ${_lo} ${_hi})
    list(APPEND _list "${_prefix}${_k}")
  endforeach()
  set(${out} "${_list}" PARENT_SCOPE)
endfunction()

# --- The files to scan. ---------------------------------------------------------------------
set(_exts cpp hpp h cc cl clh cmake txt json md sh py in)
set(_files "")
foreach(_entry IN LISTS SCAN)
  set(_p "${ROOT}/${_entry}")
  if(IS_DIRECTORY "${_p}")
    set(_globs "")
    foreach(_e IN LISTS _exts)
      list(APPEND _globs "${_p}/*.${_e}")
    endforeach()
    file(GLOB_RECURSE _found LIST_DIRECTORIES false ${_globs})
    list(APPEND _files ${_found})
  elseif(EXISTS "${_p}")
    list(APPEND _files "${_p}")
  else()
    message(FATAL_ERROR "check_citations: '${_entry}' does not exist under ${ROOT}")
  endif()
endforeach()
list(REMOVE_DUPLICATES _files)
list(SORT _files)

# --- Scan. ----------------------------------------------------------------------------------
set(_n_files 0)
set(_n_citations 0)
set(_problems "")
set(_cited_method "")
set(_cited_protocol "")
foreach(_f IN LISTS _files)
  file(RELATIVE_PATH _rel "${ROOT}" "${_f}")
  if(_rel STREQUAL "tests/docs/check_citations.cmake")
    continue()  # this file: its comments show citations
  endif()
  file(READ "${_f}" _text)
  string(FIND "${_text}" "${_sect}" _at)
  if(_at LESS 0)
    continue()
  endif()
  # Characters that CMake lists treat specially become harmless ones; lines become list items.
  string(REPLACE ";" "," _text "${_text}")
  string(REPLACE "\\" "/" _text "${_text}")
  string(REPLACE "[" "<" _text "${_text}")
  string(REPLACE "]" ">" _text "${_text}")
  string(REPLACE "\r" "" _text "${_text}")
  # A name that ends a line and its section at the start of the next: one citation, on the
  # name's line (the next line keeps its number of lines).
  string(REGEX REPLACE
         "${_name}[ \t\"]*\n([ \t]*(//+|#+|\\*+|\")?[ \t\"]*)(${_sec})"
         "\\1 \\4\n\\2" _text "${_text}")
  string(REPLACE "\n" ";" _lines "${_text}")
  set(_line_no 0)
  set(_hit OFF)
  foreach(_line IN LISTS _lines)
    math(EXPR _line_no "${_line_no} + 1")
    string(FIND "${_line}" "${_sect}" _at)
    if(_at LESS 0)
      continue()
    endif()
    string(REGEX MATCHALL "${_token}" _tokens "${_line}")
    set(_doc "")
    foreach(_t IN LISTS _tokens)
      if(_t MATCHES "^[.()]$")
        set(_doc "")
        continue()
      endif()
      if(_t MATCHES "^${_name} +${_sect}(.*)$")
        set(_id "${CMAKE_MATCH_2}")
        if(CMAKE_MATCH_1 STREQUAL "method.md")
          set(_doc method)
        else()
          set(_doc protocol)
        endif()
        set(_shown "${CMAKE_MATCH_1} ${_sect}${_id}")
      elseif(_t MATCHES "^${_sect}(.*)$" AND NOT _doc STREQUAL "")
        set(_id "${CMAKE_MATCH_1}")
        set(_shown "${_sect}${_id} (continuing a ${_doc} citation)")
      else()
        continue()  # a bare section number with no document named before it
      endif()
      set(_hit ON)
      math(EXPR _n_citations "${_n_citations} + 1")
      expand_section("${_id}" _sections _bad)
      if(NOT _bad STREQUAL "")
        list(APPEND _problems "${_rel}:${_line_no}: ${_shown}: ${_bad}")
        continue()
      endif()
      foreach(_s IN LISTS _sections)
        list(APPEND _cited_${_doc} "${_s}")
        list(FIND _defined_${_doc} "${_s}" _i)
        if(_i LESS 0)
          list(APPEND _problems
               "${_rel}:${_line_no}: ${_shown}: docs/${_doc}.md has no heading '${_sect}${_s}'")
        endif()
      endforeach()
    endforeach()
  endforeach()
  if(_hit)
    math(EXPR _n_files "${_n_files} + 1")
  endif()
endforeach()

foreach(_doc method protocol)
  if(NOT EXISTS "${DOCS_DIR}/${_doc}.md")
    list(APPEND _problems "docs/${_doc}.md does not exist (looked in ${DOCS_DIR})")
  endif()
  list(REMOVE_DUPLICATES _cited_${_doc})
  list(SORT _cited_${_doc} COMPARE NATURAL)
  string(REPLACE ";" ", " _list "${_cited_${_doc}}")
  message(STATUS "${_doc}: cited sections ${_list}")
endforeach()

list(LENGTH _problems _n_problems)
if(_n_problems GREATER 0)
  foreach(_p IN LISTS _problems)
    message("unresolved citation: ${_p}")
  endforeach()
  message(FATAL_ERROR "check_citations: ${_n_problems} unresolved citation(s) in ${_n_files} "
                      "citing file(s); add the section to the document (heading '## ${_sect}N "
                      "Title') or correct the citation")
endif()
message(STATUS "check_citations: ${_n_citations} citations in ${_n_files} files resolve")
