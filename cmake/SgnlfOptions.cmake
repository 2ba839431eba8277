# One helper sets compiler options for every target of the project.
function(sgnlf_set_options target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wno-deprecated-declarations)
  if(SGNLF_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  # OpenCL 1.2 API is what PoCL and most embedded devices expose; 2.x calls are never used.
  target_compile_definitions(${target} PRIVATE CL_TARGET_OPENCL_VERSION=120)
endfunction()

# sgnlf_add_library(<module> SOURCES ... DEPS ...): static library sgnlf_<module> whose headers
# are included as "<module>/<file>.hpp" from runtime/.
function(sgnlf_add_library module)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(sgnlf_${module} STATIC ${ARG_SOURCES})
  target_include_directories(sgnlf_${module} PUBLIC ${SGNLF_SOURCE_ROOT}/runtime)
  target_link_libraries(sgnlf_${module} PUBLIC ${ARG_DEPS})
  sgnlf_set_options(sgnlf_${module})
endfunction()
