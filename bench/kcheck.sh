#!/usr/bin/env bash
# K_I and K_II of crack-tip tracking against theory (issue 26, "each
# ingredient verified"): bench/in.kcheck (a central crack 2a = 10 mm in an
# 80 x 80 mm glass plate, 2D plane strain, remote tension or remote shear of
# 1 MPa, relaxed to its static state; nothing grows) at dx = 1, 0.5 and
# 0.333 mm (DXS), with both K fits of the tips (KFITS: kfit tip, the
# default, and kfit offset), at gamma 0 (the recommended model) and gamma 1
# (GAMMAS), modes I and II side by side on two cores. Writes
# bench/kcheck.md (bench/kcheck_report.py; the sampling constants scanned on
# the relaxed fields by bench/kcheck_scan.py).
#   bash bench/kcheck.sh            (LMP_TLSPH= another binary; DXS="0.001 0.0005")
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
LMP="${LMP_TLSPH:-$HERE/../build/lmp_tlsph}"
OUT="$HERE/out/kcheck"
mkdir -p "$OUT"
DXS="${DXS:-0.001 0.0005 0.000333333333333}"
KFITS="${KFITS:-tip offset}"
# gamma 0 (the recommended model) and 1 (hourglass control on)
GAMMAS="${GAMMAS:-0.0 1.0}"
for dx in $DXS; do
  # steps between reports: about one wave transit of the plate (c ~ 3600 m/s)
  chunk=$(python3 -c "print(round(1.0e-3 / $dx * 1000))")
  for gamma in $GAMMAS; do
  for kfit in $KFITS; do
    pids=()
    for mode in I II; do
      # the fields do not depend on the fit (nothing grows): dumped once, at gamma 0
      dumps=no; [ "$kfit" = tip ] && [ "$gamma" = 0.0 ] && dumps=yes
      tag=$kfit; [ "$gamma" = 0.0 ] || tag=$kfit-g$gamma
      (cd "$OUT" && "$LMP" -in "$HERE/in.kcheck" -var dx "$dx" -var mode "$mode" -var kfit "$kfit" \
        -var gamma "$gamma" -var dumps "$dumps" -var chunk "$chunk" -var nchunk 8 \
        -log "$OUT/k-$tag-$mode-$dx.log" -screen none > /dev/null) &
      pids+=($!)
    done
    for p in "${pids[@]}"; do wait "$p"; done
    echo "kcheck: dx $dx kfit $kfit gamma $gamma done" >&2
  done
  done
done
commit=$(git -C "$HERE/.." describe --always --dirty 2>/dev/null || echo unknown)
{ KFITS="$KFITS" GAMMAS="$GAMMAS" python3 "$HERE/kcheck_report.py" "$OUT" "$commit" $DXS
  echo
  echo "## The sampling constants (bench/kcheck_scan.py, on the fields of the runs above)"
  echo
  echo "The start r0 of the four samples (r = r0 + 0.5 h k) and the radius of their discs, each at half, at and at"
  echo "twice the model's value (1.5 h), with both fits, re-implemented in Python from grow_tips and tlsph_crack.h;"
  echo "the model's values give the K of the table above."
  echo
  python3 "$HERE/kcheck_scan.py" "$OUT" $DXS; } > "$HERE/kcheck.md"
cat "$HERE/kcheck.md"
