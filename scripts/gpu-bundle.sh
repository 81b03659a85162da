#!/usr/bin/env bash
# make gpu-bundle / make gpu-bundle-host (doc/kokkos-cuda.md, "The GPU bundle"):
# a self-contained LAMMPS for the GPU machine, built here without a GPU, and
# packed into gpu-bundle/ (git-ignored) so that it travels with the checkout:
#
#   gpu-bundle/tlsph-gpu-bundle.tar.xz    (at most 48 MiB)
#     bin/lmp            static: LAMMPS 29 Sep 2021 (Debian's source) with
#                        KOKKOS (Kokkos 3.4.01, CUDA sm_90 SASS + compute_90
#                        PTX, Serial host), PERI and this package compiled in,
#                        MPI STUBS, libstdc++/libgcc/CUDA runtime static,
#                        stripped (build-lammps-plugin.sh bundle-cuda)
#     bin/gpu_bandwidth  the device's copy bandwidth (bench/gpu_bandwidth.cu)
#     MANIFEST           commit, flags, nvcc, the glibc and driver it needs
#   gpu-bundle/tlsph-gpu-sources.tar.xz   the sources of a fallback build on
#                        the GPU machine (fallback-build.sh inside: cmake +
#                        ninja, the same configuration)
#
# The decks, the check script (scripts/gpu-check.sh) and the CPU styles that
# give its references are those of the checkout (and of bin/lmp itself).
# `gpu-bundle.sh host` builds the host twin instead (bundle-host: the same
# configuration with Kokkos Serial and g++; gpu-bundle/host/bin/lmp, not
# packed), which CI runs scripts/gpu-check.sh --host with. Both LAMMPS
# builds are cached outside the checkout (TLSPH_CACHE), keyed by the LAMMPS
# version and the flags, and rebuilt incrementally.
set -euo pipefail
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)
REPO=$(cd "$HERE/.." && pwd -P)
MODE=${1:-cuda}
OUTDIR="$REPO/gpu-bundle"
log() { printf 'gpu-bundle.sh: %s\n' "$*" >&2; }
die() { printf 'gpu-bundle.sh: error: %s\n' "$*" >&2; exit 1; }
LIMIT_MB=48

case "$MODE" in
  host)
    LMP=$(bash "$HERE/build-lammps-plugin.sh" bundle-host | tail -n1)
    mkdir -p "$OUTDIR/host/bin"
    cp "$LMP" "$OUTDIR/host/bin/lmp"
    log "host twin: $OUTDIR/host/bin/lmp"
    printf '%s\n' "$OUTDIR/host/bin/lmp"
    exit 0 ;;
  cuda) ;;
  *) die "unknown mode '$MODE' (allowed: cuda, host)" ;;
esac

CUDA_HOME=$(cd "${TLSPH_CUDA_HOME:-/usr/local/cuda}" && pwd -P)
NVCC="$CUDA_HOME/bin/nvcc"
LMP=$(bash "$HERE/build-lammps-plugin.sh" bundle-cuda | tail -n1)
PREFIX=$(dirname "$(dirname "$LMP")")
STAGE=$(mktemp -d)
trap 'rm -rf "$STAGE"' EXIT
mkdir -p "$STAGE/tlsph-gpu/bin"
cp "$LMP" "$STAGE/tlsph-gpu/bin/lmp"
"$NVCC" -O3 -std=c++17 -gencode=arch=compute_90,code=sm_90 -gencode=arch=compute_90,code=compute_90 \
  -Xcompiler -static-libstdc++ -Xcompiler -static-libgcc \
  -o "$STAGE/tlsph-gpu/bin/gpu_bandwidth" "$REPO/bench/gpu_bandwidth.cu"
strip "$STAGE/tlsph-gpu/bin/gpu_bandwidth"

# what the binaries need of the machine: the newest GLIBC_ symbol version
# they reference, and a driver for this CUDA runtime (CUDA 13.x: R580 or newer)
glibc_need() { objdump -T "$1" | sed -n 's/.*GLIBC_\([0-9.]*\).*/\1/p' | sort -V | tail -n1; }
GLIBC=$( (glibc_need "$STAGE/tlsph-gpu/bin/lmp"; glibc_need "$STAGE/tlsph-gpu/bin/gpu_bandwidth") | sort -V | tail -n1)
NVCC_VERSION=$("$NVCC" --version | sed -n 's/.*release \([0-9.]*\), V\([0-9.]*\).*/\2/p')
case "$NVCC_VERSION" in
  13.*) DRIVER=580 ;;
  12.*) DRIVER=525 ;;
  *) die "no minimum driver known for nvcc $NVCC_VERSION" ;;
esac
COMMIT=$(git -C "$REPO" describe --always --dirty 2>/dev/null || echo unknown)
{
  echo "commit $COMMIT"
  echo "built $(date -u +%Y-%m-%dT%H:%MZ) on $(uname -m), $(. /etc/os-release; echo "$PRETTY_NAME")"
  echo "lammps $(basename "$PREFIX" | sed 's/^lammps-bundle-cuda-//')"
  echo "nvcc $NVCC_VERSION"
  echo "gencode compute_90,sm_90 compute_90,compute_90"
  echo "cxx_flags_release $(sed -n 's/^CMAKE_CXX_FLAGS_RELEASE:[A-Z]*=//p' "$PREFIX/build/CMakeCache.txt")"
  echo "glibc_min $GLIBC"
  echo "driver_min $DRIVER"
  echo "needs $(ldd "$STAGE/tlsph-gpu/bin/lmp" | awk '{print $1}' | paste -sd' ')"
  echo "fatbin $(python3 "$HERE/fatbin_check.py" "$STAGE/tlsph-gpu/bin/lmp" sm_90 compute_90 2>&1 | sed 's/^fatbin_check.py: //')"
  (cd "$STAGE/tlsph-gpu" && sha256sum bin/*) | sed 's/^/sha256 /'
} > "$STAGE/tlsph-gpu/MANIFEST"
mkdir -p "$OUTDIR"
tar -C "$STAGE" -cf - tlsph-gpu | xz -9e -T2 > "$OUTDIR/tlsph-gpu-bundle.tar.xz.tmp"
mv "$OUTDIR/tlsph-gpu-bundle.tar.xz.tmp" "$OUTDIR/tlsph-gpu-bundle.tar.xz"

# the fallback sources: the bundle's LAMMPS tree as configured (src without
# the packages it does not build, the trimmed KOKKOS, PERI, STUBS, cmake,
# lib/kokkos patched) with our files in it, and its cmake command
SRC="$PREFIX/source"
mkdir -p "$STAGE/src-pack"
(cd "$SRC" && { find src -maxdepth 1 -type f; echo cmake; echo lib/kokkos; echo src/KOKKOS;
   echo src/PERI; echo src/STUBS; } | tar -cf - -T -) | tar -C "$STAGE/src-pack" -xf -
rm -rf "$STAGE/src-pack/lib/kokkos/"{example,benchmarks} "$STAGE/src-pack/lib/kokkos/"*/unit_test
cat > "$STAGE/src-pack/fallback-build.sh" <<'FALLBACK'
#!/usr/bin/env bash
# A fallback build of the bundle's LAMMPS on the GPU machine (CMake, ninja,
# nvcc, g++ there): bash fallback-build.sh [JOBS]; prints the path of lmp.
# The same configuration as scripts/build-lammps-plugin.sh bundle-cuda, with
# the nvcc of $CUDA_HOME (default /usr/local/cuda) and the arch of the GPU
# it finds (TLSPH_CUDA_GENCODE: sm_90 + compute_90 PTX unless TLSPH_ARCH=NN).
set -euo pipefail
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)
JOBS=${1:-$(nproc)}
CUDA_HOME=${CUDA_HOME:-/usr/local/cuda}
ARCH=${TLSPH_ARCH:-90}
sed -i "s|^nvcc_compiler=.*|nvcc_compiler=\"$CUDA_HOME/bin/nvcc\"|" "$HERE/lib/kokkos/bin/nvcc_wrapper"
cmake -S "$HERE/cmake" -B "$HERE/build" -G Ninja -D CMAKE_BUILD_TYPE=Release \
  -D CMAKE_CXX_FLAGS_RELEASE="@FLAGS@" \
  -D BUILD_MPI=off -D BUILD_OMP=off -D BUILD_SHARED_LIBS=off -D LAMMPS_MACHINE=bundle_cuda \
  -D LAMMPS_SIZES=smallbig -D LAMMPS_EXCEPTIONS=off -D PKG_PERI=on -D PKG_KOKKOS=on \
  -D EXTERNAL_KOKKOS=off -D DOWNLOAD_KOKKOS=off -D Kokkos_ENABLE_SERIAL=on \
  -D Kokkos_ENABLE_OPENMP=off -D Kokkos_ENABLE_CUDA=on -D Kokkos_ENABLE_CUDA_UVM=off \
  -D Kokkos_ARCH_HOPPER90=on \
  -D "TLSPH_CUDA_GENCODE=arch=compute_${ARCH},code=sm_${ARCH};arch=compute_${ARCH},code=compute_${ARCH}" \
  -D CMAKE_CXX_COMPILER="$HERE/lib/kokkos/bin/nvcc_wrapper" -D CUDAToolkit_ROOT="$CUDA_HOME" \
  -D "CMAKE_EXE_LINKER_FLAGS=-static-libstdc++ -static-libgcc" \
  -D WITH_JPEG=off -D WITH_PNG=off -D WITH_GZIP=off -D WITH_FFMPEG=off -D BUILD_TOOLS=off \
  -D BUILD_LAMMPS_SHELL=off -D BUILD_DOC=off -D ENABLE_TESTING=off -D PKG_PLUGIN=off >&2
ninja -C "$HERE/build" -j"$JOBS" lmp_bundle_cuda >&2
printf '%s\n' "$HERE/build/lmp_bundle_cuda"
FALLBACK
FLAGS=$(sed -n 's/^CMAKE_CXX_FLAGS_RELEASE:[A-Z]*=//p' "$PREFIX/build/CMakeCache.txt")
sed -i "s|@FLAGS@|$FLAGS|" "$STAGE/src-pack/fallback-build.sh"
chmod +x "$STAGE/src-pack/fallback-build.sh"
tar -C "$STAGE" --transform 's|^src-pack|tlsph-gpu-sources|' -cf - src-pack | xz -6 -T2 > "$OUTDIR/tlsph-gpu-sources.tar.xz"

b=$(du -b "$OUTDIR/tlsph-gpu-bundle.tar.xz" | cut -f1)
s=$(du -b "$OUTDIR/tlsph-gpu-sources.tar.xz" | cut -f1)
log "bundle $((b / 1024)) KiB, sources $((s / 1024)) KiB (limit ${LIMIT_MB} MiB together)"
[ $((b + s)) -le $((LIMIT_MB * 1024 * 1024)) ] ||
  die "the bundle and its sources take $(((b + s) / 1048576)) MiB, more than $LIMIT_MB MiB"
cat "$STAGE/tlsph-gpu/MANIFEST" >&2
printf '%s\n' "$OUTDIR/tlsph-gpu-bundle.tar.xz"
