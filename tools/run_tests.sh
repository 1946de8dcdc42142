#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test through ctest: C++ unit tests, headless
# Blender tests, the regression tool's tests, and the image regression and validation suites
# (whose HTML reports are listed at the end).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

install_packages
build
cd "$BUILD"
status=0
ctest --output-on-failure -j1 "$@" || status=$?
for suite in regression validation node_conformance; do
  if [ -f "$BUILD/$suite/report.html" ]; then
    echo "== $suite report: $BUILD/$suite/report.html"
  fi
done
exit $status
