#!/usr/bin/env python3
"""Compare a laminate-plate run (out/NAME.final.dump) with the CalculiX reference.

    analyse.py out/laminate-plate [--png out/x.png] [--profile-png out/y.png] [--json out/x.json]

All at the particles' reference positions X (the FE field sampled at exactly
those points, examples/laminate-common/laminate_reference.py):
  top-layer extrema   max and min of u1, u2, u3 over the top particle layer
                      (z = t - dx/2 for cell-centre layers, higher with
                      zplace moment) inside the plate -- the thesis's Table 3.7
                      stations, at the particles' depth
  point A             x = y = 75 mm: mean of the 4 particle columns around it
                      (bilinear interpolation at A on the lattice), per layer:
                      the through-thickness profiles of u1, u2, u3
Errors are (TLSPH - FE)/|FE| of the extreme values (the largest magnitude of
each component; the thesis's "error" column), and at point A.
"""

import argparse
import json
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "common"))
import laminate_compare as lc  # noqa: E402

CASE = "plate_0_90"
XA = 0.075


def analyse(prefix):
    head, rows = lc.read_dat(prefix + ".dat")
    d = lc.ref.definition(CASE)
    a, t = d["a"], d["h"]
    dx = float(head["dx"])
    ids, types, X, u = lc.read_final_dump(prefix + ".final.dump")
    inside = (X[:, 0] > 0) & (X[:, 0] < a) & (X[:, 1] > 0) & (X[:, 1] < a)
    top = inside & (X[:, 2] > t - dx)
    colA = inside & (np.abs(X[:, 0] - XA) < dx) & (np.abs(X[:, 1] - XA) < dx)
    sel = top | colA
    ufe = np.zeros_like(u)
    ufe[sel] = lc.ref.sample(CASE, X[sel])
    out = {"case": CASE, "dx": dx, "particles": int(len(ids)), "n_top": int(top.sum()),
           "z_top": float(np.median(X[top, 2])),
           "gamma": float(head.get("gamma", "nan")), "q": float(head.get("q", "nan"))}
    for k, name in enumerate(("u1", "u2", "u3")):
        ut, uf = u[top, k], ufe[top, k]
        # the FE field's largest value and TLSPH's largest of the same sign
        # (u1 and u2 are antisymmetric: max = -min, either may come first)
        big_f = uf[np.argmax(np.abs(uf))]
        big_t = ut.max() if big_f > 0 else ut.min()
        out[name] = {"tlsph_max": float(ut.max()), "tlsph_min": float(ut.min()),
                     "fe_max": float(uf.max()), "fe_min": float(uf.min()),
                     "tlsph_extreme": float(big_t), "fe_extreme": float(big_f),
                     "err": lc.rel(float(big_t), float(big_f))}
    zs = np.unique(np.round(X[colA, 2], 9))
    prof = []
    for z in zs:
        m = colA & (np.abs(X[:, 2] - z) < 1e-9)
        prof.append([float(z)] + [float(v) for v in u[m].mean(axis=0)]
                    + [float(v) for v in ufe[m].mean(axis=0)])
    prof = np.array(prof)
    out["pointA"] = {"z": prof[:, 0].tolist(), "tlsph": prof[:, 1:4].tolist(),
                     "fe": prof[:, 4:7].tolist(),
                     "err_top": [lc.rel(prof[-1, 1 + k], prof[-1, 4 + k]) for k in range(3)]}
    out["run"] = lc.read_log(prefix + ".log")
    if len(rows):
        out["resid"] = float(rows[-1, 7])
        out["fnet"] = float(rows[-1, 8]) if rows.shape[1] > 8 else None
        out["E_hg_over_E_strain"] = float(rows[-1, 5] / rows[-1, 4]) if rows[-1, 4] else None
    out["_fields"] = (X[top], u[top], ufe[top])
    return out


def report(out, label):
    r = out["run"]
    L = [f"laminate plate [0/90] {label}",
         f"dx = {out['dx'] * 1e3:.4g} mm, {out['particles']} particles (top layer {out['n_top']}), "
         f"q = {out['q']:.3g} Pa, gamma = {out['gamma']:g}; {r.get('steps', '?')} steps, loop time "
         f"{r.get('loop', float('nan')):.0f} s on {r.get('np', '?')} rank(s) "
         f"(CPU use {r.get('cpu', '?')} %), final residual {out.get('resid', float('nan')):.2g} "
         f"(net force {out.get('fnet') if out.get('fnet') is not None else float('nan'):.2g}), "
         f"E_hourglass/E_strain {out.get('E_hg_over_E_strain') or float('nan'):.2e}",
         "",
         f"top particle layer (z = {1e3 * out['z_top']:.3f} mm), x 1e-4 m:",
         f"{'':4s} {'TLSPH max':>10s} {'TLSPH min':>10s} {'FE max':>10s} {'FE min':>10s} "
         f"{'error of the extreme':>21s}"]
    for name in ("u1", "u2", "u3"):
        q = out[name]
        L.append(f"{name:4s} {1e4 * q['tlsph_max']:10.4f} {1e4 * q['tlsph_min']:10.4f} "
                 f"{1e4 * q['fe_max']:10.4f} {1e4 * q['fe_min']:10.4f} {lc.pct(q['err']):>21s}")
    L.append("")
    L.append("point A (x = y = 75 mm), through the thickness, x 1e-4 m:")
    L.append(f"{'z [mm]':>8s} " + " ".join(f"{'TLSPH ' + n:>10s} {'FE ' + n:>10s}"
                                          for n in ("u1", "u2", "u3")))
    p = out["pointA"]
    for z, ut, uf in zip(p["z"], p["tlsph"], p["fe"]):
        L.append(f"{1e3 * z:8.3f} " + " ".join(f"{1e4 * ut[k]:10.4f} {1e4 * uf[k]:10.4f}"
                                              for k in range(3)))
    L.append("errors at A, top layer: " + ", ".join(
        f"{n} {lc.pct(e)}" for n, e in zip(("u1", "u2", "u3"), p["err_top"])))
    return "\n".join(L)


def plot_fields(out, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    X, ut, uf = out["_fields"]
    fig, axs = plt.subplots(3, 3, figsize=(11, 10))
    for k, name in enumerate(("u1", "u2", "u3")):
        lim = np.max(np.abs(uf[:, k])) * 1e4
        for c, (vals, title) in enumerate(((ut[:, k], "TLSPH"), (uf[:, k], "FE (CalculiX)"),
                                           (ut[:, k] - uf[:, k], "TLSPH - FE"))):
            ax = axs[k, c]
            v = 1e4 * vals
            vmax = lim if c < 2 else max(np.max(np.abs(v)), 1e-30)
            sc = ax.tricontourf(1e3 * X[:, 0], 1e3 * X[:, 1], v, levels=21, cmap="coolwarm",
                                vmin=-vmax, vmax=vmax)
            fig.colorbar(sc, ax=ax, shrink=0.8)
            ax.set_aspect("equal")
            ax.set_title(f"{name} [1e-4 m], {title}", fontsize=9)
            if k == 2:
                ax.set_xlabel("x [mm]")
            if c == 0:
                ax.set_ylabel("y [mm]")
    fig.suptitle(f"[0/90] plate, top particle layer, dx = {out['dx'] * 1e3:.3g} mm")
    fig.tight_layout()
    fig.savefig(png, dpi=100)


def plot_profile(out, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    p = out["pointA"]
    z = 1e3 * np.array(p["z"])
    ut, uf = 1e4 * np.array(p["tlsph"]), 1e4 * np.array(p["fe"])
    fig, axs = plt.subplots(1, 2, figsize=(8, 4))
    for k, name in enumerate(("u1", "u2")):
        axs[0].plot(uf[:, k], z, "-", label=f"{name} FE")
        axs[0].plot(ut[:, k], z, "o", mfc="none", label=f"{name} TLSPH")
    axs[1].plot(uf[:, 2], z, "k-", label="u3 FE")
    axs[1].plot(ut[:, 2], z, "o", mfc="none", label="u3 TLSPH")
    for ax in axs:
        ax.set_xlabel("displacement [1e-4 m]")
        ax.set_ylabel("z [mm]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("point A (x = y = 75 mm), through the thickness")
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("prefix")
    ap.add_argument("--png")
    ap.add_argument("--profile-png")
    ap.add_argument("--json")
    ap.add_argument("--label", default="")
    a = ap.parse_args()
    out = analyse(a.prefix)
    print(report(out, a.label))
    if a.png:
        plot_fields(out, a.png)
    if a.profile_png:
        plot_profile(out, a.profile_png)
    if a.json:
        o = {k: v for k, v in out.items() if not k.startswith("_")}
        with open(a.json, "w") as f:
            json.dump(o, f, indent=1)


if __name__ == "__main__":
    main()
