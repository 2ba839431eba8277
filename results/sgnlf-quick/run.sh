#!/usr/bin/env bash
# The SG-NLF rows of the quick kitti360-low and nuscenes-low tables beside GeoNLF rows rerun by
# the same binary (issue 17), seed 1, built-in synthetic twins. nuscenes-low-c is left out:
# the committed GeoNLF quick table has a and b only.
# Usage: bash results/sgnlf-quick/run.sh BIN_DIR WORK_DIR
#   then: python3 results/sgnlf-quick/table.py WORK_DIR > results/sgnlf-quick/table.md
set -euo pipefail
BIN=$(cd "$1" && pwd); WORK=$2
mkdir -p "$WORK"; cd "$WORK"
NU=(--sequences nuscenes-low-a,nuscenes-low-b)
"$BIN/sgnlf" bench --table nuscenes-low --scale quick --rows sg-nlf "${NU[@]}" --seed 1 --out quick-nuscenes-low-sgnlf
"$BIN/sgnlf" bench --table kitti360-low --scale quick --rows sg-nlf --seed 1 --out quick-kitti360-low-sgnlf
"$BIN/sgnlf" bench --table nuscenes-low --scale quick --rows geonlf "${NU[@]}" --seed 1 --out quick-nuscenes-low-geonlf
"$BIN/sgnlf" bench --table kitti360-low --scale quick --rows geonlf --seed 1 --out quick-kitti360-low-geonlf
