#!/bin/bash
# Run one case of an example deck, skipping it if its log already finished.
#   run_case.sh DECK OUTDIR NAME [-var NAME VALUE ...]
# Writes OUTDIR/NAME.log (LAMMPS log), OUTDIR/NAME.dat (fix print), OUTDIR/NAME.screen,
# and runs a copy of the deck, OUTDIR/NAME.in (LAMMPS reads its input as it
# goes: editing the deck during a run must not change or break that run).
# Environment: LMP_TLSPH (executable, default <repo>/build/lmp_tlsph),
#              NP (MPI ranks, default 1), FORCE=1 reruns finished cases,
#              PROGRESS=1 prints a progress line every PROGRESS_EVERY (5) s.
set -u
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
lmp="${LMP_TLSPH:-$here/../../build/lmp_tlsph}"
deck="$1"; outdir="$2"; name="$3"; shift 3
mkdir -p "$outdir"
log="$outdir/$name.log"
if [ "${FORCE:-0}" != 1 ] && grep -q "^Total wall time" "$log" 2>/dev/null; then
  echo "[skip] $name (finished: $log)"
  exit 0
fi
np="${NP:-1}"
if [ "$np" -gt 1 ]; then
  launch=(mpirun --allow-run-as-root --oversubscribe -np "$np" "$lmp")
else
  launch=("$lmp")
fi
echo "[run ] $name: ${launch[*]} -in $deck $*"
start=$(date +%s)
cp "$deck" "$outdir/$name.in"
md5sum "$lmp" > "$outdir/$name.binary"
rm -f "$log"
"${launch[@]}" -in "$outdir/$name.in" -log "$log" -var out "$outdir/$name" "$@" > "$outdir/$name.screen" 2>&1 &
pid=$!
# PROGRESS=1: a line every PROGRESS_EVERY s (default 5) with the simulated
# time, steps/s and the time left, read from the log (progress.py)
if [ "${PROGRESS:-0}" = 1 ]; then
  "${TLSPH_PYTHON:-/usr/bin/python3}" "$here/progress.py" "$log" --name "$name" \
    --every "${PROGRESS_EVERY:-5}" --pid "$pid" &
  ppid=$!
fi
wait "$pid"
rc=$?
if [ -n "${ppid:-}" ]; then kill "$ppid" 2>/dev/null; wait "$ppid" 2>/dev/null; fi
echo "[done] $name rc=$rc $(( $(date +%s) - start )) s"
exit $rc
