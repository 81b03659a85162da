#!/usr/bin/env bash
# K at a kinked crack tip, and the kink the tip model would take from it
# (issue 26, "each ingredient verified": bench/kcheck.md checks K on straight
# cracks only, while every segment a tip grows starts at a kink).
# bench/in.kcheck with -var kink: a central crack 2a = 40 mm in a 120 x 120 mm
# glass plate (2D plane strain, relaxed to rest, nothing grows) whose right
# end carries a straight kink of KL h at THETA deg, under equibiaxial tension
# (mode biaxial: K_II = 0 and T = 0 at the main crack's tips) and under
# uniaxial tension normal to the crack (mode I: T = -sigma), with the
# recommended fit (kfit j: K_II / K_I from the faces' displacement jump) and
# with kfit interaction (the ratio from interaction integrals) (KFITS).
# Modes, angles and kink lengths at dx = 1 mm (THETAS, KLS), a subset at
# 0.5 mm with kfit j (SUB05); two runs at a time. Each run's commit and
# binary go to bench/out/kcheck-kink/runs.txt. Writes bench/kcheck-kink.md
# (bench/kcheck_kink.py).
#   bash bench/kcheck_kink.sh            (LMP_TLSPH= another binary)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
LMP="${LMP_TLSPH:-$HERE/../build/lmp_tlsph}"
OUT="$HERE/out/kcheck-kink"
mkdir -p "$OUT"
THETAS="${THETAS:-10 20 40}"
KLS="${KLS:-4.5 9 18}"
KFITS="${KFITS:-j interaction}"
SUB05="${SUB05:-j:biaxial:10:4.5 j:biaxial:20:4.5 j:biaxial:20:9 j:I:20:4.5}"
cases=()
for fit in $KFITS; do
  for mode in biaxial I; do
    for th in $THETAS; do
      for kl in $KLS; do cases+=("0.001:$fit:$mode:$th:$kl"); done
    done
  done
done
for c in $SUB05; do cases+=("0.0005:$c"); done
run() {    # dx:kfit:mode:theta:kl
  local dx fit mode th kl chunk log
  IFS=: read -r dx fit mode th kl <<< "$1"
  # steps between reports: about one wave transit of the 120 mm plate
  chunk=$(python3 -c "print(round(1.5e-3 / $dx * 1000))")
  log="$OUT/kink-$fit-$mode-$th-$kl-$dx.log"
  if [ "${FORCE:-0}" != 1 ] && grep -q "^Total wall time" "$log" 2>/dev/null; then return 0; fi
  echo "$(basename "$log") $(git -C "$HERE" describe --always --dirty) $(md5sum < "$LMP" | cut -c1-12)" >> "$OUT/runs.txt"
  (cd "$OUT" && "$LMP" -in "$HERE/in.kcheck" -var dx "$dx" -var mode "$mode" -var kfit "$fit" \
    -var a 0.02 -var W 0.12 -var H 0.12 -var kink "$th" -var kinkl "$kl" \
    -var chunk "$chunk" -var nchunk 8 -log "$log" -screen none > /dev/null)
  echo "kcheck_kink: $1 done" >&2
}
export -f run
export HERE LMP OUT
printf '%s\n' "${cases[@]}" | xargs -P 2 -I{} bash -c 'run {}'
/usr/bin/python3 "$HERE/kcheck_kink.py" --out "$OUT" --doc "$HERE/kcheck-kink.md"
