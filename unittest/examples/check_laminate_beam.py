"""Shortened laminate-beam example as a physics regression test (ctest examples.*).

Runs examples/laminate-beam/in.laminate-beam for the [0/90] cantilever at the
coarse dx = 1.667 mm (2,268 particles, 3 particles per 5 mm ply), kinetic-damping
relaxation to rest, and compares with the stored CalculiX reference at the same
material points (examples/laminate-beam/analyse.py):

  * tip-layer u3 within 2.5 % of the FE solution. Measured with the deck's
    defaults (particle layers placed for the exact second moment of each ply,
    support layer on the clamped face): +0.28 %; with the cell-centre layers
    and the clamp behind the face it was -10.7 % (examples/laminate-beam/
    README.md). A stiffness wrong by 5 % (e.g. a mis-rotated 90 deg ply: the
    top ply would carry E1 along x) or a return to the old discretisation
    moves it out of the band;
  * the through-thickness u1 profile at the tip: its top particle within 4 % of
    the FE value (measured -1.5 %), bottom and top of opposite sign (bending);
  * hourglass energy below 1 % of the strain energy; the run reached rest
    (net-force and force-norm residuals below 1e-5).

    check_laminate_beam.py --lmp LMP --example DIR --workdir DIR
Prints PASSED or FAILED (ctest matches PASSED) and exits 0 / 1.
"""

import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import example_args, verdict  # noqa: E402


def main():
    a = example_args("laminate-beam")
    prefix = os.path.join(a.workdir, "beam")
    cmd = [a.lmp, "-in", os.path.join(a.example, "in.laminate-beam"), "-log", prefix + ".log",
           "-screen", "none", "-var", "out", prefix, "-var", "theta2", "90",
           "-var", "common", os.path.join(a.example, "..", "laminate-common"),
           "-var", "dx", "0.00166666666666667", "-var", "tmax", "4", "-var", "tol", "1e-5"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        print(p.stdout[-2000:], p.stderr[-2000:])
        print("FAILED: LAMMPS exited with", p.returncode)
        return 1
    sys.path.insert(0, a.example)
    import analyse
    out, _ = analyse.analyse(prefix)
    print(analyse.report(out, "(ctest, dx = 1.667 mm)"))
    checks = [
        ("u3 tip layer within 2.5 % of FE", abs(out["u3_tip"]["err"]) <= 0.025),
        ("u1 top particle within 4 % of FE", abs(out["u1_top"]["err"]) <= 0.04),
        ("u1 bottom < 0 < u1 top", out["u1_bottom"]["tlsph"] < 0 < out["u1_top"]["tlsph"]),
        ("E_hourglass / E_strain < 1 %", (out.get("E_hg_over_E_strain") or 1) < 0.01),
        ("at rest: residuals < 1e-5", out.get("resid", 1) < 1e-5 and (out.get("fnet") or 1) < 1e-5),
    ]
    return verdict(checks)


if __name__ == "__main__":
    sys.exit(main())
