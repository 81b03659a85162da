#!/bin/bash
# Studies of the laminate-beam deck behind the tables of README.md, at the coarse
# dx = 1.667 mm (2,268 particles, 3 layers per ply; 1 MPI rank each, a few minutes
# per run) unless stated:
#   placement   particle layers through the thickness (uniform cell centres or
#               'moment': exact second moment per ply) x clamp (support layers
#               behind the face, 'cell', or from the face, 'face'), [0/90]
#   resolution  the default deck at dx = 1.667, 1.25 mm ([0/90]; dx = 1 mm is run.sh)
#   timesol     time to the static state, [0/90]: kinetic damping (the default),
#               a drag critical for the first mode, and the thesis's way, a slow
#               load ramp without damping (artificial viscosity alpha 0.2), over
#               2, 5 and 10 first-mode periods
#   bash studies.sh [placement] [resolution] [timesol]     (default: all)
# Writes out/studies/NAME.{log,dat,final.dump,txt,json}. Environment: LMP_TLSPH,
# TLSPH_PYTHON, NP (MPI ranks, default 1), FORCE=1 reruns finished cases.
set -u
cd "$(dirname "$0")"
py="${TLSPH_PYTHON:-/usr/bin/python3}"
out=out/studies
mkdir -p "$out"
dxc=0.00166666666666667
parts="${*:-placement resolution timesol}"

run() {    # run NAME -var ...
  local name=$1; shift
  ../common/run_case.sh in.laminate-beam "$out" "$name" "$@" &&
    "$py" analyse.py "$out/$name" --label "$name" --json "$out/$name.json" > "$out/$name.txt"
  head -9 "$out/$name.txt" | tail -6
}

for part in $parts; do
  case "$part" in
  placement)
    for z in uniform moment; do
      for c in cell face; do
        # moment + face is the default deck: one run serves all three studies
        if [ $z-$c = moment-face ]; then run default-dx1.667 -var dx $dxc -var tol 1e-5
        else run "p-${z}-${c}" -var dx $dxc -var zplace $z -var clamp $c -var tol 1e-5; fi
      done
    done ;;
  resolution)
    run default-dx1.667 -var dx $dxc -var tol 1e-5
    run "r-dx1.25" -var dx 0.00125 -var tol 1e-5 ;;
  timesol)
    run default-dx1.667 -var dx $dxc -var tol 1e-5
    run "t-viscous" -var dx $dxc -var damp viscous -var tol 1e-5
    for r in 2 5 10; do
      run "t-ramp$r" -var dx $dxc -var damp none -var alpha 0.2 -var ramp $r -var hold 0.0001
    done ;;
  *) echo "unknown part $part (placement resolution timesol)"; exit 1 ;;
  esac
done
