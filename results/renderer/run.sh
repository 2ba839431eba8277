#!/usr/bin/env bash
# Fast vs protocol renderer on two trained quick fields, one run (nothing else running).
#   bash results/renderer/run.sh LN_RUN SG_RUN OUT
# LN_RUN: sgnlf bench --table kitti360-standard --scale quick --rows lidar-nerf \
#           --sequences kitti360-1538 --seed 1 --out B1   → B1/runs/lidar-nerf/kitti360-1538
# SG_RUN: sgnlf bench --table kitti360-low --scale quick --rows sg-nlf \
#           --sequences kitti360-low-a --seed 1 --out B2  → B2/runs/sg-nlf/kitti360-low-a
set -euo pipefail
B=${SGNLF:-./build/bin/sgnlf}
LN=$1 SG=$2 OUT=$3
mkdir -p "$OUT"
for R in LN SG; do
  RUN=${!R}
  nice "$B" eval --run "$RUN" --json > "$OUT/$R-protocol.json"
  nice "$B" eval --run "$RUN" --json --renderer fast > "$OUT/$R-F1.json"
  nice "$B" eval --run "$RUN" --json --renderer fast --fast-layout march > "$OUT/$R-march.json"
done
# A stream of 16 novel views along the LiDAR-NeRF scene's trajectory, both renderers.
P=$(dirname "$0")/stream16.txt
nice "$B" render --run "$LN" --poses "$P" --out "$OUT/stream-fast" > "$OUT/stream-fast.json"
nice "$B" render --run "$LN" --poses "$P" --out "$OUT/stream-march" --fast-layout march \
  > "$OUT/stream-march.json"
nice "$B" render --run "$LN" --poses "$P" --out "$OUT/stream-protocol" --renderer protocol \
  > "$OUT/stream-protocol.json"
