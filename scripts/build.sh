#!/usr/bin/env bash
# Configures and builds sgnlf into build/ (Release). Extra arguments go to cmake configure.
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS=${JOBS:-$(nproc)}
WERROR=OFF
[ "${CI:-}" = "true" ] && WERROR=ON
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSGNLF_WERROR=$WERROR "$@"
cmake --build build -j "$JOBS"
