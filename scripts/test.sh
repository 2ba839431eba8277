#!/usr/bin/env bash
# The README's test command (and CI's): installs dependencies, builds, and runs the whole test
# suite, the real-data tests included: on ../shared/data/real (or $SGNLF_SHARED_DIR/data/real)
# when present, else on the in-repo sample datasets/real-sample (the few tests that need more
# frames skip with a warning); CI=true or SGNLF_REQUIRE_REAL_DATA=1 (.ci/run) makes the larger
# data required, failing those tests where it is missing;
# Chromium too (SGNLF_SETUP_BROWSER=1), for the report page's browser test, and Oclgrind
# (SGNLF_SETUP_OCLGRIND=1), for the device tests the suite also runs under it (label oclgrind),
# and Slurm, munge and GNU parallel (SGNLF_SETUP_SCALE_OUT=1), for the tests that run the README's
# scale-out lines (labels slurm, parallel);
# then the hardening jobs, sharing one clang build (build-ci-sanitize/): the host
# tests (without the label asan_slow) and the OpenCL test cl built with AddressSanitizer +
# UndefinedBehaviorSanitizer (SCOPE=ci scripts/sanitize.sh), and every fuzz target for
# SGNLF_FUZZ_SECONDS (default 20) from its seed corpus (scripts/fuzz.sh).
# SGNLF_HARDENING=0 skips both jobs (the fuzz corpora and fixed crash inputs are still replayed
# by the ordinary suite, CTest replay_fuzz_*). Times: docs/studies/hardening/README.md.
set -euo pipefail
cd "$(dirname "$0")/.."
t0=$(date +%s)
SGNLF_SETUP_BROWSER=1 SGNLF_SETUP_OCLGRIND=1 SGNLF_SETUP_SCALE_OUT=1 bash scripts/setup.sh
bash scripts/build.sh
clinfo -l || true
ctest --test-dir build --output-on-failure -j "${JOBS:-$(nproc)}"
t1=$(date +%s)
echo "test: build + suite $((t1 - t0)) s"
if [ "${SGNLF_HARDENING:-1}" != "0" ]; then
  SCOPE=ci BUILD=build-ci-sanitize FUZZ=ON CC=clang CXX=clang++ bash scripts/sanitize.sh
  t2=$(date +%s)
  BUILD=build-ci-sanitize bash scripts/fuzz.sh "${SGNLF_FUZZ_SECONDS:-20}"
  t3=$(date +%s)
  echo "hardening: sanitizer build + host tests $((t2 - t1)) s, fuzz build + runs $((t3 - t2)) s"
fi
echo "test: all done in $(( $(date +%s) - t0 )) s"
