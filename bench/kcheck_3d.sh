#!/usr/bin/env bash
# The tips' K, mode ratio and T-stress in 3D against 2D (issue 26, "3D K and
# T through the thickness"): bench/in.kcheck's central crack 2a = 10 mm in an
# 80 x 80 mm glass plate, relaxed to rest under 1 MPa (mode I: tension on the
# top and bottom edges; mode mixed: tension and shear, K_I = K_II), kfit
# interaction tipdir segment, dx = 1 mm, as 2D plane strain and as 3D slabs
# with the crack through the thickness (-var nz): 8 layers with periodic
# faces (plane strain again), and 4 and 8 layers (4 and 8 mm) with free
# faces. Two runs at a time; each run's commit and binary go to
# bench/out/kcheck-3d/runs.txt. Writes bench/kcheck-3d.md (bench/kcheck_3d.py).
#   bash bench/kcheck_3d.sh            (LMP_TLSPH= another binary)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
LMP="${LMP_TLSPH:-$HERE/../build/lmp_tlsph}"
OUT="$HERE/out/kcheck-3d"
mkdir -p "$OUT"
run() {    # geometry (2d | pNZ | sNZ) mode
  local g=$1 mode=$2 log nz=0 zb=p
  case "$g" in p*) nz=${g#p}; zb=p ;; s*) nz=${g#s}; zb=s ;; esac
  log="$OUT/k3-$g-$mode.log"
  if [ "${FORCE:-0}" != 1 ] && grep -q "^Total wall time" "$log" 2>/dev/null; then return 0; fi
  echo "$(basename "$log") $(git -C "$HERE" describe --always --dirty) $(md5sum < "$LMP" | cut -c1-12)" >> "$OUT/runs.txt"
  (cd "$OUT" && "$LMP" -in "$HERE/in.kcheck" -var dx 0.001 -var mode "$mode" -var kfit interaction \
    -var tipdir segment -var nz "$nz" -var zb "$zb" -var chunk 1000 -var nchunk 10 -log "$log" \
    -screen none > /dev/null)
  echo "kcheck_3d: $g $mode done" >&2
}
export -f run
export HERE LMP OUT
for g in 2d p8 s4 s8; do printf '%s I\n%s mixed\n' "$g" "$g"; done | xargs -P 2 -L 1 bash -c 'run "$0" "$1"'
/usr/bin/python3 "$HERE/kcheck_3d.py" --out "$OUT" --doc "$HERE/kcheck-3d.md"
