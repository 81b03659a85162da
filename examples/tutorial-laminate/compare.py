#!/usr/bin/env python3
"""Tutorial (doc/Howto_laminate.rst): the strip of in.strip against classical
laminate theory (CLT).

Run in the directory of the run (it reads log.lammps and strip.final.dump):

    python3 compare.py [--log log.lammps] [--dump strip.final.dump] [--json out.json]

Reference values, for the narrow two-ply strip of in.strip (ply constants
from potentials/tlsph_materials.tlsph, carbon_epoxy):

* tip deflection w = P L^3 / (3 D* b) + P L / (k G_xz b t): the bending of
  the narrow-beam CLT stiffness D* = 1 / d11 (d11: the bending compliance of
  the inverted ABD matrix, so the extension-bending coupling of the
  unsymmetric laminate is included) plus a Timoshenko estimate of transverse
  shear, k = 5/6, G_xz = the mean of the plies' G_xz(theta) =
  1 / (cos^2 theta / G13 + sin^2 theta / G23);
* the neutral axis (where the bending strain e_xx is zero) at
  z_n = -b_{11} / d_{11} from the mid-plane (b: the coupling block of the
  inverted ABD matrix), read in the TLSPH run from the Green-Lagrange strain
  E_xx of the particles at mid-span.
"""
import argparse
import json
import math
import os
import re

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
MATFILE = os.path.join(here, "..", "..", "potentials", "tlsph_materials.tlsph")


def ply_constants(name="carbon_epoxy", path=MATFILE):
    for line in open(path):
        w = line.split("#")[0].split()
        if w and w[0] == name:
            return {w[k]: float(w[k + 1]) for k in range(1, len(w) - 1, 2)}
    raise KeyError(name)


def qbar(m, theta):
    """plane-stress reduced stiffness of a ply at theta (deg), (xx, yy, xy) with engineering shear"""
    nu21 = m["nu12"] * m["E2"] / m["E1"]
    d = 1 - m["nu12"] * nu21
    Q = np.array([[m["E1"] / d, m["nu12"] * m["E2"] / d, 0], [m["nu12"] * m["E2"] / d, m["E2"] / d, 0],
                  [0, 0, m["G12"]]])
    c, s = math.cos(math.radians(theta)), math.sin(math.radians(theta))
    T = np.array([[c * c, s * s, 2 * c * s], [s * s, c * c, -2 * c * s], [-c * s, c * s, c * c - s * s]])
    R = np.diag([1.0, 1.0, 2.0])
    return np.linalg.inv(T) @ Q @ R @ T @ np.linalg.inv(R)


def clt(m, angles, L, b, t, P):
    """narrow-beam CLT of equal plies (bottom first): deflection, D*, neutral axis"""
    z = np.linspace(-t / 2, t / 2, len(angles) + 1)
    A, B, D = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3))
    for k, th in enumerate(angles):
        Q = qbar(m, th)
        A += Q * (z[k + 1] - z[k])
        B += Q * (z[k + 1] ** 2 - z[k] ** 2) / 2
        D += Q * (z[k + 1] ** 3 - z[k] ** 3) / 3
    inv = np.linalg.inv(np.block([[A, B], [B, D]]))
    Dstar = 1.0 / inv[3, 3]
    gxz = np.mean([1.0 / (math.cos(math.radians(th)) ** 2 / m["G13"]
                          + math.sin(math.radians(th)) ** 2 / m["G23"]) for th in angles])
    wb = P * L ** 3 / (3 * Dstar * b)
    ws = P * L / (5.0 / 6.0 * gxz * b * t)
    return {"Dstar": Dstar, "w_bending": wb, "w_shear": ws, "w": wb + ws, "G_xz": gxz,
            "z_n": t / 2 - inv[0, 3] / inv[3, 3]}


def read_log(path):
    txt = open(path).read()
    g = re.search(r"^strip: L (\S+) b (\S+) t (\S+) dx (\S+) P (\S+) theta2 (\S+)", txt, re.M)
    w = re.findall(r"^strip: tip deflection w = (\S+) m after (\d+) steps \(resid (\S+), net (\S+)\)",
                   txt, re.M)
    if not g or not w:
        raise RuntimeError(f"{path}: no 'strip:' lines (did the run finish?)")
    L, b, t, dx, P, th = (float(v) for v in g.groups())
    out = dict(L=L, b=b, t=t, dx=dx, P=P, theta2=th, w=-float(w[-1][0]), steps=int(w[-1][1]),
               resid=float(w[-1][2]), fnet=float(w[-1][3]))
    # the last thermo line: step time c_w v_resid v_fnet f_relax[1] c_e[1] c_e[2]
    rows = re.findall(r"^\s*(\d+(?:\s+[-+0-9.eE]+){7})\s*$", txt, re.M)
    if rows:
        v = [float(x) for x in rows[-1].split()]
        out["resets"], out["E_strain"], out["E_hourglass"] = int(v[5]), v[6], v[7]
    wall = re.search(r"^Total wall time: (\d+):(\d+):(\d+)", txt, re.M)
    if wall:
        out["wall_s"] = 3600 * int(wall.group(1)) + 60 * int(wall.group(2)) + int(wall.group(3))
    return out


def neutral_axis(dump, L, dx):
    """zero of E_xx through the thickness at mid-span (least-squares line), from the reference z"""
    with open(dump) as f:
        lines = f.read().splitlines()
    k = next(i for i, ln in enumerate(lines) if ln.startswith("ITEM: ATOMS"))
    cols = lines[k].split()[2:]
    d = np.array([[float(x) for x in ln.split()] for ln in lines[k + 1:] if ln.strip()])
    c = {n: i for i, n in enumerate(cols)}
    X = d[:, c["x"]] - d[:, c["c_u[1]"]]
    Z = d[:, c["z"]] - d[:, c["c_u[3]"]]
    sel = np.abs(X - L / 2) < 0.51 * dx
    p = np.polyfit(Z[sel], d[sel, c["c_E[1]"]], 1)
    return -p[1] / p[0]


def compare(log="log.lammps", dump="strip.final.dump"):
    r = read_log(log)
    ref = clt(ply_constants(), [0.0, r["theta2"]], r["L"], r["b"], r["t"], r["P"])
    r["z_n"] = neutral_axis(dump, r["L"], r["dx"])
    return r, ref


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--log", default="log.lammps")
    ap.add_argument("--dump", default="strip.final.dump")
    ap.add_argument("--json")
    a = ap.parse_args()
    r, ref = compare(a.log, a.dump)
    print(f"[0/{r['theta2']:g}] strip L = {r['L'] * 1e3:g} mm, b = {r['b'] * 1e3:g} mm, "
          f"t = {r['t'] * 1e3:g} mm, dx = {r['dx'] * 1e3:g} mm, P = {r['P']:g} N")
    print(f"static state after {r['steps']} steps: force residual {r['resid']:.2g} P, "
          f"net force {r['fnet']:.2g} P")
    print(f"CLT: D* = {ref['Dstar']:.2f} N m, bending {ref['w_bending'] * 1e3:.5f} mm + "
          f"shear {ref['w_shear'] * 1e3:.5f} mm (G_xz {ref['G_xz'] / 1e9:.3g} GPa)")
    print(f"tip deflection   TLSPH {r['w'] * 1e3:.5f} mm   CLT + shear {ref['w'] * 1e3:.5f} mm   "
          f"difference {100 * (r['w'] / ref['w'] - 1):+.2f} %")
    print(f"neutral axis     TLSPH {r['z_n'] * 1e3:.4f} mm   CLT {ref['z_n'] * 1e3:.4f} mm   "
          f"(height above the bottom face, mid-span)")
    if "E_hourglass" in r:
        print(f"hourglass energy {100 * r['E_hourglass'] / r['E_strain']:.2f} % of the strain energy")
    if a.json:
        json.dump({"tlsph": r, "clt": ref}, open(a.json, "w"), indent=1)


if __name__ == "__main__":
    main()
