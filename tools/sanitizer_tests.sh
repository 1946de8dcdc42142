#!/usr/bin/env bash
# Builds the C++ unit tests with AddressSanitizer + UndefinedBehaviorSanitizer (PHOTON_SANITIZE)
# in their own build tree and runs them, the scene fuzzer included (PHOTON_FUZZ_SECONDS, 30 s by
# default). Any sanitizer report fails the run: errors halt, leaks are checked at exit, and
# only the system-library reports listed (and justified) in tools/sanitizers/*.supp are
# suppressed. Registered with ctest as `sanitizer_unit_tests`; extra arguments go to
# photon_tests (e.g. --gtest_filter=SceneFuzz.*).
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
BUILD="${PHOTON_ASAN_BUILD_DIR:-$REPO/build-asan}"
SUPP="$REPO/tools/sanitizers"

use_ccache

start=$(date +%s)
# -O1 -g1 (line tables): a third of -O2 -g's compile time, and still file:line in reports.
# Without NDEBUG: this is the build where DCHECKs (base/check.h) run.
cmake -S "$REPO" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPHOTON_SANITIZE=ON \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DPHOTON_BUILD_BENCHMARKS=OFF -DPython_EXECUTABLE=/usr/bin/python3 "${CCACHE_LAUNCHER[@]}" >/dev/null
cmake --build "$BUILD" --target photon_tests -j"$(nproc)"
built=$(date +%s)

# new_delete_type_mismatch=0: Debian's OpenImageIO 2.4 frees its TextureSystemImpl in
# TextureSystem::destroy() through a sized delete of the wrong static type (a report inside
# libOpenImageIO that suppression files cannot name; glibc ignores the size). Photon's own code
# is covered by -Wall's -Wdelete-non-virtual-dtor instead.
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:check_initialization_order=1:strict_init_order=1:new_delete_type_mismatch=0:suppressions=$SUPP/asan.supp"
export LSAN_OPTIONS="suppressions=$SUPP/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$SUPP/ubsan.supp"
# Sanitized code runs several times slower: wall-time bounds (cancel latency) get 5x room here;
# the normal build checks them unscaled.
export PHOTON_TIMING_SLACK="${PHOTON_TIMING_SLACK:-5}"
export PHOTON_FUZZ_SECONDS="${PHOTON_FUZZ_SECONDS:-30}"
# The Cycles-reference node tests run every case's node code at every 31st pixel (the plain
# build checks every pixel). A stride that shares no factor with the images' power-of-two
# sizes lands off the axes, which the 2D-4D White Noise hash test needs (at 32 and 64 it kept no
# pixel there); 31 takes 50 s off the 100 s that every 16th pixel took here.
export PHOTON_NODE_REF_STRIDE="${PHOTON_NODE_REF_STRIDE:-31}"
# Statistical comparisons of whole scenes (means within a percent, error slopes) are checked in
# the plain build; here they would repeat the code of their small siblings that still run (the
# furnaces, the inverse-square planes, the thread-count and cancel tests of each integrator)
# at 5x the time, a third of this run. So is Principled v2's 200,000-sample histogram per
# case (18 s here): its sampling code runs here in the albedo and furnace tests of the same
# file. A --gtest_filter given as an argument comes after this one and replaces it.
statistical=(
  'Vcm.CornellBoxMeanAgreesWithSppmAndPhotonMapping'
  'Vcm.CausticBoxMeanAgreesWithSppm'
  'VcmModes.AgreeTileByTileWithinTheirMeasuredNoiseOnTheCornellBox'
  'Sppm.CornellBoxMeanMatchesPhotonMapping'
  'SpectralRender.DispersionKeepsTheCausticBoxsLight'
  'SpectralRender.GreyCornellBoxMatchesRgbForEveryIntegrator'
  'SpectralRender.ImageDoesNotDependOnTheThreadCount'
  'Vcm.LightMergedThroughATranslucentSheetAgreesWithConnectionsAndSppm'
  'PrincipledV2.SamplingMatchesPdf'
  '*SdsConvergence*'
  # Means and unbiasedness of estimators over many samples (5-17 s each here, 100 s in all);
  # the code they average runs in the furnace, thread-count and cancel tests.
  'ProgressiveSession.CoarsePhotonMapShowsIndirectLightBeforeTheFullMap'
  'Environment.RadiosityFloorUnderALinearSkyReceivesItsIrradiance'
  'PhotonMapIntegrator.EmissiveFurnaceConvergesToLeOverOneMinusAlbedo'
  'Sppm.CausticOfAnEmissiveMeshMatchesPhotonMapping'
  'PathWalker.*RouletteIsUnbiased'
  'SpectralRender.ColouredCornellBoxKeepsItsColours'
  'RadiositySolver.ClosedEmissiveBoxConvergesToTheAnalyticValue'
  'IrradianceCacheRender.CacheReducesPixelNoise'
  'LightTreeDirectLighting.MatchesTheEveryLightEstimator'
  'SpectralBsdf.RoughDispersiveWeightsEstimateEachWavelengthsAlbedo'
  'EmissiveSphere.IrradianceAtTheClosestPointOfAFacingPlane'
)
filter="-$(IFS=:; echo "${statistical[*]}")"
status=0
"$BUILD/photon_tests" "--gtest_filter=$filter" "$@" || status=$?
echo "== sanitizer tests: build $((built - start)) s, run $(($(date +%s) - built)) s, exit $status"
exit $status
