#!/bin/bash
# Two-ply carbon/epoxy cantilevers (thesis section 3.3.1) against the CalculiX
# reference: dx = 1 mm (10,300 particles), h = 1.33 dx, tip load 500 N on the
# central 2 mm x 2 mm of the tip, static state by kinetic damping (fix tlsph/relax).
#   bash run.sh                  both layups: [0/90] and [0/45]
#   CASES=0-90 bash run.sh       one of them (0-90 0-45)
#   NAME=x CASES=0-90 bash run.sh -var gamma 2     a variant (any -var of in.laminate-beam)
# Writes out/NAME.{log,dat,final.dump}, out/NAME.profile.png (u1 through the
# thickness at the tip, TLSPH and FE), out/NAME.json and out/summary-NAME.txt
# (analyse.py: TLSPH vs FE at the same material points), out/summary.txt (all).
# About 15-25 min per layup on 2 cores. Environment: LMP_TLSPH, TLSPH_PYTHON, NP
# (MPI ranks, default 2), FORCE=0 to keep finished runs.
set -eu
cd "$(dirname "$0")"
py="${TLSPH_PYTHON:-/usr/bin/python3}"
export NP="${NP:-2}"
mkdir -p out
for c in ${CASES:-0-90 0-45}; do
  case "$c" in
    0-90) th=90 ;;
    0-45) th=45 ;;
    *) echo "unknown case $c (0-90 0-45)"; exit 1 ;;
  esac
  name="${NAME:-laminate-beam}-$c"
  FORCE="${FORCE:-1}" ../common/run_case.sh in.laminate-beam out "$name" -var theta2 "$th" "$@"
  "$py" analyse.py out/"$name" --label "$*" --png out/"$name".profile.png \
    --json out/"$name".json | tee out/summary-"$name".txt
done
if [ -z "${NAME:-}" ]; then
  for c in 0-90 0-45; do
    [ -f out/summary-laminate-beam-$c.txt ] && { cat out/summary-laminate-beam-$c.txt; echo; }
  done > out/summary.txt
fi
