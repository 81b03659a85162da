#!/usr/bin/python3
"""examples/python/run_plate.py, shortened (ctest output.python_example).

Runs the example (python3-lammps + the package) at dx = 1 mm (800 particles),
6 us in 4 chunks, and checks what it wrote against LAMMPS's own output:
  * the PNG exists, is a PNG and matplotlib reads it back (an image of some
    size, not blank);
  * the arrays it pulled with lmp.numpy.extract_atom / extract_compute
    (plate.npz) equal, particle by particle (by id), the write_dump of the same
    state (plate.final.dump, %.17g: the doubles exactly): x, y, vx, vy, the
    stress columns sigma_xx, sigma_yy, sigma_xy and the damage;
  * momentum: the plate flies free, so its momentum from the dump's
    velocities and the particle masses is the initial one, (M vdrift, 0),
    to 1e-10 of M vdrift (round-off; measured ~1e-14), and the drift the
    script prints is below that too;
  * the crack ran: particles with damage > 0.3 beyond the pre-crack's tips
    (|x0| > c/2 + 2 dx).

    check_run_plate.py --example run_plate.py --build DIR --workdir DIR
Prints PASSED or FAILED (ctest matches PASSED) and exits 0 / 1.
"""

import argparse
import os
import re
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples"))
from checks import verdict  # noqa: E402

DX, TEND, CHUNKS, VDRIFT, CRACK = 1e-3, 6e-6, 4, 2.0, 0.010


def read_write_dump(path):
    with open(path) as f:
        lines = f.read().splitlines()
    k = lines.index("ITEM: NUMBER OF ATOMS")
    n = int(lines[k + 1])
    h = next(i for i, ln in enumerate(lines) if ln.startswith("ITEM: ATOMS"))
    names = lines[h].split()[2:]
    vals = np.array([ln.split() for ln in lines[h + 1:h + 1 + n]], dtype=float)
    return names, vals


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--example", required=True, help="examples/python/run_plate.py")
    ap.add_argument("--build", required=True, help="folder of tlsphplugin.so and tlsph.py")
    ap.add_argument("--workdir", required=True)
    a = ap.parse_args()
    wd = os.path.abspath(a.workdir)
    os.makedirs(wd, exist_ok=True)
    for f in ("plate.png", "plate.npz", "plate.final.dump"):
        if os.path.exists(os.path.join(wd, f)):
            os.remove(os.path.join(wd, f))
    cmd = [sys.executable, os.path.abspath(a.example), "--out", wd,
           "--build", os.path.abspath(a.build),
           "--dx", repr(DX), "--tend", repr(TEND), "--chunks", str(CHUNKS),
           "--vdrift", repr(VDRIFT)]
    p = subprocess.run(cmd, capture_output=True, text=True, cwd=wd)
    print(p.stdout.rstrip())
    if p.returncode != 0:
        print(p.stderr[-3000:])
        print("FAILED: run_plate.py exited with", p.returncode)
        return 1
    checks = []

    png = os.path.join(wd, "plate.png")
    ok_png = False
    if os.path.isfile(png):
        with open(png, "rb") as f:
            sig = f.read(8)
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.image as mpimg
        img = mpimg.imread(png)
        ok_png = (sig == b"\x89PNG\r\n\x1a\n" and img.ndim == 3 and img.shape[0] >= 200
                  and img.shape[1] >= 600 and float(img[..., :3].std()) > 0.05)
        checks.append((f"plate.png: a {img.shape[1]} x {img.shape[0]} PNG, not blank", ok_png))
    else:
        checks.append(("plate.png written", False))

    names, vals = read_write_dump(os.path.join(wd, "plate.final.dump"))
    st = np.load(os.path.join(wd, "plate.npz"))
    col = {n: vals[:, k] for k, n in enumerate(names)}
    order = np.argsort(col["id"])
    col = {n: v[order] for n, v in col.items()}
    same_ids = np.array_equal(col["id"].astype(np.int64), st["id"].astype(np.int64))
    checks.append((f"{len(order)} particles, the same ids in the dump and in numpy", same_ids))
    if same_ids:
        pairs = [("x", st["x"][:, 0]), ("y", st["x"][:, 1]), ("vx", st["v"][:, 0]),
                 ("vy", st["v"][:, 1]), ("c_s[1]", st["stress"][:, 0]),
                 ("c_s[2]", st["stress"][:, 1]), ("c_s[4]", st["stress"][:, 3]),
                 ("c_d[1]", st["damage"][:, 0])]
        for name, arr in pairs:
            diff = np.abs(col[name] - arr).max()
            checks.append((f"numpy {name} = write_dump's {name} (max |diff| {diff:.3g}, "
                           f"values up to {np.abs(arr).max():.3g})", diff == 0.0))
        m = st["m"]
        M = m.sum()
        P = np.array([(m * col["vx"]).sum(), (m * col["vy"]).sum()])
        drift = np.hypot(P[0] - M * VDRIFT, P[1]) / (M * VDRIFT)
        checks.append((f"momentum at t = {float(st['time']) * 1e6:.2f} us from the dump: "
                       f"|P - (M vdrift, 0)| / (M vdrift) = {drift:.2e} <= 1e-10", drift <= 1e-10))
        mt = re.search(r"momentum drift .* = (\S+)", p.stdout)
        printed = float(mt.group(1)) if mt else float("nan")
        checks.append((f"the drift the script prints, {printed:.2e}, <= 1e-10", printed <= 1e-10))
        cracked = col["c_d[1]"] > 0.3
        reach = np.abs(st["x0"][cracked, 0]).max() if cracked.any() else 0.0
        checks.append((f"the crack ran: cracked particles out to |x0| = {reach * 1e3:.1f} mm "
                       f"> {(CRACK / 2 + 2 * DX) * 1e3:.1f} mm", reach > CRACK / 2 + 2 * DX))
        checks.append((f"ran to t = {float(st['time']) * 1e6:.2f} us (asked {TEND * 1e6:g})",
                       abs(float(st["time"]) - TEND) < 0.2 * TEND))
    return verdict(checks)


if __name__ == "__main__":
    sys.exit(main())
