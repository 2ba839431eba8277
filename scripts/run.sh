#!/usr/bin/env bash
# The README's main command: installs dependencies, builds, checks the OpenCL device, then
# reproduces the quick KITTI-360 standard-frequency table on the built-in synthetic data
# (every row of the table; rows whose method is not built yet print "not implemented") and
# compares it with the committed result. OUT=<dir> changes where the results go.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/bin/sgnlf devices --smoke
OUT=${OUT:-runs/quick-kitti360-standard}
./build/bin/sgnlf bench --table kitti360-standard --scale quick --seed 1 --out "$OUT"
echo
cat "$OUT/table.md"
echo
if [ -f results/tables/kitti360-standard/quick/results.json ]; then
  ./build/bin/sgnlf compare "$OUT/results.json" results/tables/kitti360-standard/quick/results.json || true
fi
echo "run.sh: results in $OUT/results.json (schema: results/schema.md) and $OUT/table.md"
