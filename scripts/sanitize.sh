#!/usr/bin/env bash
# Builds sgnlf with AddressSanitizer and UndefinedBehaviorSanitizer (-DSGNLF_SANITIZE=address,
# undefined, -O1: scripts/configure_sanitize.sh) into build-sanitize/ and runs the tests under
# them; any finding fails its test (UBSan does not recover, ASan aborts, LeakSanitizer reports
# leaks at exit). Test timeouts are 4x the ordinary ones in this build.
#   SCOPE=ci              the host tests without the label asan_slow (the loaders, parsers,
#                         geometry, metrics and the fuzz replays) and the device test labelled
#                         asan_ci (tests/cl, on PoCL), building only their targets: what CI runs
#                         (scripts/test.sh)
#   SCOPE=host (default)  every host test (ctest label "host": no OpenCL device involved),
#                         building only their targets
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
bash scripts/configure_sanitize.sh "$B" "${FUZZ:-OFF}"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:detect_stack_use_after_return=1:strict_init_order=1:check_initialization_order=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/cmake/sanitizer/lsan.supp:print_suppressions=0}
case "$SCOPE" in
  ci) select=(-L '^(host|asan_ci)$' -LE '^asan_slow$') ;;
  host) select=(-L '^host$') ;;
  all) select=() ;;
  *) echo "sanitize: SCOPE must be ci, host or all (got '$SCOPE')"; exit 2 ;;
esac
if [ "$SCOPE" = "all" ]; then
  cmake --build "$B" -j "$JOBS"
else
  # Each selected test runs its test_<name> executable (the device and host test binaries, the
  # fuzz replays); the tests' commands cannot be read before the build, so the names are checked
  # against the build's targets: a selected test without one (an app test that needs bin/sgnlf)
  # is refused here by name instead of failing make with "No rule to make target".
  mapfile -t tests < <(ctest --test-dir "$B" "${select[@]}" -N | sed -n 's/^ *Test *#[0-9]*: *//p')
  [ ${#tests[@]} -gt 0 ] || { echo "sanitize: no tests selected (SCOPE=$SCOPE)"; exit 1; }
  known=$(cmake --build "$B" --target help | sed -n -E 's/^\.\.\. ([^ ]+).*/\1/p; s/^([A-Za-z0-9_]+): phony$/\1/p')
  targets=()
  for t in "${tests[@]}"; do
    grep -qx "test_$t" <<< "$known" || {
      echo "sanitize: test '$t' (SCOPE=$SCOPE) has no target test_$t; give it another label than host/asan_ci"
      exit 1
    }
    targets+=(--target "test_$t")
  done
  echo "sanitize: building ${#tests[@]} test targets (SCOPE=$SCOPE: ${tests[*]})"
  cmake --build "$B" -j "$JOBS" "${targets[@]}"
fi
ctest --test-dir "$B" "${select[@]}" --output-on-failure -j "$JOBS" "$@"
