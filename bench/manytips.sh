#!/usr/bin/env bash
# Cost of many crack tips (issue 26, "Cost and scale"): bench/in.manytips
# (16,000 particles, 110 tips, 300 steps) with tlsph (no damage),
# tlsph/damage criterion tension (no tips) and criterion tip, each with the
# SIMD step and with 'simd no' (the scalar step), in ONE invocation, ROUNDS
# (7) rounds alternating, medians and minima of the loop times; and criterion tip under
# 8x the load (8 MPa), where most tips grow, cut bonds and some branch
# (tip-grow, SIMD step); and criterion tip with kfit j (the recommended
# model: a domain J-integral per tip and step) at 1 MPa and at 16 MPa, where
# most of its tips grow (tipj, tipj-grow; its G is about half kfit tip's, so
# at 8 MPa none grows in the 300 steps), and the same with kratio running (the
# recommended model since c7dc05f: tipjkr, tipjkr-grow). Each round opens and closes with
# tlsph's SIMD step: the last column divides every run by the mean of its
# own round's two, the median over the rounds (the shared machine's speed
# drifts between rounds by more than the tips cost). Then the tips' own work,
# timed inside each tip run (pair tlsph/damage's end-of-run line), over the
# rest of that run's loop. Writes bench/manytips.md.
#   bash bench/manytips.sh          (LMP_TLSPH= another binary)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
LMP="${LMP_TLSPH:-$HERE/../build/lmp_tlsph}"
OUT="$HERE/out/manytips"
mkdir -p "$OUT"
: > "$OUT/times.txt"
for r in $(seq 1 "${ROUNDS:-7}"); do
  for m in tlsph tlsph-scalar tension tension-scalar tip tip-scalar tip-grow tipj tipj-grow tipjkr tipjkr-grow tlsph-end; do
    model=${m%-scalar}
    simd=(); [ "$m" != "$model" ] && simd=(env TLSPH_SIMD=no)
    model=${model%-end}
    load=1e6 kfit=tip kratio=static
    [ "$m" = tip-grow ] && model=tip load=8e6
    [ "$m" = tipj ] && model=tip kfit=j
    [ "$m" = tipj-grow ] && model=tip kfit=j load=16e6
    [ "$m" = tipjkr ] && model=tip kfit=j kratio=running
    [ "$m" = tipjkr-grow ] && model=tip kfit=j kratio=running load=16e6
    "${simd[@]}" "$LMP" -in "$HERE/in.manytips" -var model "$model" -var load "$load" -var kfit "$kfit" -var kratio "$kratio" \
      -log "$OUT/$m-$r.log" -screen none > /dev/null
    echo "$m $(grep '^Loop time' "$OUT/$m-$r.log" | tail -1 | awk '{print $4}')" >> "$OUT/times.txt"
  done
done
commit=$(git -C "$HERE/.." describe --always --dirty 2>/dev/null || echo unknown)
python3 - "$OUT" "$commit" > "$HERE/manytips.md" <<'PY'
import os, re, statistics, sys, platform, datetime
out, commit = sys.argv[1], sys.argv[2]
t = {}
for line in open(out + "/times.txt"):
    m, s = line.split()
    t.setdefault(m, []).append(float(s))
# per round: each time over the round's own tlsph baseline, the mean of the
# SIMD tlsph runs that open and close the round (the machine's speed drifts
# from round to round by more than the tips' cost); the median over rounds
base = [0.5 * (a + b) for a, b in zip(t["tlsph"], t["tlsph-end"])]
rr = {m: statistics.median(x / b for x, b in zip(v, base)) for m, v in t.items()}
med = {m: statistics.median(v) for m, v in t.items()}
low = {m: min(v) for m, v in t.items()}
tips = len(re.findall(r"crack tip at", open(out + "/tip-1.log").read()))
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(out))))  # bench/
from machine import cpu_model  # noqa: E402
cpu = cpu_model()
print("# Cost of many crack tips (bench/manytips.sh)\n")
print("- date: %s, commit `%s`, CPU: %s, 1 rank" % (datetime.datetime.now().strftime("%Y-%m-%d %H:%M"), commit, cpu))
print("- bench/in.manytips: 16,000 particles, %d crack tips, 300 steps; %d round(s) alternating in one "
      "invocation; loop time: the median and the fastest of the rounds; the ratios of the medians, and "
      "in the next-to-last column of the fastest runs (the machine is shared: the fastest run is the least "
      "disturbed one); in the last column each run over its own round's tlsph (SIMD step; the mean of "
      "the runs that open and close the round), the median over the rounds\n" % (tips, len(t["tip"])))
print("| model | step | loop time [s], median | fastest [s] | / tlsph, same step | / tlsph (SIMD step) "
      "| / tension, same step | / tlsph (SIMD step), fastest runs | / tlsph (SIMD step) of the same round, median |")
print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
names = {"tlsph": "tlsph", "tension": "tlsph/damage criterion tension (no tips)",
         "tip": "tlsph/damage criterion tip branch yoffe"}
for m in ("tlsph", "tlsph-scalar", "tension", "tension-scalar", "tip", "tip-scalar"):
    base, scalar = m.split("-")[0], m.endswith("-scalar")
    suf = "-scalar" if scalar else ""
    print("| %s | %s | %.3f | %.3f | %.2f | %.2f | %.2f | %.2f | %.2f |" % (
        names[base], "simd no (scalar)" if scalar else "SIMD step", med[m], low[m], med[m] / med["tlsph" + suf],
        med[m] / med["tlsph"], med[m] / med["tension" + suf], low[m] / low["tlsph"], rr[m]))
for m, label, mpa in (("tip-grow", "tlsph/damage criterion tip branch yoffe", 8),
                      ("tipj", "tlsph/damage criterion tip branch yoffe kfit j", 1),
                      ("tipj-grow", "tlsph/damage criterion tip branch yoffe kfit j", 16),
                      ("tipjkr", "tlsph/damage criterion tip branch yoffe kfit j kratio running (the recommended model)", 1),
                      ("tipjkr-grow", "tlsph/damage criterion tip branch yoffe kfit j kratio running", 16)):
    g = open(out + "/" + m + "-1.log").read()
    if m.endswith("grow"):
        label += ", %d MPa: %d tips grow, %d branch, %d stop at another crack, %d leave the body (round 1)" % (
            mpa, len(re.findall(r"grows, K_I", g)), len(re.findall(r"branches", g)),
            len(re.findall(r"where it meets another crack", g)), len(re.findall(r"outside the body", g)))
    print("| %s | SIMD step | %.3f | %.3f | %.2f | %.2f | %.2f | %.2f | %.2f |" % (
        label, med[m], low[m], med[m] / med["tlsph"], med[m] / med["tlsph"], med[m] / med["tension"],
        low[m] / low["tlsph"], rr[m]))
print("\n(tlsph's and tension's cost does not depend on the load: the rows under 1 MPa are their baseline. "
      "Under 1 MPa no tip grows: the tips' cost there is their K measurement every step.)")
# the tips' own work timed inside each run (pair tlsph/damage's end-of-run
# line): its ratio to the rest of the same run's loop does not see the drift
# between runs that moves the loop times above
rows = []
for m, label in (("tip", "criterion tip branch yoffe (kfit tip), 1 MPa, standing"),
                 ("tip-scalar", "the same, simd no (scalar)"),
                 ("tip-grow", "the same, 8 MPa, growing"),
                 ("tipj", "criterion tip branch yoffe kfit j, 1 MPa, standing"),
                 ("tipj-grow", "the same, 16 MPa, growing"),
                 ("tipjkr", "criterion tip branch yoffe kfit j kratio running (the recommended model), 1 MPa, standing"),
                 ("tipjkr-grow", "the same, 16 MPa, growing")):
    sh = []
    for r in range(1, len(t[m]) + 1):
        g = re.search(r"crack tips' work ([\d.eE+-]+) s of the loop's ([\d.eE+-]+) s", open("%s/%s-%d.log" % (out, m, r)).read())
        if g:
            w, L = float(g.group(1)), float(g.group(2))
            sh.append(w / (L - w))
    if sh:
        rows.append("| %s | %.3f | %.3f | %.3f |" % (label, statistics.median(sh), min(sh), max(sh)))
ir_note = ""
try:
    g = re.search(r"^\| tlsph/damage criterion tension \(no tips\) \| [^|]+ \| ([\d.]+) \|",
                  open(out + "/../../manytips-ir.md").read(), re.M)
    ir_note = ", which take %.3fx tlsph's instructions (bench/manytips-ir.md, its own commit)" % float(g.group(1))
except Exception:
    pass
if rows:
    print("\nThe tips' own work (measuring, turning, growing, splitting, nucleating, the cut particles' pass 1 "
          "again), timed inside each run and printed by pair tlsph/damage at its end, over the rest of the "
          "same run's loop: a ratio the drift between runs does not move (each run slows as a whole). The "
          "rest is tlsph's step plus the damage style's bookkeeping and velocity filter%s. %d rounds.\n"
          % (ir_note, len(t["tip"])))
    print("| model | tips' work / rest of the loop, median | lowest | highest |")
    print("|---|---:|---:|---:|")
    print("\n".join(rows))
PY
cat "$HERE/manytips.md"
