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
# KFITS may also hold j (kfit j: the size of K from the domain J-integral);
# with j, the J domain's ring (jring R1 R2, in h) is scanned at dx = 0.5 mm
# (JRINGS). REPORT names the report (default bench/kcheck.md).
#   bash bench/kcheck.sh            (LMP_TLSPH= another binary; DXS="0.001 0.0005")
#   KFITS=j GAMMAS=0.0 REPORT=kcheck-j.md bash bench/kcheck.sh   (bench/kcheck-j.md)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
LMP="${LMP_TLSPH:-$HERE/../build/lmp_tlsph}"
OUT="$HERE/out/kcheck"
mkdir -p "$OUT"
DXS="${DXS:-0.001 0.0005 0.000333333333333}"
KFITS="${KFITS:-tip offset}"
# gamma 0 (the recommended model) and 1 (hourglass control on)
GAMMAS="${GAMMAS:-0.0 1.0}"
REPORT="$HERE/${REPORT:-kcheck.md}"
# kfit j: the ring scanned (r1,r2 pairs, in h; the model's is 2,4)
JRINGS="${JRINGS:-1,4 3,4 2,3 2,8 4,8}"
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
# kfit j: the J domain's ring at dx = 0.5 mm
if [[ " $KFITS " == *" j "* ]]; then
  for ring in $JRINGS; do
    r1=${ring%,*} r2=${ring#*,}
    pids=()
    for mode in I II; do
      (cd "$OUT" && "$LMP" -in "$HERE/in.kcheck" -var dx 0.0005 -var mode "$mode" -var kfit j \
        -var jr1 "$r1" -var jr2 "$r2" -var gamma 0.0 -var dumps no -var chunk 2000 -var nchunk 8 \
        -log "$OUT/kring-$r1-$r2-$mode.log" -screen none > /dev/null) &
      pids+=($!)
    done
    for p in "${pids[@]}"; do wait "$p"; done
    echo "kcheck: ring $r1 $r2 done" >&2
  done
fi
commit=$(git -C "$HERE/.." describe --always --dirty 2>/dev/null || echo unknown)
{ KFITS="$KFITS" GAMMAS="$GAMMAS" python3 "$HERE/kcheck_report.py" "$OUT" "$commit" $DXS
  if [[ " $KFITS " == *" j "* ]]; then
    echo
    echo "## The J domain's ring (kfit j, dx = 0.5 mm, gamma 0)"
    echo
    echo "q = 1 inside r1, falling linearly to 0 at r2 (jring r1 r2, in h); the model's ring is 2 4."
    echo
    JRINGS="2,4 $JRINGS" python3 "$HERE/kcheck_report.py" --rings "$OUT"
  fi
  if [[ " $KFITS " == *" tip "* ]]; then
    echo
    echo "## The sampling constants (bench/kcheck_scan.py, on the fields of the runs above)"
    echo
    echo "The start r0 of the four samples (r = r0 + 0.5 h k) and the radius of their discs, each at half, at and at"
    echo "twice the model's value (1.5 h), with both fits, re-implemented in Python from grow_tips and tlsph_crack.h;"
    echo "the model's values give the K of the table above."
    echo
    python3 "$HERE/kcheck_scan.py" "$OUT" $DXS
  fi; } > "$REPORT"
cat "$REPORT"
