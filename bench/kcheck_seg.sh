#!/usr/bin/env bash
# The kink of 'tipdir segment' checked at rest (issue 26, "each ingredient
# verified"): does a straight segment of the default length s = 4.5 h, laid
# at the kink the rule takes, end in mode I? bench/in.kcheck with -var kink:
# a central crack 2a = 40 mm in a 120 x 120 mm glass plate (2D plane strain,
# relaxed to rest, nothing grows) whose right end carries a straight kink of
# 4.5 h at THETA deg, under uniaxial tension normal to the crack (mode I:
# T = -sigma at the main crack) and equibiaxial tension (T = 0), kfit
# interaction, dx = 1 mm. First the kinked tip alone: its K_I, K_II and
# T-stress give the kink of 'tipdir faces' (the maximum-tangential-stress
# kink) and that of 'tipdir segment'. Then the same crack with a second
# straight segment of 4.5 h from the kink's end, turned by 0, by the faces
# kink and by the segment kink (-var kink2): K_II / K_I at its end, and the
# turn that would zero it (the least-squares line through the three). Two runs at
# a time; each run's commit and binary go to bench/out/kcheck-seg/runs.txt.
# Writes bench/kcheck-seg.md (bench/kcheck_seg.py).
#   bash bench/kcheck_seg.sh            (LMP_TLSPH= another binary)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
LMP="${LMP_TLSPH:-$HERE/../build/lmp_tlsph}"
OUT="$HERE/out/kcheck-seg"
mkdir -p "$OUT"
THETAS="${THETAS:-10 20}"
MODES="${MODES:-I biaxial}"
DX=0.001
run() {    # mode theta kink2|one
  local mode=$1 th=$2 k2=$3 log extra=()
  log="$OUT/seg-$mode-$th-$k2.log"
  [ "$k2" != one ] && extra=(-var kink2 "$k2")
  if [ "${FORCE:-0}" != 1 ] && grep -q "^Total wall time" "$log" 2>/dev/null; then return 0; fi
  echo "$(basename "$log") $(git -C "$HERE" describe --always --dirty) $(md5sum < "$LMP" | cut -c1-12)" >> "$OUT/runs.txt"
  (cd "$OUT" && "$LMP" -in "$HERE/in.kcheck" -var dx "$DX" -var mode "$mode" -var kfit interaction \
    -var tipdir segment -var a 0.02 -var W 0.12 -var H 0.12 -var kink "$th" -var kinkl 4.5 \
    "${extra[@]}" -var chunk 1500 -var nchunk 8 -log "$log" -screen none > /dev/null)
  echo "kcheck_seg: $mode $th $k2 done" >&2
}
export -f run
export HERE LMP OUT DX
# the kinked tips alone, then their kinks (kcheck_seg.py --kinks), then the second segments
cases=()
for m in $MODES; do for th in $THETAS; do cases+=("$m $th one"); done; done
printf '%s\n' "${cases[@]}" | xargs -P 2 -I{} bash -c 'run {}'
cases=()
for m in $MODES; do
  for th in $THETAS; do
    read -r kf ks < <(/usr/bin/python3 "$HERE/kcheck_seg.py" --out "$OUT" --kinks "$m" "$th")
    for k2 in 0 "$kf" "$ks"; do cases+=("$m $th $k2"); done
  done
done
printf '%s\n' "${cases[@]}" | xargs -P 2 -I{} bash -c 'run {}'
/usr/bin/python3 "$HERE/kcheck_seg.py" --out "$OUT" --doc "$HERE/kcheck-seg.md"
