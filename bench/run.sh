#!/usr/bin/env bash
# Throughput and memory benchmark of pair_style tlsph (`make bench`).
#
#   bash bench/run.sh              full run (~10 min on 2 cores): 3 repeats
#   BENCH_QUICK=1 bash bench/run.sh   smoke version (fewer steps, 1 repeat)
#   BENCH_REPEAT=5 bash bench/run.sh  more repeats (BENCH_BUDGET, default 600 s,
#                                     stops starting repeats that would end later)
#
# Writes bench/results.md (Markdown) and prints it; LAMMPS logs go to
# bench/out/. Uses LMP_TLSPH (default build/lmp_tlsph), TLSPH_BUILD (for the
# LAMMPS source tree of the optional memory probe) and TLSPH_PYTHON (default
# /usr/bin/python3), as exported by the Makefile. Method: doc/bench.md.
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(dirname "$HERE")"
export LMP_TLSPH="${LMP_TLSPH:-$ROOT/build/lmp_tlsph}"
TLSPH_BUILD="${TLSPH_BUILD:-$ROOT/build}"
PY="${TLSPH_PYTHON:-/usr/bin/python3}"
OUTDIR="$HERE/out"
mkdir -p "$OUTDIR"

if [ ! -x "$LMP_TLSPH" ]; then
  echo "bench: $LMP_TLSPH not found: run 'make build' first (or set LMP_TLSPH)" >&2
  exit 1
fi

# optional: the memory probe (LAMMPS's memory accounting split by owner),
# compiled against the LAMMPS headers the plugin was built with
PROBE="$OUTDIR/memprobe.so"
probe_args=()
src="$(sed -n 's/^LAMMPS_SOURCE_DIR:PATH=//p' "$TLSPH_BUILD/CMakeCache.txt" 2>/dev/null || true)"
if [ -n "$src" ] && [ -f "$src/src/pair.h" ] && command -v mpicxx >/dev/null 2>&1; then
  if [ ! -f "$PROBE" ] || [ "$HERE/memprobe.cpp" -nt "$PROBE" ] || [ "$src/src/pair.h" -nt "$PROBE" ] \
     || [ -n "$(find "$ROOT/src/USER-TLSPH" -name '*.h' -newer "$PROBE" 2>/dev/null)" ]; then
    if ! mpicxx -O1 -std=c++11 -shared -fPIC -DLAMMPS_SMALLBIG -I"$src/src" \
         -I"$ROOT/src/USER-TLSPH" "$HERE/memprobe.cpp" -o "$PROBE" 2>"$OUTDIR/memprobe.err"; then
      echo "bench: memory probe did not compile (see $OUTDIR/memprobe.err); LAMMPS line only" >&2
      rm -f "$PROBE"
    fi
  fi
  [ -f "$PROBE" ] && probe_args=(--probe "$PROBE")
else
  echo "bench: LAMMPS source tree not found via $TLSPH_BUILD/CMakeCache.txt: memory probe skipped" >&2
fi

args=()
[ "${BENCH_QUICK:-0}" != "0" ] && args+=(--quick)
[ -n "${BENCH_REPEAT:-}" ] && args+=(--repeat "$BENCH_REPEAT")

exec "$PY" "$HERE/bench.py" --lmp "$LMP_TLSPH" --outdir "$OUTDIR" --out "$HERE/results.md" \
  "${probe_args[@]}" "${args[@]}"
