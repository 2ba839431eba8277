#!/usr/bin/env bash
# One table in full: bash scripts/reproduce.sh TABLE [SCALE=quick] [SEEDS=1, e.g. 1,2,3]
# Builds, prints the run's estimated time (from the committed results/tables/TABLE/SCALE/
# results.json, when there is one) before it starts, runs every row on every sequence with each
# seed into runs/TABLE-SCALE (OUT= to change), prints the table and compares it with the
# committed one (exit 4 on a regression). `sgnlf bench --list` names the tables and scales.
set -euo pipefail
cd "$(dirname "$0")/.."
TABLE=${1:?usage: bash scripts/reproduce.sh TABLE [SCALE=quick] [SEEDS=1] (tables: sgnlf bench --list)}
SCALE=${2:-quick}
SEEDS=${3:-1}
bash scripts/setup.sh
bash scripts/build.sh
OUT=${OUT:-runs/$TABLE-$SCALE}
COMMITTED=results/tables/$TABLE/$SCALE/results.json
SEED_FLAG=(--seed "$SEEDS")
case "$SEEDS" in *,*) SEED_FLAG=(--seeds "$SEEDS") ;; esac
./build/bin/sgnlf bench --table "$TABLE" --scale "$SCALE" "${SEED_FLAG[@]}" --out "$OUT"
cat "$OUT/table.md"
if [ -f "$COMMITTED" ]; then
  ./build/bin/sgnlf compare --no-timings "$OUT/results.json" "$COMMITTED"
else
  echo "reproduce: no committed $COMMITTED to compare with"
fi
echo "reproduce: $OUT/results.json and $OUT/table.md"
