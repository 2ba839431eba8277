#!/usr/bin/env bash
# The own-scans check: the 41 nuScenes scene-0916 scans as .pcd.bin, PCD and PLY plain folders
# (convert_scans.py), each through `sgnlf reconstruct --scans DIR --out RUN` with no other
# option, one after another; then the trajectories compared with each other and the odometry
# with `sgnlf odometry` on the genuine layout, and the poses scored against the scene's
# reference poses (a rerun with --reference-poses: nothing is trained, evaluated or rendered again;
# the errors go into reconstruct.json and the report is rewritten with them).
#   SGNLF=path/to/sgnlf OUT=dir bash run_three.sh
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
SHARED=${SGNLF_SHARED_DIR:-$HERE/../../../../shared}
SCENE=$SHARED/data/real/nuscenes-mini-scene-0916
S=${SGNLF:-$HERE/../../../build/bin/sgnlf}
OUT=${OUT:-own-scans}
python3 "$HERE/convert_scans.py" "$SCENE/samples/LIDAR_TOP" "$OUT/scans"
for f in pcdbin pcd ply; do
  /usr/bin/time -v "$S" reconstruct --scans "$OUT/scans/$f" --out "$OUT/run-$f" > "$OUT/run-$f.stdout" 2> "$OUT/run-$f.stderr"
done
"$S" odometry --data "$SCENE" --frames 41 --out "$OUT/genuine/odometry.kitti.txt" > "$OUT/genuine.stdout" 2>&1
for f in pcdbin pcd ply; do
  "$S" reconstruct --scans "$OUT/scans/$f" --out "$OUT/run-$f" \
      --reference-poses "$SCENE/reference_poses_lidar_world.txt" > "$OUT/run-$f.scored.txt" 2>&1
done
python3 "$HERE/compare_runs.py" "$OUT"/run-pcdbin/trajectories/optimised.kitti.txt \
    "$OUT"/run-pcd/trajectories/optimised.kitti.txt "$OUT"/run-ply/trajectories/optimised.kitti.txt
python3 "$HERE/compare_runs.py" "$OUT/genuine/odometry.kitti.txt" \
    "$OUT"/run-{pcdbin,pcd,ply}/odometry/odometry.kitti.txt
