#!/usr/bin/env bash
# scripts/fuzz.sh [SECONDS] [TARGET...]: builds the libFuzzer targets (fuzz/, clang with
# -fsanitize=fuzzer,address,undefined) into build-fuzz/ and runs each for SECONDS (default 60)
# from its committed seed corpus (fuzz/corpus/<target>/; new inputs go to
# build-fuzz/corpus/<target>/), FUZZ_JOBS targets at a time (default: the number of cores).
# Crashing inputs are written to build-fuzz/crashes/ and the run exits 1; logs are in
# build-fuzz/logs/. BUILD=dir changes the build folder (CI shares it with scripts/sanitize.sh:
# BUILD=... CC=clang CXX=clang++ FUZZ=ON).
#   REGEN_CORPUS=1  rewrites fuzz/corpus/ with fuzz_make_corpus (the project's own writers)
set -euo pipefail
cd "$(dirname "$0")/.."
SECS=${1:-60}
shift || true
B=${BUILD:-build-fuzz}
JOBS=${JOBS:-$(nproc)}
FUZZ_JOBS=${FUZZ_JOBS:-$JOBS}
SGNLF_SETUP_CLANG=1 bash scripts/setup.sh
export CC=clang CXX=clang++
bash scripts/configure_sanitize.sh "$B" ON
if [ $# -gt 0 ]; then
  targets=("$@")
else
  mapfile -t targets < <(cd fuzz && ls fuzz_*.cpp | sed 's/\.cpp$//')
fi
build=()
for t in "${targets[@]}"; do build+=(--target "$t"); done
cmake --build "$B" -j "$JOBS" "${build[@]}" --target fuzz_make_corpus
if [ "${REGEN_CORPUS:-0}" = "1" ]; then
  rm -rf fuzz/corpus
  "$B/fuzz/fuzz_make_corpus" fuzz/corpus results/tables/kitti360-standard/smoke/results.json
fi
mkdir -p "$B/logs" "$B/crashes"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# One target: its libFuzzer exit code goes to $B/logs/<target>.rc.
run_target() {
  local t=$1 rc
  mkdir -p "$B/corpus/$t"
  set +e
  "$B/fuzz/$t" -max_total_time="$SECS" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 \
    -print_final_stats=1 -artifact_prefix="$B/crashes/$t-" "$B/corpus/$t" "fuzz/corpus/$t" \
    > "$B/logs/$t.log" 2>&1
  rc=$?
  set -e
  echo "$rc" > "$B/logs/$t.rc"
}
running=0
for t in "${targets[@]}"; do
  rm -f "$B/logs/$t.rc"
  if [ "$running" -ge "$FUZZ_JOBS" ]; then wait -n || true; running=$((running - 1)); fi
  run_target "$t" &
  running=$((running + 1))
done
wait
failed=()
printf '%-24s %8s %10s %8s %8s %7s %s\n' target seconds execs cov features corpus result
for t in "${targets[@]}"; do
  log="$B/logs/$t.log"
  rc=$(cat "$B/logs/$t.rc" 2>/dev/null || echo "?")
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | awk '{print $2}')
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | awk '{print $2}')
  units=$(grep -o 'corp: [0-9]*' "$log" | tail -1 | awk '{print $2}')
  result=ok
  if [ "$rc" != "0" ]; then result="CRASH (exit $rc, see $log)"; failed+=("$t"); fi
  printf '%-24s %8s %10s %8s %8s %7s %s\n' "$t" "$SECS" "${execs:-?}" "${cov:-?}" "${ft:-?}" "${units:-?}" "$result"
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: ${#failed[@]} target(s) crashed: ${failed[*]}"
  for t in "${failed[@]}"; do grep -m5 -E 'ERROR|runtime error|terminate|Test unit written' "$B/logs/$t.log" || true; done
  exit 1
fi
echo "fuzz: ${#targets[@]} targets, ${SECS} s each, ${FUZZ_JOBS} at a time, no crash"
