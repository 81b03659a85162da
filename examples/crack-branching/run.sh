#!/bin/bash
# Dynamic crack branching (thesis section 3.2.2): dx = 0.333 mm, 36,000 particles,
# 1 MPI rank. Without NAME it runs two cases, about 5 minutes on a free core:
#   crack-branching      the thesis's discretisation, h = 1.33 dx, to 75 us
#   crack-branching-h2   the same deck with h = 2 dx (bonds reach 4 dx), to 90 us
# and out/summary.txt holds both summaries.  Writes into out/, for each NAME:
#   NAME.log, NAME.dump                  LAMMPS log, damage dump (tools/crack_measure.py input)
#   NAME.damage.NNNNNN.png               LAMMPS dump image snapshots of the damage (every 5 us)
#   NAME.crack.{json,csv,txt}            crack measured by tools/crack_measure.py
#   NAME.speed.png                       tip speed vs time, Rayleigh speed 2125 m/s drawn
#   NAME.montage.png                     damage field at 10, 20, ... us
#   summary-NAME.txt                     measured vs thesis vs acceptance
# Usage:
#   bash run.sh                                        the two cases above
#   NAME=rebuild bash run.sh -var corr rebuild         one variant: any -var of in.crack-branching
#   NAME=absolute bash run.sh -var crit absolute
# Environment: LMP_TLSPH (default ../../build/lmp_tlsph), TLSPH_PYTHON (default
# /usr/bin/python3), NP (MPI ranks, default 1), FORCE=0 to keep a finished run.
set -eu
cd "$(dirname "$0")"
py="${TLSPH_PYTHON:-/usr/bin/python3}"
mkdir -p out

one() {    # one NAME [-var ...]
  local name=$1; shift
  rm -f out/"$name".damage.*.png
  FORCE="${FORCE:-1}" ../common/run_case.sh in.crack-branching out "$name" "$@"
  "$py" summarise.py out/"$name" --label "$name $*" > out/summary-"$name".txt
  cat out/summary-"$name".txt
  echo "summary: out/summary-$name.txt; plots: out/$name.speed.png out/$name.montage.png out/$name.damage.*.png"
}

if [ -n "${NAME:-}" ]; then
  one "$NAME" "$@"
else
  one crack-branching "$@"
  one crack-branching-h2 -var hdx 2.0 -var tend 90e-6 "$@"
  cat out/summary-crack-branching.txt out/summary-crack-branching-h2.txt > out/summary.txt
  echo "both summaries: out/summary.txt"
fi
