#!/bin/bash
# LiDAR4D vs LiDAR-NeRF, quick presets cut to 1500 iterations, kitti360-dyn-4950, seed 1, commit 60a9fa6
D=${D:?the kitti360-dyn-4950 twin folder: sgnlf bench --table kitti360-dynamic --scale quick --sequences kitti360-dyn-4950 --rows lidar-nerf writes it under OUT/data}; B=$(realpath "${B:-./build/bin/sgnlf}"); D=$(realpath "$D")
OUT=${OUT:-runs/lidar4d-first}; mkdir -p "$OUT"; cp "$(dirname "$0")/it1500.json" "$OUT/"; cd "$OUT"
for m in lidar-nerf lidar4d; do
  rm -rf study-$m
  s=$(date +%s)
  nice $B train --method $m --preset quick --data $D --out study-$m --config it1500.json --seed 1 > study-$m.log 2>&1
  echo "$m rc=$? wall=$(( $(date +%s) - s ))" >> done.txt
done
for m in lidar-nerf lidar4d; do $B eval --run study-$m --json > study-$m.eval.json; done
