"""The stored CalculiX reference of the laminate benchmarks, evaluable at any
material point (reference configuration) inside the body.

    import sys; sys.path.insert(0, "examples/laminate-common")
    import laminate_reference as ref
    u = ref.sample("beam_0_90", [[0.0995, 0.0045, 0.0045]])      # (1, 3) metres
    u = ref.sample("plate_0_90", pts, analysis="linear")
    pts = ref.lattice_points("plate_0_90")                         # TLSPH particle centres

Cases: beam_0_90, beam_0_45 (examples/laminate-beam/reference/) and
plate_0_90 (examples/laminate-plate/reference/). analysis: "nlgeom" (the
geometrically nonlinear SVK solution the TLSPH runs are compared with) or
"linear"; mesh: "reference" (the stored fine mesh) or "coarse".

The value is the FE field itself: the 20-node serendipity interpolation of the
nodal displacements in the element that contains the point (the mesh is a
structured grid of straight-edged boxes). Points on an element boundary get the
same value from either side (the field is C0). Points outside the body raise
ValueError. numpy only.

    python3 laminate_reference.py beam_0_90 0.0995 0.005 0.005   # print u there
"""

import functools
import json
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import laminate_fe as _fe  # noqa: E402

CASES = tuple(_fe.CASES)
ANALYSES = ("nlgeom", "linear")


def definition(case):
    """the case definition (geometry, plies, load) as a dict"""
    return {k: v for k, v in _fe.CASES[case].items() if k != "folder"}


def path(case, analysis="nlgeom", mesh="reference"):
    d = _fe.reference_dir(case)
    if mesh == "coarse":
        return os.path.join(d, f"{case}_coarse.npz")
    if mesh != "reference":
        raise ValueError(f"mesh must be 'reference' or 'coarse', not {mesh!r}")
    return os.path.join(d, f"{case}.npz" if analysis == "nlgeom" else f"{case}_linear.npz")


@functools.lru_cache(maxsize=None)
def load(case, analysis="nlgeom", mesh="reference"):
    """the stored solution as a laminate_fe.Field (has .sample(points), .mesh, .U)"""
    if case not in _fe.CASES:
        raise ValueError(f"unknown case {case!r}; cases: {', '.join(CASES)}")
    if analysis not in ANALYSES:
        raise ValueError(f"analysis must be one of {ANALYSES}, not {analysis!r}")
    p = path(case, analysis, mesh)
    if not os.path.exists(p):
        raise FileNotFoundError(f"{p} missing: regenerate with "
                                "python3 examples/laminate-common/laminate_fe.py")
    return _fe.load_field(p, analysis)


def sample(case, points, analysis="nlgeom", mesh="reference"):
    """displacements (n, 3) in metres at the points (n, 3) (reference
    coordinates, metres, inside the body)"""
    return load(case, analysis, mesh).sample(np.atleast_2d(np.asarray(points, dtype=float)))


def lattice_points(case, dx=_fe.DX):
    """the centres ((i+0.5)dx, (j+0.5)dx, (k+0.5)dx) of the particles that fill
    the body, (n, 3), x slowest and z fastest"""
    c = _fe.CASES[case]
    ext = (c["L"], c["b"], c["h"]) if c["kind"] == "beam" else (c["a"], c["a"], c["h"])
    axes = [_fe.lattice(int(round(e / dx)), dx) for e in ext]
    X, Y, Z = np.meshgrid(*axes, indexing="ij")
    return np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)


def summary(case):
    """the summary.json entry of a case (stations, convergence, CLT check, runs)"""
    with open(os.path.join(_fe.reference_dir(case), "summary.json")) as f:
        return json.load(f)["cases"][case]


if __name__ == "__main__":
    if len(sys.argv) != 5:
        print(__doc__)
        sys.exit(2)
    u = sample(sys.argv[1], [[float(v) for v in sys.argv[2:5]]])[0]
    print(" ".join(f"{v:.9e}" for v in u))
