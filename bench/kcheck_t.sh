#!/usr/bin/env bash
# The T-stress of kfit interaction (the point-force interaction integral that
# tipdir segment and branch tstress read) on a straight crack at rest, at
# three resolutions (issue 26, "each ingredient verified"): bench/in.kcheck,
# a central crack 2a = 10 mm in an 80 x 80 mm glass plate (2D plane strain,
# relaxed to rest, nothing grows), 1 MPa on the top and bottom edges (mode I:
# T = -sigma for a crack small against the plate) and on all four edges
# (mode biaxial: T = 0), kfit interaction tipdir segment, dx = DXS. Two runs
# at a time; each run's commit and binary go to bench/out/kcheck-t/runs.txt.
# Writes bench/kcheck-t.md (bench/kcheck_t.py).
#   bash bench/kcheck_t.sh            (LMP_TLSPH= another binary)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
LMP="${LMP_TLSPH:-$HERE/../build/lmp_tlsph}"
OUT="$HERE/out/kcheck-t"
mkdir -p "$OUT"
DXS="${DXS:-0.001 0.0005 0.000333333333333}"
run() {    # dx mode
  local dx=$1 mode=$2 chunk log
  # steps between reports: about one wave transit of the plate (as bench/kcheck.sh)
  chunk=$(python3 -c "print(round(1.0e-3 / $dx * 1000))")
  log="$OUT/t-$mode-$dx.log"
  if [ "${FORCE:-0}" != 1 ] && grep -q "^Total wall time" "$log" 2>/dev/null; then return 0; fi
  echo "$(basename "$log") $(git -C "$HERE" describe --always --dirty) $(md5sum < "$LMP" | cut -c1-12)" >> "$OUT/runs.txt"
  (cd "$OUT" && "$LMP" -in "$HERE/in.kcheck" -var dx "$dx" -var mode "$mode" -var kfit interaction \
    -var tipdir segment -var chunk "$chunk" -var nchunk 8 -log "$log" -screen none > /dev/null)
  echo "kcheck_t: $dx $mode done" >&2
}
export -f run
export HERE LMP OUT
for dx in $DXS; do printf '%s I\n%s biaxial\n' "$dx" "$dx"; done | xargs -P 2 -L 1 bash -c 'run "$0" "$1"'
/usr/bin/python3 "$HERE/kcheck_t.py" --out "$OUT" --doc "$HERE/kcheck-t.md"
