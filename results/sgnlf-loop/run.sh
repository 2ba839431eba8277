#!/usr/bin/env bash
# SG-NLF part 1 on the loop sequences (issue 16's done criterion): GeoNLF, SG-NLF without its
# adversarial term with the sequential graph only, and with the confidence-aware pose graph,
# all quick, seed 1, from the protocol's noisy initialisation.
# Usage: bash results/sgnlf-loop/run.sh BIN_DIR WORK_DIR [sequence ...]
set -euo pipefail
BIN=$(cd "$1" && pwd); WORK=$2; shift 2
HERE=$(cd "$(dirname "$0")" && pwd)
SEQS=${*:-kitti360-loop nuscenes-loop}
mkdir -p "$WORK"
for seq in $SEQS; do
  [ -d "$WORK/data/$seq" ] || "$BIN/sgnlf" simulate --sequence "$seq" --seed 1 --out "$WORK/data/$seq"
  for row in ${ROWS:-confidence sequential geonlf}; do
    run="$WORK/runs/$seq-$row"
    [ -f "$run/metrics.json" ] && continue
    case $row in
      geonlf) args=(--method geonlf) ;;
      sequential) args=(--method sg-nlf-no-consistency --config "$HERE/sequential-only.json") ;;
      confidence) args=(--method sg-nlf-no-consistency --config "$HERE/confidence.json") ;;
    esac
    "$BIN/sgnlf" train "${args[@]}" --preset quick --seed 1 --data "$WORK/data/$seq" \
        --out "$run" > "$WORK/$seq-$row.log" 2>&1
    "$BIN/sgnlf" eval --run "$run" > "$WORK/$seq-$row.eval.txt" 2>&1
  done
done
