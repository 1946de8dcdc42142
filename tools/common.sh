# Shared by setup_and_demo.sh and run_tests.sh: Debian packages and the CMake build.
set -euo pipefail

REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${PHOTON_BUILD_DIR:-$REPO/build}"

PACKAGES=(
  cmake g++ make pkg-config clang-format ccache
  blender
  libembree-dev libtbb-dev libopenimageio-dev openimageio-tools python3-openimageio
  pybind11-dev python3-dev python3-numpy python3-pytest python3-pytest-xdist
  libgtest-dev libbenchmark-dev libnanoflann-dev
  xvfb xauth xdotool libgl1-mesa-dri  # the GUI tests (tests/blender/test_*_gui.py)
  slurm-wlm munge  # the render farm and its test cluster (tools/farm.py, tests/farm)
  debootstrap  # Debian 13 and sid roots for the Blender 4.3 and 5.2 tests (tools/debian_root.sh)
)

install_packages() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -eq 0 ]; then
    echo "== all Debian packages present"
    return
  fi
  echo "== installing: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
}

# Compiler cache: a fresh clone has new file times, so make alone rebuilds everything (four
# builds per test run: this one, the sanitizer's and one in each newer-Debian root). As root the
# cache lives in /var/cache/photon-ccache, kept on the machine like the roots; paths under the
# checkout are hashed relative to it, so clones in other folders share it. Sets CCACHE_LAUNCHER
# to the CMake arguments that use it (none without ccache).
use_ccache() {
  CCACHE_LAUNCHER=()
  command -v ccache >/dev/null || return 0
  if [ -z "${CCACHE_DIR:-}" ] && [ "$(id -u)" -eq 0 ]; then
    export CCACHE_DIR=/var/cache/photon-ccache
  fi
  export CCACHE_BASEDIR="$REPO" CCACHE_MAXSIZE="${CCACHE_MAXSIZE:-8G}"
  CCACHE_LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
}

# PHOTON_CMAKE_ARGS adds configure options (e.g. -DPHOTON_BUILD_TESTS=OFF).
build() {
  echo "== building in $BUILD"
  use_ccache
  local extra
  read -r -a extra <<<"${PHOTON_CMAKE_ARGS:-}"
  cmake -S "$REPO" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=/usr/bin/python3 \
    "${CCACHE_LAUNCHER[@]}" "${extra[@]}"
  cmake --build "$BUILD" -j"$(nproc)"
}
