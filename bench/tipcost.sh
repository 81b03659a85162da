#!/usr/bin/env bash
# Cost of crack-tip tracking (pair_style tlsph/damage criterion tip branch
# yoffe) on the crack-branching plate of bench/in.branching (36,000
# particles, 1150 steps ~ 0-40 us: the tip grows from ~14 us), beside the
# same plate with tlsph (no damage) and with the bond-stretch criterion, in
# one invocation, ROUNDS rounds alternating the three (the machine is shared:
# compare the ratios of a round). Prints the Loop times and damage / tlsph - 1.
#   bash bench/tipcost.sh            (ROUNDS=2, 1 rank; LMP_TLSPH= another binary)
set -uo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
LMP="${LMP_TLSPH:-$HERE/../build/lmp_tlsph}"
OUT="$HERE/out/tipcost"
mkdir -p "$OUT"
echo "| round | tlsph [s] | tlsph/damage tension [s] | tlsph/damage tip [s] | tension / tlsph - 1 | tip / tlsph - 1 |"
echo "|---|---|---|---|---|---|"
for r in $(seq 1 "${ROUNDS:-2}"); do
  "$LMP" -in "$HERE/in.branching" -log "$OUT/tlsph-$r.log" -screen none -var damage 0
  "$LMP" -in "$HERE/in.branching" -log "$OUT/tension-$r.log" -screen none -var damage 1
  "$LMP" -in "$HERE/in.branching" -log "$OUT/tip-$r.log" -screen none -var damage 1 -var crit tip
  # the second Loop line is the timed run
  a=$(grep "^Loop time" "$OUT/tlsph-$r.log" | tail -1 | awk '{print $4}')
  b=$(grep "^Loop time" "$OUT/tension-$r.log" | tail -1 | awk '{print $4}')
  c=$(grep "^Loop time" "$OUT/tip-$r.log" | tail -1 | awk '{print $4}')
  /usr/bin/python3 -c "a,b,c=$a,$b,$c; print(f'| {$r} | {a:.2f} | {b:.2f} | {c:.2f} | {100*(b/a-1):+.0f} % | {100*(c/a-1):+.0f} % |')"
done
grep -h "grows\|branches" "$OUT"/tip-1.log | head -3
