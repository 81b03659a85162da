"""The crack-branching deck's consistent edge load (-var load consistent) as a test.

Runs examples/crack-branching/in.crack-branching at dx = 1 mm (4,000
particles) for 2 us with the load given as the nodal forces that make the
uniform state sigma_yy = sigma0 an exact equilibrium (in.consistent-load), and
checks what the deck prints of them:

  * the resultant on the top edge is +sigma0 Lx and on the bottom edge
    -sigma0 Lx, to 1e-6 relative (the forces are measured, not prescribed:
    a band too narrow to hold every particle the uniform state loads, 3 dx
    instead of 4h, gives +0.85 %; measured at dx = 0.333 mm);
  * no net force along x (the state has sigma_xx = 0), below 1e-6 sigma0 Lx;
  * the top row carries more than sigma0 dx per particle and the rows below
    it less (the spread is the kernel's; with the nodal load the top row
    would carry exactly sigma0 dx);
  * a bad value of 'load' stops with an error that names it.

    check_consistent_load.py --lmp LMP --example DIR --workdir DIR
Prints PASSED or FAILED (ctest matches PASSED) and exits 0 / 1.
"""

import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import example_args, verdict  # noqa: E402

SIGMA0, LX, DX = 1.0e6, 0.1, 1.0e-3


def run(a, prefix, *extra):
    cmd = [a.lmp, "-in", os.path.join(a.example, "in.crack-branching"), "-log", prefix + ".log",
           "-screen", "none", "-var", "out", prefix, "-var", "dx", repr(DX), "-var", "tend", "2e-6",
           "-var", "timg", "0", "-var", "here", a.example] + list(extra)
    p = subprocess.run(cmd, capture_output=True, text=True)
    with open(prefix + ".log") as f:
        return p.returncode, f.read()


def main():
    a = example_args("crack-branching")
    rc, log = run(a, os.path.join(a.workdir, "consistent"), "-var", "load", "consistent")
    m = re.search(r"^consistent load: resultant top (\S+) N, bottom (\S+) N, x (\S+) N", log, re.M)
    if rc != 0 or not m or "Total wall time" not in log:
        print(log[-2000:])
        print("FAILED: the run did not finish (exit %d) or printed no resultant" % rc)
        return 1
    top, bot, rx = (float(v) for v in m.groups())
    total = SIGMA0 * LX
    print("resultant top %.9g N, bottom %.9g N, x %.3g N; sigma0 Lx = %.9g N" % (top, bot, rx, total))
    # the spread over the rows: the deck once more, its final run replaced by a
    # zero-step run that dumps the external force of every particle
    rows = {}
    dump = os.path.join(a.workdir, "rows-force.dump")
    extra = os.path.join(a.workdir, "rows.in")
    with open(extra, "w") as f:
        f.write("dump r all custom 1 %s id y v_fye\ndump_modify r sort id\nrun 0 post no\n" % dump)
    cmd = [a.lmp, "-log", os.path.join(a.workdir, "rows.log"), "-screen", "none",
           "-var", "out", os.path.join(a.workdir, "rows"), "-var", "dx", repr(DX),
           "-var", "timg", "0", "-var", "here", a.example, "-var", "load", "consistent"]
    deck = open(os.path.join(a.example, "in.crack-branching")).read()
    deck = re.sub(r"^run\s.*$", "include %s" % extra, deck, flags=re.M)
    p = subprocess.run(cmd, input=deck, capture_output=True, text=True)
    if p.returncode == 0 and os.path.exists(dump):
        with open(dump) as f:
            lines = f.read().split("ITEM: ATOMS")[-1].strip().splitlines()[1:]
        for ln in lines:
            _, y, fy = ln.split()
            y, fy = float(y), float(fy)
            if y > 0.02:
                r = int(round((0.04 - y) / DX - 0.5))
                rows[r] = rows.get(r, 0.0) + fy
    per = {r: rows[r] / (LX / DX) / (SIGMA0 * DX) for r in sorted(rows) if r < 6}
    print("top rows, mean force per particle / (sigma0 dx):",
          ", ".join("row %d %.4f" % (r, v) for r, v in per.items()))
    rc3, log3 = run(a, os.path.join(a.workdir, "bad"), "-var", "load", "pressure")
    bad_named = rc3 != 0 and "load must be nodal or consistent, not pressure" in log3
    return verdict([
        ("top resultant = sigma0 Lx to 1e-6", abs(top / total - 1.0) < 1e-6),
        ("bottom resultant = -sigma0 Lx to 1e-6", abs(bot / total + 1.0) < 1e-6),
        ("no net x force (< 1e-6 sigma0 Lx)", abs(rx) < 1e-6 * total),
        ("top row above sigma0 dx, second row below it",
         per.get(0, 0.0) > 1.0 and per.get(1, 1.0) < 1.0),
        ("load pressure stops with an error naming the allowed values", bad_named),
    ])


if __name__ == "__main__":
    sys.exit(main())
