#!/usr/bin/env bash
# Can a threshold on G separate the fracture benchmarks? The recommended
# model without branching, without and with J's inertia term, and with
# segments of 9 and 18 h, and with the mode ratio from the interaction
# integrals (bench/fracture.sh settings tipg-j, tipg-jin, tipg-j-seg-9,
# tipg-j-seg-18, tipg-i), on
# Kalthoff-Winkler 2D at KDX and the glass plate at BDX, the two decks at
# once (one per core), then the report bench/branch-g.md (bench/branch_g.py,
# with bench/branch-g-notes.md after its title). Runs are resumable (FORCE=1
# makes them again): bench/out/fracture/tipg-*/.
#   bash bench/branch_g.sh
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mkdir -p "$HERE/out"
# (bench/zigzag_segment.sh runs other settings into another report:
# BRANCH_G_SETTINGS, BRANCH_G_NAME, BRANCH_G_TITLE)
read -r -a settings <<< "${BRANCH_G_SETTINGS:-tipg-j tipg-jin tipg-j-seg-9 tipg-j-seg-18 tipg-i}"
name="${BRANCH_G_NAME:-branch-g}"
for s in "${settings[@]}"; do
  KDX="${KDX-1.67 1.33 1.11 1.0 0.833 0.667 0.5}" BDX="" NO_REPORT=1 \
    bash "$HERE/fracture.sh" "$s" > "$HERE/out/$name-$s-k.txt" 2>&1 &
  k=$!
  KDX="" BDX="${BDX-0.5 0.333 0.286 0.222}" NO_REPORT=1 \
    bash "$HERE/fracture.sh" "$s" > "$HERE/out/$name-$s-b.txt" 2>&1 &
  b=$!
  wait "$k" "$b"
done
title=()
[ -n "${BRANCH_G_TITLE:-}" ] && title=(--title "$BRANCH_G_TITLE")
/usr/bin/python3 "$HERE/branch_g.py" --out "$HERE/out/fracture" --doc "$HERE/$name.md" \
  --intro "$HERE/$name-notes.md" "${title[@]}" "${settings[@]}"
