#!/usr/bin/env bash
# Builds sgnlf with AddressSanitizer and UndefinedBehaviorSanitizer (-DSGNLF_SANITIZE=address,
# undefined, RelWithDebInfo) into build-sanitize/ and runs the tests under them; any finding
# fails its test (UBSan does not recover, ASan aborts, LeakSanitizer reports leaks at exit).
#   SCOPE=host (default)  only the host tests (ctest label "host": no OpenCL device involved),
#                         building only their targets: what CI runs
#   SCOPE=all             every test, device tests on PoCL included
# Extra arguments go to ctest. BUILD=dir changes the build folder.
set -euo pipefail
cd "$(dirname "$0")/.."
SCOPE=${SCOPE:-host}
B=${BUILD:-build-sanitize}
JOBS=${JOBS:-$(nproc)}
SETUP_CLANG=0
case "${CXX:-}" in *clang*) SETUP_CLANG=1 ;; esac
SGNLF_SETUP_CLANG=$SETUP_CLANG bash scripts/setup.sh
cmake -S . -B "$B" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSGNLF_SANITIZE=address,undefined \
      -DSGNLF_BUILD_BENCHMARKS=OFF -DSGNLF_BUILD_FUZZ=${FUZZ:-OFF} > "$B.configure.log" 2>&1 \
  || { cat "$B.configure.log"; exit 1; }
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:detect_stack_use_after_return=1:strict_init_order=1:check_initialization_order=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/cmake/sanitizer/lsan.supp:print_suppressions=0}
if [ "$SCOPE" = "host" ]; then
  mapfile -t tests < <(ctest --test-dir "$B" -L '^host$' -N | sed -n 's/^ *Test *#[0-9]*: *//p')
  [ ${#tests[@]} -gt 0 ] || { echo "sanitize: no host tests found"; exit 1; }
  targets=()
  for t in "${tests[@]}"; do targets+=(--target "test_$t"); done
  echo "sanitize: building ${#tests[@]} host test targets (${tests[*]})"
  cmake --build "$B" -j "$JOBS" "${targets[@]}"
  ctest --test-dir "$B" -L '^host$' --output-on-failure -j "$JOBS" "$@"
else
  cmake --build "$B" -j "$JOBS"
  ctest --test-dir "$B" --output-on-failure -j "$JOBS" "$@"
fi
