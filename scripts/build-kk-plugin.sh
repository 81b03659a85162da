#!/usr/bin/env bash
# Builds tlsphkkplugin.so: the whole package (the CPU styles of src/USER-TLSPH
# and the /kk styles of src/USER-TLSPH/kokkos) as one plugin for a
# KOKKOS-enabled shared-library LAMMPS built from the same Debian source with
# Debian's Kokkos (build-lammps-plugin.sh kokkos-stock, or kokkos);
# doc/kokkos.md, "Loading the /kk styles as a plugin". Entry point:
# src/USER-TLSPH/kokkos/tlsph_kk_plugin.cpp.
#
#   build-kk-plugin.sh [OUTDIR]     (default ${TLSPH_BUILD:-<repo>/build}/kkplugin)
#
# OUTDIR/build.ninja is written on every call and ninja (-j${TLSPH_JOBS:-2})
# recompiles what changed (header dependencies from -MD): seconds when nothing
# did. The last line on stdout is the path of OUTDIR/tlsphkkplugin.so.
#
# Compile flags: those of the KOKKOS LAMMPS's own objects (its build.ninja,
# target lammps: DEFINES, FLAGS, INCLUDES), i.e. -DLAMMPS_MEMALIGN=64
# -DLAMMPS_SMALLBIG -DLMP_KOKKOS -DLMP_PLUGIN, the MPI defines, -O2 -DNDEBUG
# -fPIC -std=c++14, the headers of the LAMMPS source tree (src, PERI, PLUGIN,
# KOKKOS) and Debian's Kokkos headers (/usr/include/trilinos, Kokkos 3.4.01,
# Serial); plus ours (include dirs and TLSPH_POTENTIALS_DIR). No built LAMMPS
# is needed; when a cached kokkos or kokkos-stock build exists, its DEFINES
# and FLAGS are compared with ours (a difference is an error).
#
# Link: -shared, MPI (like tlsphplugin.so), no liblammps and no Kokkos
# library (the host provides them), and
#   -Wl,-Bsymbolic   the plugin's references to its own symbols bind to its
#                    own definitions: loaded into a LAMMPS that has the package
#                    compiled in (the kokkos variant), the plugin's code runs,
#                    not the library's same-named classes (checked at run
#                    time: TLSPH_KK_PLUGIN_TRACE=1, tlsph_kk_plugin.cpp)
#   -Wl,-z,nodelete  dlclose() keeps the code mapped: LAMMPS unloads plugins
#                    (LAMMPS::destroy(), plugin_clear()) before it deletes the
#                    Atom instance, whose AtomVecPeriKokkos is plugin code
set -euo pipefail

log() { printf 'build-kk-plugin.sh: %s\n' "$*" >&2; }
die() { printf 'build-kk-plugin.sh: error: %s\n' "$*" >&2; exit 1; }

HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)
REPO=$(cd "$HERE/.." && pwd -P)
JOBS=${TLSPH_JOBS:-2}
OUT=${1:-${TLSPH_BUILD:-$REPO/build}/kkplugin}
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd -P)

if [ -z "${LAMMPS_SOURCE_DIR:-}" ]; then
  LAMMPS_SOURCE_DIR=$(bash "$HERE/setup.sh" | tail -n1)
fi
[ -f "$LAMMPS_SOURCE_DIR/src/KOKKOS/kokkos.h" ] || die "no LAMMPS source tree with src/KOKKOS at '$LAMMPS_SOURCE_DIR'"
KK_INC=/usr/include/trilinos
[ -f "$KK_INC/KokkosCore_config.h" ] ||
  die "no Kokkos headers in $KK_INC: libtrilinos-kokkos-dev is missing (bash scripts/build-lammps-plugin.sh kokkos-stock installs it)"
command -v ninja >/dev/null || die "ninja not found"

MPI_INC=()
for d in $(mpicxx --showme:incdirs 2>/dev/null); do MPI_INC+=(-isystem "$d"); done
[ ${#MPI_INC[@]} -gt 0 ] || die "cannot read the MPI include directories (mpicxx --showme:incdirs)"

DEFINES="-DLAMMPS_MEMALIGN=64 -DLAMMPS_SMALLBIG -DLMP_KOKKOS -DLMP_PLUGIN -DMPICH_SKIP_MPICXX -DOMPI_SKIP_MPICXX -D_MPICC_H"
FLAGS="-O2 -DNDEBUG -fPIC -std=c++14"
S=$LAMMPS_SOURCE_DIR/src
INCLUDES="-I$REPO/src/USER-TLSPH/kokkos -I$REPO/src/USER-TLSPH -I$S -I$S/PERI -I$S/PLUGIN -I$S/KOKKOS ${MPI_INC[*]} -isystem $KK_INC"
TLSPH_VERSION=$(head -n 1 "$REPO/VERSION" | tr -d '[:space:]')
OURS="-DTLSPH_POTENTIALS_DIR=\\\"$REPO/potentials\\\" -DTLSPH_VERSION=\\\"$TLSPH_VERSION\\\" -DTLSPH_KK_PLUGIN"

# the flags of a cached KOKKOS LAMMPS built from this source: must be ours
# (-Dlammps_EXPORTS only marks its own library's objects)
SRC_VER=$(dpkg-query -W -f='${source:Version}' liblammps-dev 2>/dev/null || true)
CACHE=${TLSPH_CACHE:-${XDG_CACHE_HOME:-${HOME:-/root}/.cache}/tlsph}
for v in kokkos-stock kokkos; do
  bn="$CACHE/lammps-$v-$SRC_VER/build/build.ninja"
  [ -n "$SRC_VER" ] && [ -f "$bn" ] || continue
  got=$(/usr/bin/python3 - "$bn" <<'FLAGS_OF_LAMMPS'
import re, sys
s = open(sys.argv[1]).read()
m = re.search(r"^build [^\n]*/src/KOKKOS/kokkos\.cpp\.o: [^\n]*\n((?:  [^\n]*\n)*)", s, re.M)
if not m:
    sys.exit("no src/KOKKOS/kokkos.cpp.o in " + sys.argv[1])
v = dict(re.findall(r"^  (\w+) = (.*)$", m.group(1), re.M))
d = " ".join(x for x in v["DEFINES"].split() if x != "-Dlammps_EXPORTS")
print(d + "|" + v["FLAGS"])
FLAGS_OF_LAMMPS
) || die "cannot read the compile flags of $bn"
  [ "$got" = "$DEFINES|$FLAGS" ] ||
    die "the $v LAMMPS ($bn) compiles with '$got', this script with '$DEFINES|$FLAGS'"
  break
done

SOURCES=()
for f in "$REPO"/src/USER-TLSPH/*.cpp "$REPO"/src/USER-TLSPH/kokkos/*.cpp; do
  [ "$(basename "$f")" = tlsph_plugin.cpp ] && continue   # included by tlsph_kk_plugin.cpp
  SOURCES+=("$f")
done

{
  printf '# written by scripts/build-kk-plugin.sh on every call; do not edit\n'
  printf 'defines = %s\nflags = %s\nincludes = %s\nours = %s\n' "$DEFINES" "$FLAGS" "$INCLUDES" "$OURS"
  printf 'rule cxx\n  command = c++ $defines $ours $includes $flags -MD -MF $out.d -c $in -o $out\n'
  printf '  depfile = $out.d\n  deps = gcc\n  description = CXX $out\n'
  printf 'rule link\n  command = c++ -shared -fPIC -O2 -o $out $in -Wl,-Bsymbolic -Wl,-z,nodelete %s\n' \
         "$(mpicxx --showme:link)"
  printf '  description = LINK $out\n'
  objs=()
  for f in "${SOURCES[@]}"; do
    case "$f" in */kokkos/*) o="obj/kokkos/$(basename "${f%.cpp}").o" ;; *) o="obj/$(basename "${f%.cpp}").o" ;; esac
    objs+=("$o")
    printf 'build %s: cxx %s\n' "$o" "$f"
  done
  printf 'build tlsphkkplugin.so: link %s\n' "${objs[*]}"
  printf 'default tlsphkkplugin.so\n'
} > "$OUT/build.ninja.new"
mv "$OUT/build.ninja.new" "$OUT/build.ninja"

start=$(date +%s)
ninja -C "$OUT" -j"$JOBS" >&2
so="$OUT/tlsphkkplugin.so"
# the properties the plugin relies on: an init function, -Bsymbolic, nodelete
# (nm's list read whole first: under pipefail, grep -q leaving early would
# end nm with SIGPIPE once the list outgrows the pipe's buffer, and fail)
syms=$(nm -D --defined-only "$so")
grep -q ' T lammpsplugin_init$' <<<"$syms" || die "$so exports no lammpsplugin_init"
dyn=$(readelf -d "$so")
grep -q 'SYMBOLIC' <<<"$dyn" || die "$so was not linked with -Bsymbolic"
grep -q 'Flags:.*NODELETE' <<<"$dyn" || die "$so was not linked with -z nodelete"
log "up to date in $(( $(date +%s) - start )) s: $so (${#SOURCES[@]} sources)"
printf '%s\n' "$so"
