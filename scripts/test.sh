#!/usr/bin/env bash
# The README's test command: installs dependencies, builds, and runs the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
clinfo -l || true
ctest --test-dir build --output-on-failure -j "${JOBS:-$(nproc)}"
