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
          python3-sphinx  # the doc/ build test (doc.sphinx_html)
          python3-meshio  # tools/dump2vtk.py (dumps to VTK for ParaView; ctest output.dump2vtk)
          python3-yaml    # CITATION.cff read by ctest project.basics
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
# A deb-src entry is needed when the system's apt sources have none for this
# version. It goes into a PRIVATE apt configuration under the cache (its own
# source list, list directory and archive cache), derived from the system's
# deb entries: the machine's apt configuration and package lists stay as they
# were. (Earlier versions of this script added
# /etc/apt/sources.list.d/tlsph-deb-src.sources; it is removed below.)
APT_PRIV="$CACHE/apt"
APT_OPTS=()
private_apt() {
  mkdir -p "$APT_PRIV/lists/partial" "$APT_PRIV/archives/partial" "$APT_PRIV/sources.list.d"
  : > "$APT_PRIV/sources.list"
  local f
  # one-line format: every "deb" line as "deb-src"
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -f "$f" ] || continue
    sed -n 's/^[[:space:]]*deb[[:space:]]/deb-src /p' "$f" >> "$APT_PRIV/sources.list"
  done
  # deb822 format: the stanzas of type deb, as deb-src
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    case "$(basename "$f")" in tlsph-*) continue ;; esac
    awk 'BEGIN { RS = ""; ORS = "\n\n" }
         /(^|\n)Types:[^\n]*(^|[ \t])deb([ \t]|\n|$)/ {
           sub(/(^|\n)Types:[^\n]*/, "\nTypes: deb-src"); sub(/^\n/, ""); print }' "$f" \
      > "$APT_PRIV/sources.list.d/$(basename "$f")"
  done
  APT_OPTS=(-o "Dir::Etc::SourceList=$APT_PRIV/sources.list"
            -o "Dir::Etc::SourceParts=$APT_PRIV/sources.list.d"
            -o "Dir::State::Lists=$APT_PRIV/lists"
            -o "Dir::Cache::Archives=$APT_PRIV/archives"
            -o "Dir::Cache::pkgcache=" -o "Dir::Cache::srcpkgcache=")
  # as root, apt downloads as the user _apt, who cannot enter a home cache:
  # download as root (what apt falls back to anyway, without the warning)
  [ "$(id -u)" -ne 0 ] || APT_OPTS+=(-o "APT::Sandbox::User=root")
  log "apt-get update of a private deb-src list ($APT_PRIV)"
  "${SUDO[@]}" apt-get "${APT_OPTS[@]}" update -q >&2
}
# have_src [PKG VERSION]: the source package (default: LAMMPS's) is known to apt
have_src() {
  local idx pkg=${1:-$SRC_PKG} ver=${2:-$SRC_VER}
  idx=$(apt-cache "${APT_OPTS[@]}" showsrc "$pkg" 2>/dev/null || true)
  grep -qxF "Version: $ver" <<<"$idx"
}

old_entry=/etc/apt/sources.list.d/tlsph-deb-src.sources
if [ -f "$old_entry" ] && grep -q '^# added by tlsph scripts/setup.sh' "$old_entry"; then
  log "removing $old_entry (added by an earlier version of this script)"
  "${SUDO[@]}" rm -f "$old_entry"
fi

# --check-source: only find the source package through the private list
# (the test unittest/plugin/check_apt_untouched.sh)
if [ "${1:-}" = "--check-source" ]; then
  private_apt
  have_src || die "no Debian source package $SRC_PKG $SRC_VER through the private deb-src list"
  log "found $SRC_PKG $SRC_VER through $APT_PRIV"
  exit 0
fi

# --download-source PKG VERSION DIR: download (not unpack) another Debian
# source package into DIR the same way (build-lammps-plugin.sh: trilinos, the
# Kokkos source of the kokkos-cuda and kokkos-omp builds)
if [ "${1:-}" = "--download-source" ]; then
  [ $# -eq 4 ] || die "usage: setup.sh --download-source PKG VERSION DIR"
  have_src "$2" "$3" || private_apt
  have_src "$2" "$3" || die "no Debian source package $2 $3 in the apt sources (deb-src)"
  ( cd "$4" && apt-get "${APT_OPTS[@]}" source -q --download-only "$2=$3" >&2 )
  exit 0
fi

if [ ! -f "$SRC_DIR/src/version.h" ]; then
  log "fetching the Debian source of $SRC_PKG $SRC_VER into $SRC_DIR"
  have_src || private_apt
  have_src || die "no Debian source package $SRC_PKG $SRC_VER in the apt sources (deb-src)"
  tmp=$(mktemp -d "$CACHE/.lammps-$SRC_VER.XXXXXX")
  trap 'rm -rf "$tmp"' EXIT
  ( cd "$tmp" && apt-get "${APT_OPTS[@]}" source -q --download-only "$SRC_PKG=$SRC_VER" >&2 )
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
