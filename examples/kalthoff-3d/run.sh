#!/bin/bash
# 3D Kalthoff-Winkler plate impact (thesis section 3.2.1.2), full plate (both
# notches, whole thickness), impact at 30 m/s, 100 us simulated, the deck's
# default model (recommended; -var model thesis for the thesis's).  Cases, run one
# after the other on NP MPI ranks (default 2):
#   smoke    kalthoff-3d-smoke    dx = 25/14 mm = 1.786 mm, 56 x 112 x 5 = 31,360 particles
#                                 (plate 8.93 mm thick): a quick check, not converged
#   coarse   kalthoff-3d-coarse   dx = 1.25 mm, 80 x 160 x 7 = 89,600 particles (8.75 mm)
#   thesis   kalthoff-3d          dx = 1 mm (the thesis's), 100 x 200 x 9 = 180,000 particles
#                                 (the thesis has 203,000: 101 x 201 x 10 lattice nodes
#                                 with both faces, this deck particles at cell centres)
# Wall times measured on the shared 2-core machine: see README.md.  Writes into
# out/, for each NAME:
#   NAME.log, NAME.dump                  LAMMPS log, damage dump (3D: id x y z phi phi')
#   NAME.mid.NNNNNN.png                  dump image of the mid-thickness particle layer, every 10 us
#   NAME.iso.NNNNNN.png                  dump image of the whole plate, oblique view, every 10 us
#   NAME.mid.dump, NAME.proj.dump        2D dumps made by summarise.py: the mid-thickness
#                                        layer, and the through-thickness maximum of phi
#   NAME.crack.{json,csv,txt}            both cracks on the mid-thickness layer (tools/crack_measure.py)
#   NAME.proj.crack.{json,csv,txt}       the same on the through-thickness projection
#   NAME.speed.png                       tip speeds vs time, Rayleigh speed 2803 m/s drawn
#   NAME.montage.png                     mid-layer damage at 10, 20, ... 100 us
#   summary-NAME.txt                     measured vs thesis vs experiment
# Usage:  bash run.sh                        coarse, then thesis
#         CASES=smoke bash run.sh            one case (smoke, coarse, thesis)
#         NAME=x CASES=coarse bash run.sh -var alpha 0.09      a variant (any -var of in.kalthoff-3d)
#         CASES=thesis bash run.sh -var tend 4e-6              a short run (step rate only)
# Environment: LMP_TLSPH (default ../../build/lmp_tlsph), TLSPH_PYTHON (default
# /usr/bin/python3), NP (MPI ranks, default 2), FORCE=0 to keep finished runs.
set -eu
cd "$(dirname "$0")"
py="${TLSPH_PYTHON:-/usr/bin/python3}"
cases="${CASES:-coarse thesis}"
base="${NAME:-kalthoff-3d}"
export NP="${NP:-2}"
mkdir -p out
for c in $cases; do
  case "$c" in
    smoke)  name="$base-smoke";  dxv=0.00178571428571429 ;;
    coarse) name="$base-coarse"; dxv=0.00125 ;;
    thesis) name="$base";        dxv=0.001 ;;
    *) echo "unknown case $c"; exit 1 ;;
  esac
  rm -f out/"$name".mid.*.png out/"$name".iso.*.png
  FORCE="${FORCE:-1}" ../common/run_case.sh in.kalthoff-3d out "$name" -var dx "$dxv" "$@" \
    || echo "LAMMPS stopped with an error (see out/$name.log): the dump is measured up to there"
  "$py" summarise.py out/"$name" --label "$name (dx = $dxv m) $*" | tee out/summary-"$name".txt
done
if [ "$base" = kalthoff-3d ]; then
  for n in kalthoff-3d-smoke kalthoff-3d-coarse kalthoff-3d; do
    [ -f out/summary-$n.txt ] && { cat out/summary-$n.txt; echo; }
  done > out/summary.txt
fi
echo "summaries: out/summary-*.txt; plots: out/*.speed.png out/*.montage.png out/*.mid.*.png out/*.iso.*.png"
