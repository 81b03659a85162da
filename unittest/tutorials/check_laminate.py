"""The laminate tutorial's deck as a test (ctest tutorials.laminate.strip):
doc/Howto_laminate.rst, examples/tutorial-laminate.

Runs the deck as the page shows it, `mpirun -np 2 lmp_tlsph -in in.strip`
in an empty directory (the [0/90] carbon/epoxy strip, L = 40 mm, 4 mm x 4 mm,
dx = 1 mm, tip load 10 N, kinetic damping), then the page's `compare.py`
(classical laminate theory). Checks (measured values of the page's run in
brackets):

  * the run reached the static state: force residual and net force below
    the deck's tol = 3e-5 P [2.6e-5, 9e-6];
  * tip deflection within 5 % of narrow-beam CLT plus a Timoshenko shear
    estimate (0.36096 mm; for the same beam shape, L/t = 10, b = t, the
    CalculiX solution of examples/laminate-common is within 0.3 % of that
    estimate) [0.35003 mm, -3.03 %; -1.57 % at dx = 0.667 mm]. A ply at the
    wrong angle ([0/0]: 4 times stiffer) fails it, and so do the particle
    layers at the cell centres (measured +13.0 %) and those with the support
    layers behind the clamped face (+20.6 %); the supports behind the face
    alone (+3.5 %) stay inside the band;
  * the neutral axis at mid-span (zero of the Green-Lagrange E_xx) within
    0.05 mm of CLT's, 1.1327 mm above the bottom face: the stiff 0 deg ply is
    below, the 90 deg ply above, and the extension-bending coupling is right
    [1.1330 mm; with the plies swapped it would be 2.867 mm];
  * hourglass energy below 1 % of the strain energy [0.65 %].

    check_laminate.py --mpiexec MPIRUN --lmp LMP --example DIR --workdir DIR
Prints PASSED or FAILED (ctest matches PASSED) and exits 0 / 1.
"""

import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tutorial import arg_parser, fresh_dir, mpi_cmd, run, verdict  # noqa: E402


def main():
    ap = arg_parser("examples/tutorial-laminate")
    a = ap.parse_args()
    wd = fresh_dir(a.workdir)
    ex = os.path.abspath(a.example)
    cmd = mpi_cmd(a.mpiexec, a.np) + [os.path.abspath(a.lmp), "-in", os.path.join(ex, "in.strip")]
    if not run(cmd, wd):
        return 1
    if not run([a.python, os.path.join(ex, "compare.py"), "--json", "compare.json"], wd):
        return 1
    with open(os.path.join(wd, "compare.json")) as f:
        r = json.load(f)
    t, ref = r["tlsph"], r["clt"]
    err = t["w"] / ref["w"] - 1
    print(f"w TLSPH {t['w'] * 1e3:.5f} mm, CLT + shear {ref['w'] * 1e3:.5f} mm ({100 * err:+.2f} %); "
          f"neutral axis {t['z_n'] * 1e3:.4f} mm, CLT {ref['z_n'] * 1e3:.4f} mm; residuals "
          f"{t['resid']:.2g} / {t['fnet']:.2g}; hourglass / strain energy "
          f"{t.get('E_hourglass', float('nan')) / t.get('E_strain', float('nan')):.4f}")
    tol = 3e-5
    checks = [
        (f"static state: residual and net force below {tol:g} P", t["resid"] < tol and t["fnet"] < tol),
        ("tip deflection within 5 % of CLT + shear", abs(err) <= 0.05),
        ("neutral axis within 0.05 mm of CLT's", abs(t["z_n"] - ref["z_n"]) <= 5e-5),
        ("hourglass energy below 1 % of the strain energy",
         t.get("E_hourglass", 1.0) < 0.01 * t.get("E_strain", 0.0)),
    ]
    return verdict(checks)


if __name__ == "__main__":
    sys.exit(main())
