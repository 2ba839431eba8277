#!/usr/bin/env bash
# Time-to-quality of issue 19, side by side in one run: the same method, preset, sequence and
# seed trained twice at the same time on the same machine, once with the published sampler
# (the preset as it is) and once with the fast-sampling options of FAST_CONFIG, each with an
# in-training evaluation every EVAL_EVERY steps (eval_log.jsonl: step, train_seconds without
# the evaluations, metrics). summarize.py then reads both folders.
#
# usage: run.sh SGNLF_BINARY DATA_DIR OUT_DIR [METHOD] [PRESET]
#   e.g. run.sh build/bin/sgnlf <kitti360-1538 folder> /tmp/ttq lidar-nerf quick
# env:  FAST_CONFIG  JSON file merged into the fast run (default: fast.json beside this script)
#       EVAL_EVERY   steps between evaluations (default 500)
#       FRAMES / SEQUENCE  passed to `sgnlf train` when set
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=$1 data=$2 out=$3 method=${4:-lidar-nerf} preset=${5:-quick}
fast=${FAST_CONFIG:-$here/fast.json}
every=${EVAL_EVERY:-500}
mkdir -p "$out"
printf '{"schedule": {"eval_every": %d}}\n' "$every" > "$out/base.json"
python3 - "$fast" "$every" > "$out/fast.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c.setdefault("schedule", {})["eval_every"] = int(sys.argv[2])
print(json.dumps(c))
PY
extra=()
[ -n "${SEQUENCE:-}" ] && extra+=(--sequence "$SEQUENCE")
[ -n "${FRAMES:-}" ] && extra+=(--frames "$FRAMES")
for v in base fast; do
  "$bin" train --method "$method" --preset "$preset" --seed 1 --data "$data" "${extra[@]}" \
    --config "$out/$v.json" --out "$out/$v" > "$out/$v.log" 2>&1 &
done
wait
python3 "$here/summarize.py" "$out/base" "$out/fast"
