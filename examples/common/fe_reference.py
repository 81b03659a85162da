"""Converged finite-element values of the SVK cantilever (svk_fe.py) for the
cases the examples compare with, cached in fe_reference.json beside this file.

    python3 fe_reference.py            # compute what is missing, print the table
    python3 fe_reference.py --force    # recompute everything

Each case is solved on three meshes (Q9: nx x ny = 40x4, 80x8, 160x16 in 2D;
Q27: 20x2x2, 40x4x4 in 3D); the reported value is the finest mesh and the
change from the previous mesh is the discretisation uncertainty.
"""

import json
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import svk_fe  # noqa: E402

CACHE = os.path.join(here, "fe_reference.json")

# (key, dim, plane, P, meshes)
MESH2 = [(40, 4), (80, 8), (160, 16)]
MESH3 = [(20, 2, 2), (40, 4, 4)]
CASES = [
    ("2d_strain_P17500", 2, "strain", 17500.0, MESH2),
    ("2d_stress_P17500", 2, "stress", 17500.0, MESH2),
    ("2d_stress_P1750", 2, "stress", 1750.0, MESH2),
    ("2d_strain_P175", 2, "strain", 175.0, MESH2),
    ("2d_stress_P175", 2, "stress", 175.0, MESH2),
    ("3d_P17500", 3, None, 17500.0, MESH3),
    ("3d_P175", 3, None, 175.0, MESH3),
]


def load():
    if os.path.exists(CACHE):
        with open(CACHE) as f:
            return json.load(f)
    return {}


def compute(force=False, only=None):
    data = {} if force else load()
    for key, dim, plane, P, meshes in CASES:
        if only and key not in only:
            continue
        runs = data.get(key, {}).get("meshes", [])
        done = {tuple(r["n"]) for r in runs}
        for n in meshes:
            if tuple(n) in done:
                continue
            B = 0.001 if dim == 2 else 0.01
            r = svk_fe.solve(dim, plane or "strain", P, B=B, n=n, steps=10)
            if not r.get("converged"):
                print(f"{key} {n}: Newton did not converge ({r})", file=sys.stderr)
                continue
            runs.append(r)
            print(f"{key} {n}: tip v/L {-r['tip_uy'] / 0.1:.6f} u/L {-r['tip_ux'] / 0.1:.6f} "
                  f"({r['wall_s']:.1f} s)", file=sys.stderr)
            data[key] = {"dim": dim, "plane": plane, "P": P, "meshes": runs}
            with open(CACHE + ".tmp", "w") as f:
                json.dump(data, f, indent=1)
            os.replace(CACHE + ".tmp", CACHE)
    return data


def best(data, key):
    """(v/L, u/L, uncertainty of v/L) from the finest mesh of a case"""
    runs = sorted(data[key]["meshes"], key=lambda r: r["ndof"])
    v = -runs[-1]["tip_uy"] / 0.1
    u = -runs[-1]["tip_ux"] / 0.1
    dv = abs(v + runs[-2]["tip_uy"] / 0.1) if len(runs) > 1 else float("nan")
    return v, u, dv


if __name__ == "__main__":
    d = compute(force="--force" in sys.argv)
    for key, *_ in CASES:
        if key in d:
            v, u, dv = best(d, key)
            print(f"{key:18s} v/L {v:.6f} (+-{dv:.1e})  u/L {u:.6f}")
