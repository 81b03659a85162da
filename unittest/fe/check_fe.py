#!/usr/bin/env python3
"""Checks of the CalculiX reference of the laminate benchmarks (ctest label fe).

  check_fe.py sampler
      the stored nodal solutions (examples/laminate-*/reference/*.npz) and the
      20-node sampler of examples/laminate-common: sampling at the nodes gives
      back the stored nodal values; a quadratic displacement field is
      interpolated exactly (and a cubic one is not: the check has teeth); the
      station values in summary.json are what the stored field gives.

  check_fe.py ccx [--workdir DIR]
      rebuilds the coarsest beam mesh (beam_0_90, coarse, NLGEOM and linear),
      checks the deck is the stored one (.inp.gz), runs CalculiX on it and
      compares the displacements with the stored coarse solution (1e-6 of the
      largest displacement). Needs 'ccx' (Debian package calculix-ccx,
      installed by scripts/setup.sh); fails with a message if it is missing.

Exit status 0 and a last line 'PASSED' when every check holds.
"""

import argparse
import gzip
import os
import shutil
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "examples", "laminate-common"))
import laminate_fe as F  # noqa: E402
import laminate_reference as R  # noqa: E402

failures = []


def check(ok, msg):
    print(("ok    " if ok else "FAIL  ") + msg)
    if not ok:
        failures.append(msg)


def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def quad_field(C, X):
    """the complete quadratic with coefficients C (10, 3) at points X (n, 3)"""
    x, y, z = X[:, 0], X[:, 1], X[:, 2]
    basis = np.stack([np.ones_like(x), x, y, z, x * x, y * y, z * z, x * y, y * z, x * z], axis=1)
    return basis @ C


def check_sampler():
    rng = np.random.default_rng(20240401)
    for case in R.CASES:
        for mesh in ("reference", "coarse"):
            for an in R.ANALYSES:
                p = R.path(case, an, mesh)
                if not os.path.exists(p):
                    check(False, f"{case} {mesh} {an}: stored file {p} missing")
                    continue
                size = os.path.getsize(p)
                check(size < 2.5e6, f"{os.path.relpath(p, ROOT)}: {size / 1e6:.2f} MB (< 2.5 MB)")
                f = R.load(case, an, mesh)
                X = f.mesh.coords()
                u = R.sample(case, X, an, mesh)
                err = np.abs(u - f.U).max() / np.abs(f.U).max()
                check(err < 1e-12, f"{case} {mesh} {an}: sampled at the {len(X)} nodes = stored "
                                   f"values (max rel err {err:.1e})")
        # exactness for a quadratic field on the stored mesh
        f = R.load(case)
        m = f.mesh
        X = m.coords()
        lo = np.array([g[0] for g in m.g])
        hi = np.array([g[-1] for g in m.g])
        P = lo + (hi - lo) * rng.random((3000, 3))
        # include points on element boundaries and on the body's faces
        P[:200, 0] = m.g[0][rng.integers(0, len(m.g[0]), 200)]
        P[200:400, 2] = m.g[2][rng.integers(0, len(m.g[2]), 200)]
        Xs = (X - lo) / (hi - lo)  # scaled coordinates keep the polynomial O(1)
        Ps = (P - lo) / (hi - lo)
        C = rng.normal(size=(10, 3))
        Uq = quad_field(C, Xs)
        Pq = quad_field(C, Ps)
        fq = F.Field(m, Uq)
        err = np.abs(fq.sample(P) - Pq).max() / np.abs(Pq).max()
        check(err < 1e-12, f"{case}: quadratic field exact at 3000 points (max rel err {err:.1e})")
        # negative control: x^3 is not in the serendipity space
        cub = np.stack([Xs[:, 0] ** 3, Xs[:, 1] ** 3, Xs[:, 2] ** 3], axis=1)
        fc = F.Field(m, cub)
        exact = np.stack([Ps[:, 0] ** 3, Ps[:, 1] ** 3, Ps[:, 2] ** 3], axis=1)
        errc = np.abs(fc.sample(P) - exact).max()
        check(errc > 1e-9, f"{case}: a cubic field is not exact (max err {errc:.1e}): the check can fail")
        # outside points are refused
        try:
            R.sample(case, [hi + 1e-3])
            check(False, f"{case}: a point outside the body raises ValueError")
        except ValueError:
            check(True, f"{case}: a point outside the body raises ValueError")
        # summary.json stations belong to the stored fields
        s = R.summary(case)
        for an in R.ANALYSES:
            st = F.stations(case, R.load(case, an))
            worst = max(rel(v, s[f"stations_{an}"][k]) for k, v in st.items()
                        if abs(s[f"stations_{an}"][k]) > 1e-12)
            check(worst < 1e-9, f"{case} {an}: summary.json stations reproduced from the npz "
                                f"(max rel diff {worst:.1e})")
        lat = F.lattice_stations(case, R.load(case))
        key = "u3_central4_mean" if F.CASES[case]["kind"] == "beam" else "u3_top_layer_min"
        check(rel(lat[key], s["lattice_nlgeom"][key]) < 1e-9,
              f"{case}: summary.json lattice {key} reproduced ({lat[key]:.6e})")
        # the stored mesh is converged: its key values within 0.5 % of the next coarser mesh
        conv = s["convergence"]["nlgeom"]
        meshes = list(conv)
        if len(meshes) >= 2:
            a, b = meshes[-2], meshes[-1]
            keys = ["u3_tip_centre", "u3_tip_face_mean", "u1_tip_top_centre", "u1_tip_bottom_centre"] \
                if F.CASES[case]["kind"] == "beam" else \
                ["u3_top_min", "u1_top_max", "u1_top_min", "u2_top_max", "u2_top_min",
                 "u1_A_top", "u2_A_top", "u3_A_top"]
            worst = max(conv[a][k]["rel_to_finest"] for k in keys)
            check(worst < 5e-3, f"{case}: {a} vs {b} mesh key quantities within 0.5 % "
                                f"(worst {worst * 100:.3f} %)")


def check_ccx(workdir):
    if not shutil.which("ccx"):
        check(False, "CalculiX 'ccx' not found on PATH: install the Debian package calculix-ccx "
                     "(scripts/setup.sh does: apt-get install calculix-ccx)")
        return
    print(f"ccx version {F.ccx_version()}")
    case = "beam_0_90"
    refdir = F.reference_dir(case)
    stored = np.load(R.path(case, mesh="coarse"))
    os.makedirs(workdir, exist_ok=True)
    for nl in (True, False):
        an = "nlgeom" if nl else "linear"
        t0 = time.time()
        r = F.solve(case, "coarse", nl, workdir, "C3D20R", threads=1)
        wall = time.time() - t0
        job = r["job"]
        with open(os.path.join(workdir, job + ".inp")) as f:
            deck = f.read()
        gz = os.path.join(refdir, job + ".inp.gz")
        if os.path.exists(gz):
            with gzip.open(gz, "rt") as f:
                old = f.read()
            same = deck == old
            if not same:
                a, b = deck.splitlines(), old.splitlines()
                diff = next((i for i in range(min(len(a), len(b))) if a[i] != b[i]), min(len(a), len(b)))
                print(f"      first differing line {diff + 1}:\n      new: {a[diff] if diff < len(a) else ''}"
                      f"\n      old: {b[diff] if diff < len(b) else ''}")
            check(same, f"{job}: regenerated deck identical to the stored {os.path.basename(gz)}")
        else:
            check(False, f"stored deck {gz} missing")
        U = r["field"].U
        Us = stored["U_" + an]
        check(U.shape == Us.shape, f"{job}: {U.shape[0]} nodes as stored")
        if U.shape == Us.shape:
            err = np.abs(U - Us).max() / np.abs(Us).max()
            check(err <= 1e-6, f"{job}: ccx displacements = stored coarse solution "
                               f"(max |dU| / max |U| = {err:.1e}, ccx {r['wall_s']:.1f} s, total {wall:.1f} s)")
        check(abs(r["reaction"][2] - 500.0) < 1e-3,
              f"{job}: root reaction {r['reaction'][2]:.6f} N = the 500 N tip load")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("what", choices=["sampler", "ccx"])
    ap.add_argument("--workdir", default=None)
    args = ap.parse_args()
    if args.what == "sampler":
        check_sampler()
    else:
        wd = args.workdir or tempfile.mkdtemp(prefix="fe_ccx_")
        check_ccx(wd)
    if failures:
        print(f"FAILED: {len(failures)} check(s)")
        sys.exit(1)
    print("PASSED")


if __name__ == "__main__":
    main()
