#!/usr/bin/env bash
# The README's main command: installs dependencies, builds, and runs the main job on the
# built-in synthetic data.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/bin/sgnlf devices --smoke
