"""Shortened cantilever example as a physics regression test (ctest examples.*).

Runs examples/cantilever-2d/in.cantilever-2d at dx = 2 mm with kinetic-damping
dynamic relaxation for a fixed simulated time, then checks the tip deflection
against beam theory with a tolerance band around the value this resolution is
known to give (see CMakeLists.txt and examples/cantilever-2d/README.md), plus
the health checks of the example (finite energies, det F, hourglass energy).

    check_cantilever.py --lmp LMP --deck DECK --workdir DIR --case linear|linear-uniform|large
Prints PASSED or FAILED (ctest matches PASSED) and exits 0 / 1.
"""

import argparse
import math
import os
import subprocess
import sys

L, H, T, E, NU = 0.1, 0.01, 0.001, 210e9, 0.3


def timoshenko(P, plane):
    """linear beam theory, tip deflection / L: Euler-Bernoulli + shear (k = 5/6)"""
    Eb = E / (1 - NU * NU) if plane == "strain" else E
    G = E / (2 * (1 + NU))
    alpha = P * L * L / (Eb * T * H ** 3 / 12)
    return alpha / 3 + alpha * Eb * H * H / (12 * (5 / 6) * G * L * L), alpha


# case: deck variables, the reference, the expected ratio v / reference at dx = 2 mm
# (measured with the converged relaxation, bench/out/pareto via doc/pareto.md and
# examples/cantilever-2d/README.md) and the tolerance band. The deck's default layout:
# the 5 layers through the depth placed for the exact second moment (yplace moment),
# the clamp's first column on the clamped face (clamp face).
#   linear: P = 175 N (alpha 0.091), plane strain. At dx = 2 mm TLSPH is 2.7 % stiffer
#     than Euler-Bernoulli + shear (-2.2 % against the FE solution of the same
#     continuum). Band +-3 % around the measured ratio: a 10 % error in the stiffness
#     moves the ratio by ~10 % and fails; round-off and the fixed run length (1.5 T1,
#     relaxed to < 1e-5) move it by < 1e-4.
#   linear-uniform: the same with the layout before 2026-12 (cell-centre layers, clamp
#     columns behind the face: yplace uniform, clamp cell), +6.6 % (+7.1 % against FE):
#     the comparison layout stays available and unchanged.
#   large: P = 17.5 kN (alpha 9.10), plane strain, against the elastica 0.80031: at
#     dx = 2 mm v/L = 0.80691 (+0.82 %; -0.92 % against the SVK continuum, which is
#     itself 1.76 % softer than the elastica). At this load the deflection is
#     insensitive to the stiffness (d ln v / d ln alpha = 0.14 for the elastica near
#     alpha 9-10), so the band of +-1 % catches stiffness errors above ~7 % only; this
#     case guards the large-rotation path (no instability, det F, hourglass energy),
#     the linear case the stiffness.
# Health limits: hourglass / strain energy (measured at dx = 2 mm: 0.5 % linear case,
# 0.85 % large case; 0.5 % at dx = 1 mm) and the closest pair of free particles over the
# run (measured 0.80 dx in the large case; with the hourglass and viscous terms 1000
# times too weak, as when the 2D 'thickness' keyword is missing, it was 0.47 dx with a
# zig-zag of the compressed root fibres, which this limit catches).
CASES = {
    "linear": {"vars": {"P": 175, "plane": "strain", "cfl": 0.3, "hold": 1.5},
               "expected": 0.029775 / 0.030593, "band": 0.03, "max_hg": 0.01,
               "min_dist": 0.9},
    "linear-uniform": {"vars": {"P": 175, "plane": "strain", "cfl": 0.3, "hold": 1.5,
                                "yplace": "uniform", "clamp": "cell"},
                       "expected": 0.032620 / 0.030593, "band": 0.03, "max_hg": 0.01,
                       "min_dist": 0.9},
    "large": {"vars": {"P": 17500, "plane": "strain", "cfl": 0.16, "hold": 1.2},
              "expected": 0.80691 / 0.80031, "band": 0.01, "max_hg": 0.02,
              "min_dist": 0.6},
}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--lmp", required=True)
    ap.add_argument("--deck", required=True)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--case", choices=sorted(CASES), required=True)
    a = ap.parse_args()
    case = CASES[a.case]
    os.makedirs(a.workdir, exist_ok=True)
    out = os.path.join(a.workdir, a.case)
    v = {"dx": 0.002, "grad": "quadratic", "damp": "relax", "ramp": 0, "tol": 0, "out": out,
         "common": os.path.join(os.path.dirname(os.path.abspath(a.deck)), "..", "common")}
    v.update(case["vars"])
    cmd = [a.lmp, "-in", a.deck, "-log", out + ".log", "-screen", "none"]
    for k, val in v.items():
        cmd += ["-var", k, str(val)]
    print(" ".join(cmd))
    r = subprocess.run(cmd, capture_output=True, text=True)
    ok = True
    if r.returncode != 0:
        print(f"lmp_tlsph failed (rc {r.returncode}):\n{r.stdout[-2000:]}\n{r.stderr[-2000:]}")
        print("FAILED")
        return 1
    rows = []
    with open(out + ".dat") as f:
        names = None
        for line in f:
            if line.startswith("# step"):
                names = line[1:].split("(")[0].split()
            elif not line.startswith("#") and line.strip():
                rows.append([float(x) for x in line.split()])
    last = dict(zip(names, rows[-1]))
    vL = -last["tip_uy"] / L
    if a.case.startswith("linear"):
        ref, alpha = timoshenko(v["P"], v["plane"])
        what = "Euler-Bernoulli + shear"
    else:
        ref, what = 0.80031, "elastica (alpha 9.10)"
    ratio = vL / ref
    lo, hi = case["expected"] - case["band"], case["expected"] + case["band"]
    print(f"tip deflection v/L = {vL:.6f}, {what} {ref:.6f}: ratio {ratio:.4f}, "
          f"accepted [{lo:.4f}, {hi:.4f}] (expected {case['expected']:.4f} at dx = 2 mm)")
    ok &= lo <= ratio <= hi
    finite = all(math.isfinite(x) for row in rows for x in row)
    print(f"all outputs finite: {finite}")
    ok &= finite
    hg = last["E_hourglass"] / last["E_strain"]
    print(f"hourglass / strain energy {hg:.5f} (< {case['max_hg']})")
    ok &= hg < case["max_hg"]
    dmin = min(row[names.index("min_dist/dx")] for row in rows)
    print(f"closest particle pair over the run {dmin:.4f} dx (> {case['min_dist']})")
    ok &= dmin > case["min_dist"]
    detF = min(row[names.index("min_detF")] for row in rows)
    print(f"min det F over the run {detF:.4f} (> 0.5)")
    ok &= detF > 0.5
    print("PASSED" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
