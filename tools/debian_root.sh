#!/usr/bin/env bash
# A Debian 13 (trixie) or sid root with that Debian's Blender and Photon's build dependencies, made
# with debootstrap and entered with chroot, so Photon can be built and tested against Blender 4.3 and
# 5.2 on a Debian 12 machine.
#
#   tools/debian_root.sh SUITE              make the root if needed; print its folder
#   tools/debian_root.sh SUITE run CMD...   run CMD inside it, with this checkout at /photon
#
# Roots are cached in $PHOTON_ROOT_CACHE (default /var/cache/photon-roots), one folder per suite and
# key. The key is a hash of the versions the suite's registry offers today for Blender, Python and
# the libraries Photon links, and of Photon's package list, so a machine pays for a root once (about
# 10-17 minutes, 1.5 GB) and again only when Debian moves one of those packages. Needs root.
set -euo pipefail

REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
CACHE="${PHOTON_ROOT_CACHE:-/var/cache/photon-roots}"
MIRROR="${PHOTON_DEBIAN_MIRROR:-http://deb.debian.org/debian}"
SUITE="${1:?usage: debian_root.sh trixie|sid [run CMD...]}"
shift

case "$SUITE" in
  trixie | sid) ;;
  *) echo "debian_root.sh: unknown suite '$SUITE' (trixie or sid)" >&2; exit 2 ;;
esac
[ "$(id -u)" -eq 0 ] || { echo "debian_root.sh: needs root (debootstrap, chroot)" >&2; exit 2; }

# sid's Release file on Debian's registry is often past its Valid-Until date.
APT_OPTS=(-o Acquire::Check-Valid-Until=false -o Acquire::Retries=3)

# Photon's package list, the same one tools/common.sh installs on the host (but debootstrap,
# which only the host needs, and ccache, which the set-up command inside installs: leaving it
# out of the key kept the roots made before it joined the list).
packages() {
  (source "$REPO/tools/common.sh" >/dev/null 2>&1; printf '%s\n' "${PACKAGES[@]}") |
    grep -vx -e debootstrap -e ccache
}

# The versions that decide whether a cached root is still the one this suite would give today.
suite_key() {
  local index
  index="$(mktemp)"
  curl -fsS --retry 3 -o "$index" "$MIRROR/dists/$SUITE/main/binary-amd64/Packages.xz"
  {
    xz -dc "$index" | awk '/^Package: /{p=$2} /^Version: /{
      if (p=="blender"||p=="python3"||p=="libembree-dev"||p=="libopenimageio-dev"||
          p=="libtbb-dev"||p=="pybind11-dev") print p, $2}' | sort
    packages
  } | sha256sum | cut -c1-16
  rm -f "$index"
}

# Runs a command chrooted into a root, with /proc, /sys, /dev (and this checkout at /photon when
# asked) bind-mounted in a private mount namespace: the mounts vanish with the command, even when
# it is killed, and runs in the same root at the same time do not disturb each other.
in_root() {
  local root="$1" repo="$2"
  shift 2
  unshare --mount --propagation private bash -s "$root" "$repo" "$@" <<'IN_ROOT'
set -e
root="$1" repo="$2"
shift 2
for d in proc sys dev dev/pts; do mount --bind "/$d" "$root/$d"; done
[ -z "$repo" ] || mount --bind "$repo" "$root/photon"
exec chroot "$root" "$@"
IN_ROOT
}

make_root() {
  local dest="$1" tmp="$1.partial"
  rm -rf "$tmp"
  mkdir -p "$(dirname "$dest")"
  echo "== debootstrap $SUITE into $tmp" >&2
  local t0=$SECONDS
  debootstrap --variant=minbase "$SUITE" "$tmp" "$MIRROR" >&2
  # No services start inside the root (slurm, munge).
  printf '#!/bin/sh\nexit 101\n' >"$tmp/usr/sbin/policy-rc.d"
  chmod +x "$tmp/usr/sbin/policy-rc.d"
  cp /etc/resolv.conf "$tmp/etc/resolv.conf"
  echo "APT::Install-Recommends \"false\";" >"$tmp/etc/apt/apt.conf.d/90photon"
  echo "Acquire::Check-Valid-Until \"false\";" >>"$tmp/etc/apt/apt.conf.d/90photon"
  local pkgs
  mapfile -t pkgs < <(packages)
  in_root "$tmp" "" apt-get "${APT_OPTS[@]}" update >&2
  in_root "$tmp" "" /usr/bin/env DEBIAN_FRONTEND=noninteractive apt-get "${APT_OPTS[@]}" \
    install -y --no-install-recommends curl ca-certificates git "${pkgs[@]}" >&2
  in_root "$tmp" "" apt-get clean
  mkdir -p "$tmp/photon"
  mv "$tmp" "$dest"
  echo "== $SUITE root ready in $((SECONDS - t0)) s: $(chroot "$dest" blender --version 2>/dev/null |
    head -1)" >&2
}

ensure_root() {
  local key dest
  if ! key="$(suite_key)"; then
    # Registry unreachable: the newest cached root of this suite will do.
    dest="$(ls -dt "$CACHE/$SUITE"-* 2>/dev/null | grep -v '\.partial$' | head -1 || true)"
    [ -n "$dest" ] || { echo "debian_root.sh: no $SUITE root cached and $MIRROR unreachable" >&2; exit 1; }
    echo "== $MIRROR unreachable: using the cached $dest" >&2
    echo "$dest"
    return
  fi
  dest="$CACHE/$SUITE-$key"
  if [ ! -x "$dest/usr/bin/blender" ]; then
    make_root "$dest"
    # Older roots of this suite are superseded.
    for old in "$CACHE/$SUITE"-*; do
      [ "$old" = "$dest" ] || [ ! -d "$old" ] || rm -rf --one-file-system "$old"
    done
  fi
  echo "$dest"
}

ROOT="$(ensure_root)"
if [ $# -eq 0 ]; then
  echo "$ROOT"
  exit 0
fi
[ "$1" = run ] || { echo "debian_root.sh: expected 'run CMD...', got '$1'" >&2; exit 2; }
shift

# The build folder lives inside the root: it holds objects for that Debian's compiler and Python.
in_root "$ROOT" "$REPO" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root \
  LANG=C.UTF-8 CI="${CI:-}" PHOTON_BUILD_DIR="${PHOTON_ROOT_BUILD_DIR:-/var/tmp/photon-build}" \
  PHOTON_ROOT_UNIT_TESTS="${PHOTON_ROOT_UNIT_TESTS:-}" \
  PHOTON_ROOT_CYCLES_SUITES="${PHOTON_ROOT_CYCLES_SUITES:-}" \
  bash -c 'cd /photon && "$@"' bash "$@"
