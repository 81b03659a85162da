#!/usr/bin/env bash
# Builds an `lmp` with the PLUGIN package (plus PERI for atom_style peri) from
# the same Debian LAMMPS source tree the package compiles against, so that
# `plugin load tlsphplugin.so` can be tested. Cached, keyed by the source version:
#
#   ${TLSPH_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/tlsph}/lammps-plugin-<source version>/
#       build/         LAMMPS's own CMake build
#       bin/lmp        the executable (RUNPATH $ORIGIN/../lib)
#       lib/liblammps_plugin.so.0
#         (LAMMPS_MACHINE=plugin: a library name of its own, so that it can
#          never be mixed up with Debian's liblammps.so.0)
#
# Nothing is done when bin/lmp exists. The last line on stdout is the path of
# bin/lmp. Uses `ninja -j${TLSPH_JOBS:-2}`.
#
# `build-lammps-plugin.sh bench` builds the side-by-side benchmark's LAMMPS
# instead (bench/compare.sh): the same, plus the MACHDYN package (smd/tlsph,
# with Debian's Eigen), in lammps-bench-<source version>/ (library
# liblammps_bench.so.0). MACHDYN's pair_smd_tlsph.cpp of this version calls
# domain->minimum_image(dx0) before dx0 is assigned (in its reference-distance
# loop; BENCH_PATCH below): with a periodic
# dimension -- z in every 2D run -- it then reduces an uninitialised vector,
# which can loop for a very long time. This build moves that one call after
# the assignment, on a hard-linked copy of the source tree (the shared tree
# stays untouched); nothing else of MACHDYN is changed.
#
# `build-lammps-plugin.sh kokkos` builds a LAMMPS with the KOKKOS package for
# the host (Kokkos Serial backend), plus PLUGIN and PERI, in
# lammps-kokkos-<source version>/ (library liblammps_kokkos.so.0); doc/kokkos.md.
# The Debian LAMMPS source has no lib/kokkos (stripped from the +ds tarball),
# so it is built against Debian's Kokkos, libtrilinos-kokkos-dev (Kokkos
# 3.4.01, the version this LAMMPS wants; Serial backend only; installed here
# when missing), with EXTERNAL_KOKKOS. Debian's KokkosConfig.cmake gives its
# Kokkos::kokkos target the include directory /usr/lib/include, which does
# not exist (its prefix is computed three levels up from the multiarch
# lib/x86_64-linux-gnu/cmake/Kokkos, one level short), and CMake refuses an
# imported target with a missing include directory. KOKKOS_PATCH below makes
# LAMMPS's cmake/Modules/Packages/KOKKOS.cmake drop the missing directories of
# that target and add Kokkos_INCLUDE_DIRS (/usr/include/trilinos, from the same
# config file), on a hard-linked copy of the tree, as for bench.
#
# Why BUILD_SHARED_LIBS=on: in this LAMMPS version (20220106) the CMake build
# defines LMP_PLUGIN (without which `plugin load` is a no-op that only prints
# a warning) only for a shared-library build; the plugin's undefined LAMMPS
# symbols then resolve against that liblammps.so.0. Class layout: this build
# and Debian's liblammps both use -DLAMMPS_SMALLBIG and no LAMMPS_EXCEPTIONS,
# the flags the plugin is compiled with (CMakeLists.txt of this project).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive

log() { printf 'build-lammps-plugin.sh: %s\n' "$*" >&2; }
die() { printf 'build-lammps-plugin.sh: error: %s\n' "$*" >&2; exit 1; }

HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)
JOBS=${TLSPH_JOBS:-2}
VARIANT=${1:-plugin}
case "$VARIANT" in
  plugin) EXTRA_PKGS=() ;;
  bench)  EXTRA_PKGS=(-D PKG_MACHDYN=on -D DOWNLOAD_EIGEN3=off) ;;
  kokkos) EXTRA_PKGS=(-D PKG_KOKKOS=on -D EXTERNAL_KOKKOS=on -D Kokkos_ENABLE_SERIAL=on
                      -D Kokkos_ENABLE_OPENMP=off -D Kokkos_ENABLE_CUDA=off) ;;
  *) die "unknown variant '$VARIANT' (allowed: plugin, bench, kokkos)" ;;
esac

# kokkos: Debian's Kokkos, built and at run time (libtrilinos_kokkoscore.so.13.2)
if [ "$VARIANT" = kokkos ]; then
  kk_pkg=libtrilinos-kokkos-dev
  if [ "$(dpkg-query -W -f='${db:Status-Status}' "$kk_pkg" 2>/dev/null || true)" != installed ]; then
    SUDO=()
    if [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1; then SUDO=(sudo -E); fi
    log "installing the missing Debian package $kk_pkg (Kokkos 3.4.01, Serial backend)"
    "${SUDO[@]}" apt-get update -q >&2
    "${SUDO[@]}" apt-get install -y -q --no-install-recommends "$kk_pkg" >&2
  fi
fi

# source tree: from the caller (must match the installed version, checked
# below) or from setup.sh (which fetches it when missing)
if [ -z "${LAMMPS_SOURCE_DIR:-}" ]; then
  LAMMPS_SOURCE_DIR=$(bash "$HERE/setup.sh" | tail -n1)
fi
[ -f "$LAMMPS_SOURCE_DIR/cmake/CMakeLists.txt" ] || die "no LAMMPS source tree at '$LAMMPS_SOURCE_DIR'"

SRC_VER=$(dpkg-query -W -f='${source:Version}' liblammps-dev)
[ -n "$SRC_VER" ] || die "cannot read the source version of liblammps-dev"
CACHE=${TLSPH_CACHE:-${XDG_CACHE_HOME:-${HOME:-/root}/.cache}/tlsph}
mkdir -p "$CACHE"
CACHE=$(cd "$CACHE" && pwd -P)
PREFIX="$CACHE/lammps-$VARIANT-$SRC_VER"
LMP="$PREFIX/bin/lmp"

# kokkos: our package is compiled into this LAMMPS (the CPU styles into src/,
# the /kk styles of src/USER-TLSPH/kokkos into src/KOKKOS/), so the build is
# checked on every call: ninja recompiles what changed (seconds when nothing did)
REPO=$(cd "$HERE/.." && pwd -P)
BUILD_ALWAYS=0
[ "$VARIANT" = kokkos ] && BUILD_ALWAYS=1
if [ ! -x "$LMP" ] || [ "$BUILD_ALWAYS" = 1 ]; then
  mkdir -p "$PREFIX"
  exec 9>"$PREFIX/.lock"          # one build at a time per cache
  flock 9
fi
# sync_tlsph OUT: copy our sources into the LAMMPS tree (a file only when its
# content differs, so that ninja sees real changes only), write the list of
# copies to OUT and remove the copies that the last list (tlsph-files.txt)
# has and OUT has not (files removed from the repository)
sync_tlsph() {
  local out=$1 f b dst
  : > "$out"
  for f in "$REPO"/src/USER-TLSPH/*.h "$REPO"/src/USER-TLSPH/*.cpp \
           "$REPO"/src/USER-TLSPH/kokkos/*.h "$REPO"/src/USER-TLSPH/kokkos/*.cpp; do
    [ -f "$f" ] || continue
    b=$(basename "$f")
    [ "$b" = tlsph_plugin.cpp ] && continue     # the plugin entry point: not compiled in
    case "$f" in */kokkos/*) dst="$SRC_TREE/src/KOKKOS/$b" ;; *) dst="$SRC_TREE/src/$b" ;; esac
    cmp -s "$f" "$dst" || cp "$f" "$dst"
    printf '%s\n' "$dst" >> "$out"
  done
  if [ -f "$PREFIX/tlsph-files.txt" ]; then
    while read -r dst; do
      grep -qxF "$dst" "$out" || rm -f "$dst"
    done < "$PREFIX/tlsph-files.txt"
  fi
}
if [ "$BUILD_ALWAYS" = 1 ] && [ -x "$LMP" ] && [ -f "$PREFIX/build/build.ninja" ]; then
  SRC_TREE="$PREFIX/source"
  BUILD="$PREFIX/build"
  sync_tlsph "$PREFIX/tlsph-files.new"
  if ! cmp -s "$PREFIX/tlsph-files.new" "$PREFIX/tlsph-files.txt"; then
    log "the package's file list changed: re-running cmake in $BUILD"
    cmake "$BUILD" >&2
  fi
  mv "$PREFIX/tlsph-files.new" "$PREFIX/tlsph-files.txt"
  ninja -C "$BUILD" -j"$JOBS" lmp_$VARIANT >&2
  if ! cmp -s "$BUILD/lmp_$VARIANT" "$LMP" || ! cmp -s "$BUILD/liblammps_$VARIANT.so.0" "$PREFIX/lib/liblammps_$VARIANT.so.0"; then
    cp -a "$BUILD"/liblammps_$VARIANT.so* "$PREFIX/lib/"
    cp "$BUILD/lmp_$VARIANT" "$PREFIX/bin/lmp.tmp" && mv "$PREFIX/bin/lmp.tmp" "$LMP"
  fi
  printf '%s\n' "$LMP"
  exit 0
fi
if [ ! -x "$LMP" ]; then
  # the tree must be the installed version: same date check as CMakeLists.txt
  # (version.h against the installed LAMMPSConfigVersion.cmake), and for a
  # Debian tree the exact source version from its changelog
  v=$(sed -n 's/.*LAMMPS_VERSION *"\([0-9]*\) \([A-Za-z]*\) \([0-9]*\)".*/\1 \2 \3/p' "$LAMMPS_SOURCE_DIR/src/version.h")
  vdate=$(LC_ALL=C date -d "$v" +%Y%m%d)
  cfg=$(dpkg-query -L liblammps-dev | grep -m1 '/LAMMPSConfigVersion.cmake$')
  idate=$(sed -n 's/^ *set(PACKAGE_VERSION "\([0-9]*\)").*/\1/p' "$cfg")
  [ "$vdate" = "$idate" ] ||
    die "LAMMPS source in $LAMMPS_SOURCE_DIR is version $vdate, the installed liblammps is $idate"
  if [ -f "$LAMMPS_SOURCE_DIR/debian/changelog" ]; then
    tver=$(dpkg-parsechangelog -l "$LAMMPS_SOURCE_DIR/debian/changelog" -S Version)
    [ "$tver" = "$SRC_VER" ] ||
      die "LAMMPS source in $LAMMPS_SOURCE_DIR is Debian $tver, the installed liblammps is from $SRC_VER"
  fi

  BUILD="$PREFIX/build"
  SRC_TREE=$LAMMPS_SOURCE_DIR
  if [ "$VARIANT" = bench ] || [ "$VARIANT" = kokkos ]; then
    # hard-linked copy of the tree; the one patched file becomes a real copy
    SRC_TREE="$PREFIX/source"
    rm -rf "$SRC_TREE"
    cp -al "$LAMMPS_SOURCE_DIR" "$SRC_TREE"
  fi
  # patch_file REL WHY: the copy's file REL becomes a real file (the shared
  # tree keeps its own), changed by the Python program on stdin (path: argv[1])
  patch_file() {
    f="$SRC_TREE/$1"
    cp --remove-destination "$LAMMPS_SOURCE_DIR/$1" "$f"
    /usr/bin/python3 - "$f" || die "cannot patch $f ($2)"
  }
  if [ "$VARIANT" = bench ]; then
    patch_file src/MACHDYN/pair_smd_tlsph.cpp "another MACHDYN version?" <<'BENCH_PATCH'
import re, sys
p = sys.argv[1]
s = open(p).read()
# 'if (periodic) domain->minimum_image(dx0...);' followed, after a comment, by
# 'dx0 = x0j - x0i;': swap them, so that the image is taken of the assigned vector
pat = re.compile(r"(\n[ \t]*if \(periodic\)\n[ \t]*domain->minimum_image\(dx0\(0\), dx0\(1\), dx0\(2\)\);\n)"
                 r"(\n[ \t]*//[^\n]*\n)([ \t]*dx0 = x0j - x0i;\n)")
s, n = pat.subn(lambda m: "\n" + m.group(3) + m.group(1) + m.group(2), s)
if n != 1:
    sys.exit("expected exactly one misplaced minimum_image call, found %d" % n)
open(p, "w").write(s)
BENCH_PATCH
    log "patched $f: minimum_image(dx0) after dx0 = x0j - x0i (the only change)"
  fi
  if [ "$VARIANT" = kokkos ]; then
    patch_file cmake/Modules/Packages/KOKKOS.cmake "another LAMMPS version?" <<'KOKKOS_PATCH'
import sys
p = sys.argv[1]
s = open(p).read()
# Debian's KokkosConfig.cmake (libtrilinos-kokkos-dev) sets the include
# directory of Kokkos::kokkos to a path that does not exist (/usr/lib/include):
# keep the existing ones, add Kokkos_INCLUDE_DIRS (/usr/include/trilinos)
old = "  find_package(Kokkos 3.4.01 REQUIRED CONFIG)\n"
new = old + '''  # tlsph (scripts/build-lammps-plugin.sh kokkos): Debian's Kokkos::kokkos
  # names a missing include directory; use the existing ones + Kokkos_INCLUDE_DIRS
  get_target_property(_tlsph_kk_inc Kokkos::kokkos INTERFACE_INCLUDE_DIRECTORIES)
  set(_tlsph_kk_dirs)
  foreach(_d IN LISTS _tlsph_kk_inc Kokkos_INCLUDE_DIRS)
    if(EXISTS "${_d}")
      list(APPEND _tlsph_kk_dirs "${_d}")
    endif()
  endforeach()
  list(REMOVE_DUPLICATES _tlsph_kk_dirs)
  message(STATUS "KOKKOS: include directories of Kokkos::kokkos: ${_tlsph_kk_dirs} (was: ${_tlsph_kk_inc})")
  set_target_properties(Kokkos::kokkos PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_tlsph_kk_dirs}")
'''
if s.count(old) != 1:
    sys.exit("expected exactly one 'find_package(Kokkos 3.4.01 REQUIRED CONFIG)', found %d" % s.count(old))
open(p, "w").write(s.replace(old, new))
KOKKOS_PATCH
    log "patched $f: existing include directories of Kokkos::kokkos plus Kokkos_INCLUDE_DIRS (the only change)"
  fi
  if [ "$VARIANT" = kokkos ]; then
    rm -f "$PREFIX/tlsph-files.txt"
    sync_tlsph "$PREFIX/tlsph-files.new"
    mv "$PREFIX/tlsph-files.new" "$PREFIX/tlsph-files.txt"
    log "our package compiled in: $(wc -l < "$PREFIX/tlsph-files.txt") files of src/USER-TLSPH (and kokkos/) copied into $SRC_TREE/src"
  fi
  log "building LAMMPS $SRC_VER ($VARIANT: PLUGIN+PERI ${EXTRA_PKGS[*]}) in $BUILD (ninja -j$JOBS; takes a while the first time)"
  start=$(date +%s)
  # Everything optional off: no package but PLUGIN and PERI, no OpenMP, no
  # image/movie/compression helpers, no downloads, no tests, no docs.
  # EXTRA_PKGS come last: a variant's settings override these defaults.
  cmake -S "$SRC_TREE/cmake" -B "$BUILD" -G Ninja \
    -D CMAKE_BUILD_TYPE=Release \
    -D CMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" \
    -D BUILD_MPI=on -D BUILD_OMP=off -D BUILD_SHARED_LIBS=on \
    -D LAMMPS_MACHINE=$VARIANT -D LAMMPS_SIZES=smallbig -D LAMMPS_EXCEPTIONS=off \
    -D PKG_PLUGIN=on -D PKG_PERI=on \
    -D PKG_KSPACE=off -D PKG_MANYBODY=off -D PKG_MOLECULE=off -D PKG_RIGID=off \
    -D PKG_PYTHON=off -D PKG_OPENMP=off -D PKG_KOKKOS=off -D PKG_GPU=off \
    -D WITH_JPEG=off -D WITH_PNG=off -D WITH_GZIP=off -D WITH_FFMPEG=off \
    -D BUILD_TOOLS=off -D BUILD_LAMMPS_SHELL=off -D BUILD_DOC=off \
    -D ENABLE_TESTING=off -D WITH_SWIG=off \
    -D CMAKE_INSTALL_RPATH='$ORIGIN/../lib' -D CMAKE_BUILD_WITH_INSTALL_RPATH=on \
    -D CMAKE_SKIP_INSTALL_RPATH=off -D Python_EXECUTABLE=/usr/bin/python3 \
    "${EXTRA_PKGS[@]}" >&2
  ninja -C "$BUILD" -j"$JOBS" lmp_$VARIANT >&2

  # symbols a dlopen()ed plugin needs are exported by the shared library
  so="$BUILD/liblammps_$VARIANT.so.0"
  syms=$(nm -D --defined-only "$so")
  grep -q ' T _ZN9LAMMPS_NS4PairC2EPNS_6LAMMPSE$' <<<"$syms" ||
    die "$so does not export LAMMPS_NS::Pair::Pair(LAMMPS*)"
  grep -q ' T _ZN9LAMMPS_NS15plugin_registerEP14lammpsplugin_tPv$' <<<"$syms" ||
    die "$so has no LAMMPS_NS::plugin_register: PLUGIN package not built"

  mkdir -p "$PREFIX/bin" "$PREFIX/lib"
  cp -a "$BUILD"/liblammps_$VARIANT.so* "$PREFIX/lib/"
  cp "$BUILD/lmp_$VARIANT" "$PREFIX/bin/lmp.tmp"
  # it must load our library, and 'plugin' must be a working command
  # (LMP_PLUGIN defined), not the "Ignoring plugin command" stub
  deps=$(ldd "$PREFIX/bin/lmp.tmp")
  grep -q "liblammps_$VARIANT.so.0 => /" <<<"$deps" && ! grep -q 'liblammps.so' <<<"$deps" ||
    { printf '%s\n' "$deps" >&2; die "$PREFIX/bin/lmp.tmp does not load lib/liblammps_$VARIANT.so.0"; }
  out=$(cd "$PREFIX" && echo "plugin list" | "$PREFIX/bin/lmp.tmp" -log none -echo none 2>&1) || true
  grep -q "Currently loaded plugins" <<<"$out" || { printf '%s\n' "$out" >&2;
    die "'plugin list' does not work in $PREFIX/bin/lmp.tmp"; }
  mv "$PREFIX/bin/lmp.tmp" "$LMP"      # last: its presence marks a complete build
  log "built in $(( $(date +%s) - start )) s: $LMP"
fi
printf '%s\n' "$LMP"
