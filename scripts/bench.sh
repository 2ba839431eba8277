#!/usr/bin/env bash
# Runs the kernel and step benchmarks (Google Benchmark) and writes one JSON per binary into
# OUT (default runs/bench). Each JSON carries the harness context block (git sha, build, CPU,
# OpenCL device and driver, POCL_*) and the device's roofline measured in the same process, so
# every kernel's GFLOP/s or GB/s counter can be read as a fraction of the peak (frac_peak).
# Build first (scripts/build.sh). Extra arguments go to every binary, e.g.
#   bash scripts/bench.sh --benchmark_filter=TrainStep --benchmark_repetitions=5
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-runs/bench}
BINARIES=${BINARIES:-"bench_roofline bench_field bench_render bench_reproject bench_pipeline bench_spectral bench_metrics bench_datasets"}
mkdir -p "$OUT"
for b in $BINARIES; do
  [ -x "build/bin/$b" ] || { echo "bench.sh: build/bin/$b missing (run scripts/build.sh)" >&2; exit 1; }
  echo "== $b" >&2
  "build/bin/$b" --benchmark_out="$OUT/$b.json" --benchmark_out_format=json "$@"
done
echo "bench.sh: results in $OUT/*.json" >&2
