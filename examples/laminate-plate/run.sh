#!/bin/bash
# Clamped [0/90] carbon/epoxy plate under 1 MPa (thesis section 3.3.2) against the
# CalculiX reference: dx = 1 mm (100 x 100 x 4 particles + a 3-layer clamp rim,
# 44,944 in all), h = 1.33 dx, static state by kinetic damping (fix tlsph/relax).
#   bash run.sh                        the main case (gamma 1, the package default)
#   GAMMAS="0.25 1 4" bash run.sh      the hourglass-coefficient study (one run per gamma)
#   NAME=x bash run.sh -var dx ...     a variant (any -var of in.laminate-plate)
# Writes out/NAME.{log,dat,final.dump}, out/NAME.fields.png (u1, u2, u3 on the top
# particle layer: TLSPH, FE, difference), out/NAME.pointA.png (profiles through the
# thickness at x = y = 75 mm), out/NAME.json and out/summary-NAME.txt (analyse.py).
# About 15 min per run on 2 cores. Environment: LMP_TLSPH, TLSPH_PYTHON, NP (MPI
# ranks, default 2), FORCE=0 to keep finished runs.
set -eu
cd "$(dirname "$0")"
py="${TLSPH_PYTHON:-/usr/bin/python3}"
export NP="${NP:-2}"
mkdir -p out
for g in ${GAMMAS:-1}; do
  if [ -n "${GAMMAS:-}" ]; then name="${NAME:-laminate-plate}-gamma$g"; else name="${NAME:-laminate-plate}"; fi
  FORCE="${FORCE:-1}" ../common/run_case.sh in.laminate-plate out "$name" -var gamma "$g" "$@"
  "$py" analyse.py out/"$name" --label "gamma $g $*" --png out/"$name".fields.png \
    --profile-png out/"$name".pointA.png --json out/"$name".json | tee out/summary-"$name".txt
done
