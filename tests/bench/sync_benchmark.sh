#!/usr/bin/env bash
# Prints sync-time figures for a 1M-triangle mesh (Photon vs Cycles). Needs a build in build/.
set -euo pipefail
REPO="$(cd "$(dirname "$0")/../.." && pwd)"
BLENDER_USER_SCRIPTS="$REPO/build/stage" blender -b --factory-startup --addons photon \
  -P "$REPO/tests/bench/sync_benchmark.py" 2>&1 | grep '^BENCH'
