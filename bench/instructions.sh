#!/usr/bin/env bash
# Instruction counts per step (valgrind's callgrind), for the two cost
# comparisons the issues set targets for: the orthotropic law against the
# isotropic one on the same particles (sections 5 of results.md) and
# tlsph/damage against tlsph on the crack-branching plate (section 6).
#
#   bash bench/instructions.sh          writes bench/instructions.md (~5 min)
#
# Why: on a shared machine wall-clock repeats of the same case differ by up to
# a third (results.md, raw repeats), more than the few per cent being compared.
# The number of instructions executed does not depend on the load.  Each case
# runs twice under callgrind, with N1 and N2 timed steps after the same set-up;
# instructions per step = (I(N2) - I(N1)) / (N2 - N1), which removes the set-up
# and the partner search.  Instructions are not time (cache misses and the
# 6x6 products' vectorisation are not weighed), so the two tables complement
# each other.  Smaller systems than results.md so that callgrind (~50x slower)
# stays short; the per-particle work is the same.
set -euo pipefail
# the scalar step (pair_style tlsph ... simd no): what doc/roofline.md and
# bench/instructions.md describe (valgrind runs no AVX-512 code either)
export TLSPH_SIMD=no
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(dirname "$HERE")"
LMP="${LMP_TLSPH:-$ROOT/build/lmp_tlsph}"
OUT="$HERE/out/callgrind"
REPORT="$HERE/instructions.md"
mkdir -p "$OUT"
command -v valgrind >/dev/null || { echo "instructions.sh: valgrind not installed (apt-get install valgrind)" >&2; exit 1; }
[ -x "$LMP" ] || { echo "instructions.sh: $LMP not found: make build first" >&2; exit 1; }

# ir NAME INPUT NSTEPS [-var ...]: total instructions of one run
ir() {
  local name=$1 input=$2 n=$3; shift 3
  local f="$OUT/$name-$n.out"
  (cd "$OUT" && valgrind --tool=callgrind --callgrind-out-file="$f" "$LMP" -in "$input" \
      -log "$OUT/$name-$n.log" -screen none -var nsteps "$n" "$@" 2>"$OUT/$name-$n.vg" >/dev/null) || {
    echo "instructions.sh: $name ($n steps) failed: see $OUT/$name-$n.vg and .log" >&2; return 1; }
  sed -n 's/^summary: *//p; s/^totals: *//p' "$f" | head -1 | awk '{print $1}'
}

# per_step NAME INPUT N1 N2 [-var ...]: instructions per step
per_step() {
  local name=$1 input=$2 n1=$3 n2=$4; shift 4
  local i1 i2
  i1=$(ir "$name" "$input" "$n1" "$@")
  i2=$(ir "$name" "$input" "$n2" "$@")
  echo $(( (i2 - i1) / (n2 - n1) ))
}

row() {  # row LABEL PARTICLES IREF I
  awk -v l="$1" -v np="$2" -v r="$3" -v i="$4" 'BEGIN {
    if (r == i) printf "| %s | %d | %.2f M | %.1f | - |\n", l, np, i / 1e6, i / np;
    else printf "| %s | %d | %.2f M | %.1f | %+.1f %% |\n", l, np, i / 1e6, i / np, 100 * (i / r - 1) }'
}

start=$(date +%s)
blk="$HERE/in.bench"
echo "instructions: 2D block (3,600 particles)" >&2
i2iso=$(per_step 2d-iso "$blk" 10 30 -var dim 2 -var n 60 -var mat iso -var nwarm 2)
i2ort=$(per_step 2d-ortho "$blk" 10 30 -var dim 2 -var n 60 -var mat ortho -var nwarm 2)
echo "instructions: 3D block (1,728 particles)" >&2
i3iso=$(per_step 3d-iso "$blk" 5 15 -var dim 3 -var n 12 -var mat iso -var nwarm 2)
i3ort=$(per_step 3d-ortho "$blk" 5 15 -var dim 3 -var n 12 -var mat ortho -var nwarm 2)
echo "instructions: crack-branching plate (9,000 particles)" >&2
br="$HERE/in.branching"
dxb=0.000666666666667
ibt=$(per_step branch-tlsph "$br" 20 60 -var damage 0 -var dx $dxb)
ibd=$(per_step branch-damage "$br" 20 60 -var damage 1 -var dx $dxb)

{
  echo "# Instructions per step (callgrind)"
  echo
  echo "- date: $(date '+%Y-%m-%d %H:%M:%S') ($(( $(date +%s) - start )) s), commit \`$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo '?')\`$(git -C "$ROOT" diff --quiet 2>/dev/null || echo ' + uncommitted changes')"
  echo "- binary: \`$LMP\` (built $(date -r "$LMP" '+%Y-%m-%d %H:%M:%S')), $(valgrind --version)"
  echo "- instructions per step = (I(N2) - I(N1)) / (N2 - N1) of two runs with the same set-up; 1 rank"
  echo
  echo "## Orthotropic law (bench/in.bench, material iso or ortho: the same steel as a ply at 30 deg)"
  echo
  echo "| case | particles | instructions per step | per particle-step | extra |"
  echo "|---|---:|---:|---:|---:|"
  row "2D isotropic" 3600 "$i2iso" "$i2iso"
  row "2D orthotropic" 3600 "$i2iso" "$i2ort"
  row "3D isotropic" 1728 "$i3iso" "$i3iso"
  row "3D orthotropic" 1728 "$i3iso" "$i3ort"
  echo
  echo "## Damage machinery (bench/in.branching at dx = 0.667 mm, steps 20-60: before the first break)"
  echo
  echo "| case | particles | instructions per step | per particle-step | extra |"
  echo "|---|---:|---:|---:|---:|"
  row "tlsph" 9000 "$ibt" "$ibt"
  row "tlsph/damage + pre-crack + velocity filter" 9000 "$ibt" "$ibd"
} > "$REPORT"
cat "$REPORT"
