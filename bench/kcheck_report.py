#!/usr/bin/env python3
"""bench/kcheck.md from the logs of bench/kcheck.sh: the K_I, K_II that
compute tlsph/crack/tips reports for the two tips of a central crack at the
end of the relaxation, against K = load sqrt(pi a) F(a/b) (Tada's finite-width
factor of a central crack in a strip of width 2b: F = (1 - 0.025 l^2 +
0.06 l^4) sqrt(sec(pi l / 2)), l = a / b, for mode I; taken the same for mode
II, where for l = 0.125 any finite-width factor is within 1 % of 1), and the
change over the last report interval (how far from static the run still was).
Plain Python."""
import datetime
import math
import os
import re
import sys

rings_only = len(sys.argv) > 1 and sys.argv[1] == "--rings"
if rings_only:
    out, commit, dxs = sys.argv[2], "", []
else:
    out, commit, dxs = sys.argv[1], sys.argv[2], sys.argv[3:]
A, W, LOAD = 0.005, 0.08, 1.0e6
lam = A / (W / 2)
F = (1 - 0.025 * lam ** 2 + 0.06 * lam ** 4) * math.sqrt(1 / math.cos(math.pi * lam / 2))
K0 = LOAD * math.sqrt(math.pi * A) * F


def rows(path):
    """thermo rows of the run: step, time, K1_I, K1_II, K2_I, K2_II, ke, se, resets (and, since
    in.kcheck reports them, the two tips' T-stress)"""
    r, on = [], False
    try:
        lines = open(path).readlines()
    except OSError:
        return r
    for line in lines:
        if line.startswith("Step"):
            on = True
            continue
        if on:
            w = line.split()
            if len(w) in (9, 11) and re.match(r"^\d+$", w[0]):
                r.append([float(x) for x in w])
            elif line.startswith("Loop time"):
                on = False
    return r


if rings_only:
    # kfit j's ring scan at dx = 0.5 mm (logs kring-R1-R2-MODE.log; the
    # model's ring 2 4 is the main table's run k-j-MODE-0.0005.log)
    print("| r1 / h | r2 / h | mode I: K / reference | mode II: K / reference |")
    print("|---:|---:|---:|---:|")
    for ring in os.environ.get("JRINGS", "2,4").split():
        r1, r2 = ring.split(",")
        cells = []
        for mode, col in (("I", 2), ("II", 3)):
            p = "%s/kring-%s-%s-%s.log" % (out, r1, r2, mode)
            if ring == "2,4":
                p = "%s/k-j-%s-0.0005.log" % (out, mode)
            r = rows(p)
            cells.append("%.4f" % (0.5 * (abs(r[-1][col]) + abs(r[-1][col + 2])) / K0) if r else "run failed")
        print("| %s | %s | %s | %s |" % (r1, r2, cells[0], cells[1]))
    sys.exit(0)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from machine import cpu_model  # noqa: E402
cpu = cpu_model()
print("# Stress intensity factors of crack-tip tracking against theory (bench/kcheck.sh)\n")
print("- date: %s, commit `%s`, CPU: %s" % (datetime.datetime.now().strftime("%Y-%m-%d %H:%M"), commit, cpu))
print("- bench/in.kcheck: central crack 2a = %g mm on y = 0 in a %g x %g mm glass plate (E 32 GPa, nu 0.2), "
      "2D plane strain, the recommended model (h = 1.33 dx, pair_style tlsph/damage criterion tip, gamma 0; "
      "gamma 1: the same with the hourglass control on), "
      "G_c 1e9 J/m^2 (nothing grows), remote tension (mode I) or shear (mode II) of %g MPa as edge "
      "tractions, fix tlsph/relax; K from compute tlsph/crack/tips at the end (8 report intervals of "
      "about one wave transit each); kfit tip: the fit anchored at the path's end (the default), "
      "kfit offset: the tip's effective position fitted too; kfit j: the size of K from the domain "
      "J-integral over the ring 2h-4h about the tip (jring 2 4), the mode ratio from the anchored fit "
      "(tlsph_crack.h)" % (2e3 * A, 1e3 * W, 1e3 * W, LOAD / 1e6))
print("- reference: K = load sqrt(pi a) F(a/b) = %.1f Pa m^0.5 (F = %.4f, a/b = %.3f; Tada's "
      "finite-width factor, the same for mode II)\n" % (K0, F, lam))
print("| gamma | kfit | mode | dx [mm] | a / h | K, tip 1 | K, tip 2 | K / reference | error | other mode's "
      "K / reference | change over the last interval |")
print("|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
for gamma in os.environ.get("GAMMAS", "0.0").split():
 for kfit in os.environ.get("KFITS", "tip offset").split():
  tag = kfit if gamma == "0.0" else "%s-g%s" % (kfit, gamma)
  for mode in ("I", "II"):
    for dx in dxs:
        r = rows("%s/k-%s-%s-%s.log" % (out, tag, mode, dx))
        if len(r) < 2:
            print("| %s | %s | %s | %.3f | - | run failed | | | | | |" % (gamma, kfit, mode, 1e3 * float(dx)))
            continue
        last, prev = r[-1], r[-2]
        col = 2 if mode == "I" else 3
        k1, k2 = last[col], last[col + 2]
        other = max(abs(last[5 - col]), abs(last[7 - col])) if mode == "I" else max(abs(last[2]), abs(last[4]))
        km = 0.5 * (abs(k1) + abs(k2))
        change = abs(km - 0.5 * (abs(prev[col]) + abs(prev[col + 2]))) / km if km else float("nan")
        h = 1.33 * float(dx)
        print("| %s | %s | %s | %.3f | %.2f | %.1f | %.1f | %.4f | %+.1f %% | %.2g | %.2g %% |" % (
            gamma, kfit, mode, 1e3 * float(dx), A / h, k1, k2, km / K0, 100 * (km / K0 - 1), other / K0, 100 * change))
