# Run by the build (target sgnlf_git_stamp, runtime/harness/CMakeLists.txt), not at configure
# time: writes OUT with the source tree's git sha and number of changed paths as the binary is
# built, rewriting it only when they change (so an unchanged tree recompiles nothing).
# Usage: cmake -DROOT=<source root> -DOUT=<file.cpp> -P GitStamp.cmake
execute_process(COMMAND git -C ${ROOT} rev-parse HEAD OUTPUT_VARIABLE sha
                OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
set(changed -1)
if(rc EQUAL 0 AND NOT sha STREQUAL "")
  execute_process(COMMAND git -C ${ROOT} status --porcelain OUTPUT_VARIABLE st ERROR_QUIET)
  string(REGEX MATCHALL "[^\n]+" lines "${st}")
  list(LENGTH lines changed)
else()
  set(sha "unknown")
endif()
set(content "// Generated at build time by cmake/GitStamp.cmake. Do not edit.
#include \"harness/context.hpp\"

#include \"core/config.hpp\"

namespace sgnlf::harness {

Json build_git() {
  const int changed = ${changed};  // -1: git or the tree was unavailable at build time
  return Json{{\"sha\", \"${sha}\"},
              {\"dirty\", changed < 0 ? Json() : Json(changed > 0)},
              {\"changed_paths\", changed < 0 ? Json() : Json(changed)}};
}

}  // namespace sgnlf::harness
")
set(old "")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT old STREQUAL content)
  file(WRITE ${OUT} "${content}")
endif()
