#!/usr/bin/env bash
# Prints time-to-first-pixel figures for a 1M-triangle mesh (Photon vs Cycles, min of N runs).
# Needs a build in build/. Extra arguments go to the script, e.g. --runs 5 --threads 2.
set -euo pipefail
REPO="$(cd "$(dirname "$0")/../.." && pwd)"
BLENDER_USER_SCRIPTS="$REPO/build/stage" blender -b --factory-startup --addons photon \
  -P "$REPO/tests/bench/sync_benchmark.py" -- "$@" 2>&1 | grep '^BENCH'
