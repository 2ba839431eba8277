#!/usr/bin/env bash
# The README's test command (and CI's): installs dependencies, builds, and runs the whole test
# suite, the real-data tests included (they fail when ../shared/data/real, or
# $SGNLF_SHARED_DIR/data/real, is missing: SGNLF_REQUIRE_REAL_DATA=0 skips them with a warning);
# then, with SGNLF_HARDENING=1, the hardening jobs (issue 18): the host tests built with
# AddressSanitizer + UndefinedBehaviorSanitizer, and every fuzz target for SGNLF_FUZZ_SECONDS
# (default 10) from its seed corpus, sharing one clang build (build-ci-sanitize/). Off by
# default until their CI time is measured on an unloaded machine; the fuzz corpora and fixed
# crash inputs are replayed by the ordinary suite either way (CTest replay_fuzz_*).
set -euo pipefail
cd "$(dirname "$0")/.."
export SGNLF_REQUIRE_REAL_DATA=${SGNLF_REQUIRE_REAL_DATA:-1}
bash scripts/setup.sh
bash scripts/build.sh
clinfo -l || true
ctest --test-dir build --output-on-failure -j "${JOBS:-$(nproc)}"
if [ "${SGNLF_HARDENING:-0}" = "1" ]; then
  t0=$(date +%s)
  BUILD=build-ci-sanitize FUZZ=ON CC=clang CXX=clang++ bash scripts/sanitize.sh
  t1=$(date +%s)
  BUILD=build-ci-sanitize bash scripts/fuzz.sh "${SGNLF_FUZZ_SECONDS:-10}"
  t2=$(date +%s)
  echo "hardening: sanitizer build + host tests $((t1 - t0)) s, fuzz build + runs $((t2 - t1)) s"
fi
