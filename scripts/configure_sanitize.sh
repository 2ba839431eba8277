#!/usr/bin/env bash
# scripts/configure_sanitize.sh BUILD_DIR FUZZ(ON|OFF): configures the clang build with
# AddressSanitizer + UndefinedBehaviorSanitizer that scripts/sanitize.sh and scripts/fuzz.sh
# share (CI builds one tree, build-ci-sanitize/, for both jobs). Both scripts configure through
# here so that the same folder is never reconfigured with other flags (which rebuilds it whole).
# -O1 with line tables only: what the sanitizers' and libFuzzer's documentation recommend, and
# about a fifth less compile time than RelWithDebInfo's -O2 -g; stack traces keep file:line.
# SGNLF_SAN_FLAGS overrides the optimisation and debug flags; SGNLF_SANITIZE_TIMEOUT_SCALE (default
# 4) multiplies every test's timeout (changing it rebuilds nothing).
set -euo pipefail
B=$1
FUZZ=${2:-OFF}
FLAGS=${SGNLF_SAN_FLAGS:--O1 -gline-tables-only}
mkdir -p "$B"
cmake -S . -B "$B" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$FLAGS -DNDEBUG" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=$FLAGS -DNDEBUG" \
      -DSGNLF_SANITIZE=address,undefined -DSGNLF_SANITIZE_TIMEOUT_SCALE="${SGNLF_SANITIZE_TIMEOUT_SCALE:-4}" \
      -DSGNLF_BUILD_BENCHMARKS=OFF -DSGNLF_BUILD_FUZZ="$FUZZ" \
      > "$B/configure.log" 2>&1 || { cat "$B/configure.log"; exit 1; }
