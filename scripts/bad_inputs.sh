#!/usr/bin/env bash
# scripts/bad_inputs.sh SGNLF OUT.md: the bad-input matrix. Makes each kind of
# bad input a user can bring, runs the sgnlf command that reads it, and writes one table row:
# the input, the command, the exit code, the first line of the message, and whether every file
# already written (run.json, checkpoints, logs, the input itself) is byte-identical afterwards.
# Exit 1 when a row's exit code differs from the expected one or something written was changed.
# Each row also has a library test (named in the table). Needs a built sgnlf; takes ~1-2 min.
set -uo pipefail
SGNLF=$(realpath "$1")
OUT=$(realpath -m "$2")
ROOT=$(cd "$(dirname "$0")/.." && pwd)
W=$(mktemp -d "${TMPDIR:-/tmp}/sgnlf-bad-inputs.XXXXXX")
trap 'rm -rf "$W"' EXIT
cd "$W"
export SGNLF_LOG=${SGNLF_LOG:-warn}

rows=()
bad=0
# row EXPECTED_EXIT "input" "test" PROTECTED_GLOB -- command...
row() {
  local expect=$1 what=$2 test=$3 protect=$4
  shift 5
  local before after kept rc msg
  before=$(cd "$W" && find $protect -type f 2>/dev/null | sort | xargs -r sha256sum 2>/dev/null)
  "$@" > out.txt 2> err.txt
  rc=$?
  after=$(cd "$W" && find $protect -type f 2>/dev/null | sort | xargs -r sha256sum 2>/dev/null)
  if [ -z "$protect" ]; then kept="(nothing written before)"
  elif [ "$before" = "$after" ]; then kept="yes ($(echo "$before" | grep -c .) files)"
  else kept="**NO**"; bad=1; fi
  msg=$(cat err.txt out.txt | grep -m1 -E "${PAT:-^sgnlf: |\[sgnlf (warn|error)\]|REGRESSION|FAIL}" | cut -c1-330)
  [ -z "$msg" ] && msg=$(head -c 300 err.txt | tr '\n' ' ')
  msg=${msg//|/\\|}
  msg=${msg//$W\//}
  local cmd="$*"
  cmd=${cmd//$W\//}
  cmd=${cmd//$SGNLF/sgnlf}
  cmd=${cmd//$ROOT\//}
  local mark=""
  if [ "$rc" != "$expect" ]; then mark=" **(expected $expect)**"; bad=1; fi
  rows+=("| $what | \`${cmd}\` | $rc$mark | $msg | $kept | $test |")
}

S="$SGNLF"
# A tiny synthetic sequence and a trained smoke run to damage.
$S simulate --sequence kitti360-1538 --frames 14 --width 128 --height 16 --out data > /dev/null 2>&1 || { echo "simulate failed"; exit 1; }
$S train --method lidar-nerf --preset smoke --data data --out run --seed 1 > /dev/null 2>&1 || { echo "train failed"; exit 1; }
SCANS=$(dirname "$(find data -name '*.bin' | sort | head -1)")
first_scan=$(ls $SCANS | head -1)
POSES=$(find data -name poses.txt | head -1)
[ -n "$first_scan" ] && [ -n "$POSES" ] || { echo "unexpected synthetic layout"; exit 1; }

# --- scans
cp -r data d_trunc; head -c 100 d_trunc/${SCANS#data/}/$first_scan > t.bin; mv t.bin d_trunc/${SCANS#data/}/$first_scan
row 1 "scan truncated mid-record (100 bytes)" "io: bad scans" "" -- $S inspect d_trunc
cp -r data d_empty; : > d_empty/${SCANS#data/}/$first_scan
row 1 "empty scan file" "io: bad scans" "" -- $S inspect d_empty
cp -r data d_nan; python3 -c "
import struct,sys; p='d_nan/${SCANS#data/}/$first_scan'; b=bytearray(open(p,'rb').read()); b[16*5:16*5+4]=struct.pack('<f',float('nan')); open(p,'wb').write(b)"
PAT=NaN row 0 "NaN coordinates in a scan (dropped, counted, first index named)" "io: bad scans" "d_nan" -- $S inspect d_nan
cp -r data d_long; cp d_long/${SCANS#data/}/$first_scan d_long/${SCANS#data/}/99999999999999999999.bin
row 1 "over-long numeric scan file name" "datasets: over-long numeric scan file name" "" -- $S inspect d_long
# --- poses and calibration
cp -r data d_poses; sed -i '2s/ [^ ]*$//' d_poses/${POSES#data/}
row 1 "poses.txt line with 12 fields instead of 13" "datasets: bad poses.txt" "" -- $S inspect d_poses
cp -r data d_rigid; sed -i '3s/^\([0-9]*\) [^ ]*/\1 2/' d_rigid/${POSES#data/}
row 1 "poses.txt rotation not orthonormal" "io: bad pose files" "" -- $S inspect d_rigid
cp -r data d_calib; echo "image_00: 2 0 0 0 0 2 0 0 0 0 2 0" > d_calib/calibration/calib_cam_to_pose.txt
row 1 "KITTI-360 calibration not rigid (scaled)" "datasets: calibrations must be rigid" "" -- $S inspect d_calib
cp -r data d_nocalib; rm d_nocalib/calibration/calib_cam_to_velo.txt
row 1 "KITTI-360 calibration file missing" "datasets: missing calibration" "" -- $S inspect d_nocalib
# --- dataset description and sensor
cp -r data d_stride; python3 -c "
import json; p='d_stride/sgnlf_dataset.json'; j=json.load(open(p)); j['stride']=0; json.dump(j,open(p,'w'))"
row 1 "dataset description with stride 0" "datasets: stride of 0 or below" "" -- $S inspect d_stride
echo '{"preset": "kitti360", "height": 4096, "width": 65536}' > big_sensor.json
row 2 "sensor JSON asking for 4096 x 65536 range images" "datasets: gigabyte range images" "" -- $S inspect data --sensor big_sensor.json
echo '{"preset": "kitti360", "beams": 64}' > typo_sensor.json
row 2 "sensor JSON with an unknown key" "core: strict config" "" -- $S inspect data --sensor typo_sensor.json
row 2 "--stride 0" "datasets: stride of 0 or below" "" -- $S inspect data --stride 0
# --- nuScenes tables
mkdir -p nus/v1.0-mini nus/samples/LIDAR_TOP
python3 - <<'EOF'
import json, struct
t = 'nus/v1.0-mini/'
pose = lambda tok, q: {"token": tok, "rotation": q, "translation": [1.0, 2.0, 0.5]}
cal = pose("c1", [1, 0, 0, 0]); cal["sensor_token"] = "lid"
tables = {"scene": [{"token": "sc1", "name": "scene-0001"}], "sample": [{"token": "s1", "scene_token": "sc1"}],
          "sensor": [{"token": "lid", "channel": "LIDAR_TOP"}], "calibrated_sensor": [cal],
          "ego_pose": [pose("e1", [0, 0, 0, 0])],
          "sample_data": [{"token": "d1", "sample_token": "s1", "ego_pose_token": "e1", "calibrated_sensor_token": "c1",
                           "timestamp": 1000000, "is_key_frame": True, "filename": "samples/LIDAR_TOP/a.pcd.bin"}]}
for k, v in tables.items(): json.dump(v, open(t + k + '.json', 'w'))
open('nus/samples/LIDAR_TOP/a.pcd.bin', 'wb').write(struct.pack('<10f', 3, 1, -1, 102, 5, -6, 2, .5, 255, 20))
EOF
PAT='^sgnlf: ' row 1 "nuScenes ego pose with a zero quaternion" "datasets: nuScenes zero quaternion" "" -- $S inspect nus
python3 -c "
import json; p='nus/v1.0-mini/ego_pose.json'; j=json.load(open(p)); j[0]['rotation']=[1,0,0,0]; json.dump(j,open(p,'w'))
p='nus/v1.0-mini/sample_data.json'; j=json.load(open(p)); j[0]['timestamp']='noon'; json.dump(j,open(p,'w'))"
row 1 "nuScenes sample_data with a string timestamp" "datasets: nuScenes JSON type errors" "" -- $S inspect nus
rm nus/v1.0-mini/scene.json
row 1 "nuScenes table missing" "datasets: missing table" "" -- $S inspect nus
# --- configs and run folders
echo '{"optim": {"lr": 0.01, "learning_rate": 2}}' > typo_config.json
row 2 "--config with an unknown key" "pipeline: config" "run" -- $S train --method lidar-nerf --preset smoke --data data --out run --config typo_config.json
echo '{"optim": {"lr": 0.01,' > broken_config.json
row 1 "--config that is not JSON" "core: config" "run" -- $S train --method lidar-nerf --preset smoke --data data --out run --config broken_config.json
echo '{"optim": {"lr": 0.02}}' > other_config.json
row 2 "train into a folder holding another run" "pipeline: session" "run" -- $S train --method lidar-nerf --preset smoke --data data --out run --config other_config.json
row 1 "train on a missing dataset" "datasets: layouts" "run" -- $S train --method lidar-nerf --preset smoke --data no_such_folder --out run
printf '1 0 0 0 0 1 0 0 0 0 1\n' > short_poses.txt
row 1 "render --poses with 11 numbers on a line" "io: bad pose files" "run" -- $S render --run run --poses short_poses.txt --out views
# --- checkpoints and output folders
$S train --method lidar-nerf --preset smoke --data data --out run2 --seed 1 --stop-at 40 > /dev/null 2>&1
python3 -c "
p='run2/checkpoints/latest.ckpt'; b=bytearray(open(p,'rb').read()); b[len(b)//2]^=1; open(p,'wb').write(b)"
PAT='falling back' row 0 "corrupt latest.ckpt, previous.ckpt present (resumes from it, warns)" "pipeline_crash: corrupt latest" "" -- $S train --method lidar-nerf --preset smoke --data data --out run2 --seed 1
$S train --method lidar-nerf --preset smoke --data data --out run3 --seed 1 --stop-at 20 > /dev/null 2>&1
python3 -c "
p='run3/checkpoints/latest.ckpt'; b=bytearray(open(p,'rb').read()); b[len(b)//2]^=1; open(p,'wb').write(b)"
row 1 "corrupt latest.ckpt, no earlier checkpoint" "pipeline_crash: rotating checkpoints" "run3" -- $S train --method lidar-nerf --preset smoke --data data --out run3 --seed 1
$S train --method lidar-nerf --preset smoke --data data --out run4 --seed 1 --stop-at 20 > /dev/null 2>&1
mkdir run4/checkpoints/latest.ckpt.tmp
row 1 "checkpoint folder not writable (a directory in the way)" "pipeline_crash: unwritable" "run4/checkpoints/latest.ckpt run4/run.json" -- $S train --method lidar-nerf --preset smoke --data data --out run4 --seed 1
rmdir run4/checkpoints/latest.ckpt.tmp
row 1 "disk full while writing a checkpoint (ulimit -f 2000 kB)" "pipeline_crash: full disk" "run4/checkpoints/latest.ckpt run4/run.json" -- bash -c "trap '' XFSZ; ulimit -f 2000; exec $S train --method lidar-nerf --preset smoke --data data --out run4 --seed 1"
# --- results and kernels
row 1 "compare with a file that is not JSON" "harness: compare" "" -- $S compare broken_config.json $ROOT/results/tables/kitti360-standard/smoke/results.json
python3 -c "
import json; j=json.load(open('$ROOT/results/tables/kitti360-standard/smoke/results.json'))
j['context']['opencl']['device']='another OpenCL device'
[r for r in j['rows'] if r['status'] == 'ok'][0]['mean']['cd'] = 1000.0; json.dump(j, open('other_device.json','w'))"
PAT='FAIL' row 4 "compare a smoke result made on another device, CD beyond even the loose tolerance" "harness: smoke table on another device" "" -- $S compare other_device.json $ROOT/results/tables/kitti360-standard/smoke/results.json
row 3 "--device 7 (no such OpenCL device)" "cl: device selection" "" -- $S devices --smoke --device 7
cp -r $ROOT/kernels kdir; echo '__kernel void field_broken_fwd(__global float* x) { x[0] = undeclared_name; }' >> kdir/field/mlp.cl
row 1 "a kernel that does not build (SGNLF_KERNEL_DIR)" "cl: kernel build errors" "run" -- env SGNLF_KERNEL_DIR=$W/kdir $S train --method lidar-nerf --preset smoke --data data --out run5 --seed 1

{
  echo "| bad input | command | exit | message (first line) | files written before kept | test |"
  echo "|---|---|---:|---|---|---|"
  printf '%s\n' "${rows[@]}"
} > "$OUT"
cat "$OUT"
exit $bad
