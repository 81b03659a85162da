#!/usr/bin/env python3
"""Compare a laminate-beam run (out/NAME.final.dump) with the CalculiX reference.

    analyse.py out/laminate-beam-0-90 [--png out/x.png] [--json out/x.json]

Quantities, all at the particles' reference positions X (the FE field sampled
at exactly those points, examples/laminate-common/laminate_reference.py):
  u3 patch     mean u3 of the loaded particles (central 2 mm x 2 mm of the tip layer)
  u3 tip       mean u3 of the whole tip layer (x = L - dx/2)
  u1 profile   u1 through the thickness at the tip layer, mean of the particle
               columns next to the mid-width (|y - b/2| < dx), one value per layer
Errors are (TLSPH - FE)/|FE|; for the profile, max |TLSPH - FE| / max |FE|.
"""

import argparse
import json
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "common"))
import laminate_compare as lc  # noqa: E402


def analyse(prefix):
    head, rows = lc.read_dat(prefix + ".dat")
    with open(prefix + ".dat") as f:
        first = f.readline()
    theta2 = int(first.split("[0/")[1].split("]")[0])
    case = f"beam_0_{theta2}"
    d = lc.ref.definition(case)
    L, b, t = d["L"], d["b"], d["h"]
    dx = float(head["dx"])
    ids, types, X, u = lc.read_final_dump(prefix + ".final.dump")
    free = X[:, 0] > 0
    tip = free & (X[:, 0] > L - dx)
    patch = tip & (np.abs(X[:, 1] - b / 2) < 0.001) & (np.abs(X[:, 2] - t / 2) < 0.001)
    mid = tip & (np.abs(X[:, 1] - b / 2) < dx)
    # the two central layers of the outermost tip columns (twist of the tip)
    zc = np.abs(X[:, 2] - t / 2) < dx
    yl = tip & zc & (X[:, 1] < X[tip, 1].min() + 1e-9)
    yh = tip & zc & (X[:, 1] > X[tip, 1].max() - 1e-9)
    sel = tip | patch | mid
    ufe = np.zeros_like(u)
    ufe[sel] = lc.ref.sample(case, X[sel])
    out = {"case": case, "dx": dx, "particles": int(len(ids)), "n_patch": int(patch.sum()),
           "n_tip": int(tip.sum())}
    for key, m in (("u3_patch", patch), ("u3_tip", tip)):
        out[key] = {"tlsph": float(u[m, 2].mean()), "fe": float(ufe[m, 2].mean())}
        out[key]["err"] = lc.rel(out[key]["tlsph"], out[key]["fe"])
    out["u2_patch"] = {"tlsph": float(u[patch, 1].mean()), "fe": float(ufe[patch, 1].mean())}
    out["u2_patch"]["err"] = lc.rel(out["u2_patch"]["tlsph"], out["u2_patch"]["fe"])
    span = X[yh, 1].mean() - X[yl, 1].mean()
    out["twist"] = {"tlsph": float((u[yh, 2].mean() - u[yl, 2].mean()) / span),
                    "fe": float((ufe[yh, 2].mean() - ufe[yl, 2].mean()) / span)}
    out["twist"]["err"] = lc.rel(out["twist"]["tlsph"], out["twist"]["fe"])
    zs = np.unique(np.round(X[mid, 2], 9))
    prof = []
    for z in zs:
        m = mid & (np.abs(X[:, 2] - z) < 1e-9)
        prof.append((float(z), float(u[m, 0].mean()), float(ufe[m, 0].mean())))
    prof = np.array(prof)
    out["u1_profile"] = {"z": prof[:, 0].tolist(), "tlsph": prof[:, 1].tolist(),
                         "fe": prof[:, 2].tolist(),
                         "err": float(np.max(np.abs(prof[:, 1] - prof[:, 2]))
                                      / np.max(np.abs(prof[:, 2])))}
    out["u1_top"] = {"tlsph": prof[-1, 1], "fe": prof[-1, 2], "err": lc.rel(prof[-1, 1], prof[-1, 2])}
    out["u1_bottom"] = {"tlsph": prof[0, 1], "fe": prof[0, 2], "err": lc.rel(prof[0, 1], prof[0, 2])}
    log = lc.read_log(prefix + ".log")
    out["run"] = log
    if len(rows):
        out["resid"] = float(rows[-1, 8])
        out["fnet"] = float(rows[-1, 9]) if rows.shape[1] > 9 else None
        out["E_hg_over_E_strain"] = float(rows[-1, 6] / rows[-1, 5]) if rows[-1, 5] else None
    return out, prof


def report(out, label):
    r = out["run"]
    L = [f"laminate beam [0/{out['case'].split('_')[-1]}] {label}",
         f"dx = {out['dx'] * 1e3:.4g} mm, {out['particles']} particles (tip layer {out['n_tip']}, "
         f"load patch {out['n_patch']}); {r.get('steps', '?')} steps, loop time "
         f"{r.get('loop', float('nan')):.0f} s on {r.get('np', '?')} rank(s) "
         f"(CPU use {r.get('cpu', '?')} %), final residual {out.get('resid', float('nan')):.2g} "
         f"(net force {out.get('fnet') if out.get('fnet') is not None else float('nan'):.2g}), "
         f"E_hourglass/E_strain {out.get('E_hg_over_E_strain') or float('nan'):.2e}",
         "",
         f"{'quantity':34s} {'TLSPH':>14s} {'FE (CalculiX)':>14s} {'error':>9s}"]
    for key, name in (("u3_patch", "u3, mean of the loaded patch [mm]"),
                      ("u3_tip", "u3, mean of the tip layer [mm]"),
                      ("u1_top", "u1, tip layer, top particle [mm]"),
                      ("u1_bottom", "u1, tip layer, bottom particle [mm]")):
        q = out[key]
        L.append(f"{name:34s} {1e3 * q['tlsph']:14.5f} {1e3 * q['fe']:14.5f} {lc.pct(q['err']):>9s}")
    if abs(out["u2_patch"]["fe"]) > 1e-3 * abs(out["u3_patch"]["fe"]):
        # [0/45]: the lateral deflection and the twist of the bend-twist coupling
        q = out["u2_patch"]
        L.append(f"{'u2, mean of the loaded patch [mm]':34s} {1e3 * q['tlsph']:14.5f} "
                 f"{1e3 * q['fe']:14.5f} {lc.pct(q['err']):>9s}")
        q = out["twist"]
        L.append(f"{'tip twist du3/dy (outer columns) [mrad]':34s} {1e3 * q['tlsph']:14.5f} "
                 f"{1e3 * q['fe']:14.5f} {lc.pct(q['err']):>9s}")
    L.append(f"{'u1 profile, max|diff|/max|FE|':34s} {'':14s} {'':14s} "
             f"{100 * out['u1_profile']['err']:8.2f} %")
    L.append("")
    L.append("u1 through the thickness at the tip layer (mid-width columns):")
    L.append(f"{'z [mm]':>8s} {'TLSPH [mm]':>12s} {'FE [mm]':>12s}")
    p = out["u1_profile"]
    for z, a, f in zip(p["z"], p["tlsph"], p["fe"]):
        L.append(f"{1e3 * z:8.3f} {1e3 * a:12.5f} {1e3 * f:12.5f}")
    return "\n".join(L)


def plot(out, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    p = out["u1_profile"]
    fig, ax = plt.subplots(figsize=(4.5, 4))
    ax.plot(1e3 * np.array(p["fe"]), 1e3 * np.array(p["z"]), "k-", label="FE (CalculiX)")
    ax.plot(1e3 * np.array(p["tlsph"]), 1e3 * np.array(p["z"]), "o", mfc="none", label="TLSPH")
    ax.set_xlabel("u1 at the tip [mm]")
    ax.set_ylabel("z [mm]")
    ax.set_title(f"[0/{out['case'].split('_')[-1]}] beam, dx = {out['dx'] * 1e3:.3g} mm")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(png, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("prefix")
    ap.add_argument("--png")
    ap.add_argument("--json")
    ap.add_argument("--label", default="")
    a = ap.parse_args()
    out, _ = analyse(a.prefix)
    print(report(out, a.label))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)
    if a.png:
        plot(out, a.png)


if __name__ == "__main__":
    main()
