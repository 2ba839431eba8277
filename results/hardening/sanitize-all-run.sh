#!/usr/bin/env bash
# The whole-suite sanitizer run of results/hardening/README.md: the ctest step of
# `SCOPE=all scripts/sanitize.sh` with the same ASan/UBSan/LSan options, on a tree built with
#   CC=clang CXX=clang++ bash scripts/configure_sanitize.sh build-san-all OFF
#   cmake --build build-san-all -j2
# timed, with the real-data tests required. Run from anywhere: bash results/hardening/sanitize-all-run.sh
cd "$(dirname "$0")/../.."
export ASAN_OPTIONS=detect_leaks=1:detect_stack_use_after_return=1:strict_init_order=1:check_initialization_order=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/cmake/sanitizer/lsan.supp:print_suppressions=0
export SGNLF_SHARED_DIR=${SGNLF_SHARED_DIR:-$PWD/../shared} SGNLF_REQUIRE_REAL_DATA=1
echo "start $(date -u +%FT%TZ) git $(git rev-parse --short HEAD) $(git status --porcelain | wc -l) changed"
/usr/bin/time -v ctest --test-dir "${BUILD:-build-san-all}" --output-on-failure -j 2
echo "rc $? end $(date -u +%FT%TZ)"
