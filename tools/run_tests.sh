#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test: C++ unit tests and headless Blender
# tests (ctest runs both).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

install_packages
build
cd "$BUILD"
ctest --output-on-failure -j1 "$@"
