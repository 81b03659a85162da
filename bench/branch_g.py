#!/usr/bin/env python3
"""Can a threshold on G separate the two fracture benchmarks? (bench/branch_g.sh)

Reads the runs of the bench/fracture.sh settings given (tipg-j, tipg-jin,
tipg-j-seg-N, tipg-i: branching off, the tips' G/G_c written at every step by
the decks' -var tips 1 -var ttips 1e-12) and writes bench/branch-g.md: a
summary over the settings, then per setting and resolution, the largest G/G_c a Kalthoff-Winkler 2D
notch tip reaches while it grows, and the largest the glass plate's single tip
reaches before 25 us and before 45 us (the issues' branching window).

A branching rule "split where G >= X G_c", tested at every step, branches the
plate inside the window and leaves the Kalthoff-Winkler cracks whole only if
max(KW, plate before 25 us) < X <= plate before 45 us. The tips' speed is
Freund's c_R (1 - G_c / G), a function of G alone, so a threshold on the speed
is the same rule (X = 1 / (1 - v / c_R)).
"""
import argparse
import glob
import os
import re
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "examples", "common"))
import acceptance as A  # noqa: E402  (the window and the Rayleigh speeds, one place)
import run_info  # noqa: E402  (the runs' code)

BR_LO, BR_HI = A.BR_WINDOW.value    # s


def growing(t, length, g):
    """The records while the tip grows: from its first move to the record where
    its path reaches its final length (a tip that stopped keeps its last G)."""
    moved = np.nonzero(length > length[0] + 1e-12)[0]
    if len(moved) == 0:
        return np.zeros(0, dtype=bool)
    last = np.nonzero(length >= length[-1] - 1e-12)[0][0]
    sel = np.zeros(len(t), dtype=bool)
    sel[moved[0] - 1 if moved[0] > 0 else 0:last + 1] = True
    return sel


WINDOW = 1e-6    # s, the running mean's width


def running_mean(t, g):
    """G/G_c averaged over WINDOW (centred, records at every step)"""
    n = max(1, int(round(WINDOW / np.median(np.diff(t))))) if len(t) > 1 else 1
    if len(g) < n:
        return np.array([g.mean()]) if len(g) else g
    return np.convolve(g, np.ones(n) / n, mode="valid")


def segments(x, y, g):
    """The straight segments a tip grew (runs of one direction of motion):
    their directions [deg], the kinks between them [deg], and G/G_c averaged
    over each segment's first quarter of steps and over the rest (segments of
    8 steps or more)."""
    dx, dy = np.diff(x), np.diff(y)
    mv = np.nonzero(np.hypot(dx, dy) > 1e-9)[0]
    if len(mv) < 2:
        return None
    ang = np.degrees(np.arctan2(dy[mv], dx[mv]))
    b = [0] + list(np.nonzero(np.abs(np.diff(ang)) > 0.05)[0] + 1) + [len(ang)]
    dirs = [ang[b[k]:b[k + 1]].mean() for k in range(len(b) - 1)]
    first, rest = [], []
    for k in range(1, len(b) - 1):
        rec = mv[b[k]:b[k + 1]] + 1    # the records after each move of the segment
        if len(rec) >= 8:
            q = len(rec) // 4
            first.append(g[rec[:q]].mean())
            rest.append(g[rec[q:]].mean())
    return dict(dirs=np.array(dirs), kinks=np.abs(np.diff(dirs)), mean=ang.mean(),
                p5=np.percentile(ang, 5), p95=np.percentile(ang, 95),
                gfirst=np.mean(first) if first else float("nan"),
                grest=np.mean(rest) if rest else float("nan"))


def finished(tips):
    """the run of this .tips file ended (its log has LAMMPS's last line)"""
    log = tips[:-len(".tips")] + ".log"
    return os.path.exists(log) and "Total wall time" in open(log).read()


def mm_of(path):
    return re.search(r"-([0-9.]+)\.tips$", path).group(1)


def measure(out):
    """the tips' figures of one setting's runs (folder out)"""
    kw, pl = {}, {}
    for f in filter(finished, glob.glob(os.path.join(out, "kalthoff-*.tips"))):
        d = np.loadtxt(f, ndmin=2)    # time, x y length G/Gc of the upper tip, the same of the lower
        sel = growing(d[:, 0], d[:, 3], d[:, 4])
        g = d[sel, 4]
        if len(g):
            kw[mm_of(f)] = dict(n=len(g), gmax=g.max(), gmean=running_mean(d[sel, 0], g).max(),
                                tmax=d[sel, 0][g.argmax()], ymax=d[sel, 2][g.argmax()],
                                f2=np.mean(g >= 2.0), med=np.median(g),
                                mirror=np.max(np.abs(d[:, 4] - d[:, 8])),
                                seg=segments(d[:, 1], d[:, 2], d[:, 4]))
    for f in filter(finished, glob.glob(os.path.join(out, "branching-*.tips"))):
        d = np.loadtxt(f, ndmin=2)    # time, x y length G/Gc speed of the pre-crack's tip
        t, g = d[:, 0], d[:, 4]
        first2 = t[np.nonzero(g >= 2.0)[0][0]] if np.any(g >= 2.0) else float("nan")
        w = t <= BR_HI
        pl[mm_of(f)] = dict(g25=g[t < BR_LO].max(), g45=g[w].max(), m45=running_mean(t[w], g[w]).max(),
                            t45=t[w][g[w].argmax()], gall=g.max(), first2=first2)
    return kw, pl


def section(setting, kw, pl):
    rows_k = sorted(kw, key=lambda m: -float(m))
    rows_p = sorted(pl, key=lambda m: -float(m))
    L = [f"## Setting `{setting}`", "", "Kalthoff-Winkler 2D, the notch tips while they grow:", "",
         f"| dx [mm] | steps | largest G/G_c | at [us] | at y [mm] | largest {WINDOW * 1e6:g} us mean "
         "| median G/G_c | steps with G >= 2 G_c | upper - lower, largest difference |",
         "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for m in rows_k:
        r = kw[m]
        L.append(f"| {m} | {r['n']} | {r['gmax']:.2f} | {r['tmax'] * 1e6:.1f} | {r['ymax'] * 1e3:.1f} | "
                 f"{r['gmean']:.2f} | {r['med']:.2f} | {100 * r['f2']:.0f} % | {r['mirror']:.2g} |")
    L += ["", "The same tips' path: the straight segments they grew (the tip model's segments, "
          "each kinked by the maximum tangential stress rule where it starts), the directions "
          "of their steps from the x axis, and G/G_c over each segment's first quarter of steps "
          "against its rest:", "",
          "| dx [mm] | segments | directions, 5th-95th percentile of the steps [deg] | "
          "mean step direction [deg] | kink between segments, mean / largest [deg] | "
          "G/G_c first quarter / rest |", "|---|---:|---|---:|---|---|"]
    for m in rows_k:
        q = kw[m]["seg"]
        if q is None:
            continue
        L.append(f"| {m} | {len(q['dirs'])} | {q['p5']:.1f}-{q['p95']:.1f} | "
                 f"{q['mean']:.1f} | {q['kinks'].mean():.1f} / {q['kinks'].max():.1f} | "
                 f"{q['gfirst']:.2f} / {q['grest']:.2f} |")
    L += ["", "The glass plate, the pre-crack's tip (unbranched):", "",
          f"| dx [mm] | largest G/G_c before {BR_LO * 1e6:g} us | before {BR_HI * 1e6:g} us | at [us] | "
          f"largest {WINDOW * 1e6:g} us mean before {BR_HI * 1e6:g} us | over the run (90 us) "
          "| G >= 2 G_c first at [us] |",
          "|---|---:|---:|---:|---:|---:|---:|"]
    for m in rows_p:
        r = pl[m]
        f2 = "never" if r["first2"] != r["first2"] else f"{r['first2'] * 1e6:.1f}"
        L.append(f"| {m} | {r['g25']:.2f} | {r['g45']:.2f} | {r['t45'] * 1e6:.1f} | {r['m45']:.2f} | "
                 f"{r['gall']:.2f} | {f2} |")
    if not kw or not pl:
        return L + ["", "(runs missing: no verdict)", ""]
    gk = max(kw[m]["gmax"] for m in kw)
    lo = max([gk] + [pl[m]["g25"] for m in pl])
    hi = min(pl[m]["g45"] for m in pl)
    L += ["", f"A rule 'split where G >= X G_c' tested at every step needs X above every "
          f"Kalthoff-Winkler tip's largest G/G_c ({gk:.2f}, over the {len(kw)} resolutions) "
          f"and above the plate's before {BR_LO * 1e6:g} us, and X at most the plate's largest "
          f"before {BR_HI * 1e6:g} us at every resolution ({hi:.2f} at the least): "
          + (f"X in ({lo:.2f}, {hi:.2f}]." if lo < hi else
             f"no X exists ({lo:.2f} >= {hi:.2f}). With Freund's speed law the same holds "
             f"for a threshold on the tips' speed: the Kalthoff-Winkler tips reach "
             f"{1 - 1 / gk:.2f} c_R, the plate's {1 - 1 / hi:.2f} c_R before {BR_HI * 1e6:g} us "
             f"(its smallest over the resolutions).")]
    km = max(kw[m]["gmean"] for m in kw)
    kmin = min(kw[m]["gmean"] for m in kw)
    pm = min(pl[m]["m45"] for m in pl)
    L += ["", f"The same with G/G_c averaged over {WINDOW * 1e6:g} us: the Kalthoff-Winkler tips' "
          f"largest means are {kmin:.2f}-{km:.2f}, the plate's before {BR_HI * 1e6:g} us "
          f"{pm:.2f} at the least: "
          + ("a threshold between them exists." if km < pm else "no threshold separates them either."), ""]
    return L


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", required=True, help="bench/out/fracture")
    ap.add_argument("--doc", required=True)
    ap.add_argument("--title", default="Can a threshold on G separate the fracture benchmarks? "
                    "(generated by bench/branch_g.sh)")
    ap.add_argument("--intro", help="a Markdown file after the title (default bench/branch-g-notes.md)")
    ap.add_argument("settings", nargs="+", help="tipg-j, tipg-jin")
    a = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    commit = subprocess.run(["git", "-C", root, "describe", "--always", "--dirty"],
                            capture_output=True, text=True).stdout.strip()
    L = [f"# {a.title}", ""]
    intro = a.intro or os.path.join(root, "bench", "branch-g-notes.md")
    if os.path.exists(intro):
        L += [open(intro).read().rstrip(), ""]
    codes = run_info.runs_code([os.path.join(a.out, st) for st in a.settings])
    L += [f"Runs made with code {codes}; report written at {commit}. "
          "Settings of bench/fracture.sh: `tipg-j` is the recommended model (`criterion tip kfit j`, "
          "h = 1.33 dx, alpha 0.09, alpha_d 3.1, gamma 0, filter 0.65 0.1) with branching off; "
          "`tipg-jin` the same with J's inertia term (`jinertia yes`); `tipg-j-seg-N` the same as "
          "`tipg-j` with the tips' straight segments N h long (`tipseg N`; the default is the K "
          "samples' reach, 4.5 h); `tipg-i` the same as `tipg-j` with K_II / K_I from the "
          "interaction integrals (`kfit interaction`); `tipg-is` the same as `tipg-i` with `tipdir segment` "
          "(the kink that leaves each segment's end in mode I, from the T-stress). Each writes the tips' G/G_c from compute tlsph/crack/tips at "
          "every step (the decks' `-var tips 1 -var ttips 1e-12`). Kalthoff-Winkler 2D at 16.5 m/s "
          "for 110 us, the glass plate at 1 MPa for 90 us, 1 MPI rank. A Kalthoff-Winkler tip "
          "counts while it grows (from its first move until its path stops lengthening); its "
          "tables' last column compares it with its mirror image.", ""]
    data = {st: measure(os.path.join(a.out, st)) for st in a.settings}
    L += ["## Summary", "",
          "| setting | Kalthoff-Winkler: largest G/G_c | largest 1 us mean | kink between segments, mean [deg] "
          f"| plate: largest G/G_c before {BR_HI * 1e6:g} us (least over dx) | a threshold on G separates them |",
          "|---|---|---|---|---:|---|"]
    for st, (kw, pl) in data.items():
        if not kw or not pl:
            L.append(f"| `{st}` | - | - | - | - | runs missing |")
            continue
        gm = [kw[m]["gmax"] for m in kw]
        g1 = [kw[m]["gmean"] for m in kw]
        kk = [kw[m]["seg"]["kinks"].mean() for m in kw if kw[m]["seg"] is not None and len(kw[m]["seg"]["kinks"])]
        lo = max([max(gm)] + [pl[m]["g25"] for m in pl])
        hi = min(pl[m]["g45"] for m in pl)
        L.append(f"| `{st}` | {min(gm):.2f}-{max(gm):.2f} ({len(kw)} dx) | {min(g1):.2f}-{max(g1):.2f} | "
                 + (f"{min(kk):.1f}-{max(kk):.1f}" if kk else "-")
                 + f" | {hi:.2f} ({len(pl)} dx) | " + ("yes" if lo < hi else "no") + " |")
    L.append("")
    for st, (kw, pl) in data.items():
        L += section(st, kw, pl)
    open(a.doc, "w").write("\n".join(L))
    print("\n".join(L))


if __name__ == "__main__":
    main()
