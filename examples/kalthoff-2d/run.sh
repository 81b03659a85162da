#!/bin/bash
# 2D Kalthoff-Winkler plate impact (thesis section 3.2.1.1), full plate, plane strain,
# 110 us of impact at 16.5 m/s, the deck's default model (recommended: criterion
# tip branch yoffe; add -var model thesis for the thesis's method, e.g.
# NAME=kalthoff-2d-thesis bash run.sh -var model thesis).  Runs four cases, one
# after the other (1 MPI rank):
#   kalthoff-2d                 dx = 1 mm    (20,000 particles), correction setup (package
#                               default, the thesis's: the correction is kept from setup)
#   kalthoff-2d-coarse          dx = 1.67 mm ( 7,200 particles), correction setup
#   kalthoff-2d-rebuild         dx = 1 mm,    correction rebuild (from the intact bonds)
#   kalthoff-2d-coarse-rebuild  dx = 1.67 mm, correction rebuild
# about 2 minutes in all on a free core, and writes into out/, for each NAME:
#   NAME.log, NAME.dump                  LAMMPS log, damage dump (tools/crack_measure.py input)
#   NAME.damage.NNNNNN.png               LAMMPS dump image snapshots of the damage (every 10 us)
#   NAME.crack.{json,csv,txt}            both cracks measured by tools/crack_measure.py
#   NAME.speed.png                       tip speeds vs time, Rayleigh speed 2803 m/s drawn
#   NAME.montage.png                     damage field at 20, 35, ... 110 us
#   summary-NAME.txt                     measured vs thesis vs experiment
# and out/summary.txt (all summaries).
# Usage:  bash run.sh                       all four cases
#         CASES="fine coarse" bash run.sh   some of them (fine coarse fine-rebuild coarse-rebuild)
#         NAME=x CASES=fine bash run.sh -var notch delete     a variant (any -var of in.kalthoff-2d)
# Environment: LMP_TLSPH (default ../../build/lmp_tlsph), TLSPH_PYTHON (default
# /usr/bin/python3), NP (MPI ranks, default 1), FORCE=0 to keep finished runs,
# PROGRESS=1 for a progress line every 5 s.
set -eu
cd "$(dirname "$0")"
py="${TLSPH_PYTHON:-/usr/bin/python3}"
cases="${CASES:-fine coarse fine-rebuild coarse-rebuild}"
base="${NAME:-kalthoff-2d}"
mkdir -p out
for c in $cases; do
  extra=()
  case "$c" in
    fine)         name="$base";              dxv=0.001 ;;
    coarse)       name="$base-coarse";       dxv=0.00166666666666667 ;;
    fine-rebuild)   name="$base-rebuild";        dxv=0.001;               extra=(-var corr rebuild) ;;
    coarse-rebuild) name="$base-coarse-rebuild"; dxv=0.00166666666666667; extra=(-var corr rebuild) ;;
    *) echo "unknown case $c"; exit 1 ;;
  esac
  rm -f out/"$name".damage.*.png
  FORCE="${FORCE:-1}" ../common/run_case.sh in.kalthoff-2d out "$name" -var dx "$dxv" -var tend 110e-6 \
    "${extra[@]}" "$@" \
    || echo "LAMMPS stopped with an error (see out/$name.log): the dump is measured up to there"
  "$py" summarise.py out/"$name" --label "$name (dx = $dxv m) ${extra[*]} $*" | tee out/summary-"$name".txt
done
if [ "$base" = kalthoff-2d ]; then
  for n in kalthoff-2d kalthoff-2d-coarse kalthoff-2d-rebuild kalthoff-2d-coarse-rebuild; do
    [ -f out/summary-$n.txt ] && { cat out/summary-$n.txt; echo; }
  done > out/summary.txt
fi
echo "summaries: out/summary*.txt; plots: out/*.speed.png out/*.montage.png out/*.damage.*.png"
