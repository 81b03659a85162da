#!/usr/bin/env bash
# Roofline of the TLSPH step on this CPU (doc/roofline.md, doc/roofline.png):
#   1. the ceilings, one core: bench/roofline.cpp (STREAM-like triad in DRAM
#      and in the last-level cache; scalar and AVX2-FMA multiply-add peaks);
#   2. the step of the bench/in.bench blocks (2D 36,100 and 3D 39,304
#      particles, full model, quadratic gradient, newton on, 1 rank) under
#      `perf record` (cpu-clock samples at 2 kHz), two run lengths: particle-
#      steps per second (the timed loop of the longer run) and the CPU time of
#      each pass per particle-step (the difference of the two runs' samples);
#   3. instructions per particle-step of each pass (callgrind, smaller blocks,
#      difference of two run lengths);
#      the same for the SIMD step (the default);
#   4. bench/roofline.py: flops and bytes per particle-step of each pass
#      counted from the source (tlsph_particle.h) with the measured bonds per
#      particle, against the ceilings.
#   bash bench/roofline.sh        (~4 min; needs perf and valgrind, Debian's
#                                  linux-perf and valgrind packages)
set -euo pipefail
# the scalar step (pair_style tlsph ... simd no): what doc/roofline.md and
# bench/instructions.md describe (valgrind runs no AVX-512 code either)
export TLSPH_SIMD=no
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(dirname "$HERE")"
LMP="${LMP_TLSPH:-$ROOT/build/lmp_tlsph}"
PY="${TLSPH_PYTHON:-/usr/bin/python3}"
OUT="$HERE/out/roofline"; mkdir -p "$OUT"
[ -x "$LMP" ] || { echo "roofline: $LMP not found: make build first" >&2; exit 1; }
for t in perf valgrind; do
  command -v $t >/dev/null || { echo "roofline: $t not installed (apt-get install linux-perf valgrind)" >&2; exit 1; }
done

git -C "$ROOT" describe --always --dirty > "$OUT/commit.txt" 2>/dev/null || echo "?" > "$OUT/commit.txt"

# 1. ceilings
g++ -O3 -o "$OUT/roofline" "$HERE/roofline.cpp"
"$OUT/roofline" > "$OUT/ceilings.txt"
cat "$OUT/ceilings.txt"

# 2. throughput and the share of each pass (perf sampling, 1 rank), for the
#    scalar step (prefix perf-) and the SIMD step (perf-simd-: the default,
#    AVX-512 or AVX2 kernels chosen at run time), the same run lengths (longer
#    2D SIMD runs slow down: 8.5 ms per step over 800 steps against 5.2 over
#    200, not investigated)
blk="$HERE/in.bench"
for step in scalar simd; do
  pre=perf; envs=()
  [ $step = simd ] && pre=perf-simd envs=(-u TLSPH_SIMD)
  for c in "2 190 60 260" "3 34 10 40"; do
    set -- $c; dim=$1 n=$2
    for ns in $3 $4; do
      (cd "$OUT" && env "${envs[@]}" perf record -q -e cpu-clock -F 2000 -o "$OUT/$pre-$dim-$ns.data" -- \
         "$LMP" -in "$blk" -var dim $dim -var n $n -var nsteps $ns -log "$OUT/$pre-$dim-$ns.log" \
         -screen none > /dev/null 2>&1)
      perf report -i "$OUT/$pre-$dim-$ns.data" --stdio --no-children -F overhead,sample,sym 2>/dev/null \
        | grep -E '^ +[0-9.]+%' > "$OUT/$pre-$dim-$ns.txt" || true
    done
    echo "$3 $4" > "$OUT/$pre-$dim.steps"
  done
done

# 3. instructions per step of each pass (inclusive, callgrind), N2 - N1 steps
#    (the scalar step only: valgrind runs no AVX-512 code)
for c in "2 60 10 30" "3 12 4 12"; do
  set -- $c; dim=$1 n=$2 n1=$3 n2=$4
  for ns in $n1 $n2; do
    f="$OUT/cg-$dim-$ns.out"
    (cd "$OUT" && valgrind --tool=callgrind --callgrind-out-file="$f" "$LMP" -in "$blk" \
       -var dim $dim -var n $n -var nsteps $ns -var nwarm 2 -log "$OUT/cg-$dim-$ns.log" -screen none \
       > /dev/null 2> "$OUT/cg-$dim-$ns.vg")
    callgrind_annotate --inclusive=yes "$f" 2>/dev/null | grep -E 'compute_deformation|compute_forces|PairTLSPH::compute\(' \
      > "$OUT/cg-$dim-$ns.txt" || true
    sed -n 's/^summary: *//p; s/^totals: *//p' "$f" | head -1 | awk '{print $1}' > "$OUT/cg-$dim-$ns.total"
  done
  echo "$n1 $n2 $n" > "$OUT/cg-$dim.steps"
done

# 4. the analysis
"$PY" "$HERE/roofline.py" --out "$OUT" --doc "$ROOT/doc"
