# SGNLF_SANITIZE=address,undefined (any list -fsanitize= accepts): instruments every target of
# the project, tests included. Undefined behaviour aborts (no recovery), so a finding fails the
# test that triggers it. scripts/sanitize.sh builds build-sanitize/ with it and runs the tests
# with the runtime options (ASAN_OPTIONS, UBSAN_OPTIONS, LSan suppressions for the OpenCL
# driver) in cmake/sanitizer/.
if(SGNLF_SANITIZE)
  string(REPLACE ";" "," _sgnlf_san "${SGNLF_SANITIZE}")
  message(STATUS "sgnlf: building with -fsanitize=${_sgnlf_san}")
  add_compile_options(-fsanitize=${_sgnlf_san} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=${_sgnlf_san})
endif()

# SGNLF_BUILD_FUZZ: every library gets libFuzzer's coverage instrumentation (the fuzz targets
# themselves link -fsanitize=fuzzer, fuzz/CMakeLists.txt).
if(SGNLF_BUILD_FUZZ)
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
