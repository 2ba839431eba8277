#!/usr/bin/env bash
# Reproduces results/odometry: the LiDAR odometry alone on the real nuScenes scene-0916
# keyframes (the protocol's first 36, and all 41), the real KITTI odometry slice, and the
# simulated low-frequency (2 Hz) and 10 Hz sequences. Usage (from the checkout, after a build):
#   bash results/odometry/run.sh [BUILD_DIR=build] [OUT=results/odometry] [DATA=/tmp/sgnlf-odometry-data]
set -euo pipefail
BUILD=${BUILD:-build}
OUT=${OUT:-results/odometry}
DATA=${DATA:-/tmp/sgnlf-odometry-data}
REAL=${SGNLF_SHARED_DIR:-../shared}/data/real
S=$BUILD/bin/sgnlf
run() {  # name, then sgnlf odometry arguments
  local name=$1; shift
  mkdir -p "$OUT/$name"
  "$S" odometry "$@" --out "$OUT/$name/poses.txt" --svg "$OUT/$name/top_view.svg" \
      --log "$OUT/$name/odometry.json" | tee "$OUT/$name/stdout.txt"
}
run real-nuscenes-0916-36 --data "$REAL/nuscenes-mini-scene-0916" --sequence scene-0916 --frames 36
run real-nuscenes-0916-41 --data "$REAL/nuscenes-mini-scene-0916" --sequence scene-0916 --frames 41
run real-kitti-00-40-49 --data "$REAL/kitti-odometry-00-slice" --start 40 --frames 10
for seq in kitti360-low-a kitti360-low-b kitti360-low-c nuscenes-low-a nuscenes-low-b nuscenes-low-c kitti360-1538; do
  [ -d "$DATA/$seq" ] || "$S" simulate --sequence "$seq" --out "$DATA/$seq" > /dev/null
  run "sim-$seq" --data "$DATA/$seq"
done
