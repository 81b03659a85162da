#!/usr/bin/env bash
# Two builds side by side on bench/in.manytips (1 MPa, 110 standing tips):
# tlsph and tlsph/damage criterion tip kfit j, each with build A and build
# B, alternating in ROUNDS (7) rounds of STEPS (1000) steps in one
# invocation; per round each build's tip run over its own tlsph run, and B's
# loop over A's; medians over the rounds. Writes bench/manytips-ab.md
# (STRENGTH=S: crack nucleation with the strength S in both runs of the
# damage style; bench/manytips-ab-strength.md).
#   bash bench/manytips_ab.sh LMP_A LABEL_A LMP_B LABEL_B
# (LABEL: the commit whose clean tree the build was made from)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
A=$1 LA=$2 B=$3 LB=$4
OUT="$HERE/out/manytips-ab"
mkdir -p "$OUT"
: > "$OUT/times.txt"
for r in $(seq 1 "${ROUNDS:-7}"); do
  for side in A B; do
    lmp=$A; [ $side = B ] && lmp=$B
    for m in tlsph tip; do
      "$lmp" -in "$HERE/in.manytips" -var model $m -var kfit j -var steps "${STEPS:-1000}" -var strength "${STRENGTH:-0}" \
        -log "$OUT/$side-$m-$r.log" -screen none > /dev/null
      echo "$r $side $m $(grep '^Loop time' "$OUT/$side-$m-$r.log" | tail -1 | awk '{print $4}')" >> "$OUT/times.txt"
    done
  done
done
REPORT="$HERE/manytips-ab.md"
[ "${STRENGTH:-0}" != 0 ] && REPORT="$HERE/manytips-ab-strength.md"
python3 - "$OUT/times.txt" "$LA" "$LB" "${STEPS:-1000}" "${STRENGTH:-0}" > "$REPORT" <<'PY'
import os, sys, statistics, datetime
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(sys.argv[1])))))  # bench/
from machine import cpu_model  # noqa: E402
t = {}
for line in open(sys.argv[1]):
    r, s, m, x = line.split()
    t[(int(r), s, m)] = float(x)
la, lb, steps, strength = sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5])
rounds = sorted({k[0] for k in t})
print("# Two builds side by side on bench/in.manytips (bench/manytips_ab.sh)\n")
print("- date: %s, CPU: %s, 1 rank; A: a build of `%s`, B: a build of `%s`" % (
    datetime.datetime.now().strftime("%Y-%m-%d %H:%M"), cpu_model(), la, lb))
print("- 16,000 particles, 110 standing crack tips (1 MPa), %s steps; %d rounds, each: A tlsph, A "
      "tlsph/damage criterion tip branch yoffe kfit j%s, then B the same; loop times [s]\n" % (
          steps, len(rounds), ", pair_coeff strength %g Pa (crack nucleation; never reached)" % strength
          if strength > 0 else ""))
print("| round | A tlsph | A kfit j | B tlsph | B kfit j | A kfit j / A tlsph | B kfit j / B tlsph | B kfit j / A kfit j |")
print("|---:|---:|---:|---:|---:|---:|---:|---:|")
ra, rb, rba = [], [], []
for r in rounds:
    a0, a1, b0, b1 = t[(r, "A", "tlsph")], t[(r, "A", "tip")], t[(r, "B", "tlsph")], t[(r, "B", "tip")]
    ra.append(a1 / a0), rb.append(b1 / b0), rba.append(b1 / a1)
    print("| %d | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f |" % (r, a0, a1, b0, b1, ra[-1], rb[-1], rba[-1]))
med = statistics.median
print("| median | | | | | %.3f | %.3f | %.3f |" % (med(ra), med(rb), med(rba)))
PY
cat "$REPORT"
