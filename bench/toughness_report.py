#!/usr/bin/env python3
"""Report of bench/toughness.sh: the fracture energy the damage model
dissipates (pure-shear strip, bench/in.toughness) against the G_c it is given.

  toughness_report.py --out DIR --doc doc/toughness.md CASE ...

Ramp cases ('ramp-...'): the grip strain rises slowly; the onset G is the
energy release rate G = W D = M eps^2 D / 2 at the first bond broken after
set-up, i.e. the model's static fracture energy.  Also G at a tip advance of
1 mm.  Fixed-strain cases ('run-...'): the strip starts in the uniform strain
with G = G0 and the crack runs at fixed grips; its steady speed (a line fitted
to the tip position over 10-30 mm of advance) is the speed at which the
model dissipates G0 per unit crack area, Gamma(v) = G0.
"""
import argparse
import os
import re
import subprocess
import sys

import numpy as np

C_R = 2125.0    # Rayleigh speed of the glass (m/s), as in examples/crack-branching
# the '-cal' cases (glass) are given G_c / k, k = the measured G_onset / G_c
# given: the glass's own G_c is what the model should then dissipate
GLASS_GC = 3.0


def log_values(path):
    """Gc given, s_c, h/dx, dx, nu, family from the case's log (LAMMPS echoes
    a command once per substitution: the last echo that parses is the one run)."""
    txt = open(path).read()

    def last(pattern, groups=1):
        val = None
        for m in re.finditer(pattern, txt):
            try:
                val = [float(m.group(i + 1)) for i in range(groups)]
            except ValueError:
                pass
        return val

    out = {}
    v = last(r"pair_coeff\s+1 1 E \S+ nu (\S+) rho \S+ Gc (\S+)", 2)
    if v:
        out["nu"], out["Gc"] = v
    v = last(r"critical stretch s_c = (\S+)")
    if v:
        out["sc"] = v[0]
    # the deck's 'variable h equal ${hdx}*${dx}', as run (the lattice spacing
    # LAMMPS prints is not dx for a turned lattice)
    v = last(r"variable h\s+equal (\S+)\*(\S+)", 2)
    if v:
        out["hdx"], out["dx"] = v
    v = last(r"\nfamily (\S+)")
    out["family"] = v[0] / out["dx"] if v and "dx" in out else None
    out["finished"] = "Total wall time" in txt
    return out


def ramp(dat):
    d = np.loadtxt(dat, ndmin=2)
    b0, tip0 = d[0, 3], d[0, 4]
    grew = np.nonzero(d[:, 3] > b0)[0]
    if len(grew) == 0:
        return None
    i = grew[0]
    res = {"G_onset": d[i, 2], "t_onset": d[i, 0], "strain_onset": d[i, 1]}
    adv = np.nonzero(d[:, 4] - tip0 >= 0.001)[0]
    res["G_1mm"] = d[adv[0], 2] if len(adv) else float("nan")
    return res


def steady(dat):
    """Crack speed between the first times the tip has advanced 10 and 30 mm
    (first crossings, so that an arrest later does not enter); a crack that
    stops short of 30 mm: its mean speed from 5 mm to where it stopped."""
    d = np.loadtxt(dat, ndmin=2)
    t, tip, off = d[:, 0], d[:, 4], d[:, 5]
    adv = tip - tip[0]
    res = {"G0": d[0, 2], "off_max": int(off.max()), "adv_max": adv.max(), "arrested": adv.max() < 0.03}

    def first(a):
        i = np.nonzero(adv >= a)[0]
        return t[i[0]] if len(i) else None

    if not res["arrested"]:
        dt = first(0.03) - first(0.01)
        res["v"] = 0.02 / dt if dt > 0 else float("nan")    # nan: the tip jumped
    elif adv.max() > 0.01:
        res["v"] = (adv.max() - 0.005) / (first(adv.max()) - first(0.005))
    else:
        res["v"] = float("nan")
    return res


def orient(dat, final):
    """ramp with a turned lattice: G at onset, 1 mm and 5 mm of growth; the
    crack path's angle to the crack line (a line fitted to the reference
    positions of the particles with phi >= 0.3 beyond 1 mm ahead of the
    pre-crack tip, from the final damage dump)"""
    r = ramp(dat)
    if r is None:
        return None
    d = np.loadtxt(dat, ndmin=2)
    tip0 = d[0, 4]
    adv = np.nonzero(d[:, 4] - tip0 >= 0.005)[0]
    r["G_5mm"] = d[adv[0], 2] if len(adv) else float("nan")
    r["off"] = int(d[:, 5].max())
    rows = [ln.split() for ln in open(final) if len(ln.split()) == 4 and not ln.startswith("ITEM")]
    p = np.array([[float(v) for v in row[1:]] for row in rows]) if rows else np.zeros((0, 3))
    m = (p[:, 0] > tip0 + 0.001) & (p[:, 2] >= 0.3) if len(p) else np.zeros(0, bool)
    r["path"] = np.degrees(np.arctan(np.polyfit(p[m, 0], p[m, 1], 1)[0])) if m.sum() > 3 else float("nan")
    return r


def code_of(outdir, names):
    """The commits the runs were made at (from the md5 of the binary is not
    enough: the report lists the git commit at report time and the binaries)."""
    md5 = set()
    for n in names:
        p = os.path.join(outdir, n + ".binary")
        if os.path.exists(p):
            md5.add(open(p).read().split()[0][:12])
    return sorted(md5)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("--doc", required=True)
    ap.add_argument("cases", nargs="+")
    a = ap.parse_args()

    rows_r, rows_s, rows_o = [], [], []
    for n in a.cases:
        logp = os.path.join(a.out, n + ".log")
        datp = os.path.join(a.out, n + ".dat")
        if not (os.path.exists(logp) and os.path.exists(datp)):
            print(f"toughness_report: {n}: no run", file=sys.stderr)
            continue
        lv = log_values(logp)
        if n.startswith("orient-"):
            rows_o.append((n, lv, orient(datp, os.path.join(a.out, n + ".final.dump"))))
        elif n.startswith("ramp-"):
            r = ramp(datp)
            rows_r.append((n, lv, r))
        else:
            rows_s.append((n, lv, steady(datp)))

    try:
        commit = subprocess.run(["git", "-C", os.path.dirname(os.path.abspath(a.doc)), "log", "-1",
                                 "--format=%h %ci"], capture_output=True, text=True).stdout.strip()
    except OSError:
        commit = "?"
    L = []
    L.append("# The fracture energy the damage model dissipates")
    L.append("")
    L.append("Generated by `bash bench/toughness.sh` (deck `bench/in.toughness`, report "
             "`bench/toughness_report.py`); report written at " + commit +
             "; LAMMPS binaries (md5) of the runs: " + ", ".join(code_of(a.out, a.cases)) + ".")
    L.append("")
    L.append("`pair_style tlsph/damage` breaks a bond at the critical stretch s_c that the thesis's "
             "Eq. 2.28 derives from the fracture energy G_c (a peridynamic formula with the horizon "
             "delta = h). Whether the discretisation then dissipates G_c per unit crack area is a "
             "property of the TLSPH model, not of the formula, so it is measured here with the "
             "pure-shear strip of Rivlin and Thomas: a strip of height D between rigid grips, "
             "pulled apart in uniaxial strain eps, with a crack along its mid-height. Far ahead of "
             "the tip the strain energy density is W = M eps^2 / 2 (M = lambda + 2 mu, plane "
             "strain), far behind it zero, so a crack advancing by da releases G = W D per unit "
             "length whatever its length; the crack grows when G reaches the model's fracture "
             "energy. 60 mm x 10.x mm strip (D = the height between the grips' inner particle "
             "rows), pre-crack 20 mm from the left edge, grips >= 2h thick, glass (E 32 GPa, "
             "rho 2450) unless stated, the crack-branching deck's coefficients (alpha 0.03, "
             "alpha_d 0.4, gamma 1, filter 0.5 0.5).")
    L.append("")
    L.append("## Static fracture energy (slow loading, onset of growth)")
    L.append("")
    L.append("Grip strain rate 2 /s (steel: 40 /s), about 30 (steel 70) wave transits of D "
             "before the onset; G_onset = M eps^2 D / 2 at the first bond broken after set-up "
             "(thermo every 0.25 us: the strain is read to 0.3 %, G to 0.7 %).")
    L.append("")
    L.append("| case | h/dx | family | nu | dx [mm] | G_c given [J/m^2] | s_c | G_onset [J/m^2] | "
             "**G_onset / G_c given** | G at 1 mm advance / G_c given | G_onset / material G_c |")
    L.append("|---|---|---|---|---|---|---|---|---|---|---|")
    for n, lv, r in rows_r:
        if r is None:
            L.append(f"| {n} | | | | | | | no growth | | |")
            continue
        fam = f"{lv['family']:.0f} dx" if lv.get("family") else "2h"
        L.append(f"| {n} | {lv.get('hdx', float('nan')):.2f} | {fam} | {lv.get('nu', float('nan')):g} | "
                 f"{lv.get('dx', 0) * 1e3:.3g} | {lv.get('Gc', float('nan')):.5g} | {lv.get('sc', float('nan')):.4g} | "
                 f"{r['G_onset']:.4g} | **{r['G_onset'] / lv['Gc']:.3f}** | {r['G_1mm'] / lv['Gc']:.3f} | "
                 + (f"{r['G_onset'] / GLASS_GC:.3f} |" if n.endswith("-cal") else " |"))
    L.append("")
    L.append("## Direction: the lattice turned against the crack")
    L.append("")
    L.append("The same ramp with the square lattice turned by theta against the crack line (LAMMPS "
             "`lattice sq ... orient x a b 0`, theta = atan(b/a)); dx = 0.5 mm; G in units of the "
             "G_c given. A continuum of the same material has the same fracture energy in every "
             "direction and grows the crack straight along its line (mode I). Path: the angle to "
             "the crack line of a line fitted to the particles with phi >= 0.3 more than 1 mm "
             "ahead of the pre-crack tip at the end (10 mm of growth); off: particles with a broken "
             "bond farther than D/4 from the line.")
    L.append("")
    L.append("| case | h/dx | family | theta [deg] | G_onset / G_c | G at 1 mm / G_c | G at 5 mm / G_c | "
             "path [deg] | off |")
    L.append("|---|---|---|---|---|---|---|---|---|")
    for n, lv, r in rows_o:
        o = n.rsplit("-o", 1)[1]
        th = np.degrees(np.arctan2(int(o[1]), int(o[0])))
        fam = f"{lv['family']:.0f} dx" if lv.get("family") else "2h"
        if r is None:
            L.append(f"| {n} | {lv.get('hdx', 0):.2f} | {fam} | {th:.1f} | no growth | | | | |")
            continue
        L.append(f"| {n} | {lv.get('hdx', 0):.2f} | {fam} | {th:.1f} | {r['G_onset'] / lv['Gc']:.3f} | "
                 f"{r['G_1mm'] / lv['Gc']:.3f} | {r['G_5mm'] / lv['Gc']:.3f} | {r['path']:.1f} | {r['off']} |")
    L.append("")
    L.append("## Dynamic fracture energy (fixed grips, steady crack speed)")
    L.append("")
    L.append("The strip starts in the uniform strain with G = G0 (grips fixed) and the crack runs; "
             "v is the mean speed between the tip's first advance by 10 mm and by 30 mm (a crack "
             "that stops earlier: from 5 mm to where it stopped, marked 'arrested'). 'off' counts the "
             "particles with a broken bond farther than D/4 from the crack line (branches; 0 for one "
             "straight crack). Rayleigh speed of the glass c_R = 2125 m/s.")
    L.append("")
    L.append("| case | h/dx | dx [mm] | G0 [J/m^2] | G0 / G_onset | G0 / G_c given | v [m/s] | v / c_R | off (max) | note |")
    L.append("|---|---|---|---|---|---|---|---|---|---|")
    onset = {}
    for n, lv, r in rows_r:
        if (r and lv.get("Gc") == 3.0 and "nu0.2" in n and "fam" not in n and "rate" not in n
                and n.startswith("ramp-h")):    # the stretch criterion only
            onset.setdefault(round(lv["hdx"], 2), []).append(r["G_onset"])
    curves = {}
    for n, lv, r in rows_s:
        hd = round(lv.get("hdx", 0), 2)
        go = np.mean(onset[hd]) if hd in onset else float("nan")
        what = ("arrested at %.1f mm" % (r["adv_max"] * 1e3) if r["arrested"] else "") + \
               ("; branched" if r["off_max"] > 0 else "")
        L.append(f"| {n} | {hd:.2f} | {lv.get('dx', 0) * 1e3:.3g} | {r['G0']:.4g} | {r['G0'] / go:.2f} | "
                 f"{r['G0'] / lv['Gc']:.2f} | {r['v']:.0f} | {r['v'] / C_R:.2f} | {r['off_max']} | {what.strip('; ')} |")
        if r["off_max"] == 0:
            curves.setdefault((hd, round(lv.get("dx", 0) * 1e3, 3)), []).append((r["G0"] / go, r["v"] / C_R))
    L.append("")
    png = os.path.splitext(a.doc)[0] + ".png"
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        for (hd, dxmm), pts in sorted(curves.items()):
            pts = sorted(pts)
            fine = dxmm < 0.4    # the finer strip: open squares over the 0.5 mm line
            ax.plot([p[1] for p in pts], [p[0] for p in pts], "s--" if fine else "o-", mfc="none" if fine else None,
                    ms=10 if fine else 6, label=f"h = {hd} dx, dx = {dxmm} mm")
        ax.set_xlabel("steady crack speed v / c_R")
        ax.set_ylabel("G / G_onset  (dynamic / static fracture energy)")
        ax.set_title("one straight crack at fixed G (branched runs left out)", fontsize=9)
        ax.set_xlim(0, 1)
        ax.grid(alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(png, dpi=110)
        L.append(f"![Gamma(v)]({os.path.basename(png)})")
        L.append("")
    except ImportError:
        pass
    notes = os.path.join(os.path.dirname(os.path.abspath(__file__)), "toughness-notes.md")
    if os.path.exists(notes):
        L.append(open(notes).read().rstrip())
        L.append("")
    open(a.doc, "w").write("\n".join(L) + "\n")
    print("\n".join(L))


if __name__ == "__main__":
    main()
