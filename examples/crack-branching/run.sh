#!/bin/bash
# Dynamic crack branching (thesis section 3.2.2): dx = 0.333 mm, 36,000 particles,
# about 2 minutes on a free core (1 MPI rank).  Writes into out/:
#   NAME.log, NAME.dump                  LAMMPS log, damage dump (tools/crack_measure.py input)
#   NAME.damage.NNNNNN.png               LAMMPS dump image snapshots of the damage (every 5 us)
#   NAME.crack.{json,csv,txt}            crack measured by tools/crack_measure.py
#   NAME.speed.png                       tip speed vs time, Rayleigh speed 2125 m/s drawn
#   NAME.montage.png                     damage field at 10, 20, ... us
#   summary.txt (NAME = crack-branching) or summary-NAME.txt: measured vs thesis vs acceptance
# Usage:
#   bash run.sh                                        the thesis deck (correction setup, criterion tension)
#   NAME=rebuild bash run.sh -var corr rebuild         a variant: any -var of in.crack-branching
#   NAME=absolute bash run.sh -var crit absolute
# Environment: LMP_TLSPH (default ../../build/lmp_tlsph), TLSPH_PYTHON (default
# /usr/bin/python3), NP (MPI ranks, default 1), FORCE=0 to keep a finished run.
set -eu
cd "$(dirname "$0")"
py="${TLSPH_PYTHON:-/usr/bin/python3}"
name="${NAME:-crack-branching}"
mkdir -p out
rm -f out/"$name".damage.*.png
FORCE="${FORCE:-1}" ../common/run_case.sh in.crack-branching out "$name" "$@"
if [ "$name" = crack-branching ]; then sum=out/summary.txt; else sum=out/summary-"$name".txt; fi
"$py" summarise.py out/"$name" --label "$name $*" | tee "$sum"
echo "summary: $sum; plots: out/$name.speed.png out/$name.montage.png out/$name.damage.*.png"
