#!/usr/bin/env bash
# Builds and tests Photon in a newer Debian's Blender: Debian 13 (trixie, Blender 4.3) or sid
# (Blender 5.2), in a root made by tools/debian_root.sh (cached on the machine). Inside the root it
# runs the README's set-up command (install, build, install the add-on, render the demo), the
# extension install, the C++ unit tests (Embree 4, OpenImageIO 2.5/3.1) and the Blender tests
# that apply to that Blender.
#
#   tools/newer_blender_tests.sh trixie|sid
#
# Exit 77 (ctest: skipped) where a root cannot be made: not root, or no debootstrap.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SUITE="${1:?usage: newer_blender_tests.sh trixie|sid}"

if [ "$(id -u)" -ne 0 ] || ! command -v debootstrap >/dev/null || ! command -v unshare >/dev/null
then
  echo "SKIPPED: the $SUITE root needs root, debootstrap and unshare"
  exit 77
fi

t0=$SECONDS
"$REPO/tools/debian_root.sh" "$SUITE" >/dev/null
echo "== $SUITE root ready after $((SECONDS - t0)) s"
exec "$REPO/tools/debian_root.sh" "$SUITE" run bash tools/newer_blender_tests_inside.sh
