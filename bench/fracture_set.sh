#!/usr/bin/env bash
# A set of bench/fracture.sh settings side by side on the fracture
# benchmarks, Kalthoff-Winkler 2D at KDX and the crack-branching plate at
# BDX, two settings at a time (one per core), then the report bench/NAME.md
# (bench/fracture_report.py, with bench/NAME-notes.md after its title).
# Runs are resumable (FORCE=1 makes them again): bench/out/fracture/<setting>/;
# each setting's log in bench/out/NAME-<k>.txt.
#   bash bench/fracture_set.sh NAME "TITLE" SETTING...
# (bench/kfit_interaction.sh, kfit_inertia.sh, branch_step.sh, tipdir_segment.sh,
# tstress_scan.sh, tstress_dynamic_scan.sh, kfit_j_tstress.sh, kw_speed.sh and
# kratio_running.sh call it)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if [ $# -lt 3 ]; then
  echo "usage: bench/fracture_set.sh NAME TITLE SETTING..." >&2
  exit 2
fi
name=$1 title=$2
shift 2
export KDX="${KDX-1.67 1.33 1.11 1.0 0.833 0.667 0.5}" BDX="${BDX-0.5 0.333 0.286 0.222}" NO_REPORT=1
mkdir -p "$HERE/out"
k=0
settings=("$@")    # (an odd count: the last pair has one setting)
for ((i = 0; i < ${#settings[@]}; i += 2)); do
  pids=()
  for s in "${settings[@]:i:2}"; do
    k=$((k + 1))
    bash "$HERE/fracture.sh" "$s" > "$HERE/out/$name-$k.txt" 2>&1 &
    pids+=($!)
  done
  wait "${pids[@]}"
done
/usr/bin/python3 "$HERE/fracture_report.py" --out "$HERE/out/fracture" --doc "$HERE/$name.md" \
  --title "$title" --intro "$HERE/$name-notes.md" "${settings[@]}"
