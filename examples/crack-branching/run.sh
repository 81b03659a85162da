#!/bin/bash
# Dynamic crack branching (thesis section 3.2.2): dx = 0.333 mm, 36,000 particles,
# 1 MPI rank. Without NAME it runs, by VARIANT:
#   recommended (default)  crack-branching: the deck's default, the package's
#                          recommended model (criterion tip branch yoffe, h = 1.33 dx,
#                          in.crack-branching's header), to 90 us
#   thesis                 crack-branching-thesis: the thesis's method (-var model
#                          thesis), h = 1.33 dx, to 75 us; and crack-branching-thesis-h2:
#                          the same with h = 2 dx (bonds reach 4 dx), to 90 us
# and out/summary.txt (VARIANT thesis: out/summary-thesis.txt) holds the summaries.
# Writes into out/, for each NAME:
#   NAME.log, NAME.dump                  LAMMPS log, damage dump (tools/crack_measure.py input)
#   NAME.damage.NNNNNN.png               LAMMPS dump image snapshots of the damage (every 5 us)
#   NAME.crack.{json,csv,txt}            crack measured by tools/crack_measure.py
#   NAME.speed.png                       tip speed vs time, Rayleigh speed 2125 m/s drawn
#   NAME.montage.png                     damage field at 10, 20, ... us
#   summary-NAME.txt                     measured vs thesis vs acceptance
# Usage:
#   bash run.sh                                        the recommended model
#   VARIANT=thesis bash run.sh                         the thesis's method, h = 1.33 and 2 dx
#   NAME=rebuild bash run.sh -var corr rebuild         one variant: any -var of in.crack-branching
#   NAME=thesis-abs bash run.sh -var model thesis -var crit absolute
# Environment: LMP_TLSPH (default ../../build/lmp_tlsph), TLSPH_PYTHON (default
# /usr/bin/python3), NP (MPI ranks, default 1), FORCE=0 to keep a finished run,
# PROGRESS=1 for a progress line every 5 s.
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
elif [ "${VARIANT:-recommended}" = recommended ]; then
  one crack-branching "$@"
  cp out/summary-crack-branching.txt out/summary.txt
  echo "summary: out/summary.txt"
elif [ "${VARIANT}" = thesis ]; then
  one crack-branching-thesis -var model thesis "$@"
  one crack-branching-thesis-h2 -var model thesis -var hdx 2.0 -var tend 90e-6 "$@"
  cat out/summary-crack-branching-thesis.txt out/summary-crack-branching-thesis-h2.txt \
    > out/summary-thesis.txt
  echo "both summaries: out/summary-thesis.txt"
else
  echo "run.sh: VARIANT must be recommended or thesis, not '${VARIANT}'" >&2
  exit 1
fi
