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
# Nothing is done when bin/lmp exists (kokkos, kokkos-cuda: rebuilt
# incrementally on every call, below). The last line on stdout is the path of
# bin/lmp. Uses `ninja -j${TLSPH_JOBS:-2}`.
#
# `build-lammps-plugin.sh bench` builds the side-by-side benchmark's LAMMPS
# instead (bench/compare.sh): the same, plus the MACHDYN package (smd/tlsph,
# with Debian's Eigen), in lammps-bench-<source version>-O3--DNDEBUG/
# (library liblammps_bench.so.0), compiled with the plugin's own flags (see
# RELEASE_FLAGS below). MACHDYN's pair_smd_tlsph.cpp of this version calls
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
# `build-lammps-plugin.sh kokkos-stock` builds the same KOKKOS LAMMPS as
# kokkos (Debian's Kokkos, KOKKOS_PATCH, PLUGIN and PERI) but without our
# package: a stock KOKKOS LAMMPS, in lammps-kokkos-stock-<source version>/
# (library liblammps_kokkos_stock.so.0), into which the /kk styles are loaded
# as a plugin (tlsphkkplugin.so, scripts/build-kk-plugin.sh; doc/kokkos.md,
# "Loading the /kk styles as a plugin"). Nothing is done when bin/lmp exists.
#
# `build-lammps-plugin.sh kokkos-cuda` builds a LAMMPS with KOKKOS for NVIDIA
# GPUs (Kokkos CUDA backend, Serial on the host), plus PLUGIN and PERI and our
# package compiled in (as for kokkos), in lammps-kokkos-cuda-<source version>/
# (LAMMPS_MACHINE=kokkos_cuda: library liblammps_kokkos_cuda.so.0, beside it
# Kokkos's libkokkoscore.so.3.4 and libkokkoscontainers.so.3.4);
# doc/kokkos-cuda.md. It only compiles here: running needs an NVIDIA GPU and
# driver. Needs a CUDA toolkit in ${TLSPH_CUDA_HOME:-/usr/local/cuda} (nvcc
# need not be on PATH; written for CUDA 13). Debian's Kokkos has no CUDA, so
# the Kokkos 3.4.01 source comes from Debian's `trilinos` source package
# (${TLSPH_TRILINOS_VERSION:-13.2.0-4}, packages/kokkos; downloaded once with
# `apt-get source --download-only` through the private deb-src list of
# setup.sh into ${TLSPH_CACHE}/trilinos-<version>/, 166 MB) and is built by
# LAMMPS as its bundled lib/kokkos (no EXTERNAL_KOKKOS), with nvcc_wrapper as
# the C++ compiler. KOKKOS_CUDA_PATCH below adapts Kokkos 3.4.01 to CUDA 13
# and adds a Hopper arch (HOPPER90) whose code is, through the list
# TLSPH_CUDA_GENCODE, native sm_90 (+ compute_90 PTX) plus sm_80 in one fat
# binary (Kokkos 3.4's CMake takes one GPU arch); FATBIN_CHECK checks that
# the library holds that code. The prepared source/ is kept and lib/kokkos
# updated file by file, so that a failed build resumes where it stopped
# (nvcc_wrapper compiles every LAMMPS file: about 45 min on 2 shared cores).
# The nvcc version is recorded (nvcc-version.txt): another nvcc is refused.
#
# `build-lammps-plugin.sh kokkos-omp` builds the same bundled Kokkos (from the
# same trilinos source, unpatched) for the host with the OpenMP and Serial
# backends (BUILD_OMP), g++ as the compiler, our package compiled in, in
# lammps-kokkos-omp-<source version>/ (liblammps_kokkos_omp.so.0): the
# threads-against-ranks benchmark of bench/kokkos.sh (doc/kokkos.md).
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
  kokkos|kokkos-stock)
          EXTRA_PKGS=(-D PKG_KOKKOS=on -D EXTERNAL_KOKKOS=on -D Kokkos_ENABLE_SERIAL=on
                      -D Kokkos_ENABLE_OPENMP=off -D Kokkos_ENABLE_CUDA=off) ;;
  # kokkos-cuda: bundled Kokkos (lib/kokkos, from trilinos), CUDA + Serial;
  # HOPPER90 and TLSPH_CUDA_GENCODE exist through KOKKOS_CUDA_PATCH below
  # (CMAKE_CXX_COMPILER, nvcc_wrapper, is added once the tree is known)
  kokkos-cuda)
          EXTRA_PKGS=(-D PKG_KOKKOS=on -D EXTERNAL_KOKKOS=off -D DOWNLOAD_KOKKOS=off
                      -D Kokkos_ENABLE_SERIAL=on -D Kokkos_ENABLE_OPENMP=off
                      -D Kokkos_ENABLE_CUDA=on -D Kokkos_ENABLE_CUDA_UVM=off
                      -D Kokkos_ARCH_HOPPER90=on
                      -D "TLSPH_CUDA_GENCODE=arch=compute_90,code=sm_90;arch=compute_90,code=compute_90;arch=compute_80,code=sm_80") ;;
  # kokkos-omp: the same bundled Kokkos for the host, OpenMP + Serial (no patch
  # needed): the threads-against-ranks benchmark (bench/kokkos.sh)
  kokkos-omp)
          EXTRA_PKGS=(-D PKG_KOKKOS=on -D EXTERNAL_KOKKOS=off -D DOWNLOAD_KOKKOS=off
                      -D Kokkos_ENABLE_SERIAL=on -D Kokkos_ENABLE_OPENMP=on
                      -D Kokkos_ENABLE_CUDA=off -D BUILD_OMP=on) ;;
  # bundle-cuda, bundle-host: the GPU bundle (scripts/gpu-bundle.sh,
  # doc/kokkos-cuda.md) and its host twin: one static lmp, MPI STUBS, no
  # PLUGIN, KOKKOS with only the styles a TLSPH run uses (TRIM_KOKKOS below),
  # PERI, our package compiled in; sm_90 SASS + compute_90 PTX, or Kokkos
  # Serial on the host (the same configuration, for CI)
  bundle-cuda)
          EXTRA_PKGS=(-D PKG_KOKKOS=on -D EXTERNAL_KOKKOS=off -D DOWNLOAD_KOKKOS=off
                      -D Kokkos_ENABLE_SERIAL=on -D Kokkos_ENABLE_OPENMP=off
                      -D Kokkos_ENABLE_CUDA=on -D Kokkos_ENABLE_CUDA_UVM=off
                      -D Kokkos_ARCH_HOPPER90=on
                      -D "TLSPH_CUDA_GENCODE=arch=compute_90,code=sm_90;arch=compute_90,code=compute_90") ;;
  bundle-host)
          EXTRA_PKGS=(-D PKG_KOKKOS=on -D EXTERNAL_KOKKOS=off -D DOWNLOAD_KOKKOS=off
                      -D Kokkos_ENABLE_SERIAL=on -D Kokkos_ENABLE_OPENMP=off
                      -D Kokkos_ENABLE_CUDA=off) ;;
  *) die "unknown variant '$VARIANT' (allowed: plugin, bench, kokkos, kokkos-stock, kokkos-cuda, kokkos-omp, bundle-cuda, bundle-host)" ;;
esac
# LAMMPS_MACHINE: the variant's name, with '_' for '-' (lmp_kokkos_cuda,
# liblammps_kokkos_cuda.so.0); the same as the variant for the others
MACHINE=${VARIANT//-/_}
# CUDA: the variants built with nvcc; BUNDLE: the static, MPI-free bundle builds
CUDA=0; BUNDLE=0
case "$VARIANT" in kokkos-cuda|bundle-cuda) CUDA=1 ;; esac
case "$VARIANT" in bundle-*) BUNDLE=1
  EXTRA_PKGS+=(-D BUILD_MPI=off -D BUILD_SHARED_LIBS=off -D PKG_PLUGIN=off
               -D "CMAKE_EXE_LINKER_FLAGS=-static-libstdc++ -static-libgcc") ;;
esac

# kokkos-cuda: the CUDA toolkit (nvcc need not be on PATH)
if [ "$CUDA" = 1 ]; then
  CUDA_HOME=${TLSPH_CUDA_HOME:-/usr/local/cuda}
  [ -x "$CUDA_HOME/bin/nvcc" ] ||
    die "kokkos-cuda needs a CUDA toolkit: no $CUDA_HOME/bin/nvcc (set TLSPH_CUDA_HOME)"
  CUDA_HOME=$(cd "$CUDA_HOME" && pwd -P)
  NVCC_VERSION=$("$CUDA_HOME/bin/nvcc" --version | sed -n 's/.*release \([0-9.]*\), V\([0-9.]*\).*/\2/p')
  [ -n "$NVCC_VERSION" ] || die "cannot read the version of $CUDA_HOME/bin/nvcc"
fi

# kokkos, kokkos-stock: Debian's Kokkos, built and at run time (libtrilinos_kokkoscore.so.13.2)
if [ "$VARIANT" = kokkos ] || [ "$VARIANT" = kokkos-stock ]; then
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
# Optimisation flags of the LAMMPS build (CMAKE_CXX_FLAGS_RELEASE). bench
# takes the plugin's own (the set(CMAKE_CXX_FLAGS_RELEASE ...) line of this
# project's CMakeLists.txt), so that both sides of bench/compare.sh are
# compiled alike, and its cache folder is keyed by them
# (lammps-bench-<version>-O3--DNDEBUG: each space a dash); the others keep
# -O2 -DNDEBUG. Every
# call reads the flags back from the build's CMakeCache.txt and refuses a
# build made with other flags, so an old build is never silently reused.
PLUGIN_FLAGS=$(sed -n 's/^set(CMAKE_CXX_FLAGS_RELEASE "\(.*\)")$/\1/p' "$HERE/../CMakeLists.txt")
[ -n "$PLUGIN_FLAGS" ] || die "cannot read CMAKE_CXX_FLAGS_RELEASE from $HERE/../CMakeLists.txt"
case "$VARIANT" in
  bench) RELEASE_FLAGS=$PLUGIN_FLAGS ;;
  bundle-*) RELEASE_FLAGS=$PLUGIN_FLAGS ;;    # the speed runs of gpu-check.sh
  *)     RELEASE_FLAGS="-O2 -DNDEBUG" ;;
esac
PREFIX="$CACHE/lammps-$VARIANT-$SRC_VER"
[ "$VARIANT" = bench ] && PREFIX="$PREFIX$(printf '%s' "$RELEASE_FLAGS" | tr -s ' ' | tr ' ' '-' | tr -cd 'A-Za-z0-9=_.-' | sed 's/^-*/-/')"
LMP="$PREFIX/bin/lmp"
# flags_of BUILD: CMAKE_CXX_FLAGS_RELEASE as the build's CMakeCache.txt holds it
flags_of() { sed -n 's/^CMAKE_CXX_FLAGS_RELEASE:[A-Z]*=//p' "$1/CMakeCache.txt" 2>/dev/null; }
if [ -x "$LMP" ] && [ -f "$PREFIX/build/CMakeCache.txt" ] &&
   [ "$(flags_of "$PREFIX/build")" != "$RELEASE_FLAGS" ]; then
  die "$PREFIX was built with CMAKE_CXX_FLAGS_RELEASE='$(flags_of "$PREFIX/build")', this variant wants '$RELEASE_FLAGS': remove $PREFIX to rebuild"
fi

# kokkos-cuda: a build (or a partial one) is never continued with another nvcc
if [ "$CUDA" = 1 ] && [ -f "$PREFIX/nvcc-version.txt" ] &&
   [ "$(cat "$PREFIX/nvcc-version.txt")" != "$NVCC_VERSION" ]; then
  die "$PREFIX was built with nvcc $(cat "$PREFIX/nvcc-version.txt"), $CUDA_HOME/bin/nvcc is $NVCC_VERSION: remove $PREFIX to rebuild"
fi

# kokkos-cuda: the Kokkos source, from Debian's trilinos source package,
# downloaded once (apt-get source --download-only, whose files apt checks
# against the signed index) into $CACHE/trilinos-<version>/, through the
# private deb-src list of setup.sh ($CACHE/apt; `setup.sh --check-source`
# writes and updates it when it has no such trilinos)
if [ "$VARIANT" = kokkos-cuda ] || [ "$VARIANT" = kokkos-omp ] || [ "$BUNDLE" = 1 ]; then
  TRILINOS_VER=${TLSPH_TRILINOS_VERSION:-13.2.0-4}
  TRILINOS_DIR="$CACHE/trilinos-$TRILINOS_VER"
  trilinos_orig() { ls "$TRILINOS_DIR"/trilinos_*.orig.tar.* 2>/dev/null | head -n1 || true; }
  if [ -z "$(trilinos_orig)" ]; then
    exec 8>"$CACHE/.trilinos-source.lock"      # one download at a time
    flock 8
  fi
  if [ -z "$(trilinos_orig)" ]; then
    log "downloading the Debian source of trilinos $TRILINOS_VER (166 MB, once) into $TRILINOS_DIR"
    tmp=$(mktemp -d "$CACHE/.trilinos-$TRILINOS_VER.XXXXXX")
    # through setup.sh's private deb-src list, as for the LAMMPS source
    bash "$HERE/setup.sh" --download-source trilinos "$TRILINOS_VER" "$tmp" >&2 ||
      { rm -rf "$tmp"; die "no Debian source of trilinos $TRILINOS_VER (setup.sh --download-source)"; }
    rm -rf "$TRILINOS_DIR"
    mv "$tmp" "$TRILINOS_DIR"
    [ -n "$(trilinos_orig)" ] || die "no trilinos_*.orig.tar.* in $TRILINOS_DIR"
  fi
fi

# kokkos: our package is compiled into this LAMMPS (the CPU styles into src/,
# the /kk styles of src/USER-TLSPH/kokkos into src/KOKKOS/), so the build is
# checked on every call: ninja recompiles what changed (seconds when nothing did)
REPO=$(cd "$HERE/.." && pwd -P)
BUILD_ALWAYS=0
case "$VARIANT" in kokkos|kokkos-cuda|kokkos-omp|bundle-*) BUILD_ALWAYS=1 ;; esac
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
    # the plugin entry points (tlsphplugin.so, tlsphkkplugin.so): not compiled in
    case "$b" in tlsph_plugin.cpp|tlsph_kk_plugin.cpp) continue ;; esac
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
  ninja -C "$BUILD" -j"$JOBS" lmp_$MACHINE >&2
  if [ "$BUNDLE" = 1 ]; then
    # static: the executable alone, stripped
    strip -o "$PREFIX/bin/lmp.tmp" "$BUILD/lmp_$MACHINE"
    cmp -s "$PREFIX/bin/lmp.tmp" "$LMP" && rm -f "$PREFIX/bin/lmp.tmp" || mv "$PREFIX/bin/lmp.tmp" "$LMP"
  elif ! cmp -s "$BUILD/lmp_$MACHINE" "$LMP" || ! cmp -s "$BUILD/liblammps_$MACHINE.so.0" "$PREFIX/lib/liblammps_$MACHINE.so.0"; then
    cp -a "$BUILD"/liblammps_$MACHINE.so* "$PREFIX/lib/"
    case "$VARIANT" in kokkos-cuda|kokkos-omp) cp -a "$BUILD"/lib/kokkos/*/src/libkokkos*.so* "$PREFIX/lib/" ;; esac
    cp "$BUILD/lmp_$MACHINE" "$PREFIX/bin/lmp.tmp" && mv "$PREFIX/bin/lmp.tmp" "$LMP"
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
  if [ "$VARIANT" = bench ] || [ "$VARIANT" = kokkos ] || [ "$VARIANT" = kokkos-stock ]; then
    # hard-linked copy of the tree; the one patched file becomes a real copy
    SRC_TREE="$PREFIX/source"
    rm -rf "$SRC_TREE"
    cp -al "$LAMMPS_SOURCE_DIR" "$SRC_TREE"
  elif [ "$VARIANT" = kokkos-cuda ] || [ "$VARIANT" = kokkos-omp ] || [ "$BUNDLE" = 1 ]; then
    # hard-linked copy of the tree, kept once complete: after a failed or
    # interrupted build, ninja goes on from where it stopped (the hard links
    # keep their times; lib/kokkos and our files are updated by content below)
    SRC_TREE="$PREFIX/source"
    if [ ! -f "$PREFIX/source.complete" ]; then
      rm -rf "$SRC_TREE"
      cp -al "$LAMMPS_SOURCE_DIR" "$SRC_TREE"
      if [ "$BUNDLE" = 1 ]; then
        # TRIM_KOKKOS: only the KOKKOS styles a TLSPH run uses. Every style
        # file (a header with a PairStyle(, FixStyle(, ... line, and its .cpp) of src/KOKKOS is
        # removed from the copy unless kept below or included by a kept file
        # (the include closure over src/KOKKOS); LAMMPS's CMake registers what
        # is left. A style missing here falls back to its CPU version at run
        # time (-sf kk), as without KOKKOS.
        /usr/bin/python3 - "$SRC_TREE/src/KOKKOS" <<'TRIM_KOKKOS' >&2 || die "cannot trim $SRC_TREE/src/KOKKOS"
import os, re, sys
d = sys.argv[1]
keep_styles = {"fix_nve", "fix_nh", "fix_nvt", "fix_npt", "fix_nph", "fix_setforce",
               "fix_enforce2d", "fix_momentum", "fix_freeze", "fix_gravity",
               "fix_wall_reflect", "fix_property_atom", "fix_deform", "fix_minimize",
               "verlet", "min_cg", "atom_vec_atomic", "atom_vec_hybrid", "region_block",
               "compute_temp", "compute_ke_atom"}
files = sorted(os.listdir(d))
# (neighbor styles, NBinStyle/NPairStyle/NStencilStyle, are the core: kept)
style = re.compile(r"^\s*(Pair|Compute|Fix|Bond|Angle|Dihedral|Improper|Region|Atom|Integrate|Minimize|Command|KSpace)Style\(", re.M)
def base(f):
    return re.sub(r"_kokkos(_impl)?\.(h|cpp)$", "", f)
styles = set()
for f in files:
    if f.endswith("_kokkos.h") and style.search(open(os.path.join(d, f), errors="replace").read()):
        styles.add(base(f))
drop = {s for s in styles if s not in keep_styles}
kept = [f for f in files if base(f) not in drop]
inc = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
changed = True
while changed:
    changed = False
    for f in kept:
        for h in inc.findall(open(os.path.join(d, f), errors="replace").read()):
            b = base(h)
            if b in drop and os.path.exists(os.path.join(d, h)):
                drop.discard(b)
                kept = [g for g in files if base(g) not in drop]
                changed = True
n = 0
for f in files:
    if base(f) in drop:
        os.remove(os.path.join(d, f))
        n += 1
print("build-lammps-plugin.sh: TRIM_KOKKOS: %d of %d KOKKOS styles removed (%d files); kept: %s"
      % (len(drop), len(styles), n, " ".join(sorted(styles - drop))))
TRIM_KOKKOS
      fi
      : > "$PREFIX/source.complete"
    fi
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
  if [ "$VARIANT" = kokkos ] || [ "$VARIANT" = kokkos-stock ]; then
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
  if [ "$VARIANT" = kokkos-cuda ] || [ "$VARIANT" = kokkos-omp ] || [ "$BUNDLE" = 1 ]; then
    # Kokkos 3.4.01 from the trilinos source: extracted afresh (5-10 s) into
    # kokkos.new, patched there (KOKKOS_CUDA_PATCH), then copied into
    # source/lib/kokkos (which the +ds LAMMPS tree lacks) file by file, only
    # where the content differs, so that ninja sees real changes only
    orig=$(trilinos_orig)
    rm -rf "$PREFIX/kokkos.x" "$PREFIX/kokkos.new"
    mkdir -p "$PREFIX/kokkos.x"
    log "extracting packages/kokkos of $(basename "$orig")"
    tar -xf "$orig" -C "$PREFIX/kokkos.x" --wildcards '*/packages/kokkos/*' ||
      die "cannot extract packages/kokkos from $orig"
    mv "$PREFIX"/kokkos.x/*/packages/kokkos "$PREFIX/kokkos.new"
    rm -rf "$PREFIX/kokkos.x"
    kkv=$(sed -n 's/^set(Kokkos_VERSION_\(MAJOR\|MINOR\|PATCH\) \([0-9]*\))$/\2/p' "$PREFIX/kokkos.new/CMakeLists.txt" | paste -sd.)
    [ "$kkv" = 3.4.01 ] || die "trilinos $TRILINOS_VER has Kokkos '$kkv', KOKKOS_CUDA_PATCH is for 3.4.01"
    # (kokkos-omp: Kokkos unpatched; the CUDA patch runs for kokkos-cuda only)
    [ "$CUDA" != 1 ] || /usr/bin/python3 - "$PREFIX/kokkos.new" "$CUDA_HOME/bin/nvcc" <<'KOKKOS_CUDA_PATCH' ||
import os, re, sys
kk, nvcc = sys.argv[1], sys.argv[2]

def edit(rel, why, *pairs):
    """replace each (old, new) in KK/rel, old exactly once; why: the reason"""
    p = os.path.join(kk, rel)
    s = open(p).read()
    for old, new in pairs:
        n = s.count(old)
        if n != 1:
            sys.exit("%s: expected exactly one %r, found %d (%s)" % (rel, old, n, why))
        s = s.replace(old, new)
    open(p, "w").write(s)
    print("patched lib/kokkos/%s: %s" % (rel, why), file=sys.stderr)

# 1. nvcc_wrapper. (a) The default arch, used when no -arch is given (CMake's
# compiler probes): sm_35, which CUDA 13 rejects (its oldest is sm_75); sm_80
# is the oldest arch of this build. (b) nvcc is not on PATH: its absolute path
# (CUDA_ROOT still overrides). (c) Several distinct -gencode= flags are kept
# (one per target arch, TLSPH_CUDA_GENCODE below); the wrapper stops at a
# second arch flag otherwise ("ARCH is being set twice").
edit("bin/nvcc_wrapper", "CUDA 13 default arch, nvcc path, several -gencode",
     ('default_arch="sm_35"\n',
      '# tlsph: sm_35 is rejected by CUDA 13 (oldest: sm_75); used only when no\n'
      '# -arch/-gencode is given (CMake\'s compiler probes)\n'
      'default_arch="sm_80"\n'),
     ('nvcc_compiler=nvcc\n',
      '# tlsph: the toolkit of this build (nvcc need not be on PATH)\n'
      'nvcc_compiler="%s"\n' % nvcc),
     ('''    elif [  "$arch_flag" != "$1" ]; then
        echo "ARCH is being set twice with different flags, which is not handled"
''', '''    elif [[ "$arch_flag" == -gencode=* && "$1" == -gencode=* ]]; then
        # tlsph: several -gencode= flags, one per target (duplicates dropped)
        case " $arch_flag " in
          *" $1 "*) ;;
          *) arch_flag="$arch_flag $1"; cuda_args="$cuda_args $1" ;;
        esac
    elif [  "$arch_flag" != "$1" ]; then
        echo "ARCH is being set twice with different flags, which is not handled"
'''))

# 2. CMake: a Hopper arch (Kokkos 3.4.01 knows NVIDIA archs up to AMPERE86),
# and TLSPH_CUDA_GENCODE: when set (a list of nvcc "arch=...,code=..." pairs),
# the arch option adds one -gencode= per entry instead of -arch=sm_XX, to the
# compile and the link flags (Kokkos 3.4's CMake takes one GPU arch; nvcc
# builds one fat binary from several -gencode)
edit("cmake/kokkos_arch.cmake", "HOPPER90 (sm_90), TLSPH_CUDA_GENCODE",
     ('KOKKOS_ARCH_OPTION(AMPERE86        GPU  "NVIDIA Ampere generation CC 8.6")\n',
      'KOKKOS_ARCH_OPTION(AMPERE86        GPU  "NVIDIA Ampere generation CC 8.6")\n'
      '# tlsph: Hopper (H100/H200), not in Kokkos 3.4.01\n'
      'KOKKOS_ARCH_OPTION(HOPPER90        GPU  "NVIDIA Hopper generation CC 9.0")\n'),
     ('''      GLOBAL_APPEND(KOKKOS_CUDA_OPTIONS "${CUDA_ARCH_FLAG}=${FLAG}")
      IF(KOKKOS_ENABLE_CUDA_RELOCATABLE_DEVICE_CODE OR KOKKOS_CXX_COMPILER_ID STREQUAL NVIDIA)
        GLOBAL_APPEND(KOKKOS_LINK_OPTIONS "${CUDA_ARCH_FLAG}=${FLAG}")
      ENDIF()
''', '''      # tlsph: TLSPH_CUDA_GENCODE (nvcc only): one -gencode= per entry instead
      SET(_TLSPH_ARCH_FLAGS "${CUDA_ARCH_FLAG}=${FLAG}")
      IF(TLSPH_CUDA_GENCODE AND KOKKOS_CXX_COMPILER_ID STREQUAL NVIDIA)
        SET(_TLSPH_ARCH_FLAGS)
        FOREACH(_TLSPH_GC IN LISTS TLSPH_CUDA_GENCODE)
          LIST(APPEND _TLSPH_ARCH_FLAGS "-gencode=${_TLSPH_GC}")
        ENDFOREACH()
        MESSAGE(STATUS "Kokkos arch ${ARCH}: nvcc flags ${_TLSPH_ARCH_FLAGS} (TLSPH_CUDA_GENCODE)")
      ENDIF()
      GLOBAL_APPEND(KOKKOS_CUDA_OPTIONS ${_TLSPH_ARCH_FLAGS})
      IF(KOKKOS_ENABLE_CUDA_RELOCATABLE_DEVICE_CODE OR KOKKOS_CXX_COMPILER_ID STREQUAL NVIDIA)
        GLOBAL_APPEND(KOKKOS_LINK_OPTIONS ${_TLSPH_ARCH_FLAGS})
      ENDIF()
'''),
     ('CHECK_CUDA_ARCH(AMPERE86  sm_86)\n',
      'CHECK_CUDA_ARCH(AMPERE86  sm_86)\n'
      'CHECK_CUDA_ARCH(HOPPER90  sm_90)  # tlsph\n'))

# 3. half_t casts of the CUDA >= 11.1 branch: half_t converts to __half only
# explicitly (explicit operator impl_type), and CUDA 13's __half2* functions
# take __half (no implicit conversion path any more): give them
# half_t::impl_type(val), as the CUDA < 11.1 branch does. CUDA 13 has no
# __half2double: the float value, widened (exact: every half is a float).
p = "core/src/Cuda/Kokkos_Cuda_Half.hpp"
s = open(os.path.join(kk, p)).read()
mark = "#else  // CUDA 11.1 versions follow\n"
if s.count(mark) != 1:
    sys.exit("%s: expected one %r" % (p, mark))
head, tail = s.split(mark)
tail, n1 = re.subn(r"__half2double\(val\)",
                   "static_cast<double>(__half2float(half_t::impl_type(val)))", tail)
tail, n2 = re.subn(r"(__half2(?:float|short_rz|ushort_rz|int_rz|uint_rz|ll_rz|ull_rz))\(val\)",
                   r"\1(half_t::impl_type(val))", tail)
if (n1, n2) != (1, 7):
    sys.exit("%s: expected 1 __half2double(val) and 7 __half2*(val), found %d, %d" % (p, n1, n2))
open(os.path.join(kk, p), "w").write(
    head + "#else  // CUDA 11.1 versions follow\n"
    "// tlsph: explicit half_t::impl_type(val) for CUDA 13, no __half2double\n" + tail)
print("patched lib/kokkos/%s: explicit impl_type in the __half2* casts" % p, file=sys.stderr)

# 4. cudaMemPrefetchAsync: CUDA 13 takes (ptr, bytes, cudaMemLocation, flags,
# stream) instead of (ptr, bytes, device, stream)
edit("core/src/Cuda/Kokkos_CudaSpace.cpp", "CUDA 13 cudaMemPrefetchAsync",
     ('''    CUDA_SAFE_CALL(cudaMemPrefetchAsync(ptr, bytes, space.cuda_device(),
                                        space.cuda_stream()));
''', '''#if defined(CUDART_VERSION) && CUDART_VERSION >= 13000
    // tlsph: CUDA 13 signature (ptr, bytes, location, flags, stream)
    cudaMemLocation location = {};
    location.type            = cudaMemLocationTypeDevice;
    location.id              = space.cuda_device();
    CUDA_SAFE_CALL(
        cudaMemPrefetchAsync(ptr, bytes, location, 0, space.cuda_stream()));
#else
    CUDA_SAFE_CALL(cudaMemPrefetchAsync(ptr, bytes, space.cuda_device(),
                                        space.cuda_stream()));
#endif
'''))

# 5. Start-up check: Kokkos aborts unless the arch of the code that runs
# (__CUDA_ARCH__ of a probe kernel) has the device's major version. In a fat
# binary the CUDA runtime picks the best SASS (sm_90 on an H100/H200, sm_80 on
# A100/A30, sm_80 on sm_86/sm_89) or JIT-compiles the compute_90 PTX on newer
# GPUs, all of which run; reject only code for a newer arch than the device.
edit("core/src/Cuda/Kokkos_Cuda_Instance.cpp", "arch check: reject only newer-than-device code",
     ('    if (compiled_major != cudaProp.major || compiled_minor > cudaProp.minor) {\n',
      '    // tlsph: reject only code compiled for a newer arch than the device\n'
      '    // (fat binary: the runtime picks sm_90/sm_80 SASS or JITs compute_90)\n'
      '    if (m_cudaArch > cudaProp.major * 100 + cudaProp.minor * 10) {\n'))
KOKKOS_CUDA_PATCH
      die "cannot patch Kokkos in $PREFIX/kokkos.new (another Kokkos version?)"
    /usr/bin/python3 - "$PREFIX/kokkos.new" "$SRC_TREE/lib/kokkos" <<'SYNC_KOKKOS' >&2
import filecmp, os, shutil, sys
src, dst = sys.argv[1:3]
changed = removed = 0
for root, dirs, files in os.walk(src):
    d = os.path.normpath(os.path.join(dst, os.path.relpath(root, src)))
    os.makedirs(d, exist_ok=True)
    for f in files:
        a, b = os.path.join(root, f), os.path.join(d, f)
        if (os.path.isfile(b) and not os.path.islink(b) and filecmp.cmp(a, b, shallow=False)
                and os.stat(a).st_mode & 0o777 == os.stat(b).st_mode & 0o777):
            continue
        shutil.copy(a, b + ".tlsph-tmp")       # a new file (never a hard link), new mtime
        os.replace(b + ".tlsph-tmp", b)
        changed += 1
for root, dirs, files in os.walk(dst):
    for f in files:
        if not os.path.lexists(os.path.join(src, os.path.relpath(root, dst), f)):
            os.remove(os.path.join(root, f))
            removed += 1
print("build-lammps-plugin.sh: lib/kokkos: %d files new or changed, %d removed" % (changed, removed))
SYNC_KOKKOS
    rm -rf "$PREFIX/kokkos.new"
    if [ "$CUDA" = 1 ]; then
      # nvcc_wrapper as the C++ compiler (it runs nvcc, and g++ for the host
      # code); Kokkos's find_package(CUDAToolkit) (libcudart) in the same
      # toolkit; RUNPATH: also the toolkit's libcudart.so.13, wherever ld.so looks
      EXTRA_PKGS+=(-D CMAKE_CXX_COMPILER="$SRC_TREE/lib/kokkos/bin/nvcc_wrapper"
                   -D CUDAToolkit_ROOT="$CUDA_HOME"
                   -D "CMAKE_INSTALL_RPATH=\$ORIGIN/../lib;$CUDA_HOME/lib64")
      # bundle-cuda: the CUDA runtime linked statically (Kokkos links
      # CUDA::cudart, whose library is CMake's CUDA_cudart_LIBRARY, or
      # CUDA_CUDART with CMake < 3.17: libcudart.so by default)
      [ "$BUNDLE" = 1 ] && EXTRA_PKGS+=(-D "CUDA_cudart_LIBRARY=$CUDA_HOME/lib64/libcudart_static.a"
                                        -D "CUDA_CUDART=$CUDA_HOME/lib64/libcudart_static.a")
      printf '%s\n' "$NVCC_VERSION" > "$PREFIX/nvcc-version.txt"
    fi
    # our files: updated by content, the list of the last sync kept
    sync_tlsph "$PREFIX/tlsph-files.new"
    mv "$PREFIX/tlsph-files.new" "$PREFIX/tlsph-files.txt"
    log "our package compiled in: $(wc -l < "$PREFIX/tlsph-files.txt") files of src/USER-TLSPH (and kokkos/) in $SRC_TREE/src"
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
    -D CMAKE_CXX_FLAGS_RELEASE="$RELEASE_FLAGS" \
    -D BUILD_MPI=on -D BUILD_OMP=off -D BUILD_SHARED_LIBS=on \
    -D LAMMPS_MACHINE=$MACHINE -D LAMMPS_SIZES=smallbig -D LAMMPS_EXCEPTIONS=off \
    -D PKG_PLUGIN=on -D PKG_PERI=on \
    -D PKG_KSPACE=off -D PKG_MANYBODY=off -D PKG_MOLECULE=off -D PKG_RIGID=off \
    -D PKG_PYTHON=off -D PKG_OPENMP=off -D PKG_KOKKOS=off -D PKG_GPU=off \
    -D WITH_JPEG=off -D WITH_PNG=off -D WITH_GZIP=off -D WITH_FFMPEG=off \
    -D BUILD_TOOLS=off -D BUILD_LAMMPS_SHELL=off -D BUILD_DOC=off \
    -D ENABLE_TESTING=off -D WITH_SWIG=off \
    -D CMAKE_INSTALL_RPATH='$ORIGIN/../lib' -D CMAKE_BUILD_WITH_INSTALL_RPATH=on \
    -D CMAKE_SKIP_INSTALL_RPATH=off -D Python_EXECUTABLE=/usr/bin/python3 \
    "${EXTRA_PKGS[@]}" >&2
  ninja -C "$BUILD" -j"$JOBS" lmp_$MACHINE >&2

  if [ "$BUNDLE" = 1 ]; then
    # the bundle: one static executable (libstdc++, libgcc, LAMMPS, Kokkos,
    # and the CUDA runtime for bundle-cuda), stripped; its GPU code checked
    mkdir -p "$PREFIX/bin"
    exe="$BUILD/lmp_$MACHINE"
    if [ "$CUDA" = 1 ]; then
      so=$exe
      /usr/bin/python3 "$HERE/fatbin_check.py" "$exe" sm_90 compute_90 >&2 ||
        die "$exe lacks GPU code of TLSPH_CUDA_GENCODE"
    fi
    deps=$(ldd "$exe" 2>&1 || true)
    if grep -Eq 'libstdc\+\+|libgcc_s|liblammps|libkokkos|libmpi|libcudart' <<<"$deps"; then
      printf '%s\n' "$deps" >&2
      die "$exe links a library that the bundle must hold statically (above)"
    fi
    strip -o "$PREFIX/bin/lmp.tmp" "$exe"
    mv "$PREFIX/bin/lmp.tmp" "$LMP"
    log "built in $(( $(date +%s) - start )) s: $LMP ($(du -k "$LMP" | cut -f1) kB stripped); needs: $(tr -s ' \t' ' ' <<<"$deps" | sed 's/ (0x[0-9a-f]*)//' | paste -sd';')"
    printf '%s\n' "$LMP"
    exit 0
  fi
  # symbols a dlopen()ed plugin needs are exported by the shared library
  so="$BUILD/liblammps_$MACHINE.so.0"
  syms=$(nm -D --defined-only "$so")
  grep -q ' T _ZN9LAMMPS_NS4PairC2EPNS_6LAMMPSE$' <<<"$syms" ||
    die "$so does not export LAMMPS_NS::Pair::Pair(LAMMPS*)"
  grep -q ' T _ZN9LAMMPS_NS15plugin_registerEP14lammpsplugin_tPv$' <<<"$syms" ||
    die "$so has no LAMMPS_NS::plugin_register: PLUGIN package not built"
  # kokkos-cuda: the library's fat binaries hold GPU code for every arch of
  # TLSPH_CUDA_GENCODE (what `cuobjdump --list-elf` shows; CUDA 13 fat
  # binaries, read here from .nv_fatbin, as this toolkit may lack cuobjdump)
  if [ "$VARIANT" = kokkos-cuda ]; then
    /usr/bin/python3 "$HERE/fatbin_check.py" "$so" sm_90 sm_80 compute_90 >&2 ||
      die "$so lacks GPU code of TLSPH_CUDA_GENCODE"
  fi

  mkdir -p "$PREFIX/bin" "$PREFIX/lib"
  cp -a "$BUILD"/liblammps_$MACHINE.so* "$PREFIX/lib/"
  # kokkos-cuda: the bundled Kokkos is built as shared libraries too
  case "$VARIANT" in kokkos-cuda|kokkos-omp) cp -a "$BUILD"/lib/kokkos/*/src/libkokkos*.so* "$PREFIX/lib/" ;; esac
  cp "$BUILD/lmp_$MACHINE" "$PREFIX/bin/lmp.tmp"
  # it must load our library, and 'plugin' must be a working command
  # (LMP_PLUGIN defined), not the "Ignoring plugin command" stub
  deps=$(ldd "$PREFIX/bin/lmp.tmp")
  grep -q "liblammps_$MACHINE.so.0 => /" <<<"$deps" && ! grep -q 'liblammps.so' <<<"$deps" ||
    { printf '%s\n' "$deps" >&2; die "$PREFIX/bin/lmp.tmp does not load lib/liblammps_$MACHINE.so.0"; }
  # (kokkos-cuda: runs without a GPU, as the CUDA driver, libcuda.so.1, is
  # not linked but loaded by the CUDA runtime at the first CUDA call, and
  # without -k on Kokkos is not initialised)
  out=$(cd "$PREFIX" && echo "plugin list" | "$PREFIX/bin/lmp.tmp" -log none -echo none 2>&1) || true
  grep -q "Currently loaded plugins" <<<"$out" || { printf '%s\n' "$out" >&2;
    die "'plugin list' does not work in $PREFIX/bin/lmp.tmp"; }
  mv "$PREFIX/bin/lmp.tmp" "$LMP"      # last: its presence marks a complete build
  log "built in $(( $(date +%s) - start )) s: $LMP"
fi
printf '%s\n' "$LMP"
