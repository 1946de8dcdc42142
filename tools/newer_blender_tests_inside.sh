#!/usr/bin/env bash
# Run by tools/newer_blender_tests.sh inside a Debian 13 / sid root (this checkout at /photon).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
BUILD="${PHOTON_BUILD_DIR:?}"
echo "== $(blender --version 2>/dev/null | head -1), $(python3 --version)"

version="$(blender --version 2>/dev/null | head -1 | awk '{print $2}' | cut -d. -f1,2)"

# CI runs 90 minutes at most, and a change to a header most sources include rebuilds the host,
# sanitizer and both roots' trees (that alone took a run from 81 to 90 minutes). So each root
# builds what Blender needs and no more: the C++ unit tests (their build and 147 s run in sid)
# and the Google Benchmark kernels are the host's. PHOTON_ROOT_UNIT_TESTS=1 builds and runs the
# unit tests against the root's GCC, Embree 4 and OpenImageIO (2.5 in Debian 13, 3.1 in sid).
unit_tests="${PHOTON_ROOT_UNIT_TESTS:-0}"
export PHOTON_CMAKE_ARGS="-DPHOTON_BUILD_TESTS=OFF -DPHOTON_BUILD_BENCHMARKS=OFF"
if [ "$unit_tests" = 1 ]; then
  export PHOTON_CMAKE_ARGS="-DPHOTON_BUILD_BENCHMARKS=OFF"
fi
# The stored validation scenes and shader-node cases against this Blender's Cycles: in sid
# (Blender 5.2) by default; Debian 13's 4.3 references stay beside them for
# PHOTON_ROOT_CYCLES_SUITES=1 (3.5 minutes there). Its Blender tests compare with Cycles 4.3.
cycles_suites="${PHOTON_ROOT_CYCLES_SUITES:-}"
if [ -z "$cycles_suites" ]; then
  cycles_suites=1
  [ "$version" = "4.3" ] && cycles_suites=0
fi

t=$SECONDS
./tools/setup_and_demo.sh
echo "== set-up and demo: $((SECONDS - t)) s"

status=0
if [ "$unit_tests" = 1 ]; then
  t=$SECONDS
  "$BUILD/photon_tests" --gtest_brief=1 || status=1
  echo "== unit tests: $((SECONDS - t)) s"
fi

# The Blender tests that pass in the newer Blenders (tests/blender/newer_blenders.txt; a line's
# "skip=5.2" leaves the file out in that Blender, its comment says why). The others compare with
# references rendered in 3.4 or assert 3.4's behaviour: docs/blender_versions.md.
tests="$(awk -v v="$version" '/^#/ || !NF { next } {
  keep = 1
  for (i = 2; i <= NF && $i != "#"; i++)
    if ($i ~ /^skip=/) { n = split(substr($i, 6), vs, ","); for (k = 1; k <= n; k++) if (vs[k] == v) keep = 0 }
  if (keep) print $1 }' tests/blender/newer_blenders.txt)"
t=$SECONDS
# shellcheck disable=SC2086
python3 -m pytest -q -rs -n 2 --dist loadfile -m "not serial" $tests \
  --photon-stage="$BUILD/stage" --blender=blender --photon-out="$BUILD/test_out" || status=1
echo "== Blender tests: $((SECONDS - t)) s"

if [ "$cycles_suites" = 1 ]; then
  # The validation scenes against this Blender's own Cycles (test_scenes/validation/blender-X.Y:
  # the stored scenes as this Blender reads them, rendered by its Cycles with tools/regress.py
  # --update). Left out in 5.2: bump_normal, whose image mean agrees (0.08%) but 3.06% of its
  # pixels differ by more than the threshold (3% allowed), around the bumped sphere's highlight:
  # Cycles 5.2 differs there from 4.3, not yet explained.
  case "$(blender --version 2>/dev/null | head -1)" in
    "Blender 5.2"*) excluded=" bump_normal " ;;
    *) excluded=" " ;;
  esac
  scenes=()
  for blend in test_scenes/validation/*.blend; do
    name="$(basename "$blend" .blend)"
    [[ "$excluded" == *" $name "* ]] || scenes+=("$name")
  done
  t=$SECONDS
  python3 tools/regress.py test_scenes/validation --blender blender --addon-dir "$BUILD/stage" \
    --out "$BUILD/validation" --only "${scenes[@]}" || status=1
  echo "== validation suite: $((SECONDS - t)) s"

  # Shader-node conformance against this Blender's own Cycles (test_scenes/nodes/*/blender-X.Y).
  # Left out, each for a difference not yet explained: in 4.3 RGB Curves far outside [0, 1]
  # (color/rgb_curves_wide_range); in 5.2 the 2D-4D Voronoi cells and five sRGB/premultiplied
  # EXR image cases.
  case "$(blender --version 2>/dev/null | head -1)" in
    "Blender 4.3"*) manifests=(attribute camera_coords gabor image math nodes_4x noise noise_fractal
                               normal_map object_info pattern voronoi voronoi_fractal) ;;
    *) manifests=(attribute camera_coords color gabor math nodes_4x noise noise_fractal normal_map
                  object_info pattern) ;;
  esac
  paths=()
  for m in "${manifests[@]}"; do paths+=("test_scenes/nodes/$m.json"); done
  t=$SECONDS
  python3 tools/node_conformance.py --blender blender --addon-dir "$BUILD/stage" \
    --out "$BUILD/node_conformance" --manifests "${paths[@]}" || status=1
  echo "== node conformance: $((SECONDS - t)) s"
fi
exit $status
