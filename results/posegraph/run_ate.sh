#!/usr/bin/env bash
# Reproduces results/posegraph/README.md's ATE table: the geometric optimiser alone on the
# synthetic kitti360-loop from the protocol's noisy init (seed 1, 0.151 rad / 2.0 m), 300 steps,
# sequential graph vs SG-NLF's confidence graph with the STAND-IN features, and its ablations.
# Usage: bash results/posegraph/run_ate.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-build}"
out="${2:-runs/posegraph-ate}"
sgnlf="$build/bin/sgnlf"
mkdir -p "$out"
data="$out/data/kitti360-loop"
[ -d "$data" ] || "$sgnlf" simulate --sequence kitti360-loop --seed 1 --out "$data" --threads 2
run() {  # name, extra args...
  local name="$1"; shift
  "$sgnlf" posegraph --data "$data" --out "$out/$name" "$@" > "$out/$name.log" 2>&1
  printf '%-32s %s\n' "$name" "$(grep '^call' "$out/$name.log" | tail -1)"
}
run sequential
run confidence-default --graph confidence --graph-config "$here/configs/default.json"
run confidence-default-no-alpha --graph confidence --graph-config "$here/configs/default-no-alpha.json"
run confidence-default-start0 --graph confidence --graph-config "$here/configs/default.json" --confidence-start 0
run compat-k-6-gap10 --graph confidence --graph-config "$here/configs/compat-k-6-gap10.json"
run compat-k0-gap0 --graph confidence --graph-config "$here/configs/compat-k0-gap0.json"
run compat-k-3-gap0 --graph confidence --graph-config "$here/configs/compat-k-3-gap0.json"
run all-candidates-gap0 --graph confidence --graph-config "$here/configs/all-candidates-gap0.json"
run all-candidates-gap0-no-alpha --graph confidence --graph-config "$here/configs/all-candidates-gap0-no-alpha.json"
