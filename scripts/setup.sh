#!/usr/bin/env bash
# Set-up for building USER-TLSPH on Debian 12 (bookworm). Idempotent, and fast
# (a few dpkg-query calls) when everything is already there.
#
#  1. installs the Debian packages the build and the tests need (apt-get),
#  2. fetches the LAMMPS source tree of exactly the installed liblammps version
#     (its internal headers are what the styles compile against) into
#     ${TLSPH_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/tlsph}/lammps-<source version>.
#
# All progress goes to stderr; stdout gets exactly one line: the absolute path
# of that LAMMPS source tree (pass it to cmake as -DLAMMPS_SOURCE_DIR=...).
# It is also written to ${TLSPH_CACHE}/lammps-source-dir.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive

log() { printf 'setup.sh: %s\n' "$*" >&2; }
die() { printf 'setup.sh: error: %s\n' "$*" >&2; exit 1; }

SUDO=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO=(sudo -E); fi
fi

command -v dpkg-query >/dev/null 2>&1 || die "this set-up needs Debian 12 (dpkg-query not found)"

PACKAGES=(lammps liblammps-dev python3-lammps libeigen3-dev libopenmpi-dev openmpi-bin
          libgtest-dev cmake ninja-build g++ make dpkg-dev python3-numpy python3-matplotlib
          xz-utils
          calculix-ccx)  # ccx: the FE reference of the laminate examples (unittest/fe)

is_installed() {
  [ "$(dpkg-query -W -f='${db:Status-Status}' "$1" 2>/dev/null || true)" = installed ]
}

apt_updated=0
apt_update() {
  if [ "$apt_updated" -eq 0 ]; then
    log "apt-get update"
    "${SUDO[@]}" apt-get update -q >&2
    apt_updated=1
  fi
}

# ---------------------------------------------------------------- 1. packages
missing=()
for p in "${PACKAGES[@]}"; do is_installed "$p" || missing+=("$p"); done
if [ "${#missing[@]}" -gt 0 ]; then
  log "installing missing Debian packages: ${missing[*]}"
  apt_update
  "${SUDO[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}" >&2
fi

# -------------------------------------------------- 2. matching LAMMPS source
# The binary package may be a binNMU (+b2): the source version is the one to fetch.
SRC_PKG=$(dpkg-query -W -f='${source:Package}' liblammps-dev)
SRC_VER=$(dpkg-query -W -f='${source:Version}' liblammps-dev)
[ -n "$SRC_PKG" ] && [ -n "$SRC_VER" ] || die "cannot read the source version of liblammps-dev"

CACHE=${TLSPH_CACHE:-${XDG_CACHE_HOME:-${HOME:-/root}/.cache}/tlsph}
SRC_DIR="$CACHE/lammps-$SRC_VER"
mkdir -p "$CACHE"
CACHE=$(cd "$CACHE" && pwd -P)
SRC_DIR="$CACHE/lammps-$SRC_VER"

if [ ! -f "$SRC_DIR/src/version.h" ]; then
  # one fetch at a time per cache (two builds may set up concurrently)
  exec 9>"$CACHE/.lammps-source.lock"
  flock 9
fi
if [ ! -f "$SRC_DIR/src/version.h" ]; then
  log "fetching the Debian source of $SRC_PKG $SRC_VER into $SRC_DIR"
  # the source index must offer exactly this version: if it does not, add a
  # deb-src entry for Debian's archive (unless ours is there already), update
  have_src() {
    local idx
    idx=$(apt-cache showsrc "$SRC_PKG" 2>/dev/null || true)
    grep -qxF "Version: $SRC_VER" <<<"$idx"
  }
  have_src || apt_update
  if ! have_src; then
    f=/etc/apt/sources.list.d/tlsph-deb-src.sources
    if [ ! -f "$f" ]; then
      log "adding $f"
      "${SUDO[@]}" tee "$f" >/dev/null <<'SOURCES'
# added by tlsph scripts/setup.sh: the LAMMPS source package matching liblammps
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SOURCES
    fi
    apt_updated=0
    apt_update
    have_src || die "no Debian source package $SRC_PKG $SRC_VER in the apt sources (deb-src)"
  fi
  tmp=$(mktemp -d "$CACHE/.lammps-$SRC_VER.XXXXXX")
  trap 'rm -rf "$tmp"' EXIT
  ( cd "$tmp" && apt-get source -q --download-only "$SRC_PKG=$SRC_VER" >&2 )
  dscs=("$tmp"/*.dsc)
  dsc=${dscs[0]}
  [ -f "$dsc" ] || die "apt-get source downloaded no .dsc"
  log "unpacking $(basename "$dsc")"
  ( cd "$tmp" && dpkg-source -q -x "$dsc" tree >&2 )
  [ -f "$tmp/tree/src/version.h" ] || die "unpacked source has no src/version.h"
  mv "$tmp/tree" "$SRC_DIR"        # atomic: never a half tree under the final name
  rm -rf "$tmp"
  trap - EXIT
fi

f=$(mktemp "$CACHE/.lammps-source-dir.XXXXXX")
printf '%s\n' "$SRC_DIR" >"$f" && chmod 644 "$f" && mv "$f" "$CACHE/lammps-source-dir"
log "LAMMPS $SRC_VER source: $SRC_DIR"
printf '%s\n' "$SRC_DIR"
