"""Summary and plot of one cantilever run (used by the examples' run.sh).

    summarise_run.py OUTPREFIX --dim 2|3 [--fe-key KEY] [--png FILE]

Reads OUTPREFIX.dat, OUTPREFIX.log and OUTPREFIX.final.dump; prints the tip
deflection against the elastica, linear beam theory and the FE value of the
same SVK continuum (fe_reference.json), the quality checks (hourglass energy,
det F, closest particle pair, zig-zag indicator), and draws the tip
displacement against time and the deformed beam coloured by det F.
"""

import argparse
import os
import sys

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import elastica as el  # noqa: E402
import fe_reference  # noqa: E402
import tlsph_analysis as ta  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("prefix")
    ap.add_argument("--dim", type=int, default=2)
    ap.add_argument("--fe-key", default=None)
    ap.add_argument("--png", default=None)
    a = ap.parse_args()
    outdir, name = os.path.split(a.prefix)
    c = ta.Case(outdir or ".", name, dim=a.dim, L=0.1)
    m = c.dat["meta"]
    alpha = m["alpha"]
    e = el.elastica(alpha)
    lines = []
    w = lines.append
    kind = f"plane {m['plane']}" if a.dim == 2 else "3D solid"
    w(f"case {name}: {kind}, dx = {c.dx * 1e3:g} mm, P = {m['P']:g} N, gradient {m['grad']}, "
      f"damping {m['damp']}, Courant {m['cfl']:g}, {int(m['natoms'])} particles")
    w(f"status: {c.status()}; {c.steps} steps, Loop time {c.loop or float('nan'):.1f} s, "
      f"t = {c.dat['t/T1'][-1]:.2f} T1 (T1 = {m['T1'] * 1e3:.4f} ms), final residual {c.resid:.1e}")
    w(f"alpha = P L^2/(E' I) = {alpha:.4f}")
    w(f"tip deflection  v/L = {c.v:.5f}   elastica {e['v']:.5f} ({100 * (c.v / e['v'] - 1):+.2f} %)")
    w(f"tip retreat     u/L = {c.u:.5f}   elastica {e['u']:.5f} ({100 * (c.u / e['u'] - 1):+.2f} %)")
    fe = fe_reference.load()
    if a.fe_key and a.fe_key in fe:
        fv, fu, fdv = fe_reference.best(fe, a.fe_key)
        w(f"FE, same SVK continuum: v/L = {fv:.5f} ({100 * (c.v / fv - 1):+.2f} %), "
          f"u/L = {fu:.5f} ({100 * (c.u / fu - 1):+.2f} %)")
    w(f"hourglass / strain energy = {c.hg_ratio:.4f}; min det F = {c.min_detF:.3f}; "
      f"closest pair / dx = {c.min_dist_final:.3f}; zig-zag indicator "
      f"max |F_i X_ij - x_ij| / dx = {c.hg_ind:.3f}")
    print("\n".join(lines))

    if a.png:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        d = c.dat
        fig, ax = plt.subplots(1, 3, figsize=(15, 4.4), gridspec_kw={"width_ratios": [1.2, 1, 1]})
        ax[0].plot(d["t/T1"], -d["tip_uy"] / 0.1, label="v/L (TLSPH)")
        ax[0].plot(d["t/T1"], -d["tip_ux"] / 0.1, label="u/L (TLSPH)")
        ax[0].axhline(e["v"], color="k", ls=":", lw=0.8, label=f"elastica v/L {e['v']:.4f}")
        ax[0].axhline(e["u"], color="k", ls="-.", lw=0.8, label=f"elastica u/L {e['u']:.4f}")
        ax[0].set_xlabel("t / T1")
        ax[0].set_ylabel("tip displacement / L")
        ax[0].legend(fontsize=8)
        ax[0].grid(True, alpha=0.3)
        if c.dump is not None:
            dp = c.dump
            x, y, J = dp["x"], dp["y"], dp["c_F[10]"]
            X0 = x - dp["c_d[1]"]
            if a.dim == 3:    # the mid-plane layer z ~ B/2
                z0 = dp["z"] - dp["c_d[3]"]
                layers = np.unique(np.round(z0 / c.dx, 3))
                zmid = layers[np.argmin(np.abs(layers * c.dx - np.median(z0)))] * c.dx
                k = np.abs(z0 - zmid) < 0.01 * c.dx
                x, y, J, X0 = x[k], y[k], J[k], X0[k]
            sc = ax[1].scatter(x * 1e3, y * 1e3, c=J, s=4, cmap="coolwarm", vmin=0.5, vmax=1.5)
            plt.colorbar(sc, ax=ax[1], label="det F")
            # the elastica's centre line
            sol = el._shoot(alpha, el.brentq(lambda k: el._shoot(alpha, k).y[1, -1], 1e-12 * alpha,
                                              alpha * (1 + 1e-9)), dense=True)
            s = np.linspace(0, 1, 200)
            xy = sol.sol(s)
            ax[1].plot(xy[2] * 100, 5 - xy[3] * 100, "k-", lw=0.8, label="elastica centre line")
            ax[1].set_aspect("equal")
            ax[1].set_xlabel("x [mm]")
            ax[1].set_ylabel("y [mm]")
            ax[1].legend(fontsize=8, loc="upper right")
            # zoom on the root, where the compressed face meets the clamp
            root = X0 < 0.02
            ax[2].scatter(x[root] * 1e3, y[root] * 1e3, c=J[root], s=14, cmap="coolwarm",
                          vmin=0.5, vmax=1.5, edgecolors="k", linewidths=0.2)
            ax[2].set_aspect("equal")
            ax[2].set_xlabel("x [mm]")
            ax[2].set_title("root zone, reference x < 20 mm", fontsize=9)
        ax[1].set_title("final state" + (" (mid-plane layer)" if a.dim == 3 else ""), fontsize=9)
        fig.tight_layout()
        fig.savefig(a.png, dpi=120)


if __name__ == "__main__":
    main()
