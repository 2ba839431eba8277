# Embeds every kernels/**/*.cl and *.clh file into a generated C++ source at build time,
# using CMake alone. The generated table maps the path relative to kernels/ to its text.
function(sgnlf_embed_kernels out_var)
  file(GLOB_RECURSE _files CONFIGURE_DEPENDS
       ${SGNLF_KERNEL_ROOT}/*.cl ${SGNLF_KERNEL_ROOT}/*.clh)
  list(SORT _files)
  set(_out ${CMAKE_CURRENT_BINARY_DIR}/embedded_kernels.cpp)
  add_custom_command(
    OUTPUT ${_out}
    COMMAND ${CMAKE_COMMAND} -DKERNEL_ROOT=${SGNLF_KERNEL_ROOT} -DOUT=${_out}
            -P ${SGNLF_SOURCE_ROOT}/cmake/embed_kernels_script.cmake
    DEPENDS ${_files} ${SGNLF_SOURCE_ROOT}/cmake/embed_kernels_script.cmake
    COMMENT "Embedding OpenCL kernels"
    VERBATIM)
  set(${out_var} ${_out} PARENT_SCOPE)
endfunction()
