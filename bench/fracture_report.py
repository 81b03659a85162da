#!/usr/bin/env python3
"""The fracture convergence report (bench/fracture.sh): for each model setting,
the Kalthoff-Winkler 2D crack angles, initiation, peak tip speed and edge
times, and the crack-branching plate's initiation, branching time, branches
and right-edge times, against dx; tables into a Markdown page and plots with
the literature bands (experiment about 70 deg and the issues' 63-72 deg band
for the angle; the issues' branching window 25-45 us and the 25-40 us of the
phase-field and XFEM studies the thesis cites; the Rayleigh speeds). Every
band and criterion comes from examples/common/acceptance.py.

    fracture_report.py --out bench/out/fracture --doc doc/fracture-convergence.md SETTING ...

Reads <out>/<setting>/{kalthoff,branching}-<dx mm>.crack.json (from the
examples' summarise.py, tools/crack_measure.py) and the LAMMPS logs."""
import argparse
import json
import os
import re
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "examples", "common"))
import acceptance as A  # noqa: E402  (the acceptance bands, one place)
import run_info  # noqa: E402  (the runs' code)

RAYLEIGH_KW, RAYLEIGH_GLASS = A.RAYLEIGH_STEEL.value, A.RAYLEIGH_GLASS.value    # m/s
BAND_LO, BAND_HI = A.KW_ANGLE_BAND.value           # deg, the Kalthoff-Winkler angle band
MIRROR = A.KW_MIRROR_DEG.value                     # deg
SPREAD = A.KW_SPREAD_DEG.value                     # deg
NRES = A.KW_MIN_RESOLUTIONS.value                  # resolutions in the band, at least
BR_LO, BR_HI = A.BR_WINDOW.value                   # s, the branching window (issues 12, 26)
LIT_LO, LIT_HI = A.LIT_BRANCHING_BAND.value        # s, phase-field / XFEM


def fmt(v, f="{:.1f}", scale=1.0):
    return "-" if v is None else f.format(v * scale)


def log_info(prefix):
    """particles and wall time from a LAMMPS log"""
    try:
        txt = open(prefix + ".log").read()
    except OSError:
        return None, None
    n = re.findall(r"^Loop time of [\d.eE+-]+ on \d+ procs for \d+ steps with (\d+) atoms", txt, re.M)
    w = re.search(r"^Total wall time: (\d+):(\d+):(\d+)", txt, re.M)
    wall = int(w.group(1)) * 3600 + int(w.group(2)) * 60 + int(w.group(3)) if w else None
    return (int(n[-1]) if n else None), wall


def cases(out, setting, kind):
    d = os.path.join(out, setting)
    rows = []
    if not os.path.isdir(d):
        return rows
    for f in os.listdir(d):
        m = re.fullmatch(kind + r"-([\d.]+)\.crack\.json", f)
        if m:
            prefix = os.path.join(d, f[:-len(".crack.json")])
            rows.append((float(m.group(1)), json.load(open(prefix + ".crack.json")), prefix))
    return sorted(rows, key=lambda r: -r[0])


def first_edge(c):
    e = c.get("edge_reached_time") or {}
    if not e:
        return None, None
    k = min(e, key=e.get)
    return k, e[k]


def kalthoff_table(rows):
    out = ["| dx [mm] | particles | angle upper / lower [deg] | mirror difference [deg] | "
           "initiation [us] | first edge reached | peak tip speed [m/s] | branches at the end / "
           "short side branches (max), upper | wall [s] |",
           "|---|---:|---|---:|---:|---|---:|---|---:|"]
    for mm, j, prefix in rows:
        cr = j["cracks"]
        up, lo = cr.get("upper", {}), cr.get("lower", {})
        n, wall = log_info(prefix)
        k, t = first_edge(up)
        out.append(f"| {mm:g} | {n or '-'} | {fmt(up.get('angle_deg'))} / {fmt(lo.get('angle_deg'))} | "
                   f"{fmt(j.get('symmetry', {}).get('angle_diff_deg'), '{:.2f}')} | "
                   f"{fmt(up.get('initiation_time'), scale=1e6)} | "
                   f"{'-' if k is None else f'{k} at {t * 1e6:.1f} us'} | "
                   f"{fmt(up.get('speed_max'), '{:.0f}')} | "
                   f"{up.get('branches_final', '-')} / {up.get('side_branches_max', '-')} | "
                   f"{wall if wall is not None else '-'} |")
    return out


def branching_table(rows):
    out = ["| dx [mm] | particles | initiation [us] | branching [us] | branches at the end | "
           "short side branches (max) | branch point [mm] | right edge reached [us] | "
           "branches end at (x, y) [mm], angle [deg] | peak tip speed [m/s] | wall [s] |",
           "|---|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|"]
    for mm, j, prefix in rows:
        c = list(j["cracks"].values())[0]
        n, wall = log_info(prefix)
        edge = (c.get("edge_reached_time") or {}).get("xmax")
        out.append(f"| {mm:g} | {n or '-'} | {fmt(c.get('initiation_time'), scale=1e6)} | "
                   f"{fmt(c.get('branching_time'), scale=1e6)} | {c.get('branches_final', '-')} | "
                   f"{c.get('side_branches_max', '-')} | {fmt(c.get('branch_point_s'), scale=1e3)} | "
                   f"{fmt(edge, scale=1e6)} | {branch_ends(c)} | "
                   f"{fmt(c.get('speed_max'), '{:.0f}')} | {wall if wall is not None else '-'} |")
    return out


def branch_ends(c):
    """where the branches at the end of the run end: each one's tip (x, y) in
    mm, lowest y first (the glass plate is 100 x 40 mm: its right corners are
    (100, 0) and (100, 40)), with the edges it touches, and its angle to +x
    (a line fitted over the whole branch, tools/crack_measure.py). The
    branch point (the column before) is the crack's arc length from the
    pre-crack's tip to where it split."""
    ends = sorted(c.get("branches_at_end") or [], key=lambda b: b["tip"][1])
    if not ends:
        return "-"
    return "; ".join(f"{b['tip'][0] * 1e3:.1f}, {b['tip'][1] * 1e3:.1f}"
                     + (f" ({'+'.join(b['edges'])})" if b.get("edges") else "")
                     + (f", {b['angle_deg']:+.1f}" if b.get("angle_deg") is not None else "") for b in ends)


def kalthoff_verdict(rows):
    """the issue's Kalthoff-Winkler criteria over the resolutions run:
    (angle range text, list of failed criteria)"""
    if not rows:
        return "-", ["not run"]
    angs, bad, good = [], [], []
    for mm, j, prefix in rows:
        cr = j["cracks"]
        up, lo = cr.get("upper", {}), cr.get("lower", {})
        # this resolution meets the band, the speed limit and the mirror symmetry
        d0 = j.get("symmetry", {}).get("angle_diff_deg")
        pair = [c.get("angle_deg") for c in (up, lo)]
        if (all(a is not None and BAND_LO <= a <= BAND_HI for a in pair) and d0 is not None
                and abs(d0) <= MIRROR
                and all((c.get("speed_max") or 0.0) < RAYLEIGH_KW for c in (up, lo))):
            good.append((mm, pair))
        for c in (up, lo):
            a = c.get("angle_deg")
            angs.append(a)
            if a is None or not BAND_LO <= a <= BAND_HI:
                bad.append(f"angle {fmt(a)} at {mm:g} mm")
            if (c.get("speed_max") or 0.0) >= RAYLEIGH_KW:
                bad.append(f"tip speed {fmt(c.get('speed_max'), '{:.0f}')} m/s at {mm:g} mm")
            # the experiment: one crack from each notch, unbranched
            nb, side = c.get("branches_final"), c.get("side_branches_max") or 0
            if (nb is not None and nb > 1) or side > 0:
                bad.append(f"branched at {mm:g} mm ({nb} branch(es) at the end, {side} short side "
                           f"branch(es))")
        d = j.get("symmetry", {}).get("angle_diff_deg")
        if d is None or abs(d) > MIRROR:
            bad.append(f"mirror difference {fmt(d)} at {mm:g} mm")
    ok = [a for a in angs if a is not None]
    spread = max(ok) - min(ok) if ok else None
    if spread is None or spread > SPREAD:
        bad.append(f"spread {fmt(spread)} deg")
    if len(rows) < NRES:
        bad.append(f"{len(rows)} resolution(s) ({NRES} asked)")
    rng = f"{min(ok):.1f}-{max(ok):.1f} ({len(rows)} dx)" if ok else "-"
    # the issue asks the band at four resolutions at least, spread <= 5 deg
    if good:
        ga = [a for _, p in good for a in p]
        rng += (f"; in the band at {len(good)} dx ({', '.join(f'{mm:g}' for mm, _ in good)} mm), "
                f"spread {max(ga) - min(ga):.1f} deg")
    # de-duplicate (both cracks of a run fail alike)
    return rng, list(dict.fromkeys(bad))


def branching_verdict(rows):
    if not rows:
        return "-", ["not run"]
    res, bad = [], []
    for mm, j, prefix in rows:
        c = list(j["cracks"].values())[0]
        t = c.get("branching_time")
        nb = c.get("branches_final")
        side = c.get("side_branches_max") or 0
        two = c.get("two_branches_at_target_time")
        res.append(f"{mm:g} mm: " + ("none" if t is None else f"{t * 1e6:.1f} us, {nb} at the end"))
        if t is None:
            bad.append(f"no branching at {mm:g} mm")
            continue
        if not BR_LO <= t <= BR_HI:
            bad.append(f"branching at {t * 1e6:.1f} us at {mm:g} mm")
        if nb != A.BR_MAIN_BRANCHES.value:
            bad.append(f"{nb} branches at the end at {mm:g} mm")
        if side:
            bad.append(f"{side} side branches at {mm:g} mm")
        if two is None:
            bad.append(f"not two branches at the right edge at {mm:g} mm")
        if (c.get("speed_max") or 0.0) >= RAYLEIGH_GLASS:
            bad.append(f"tip speed at {mm:g} mm")
    return "; ".join(res), list(dict.fromkeys(bad))


def _series(axes, setting, krows, brows, col):
    """draw one setting's runs into axes (dict: ang, ini, br, sp and, optionally, edge)"""
    if krows:
        dx = [r[0] for r in krows]
        for side, mk in (("upper", "o"), ("lower", "v")):
            axes["ang"].plot(dx, [r[1]["cracks"].get(side, {}).get("angle_deg") or float("nan")
                                  for r in krows], mk + "-", color=col, label=f"{setting}, {side}")
        up = [r[1]["cracks"]["upper"] for r in krows]
        axes["ini"].plot(dx, [(c.get("initiation_time") or float("nan")) * 1e6 for c in up], "o-",
                         color=col, label=f"{setting}, Kalthoff")
        axes["sp"].plot(dx, [c.get("speed_max") or float("nan") for c in up], "o-", color=col,
                        label=f"{setting}, Kalthoff")
        if "edge" in axes:
            axes["edge"].plot(dx, [(first_edge(c)[1] or float("nan")) * 1e6 for c in up], "o-",
                              color=col, label=f"{setting}, Kalthoff: a plate edge")
    if brows:
        dx = [r[0] for r in brows]
        cs = [list(r[1]["cracks"].values())[0] for r in brows]
        axes["br"].plot(dx, [(c.get("branching_time") or float("nan")) * 1e6 for c in cs], "s-",
                        color=col, label=setting)
        axes["ini"].plot(dx, [(c.get("initiation_time") or float("nan")) * 1e6 for c in cs], "s--",
                         color=col, label=f"{setting}, branching plate")
        axes["sp"].plot(dx, [c.get("speed_max") or float("nan") for c in cs], "s--", color=col,
                        label=f"{setting}, branching plate")
        if "edge" in axes:
            axes["edge"].plot(dx, [((c.get("edge_reached_time") or {}).get("xmax") or float("nan"))
                                   * 1e6 for c in cs], "s--", color=col,
                              label=f"{setting}, plate: right edge")


def _frame(axes):
    """the literature bands, titles, labels and the dx range of every panel"""
    ex = A.EXP_KW_ANGLE.value
    axes["ang"].axhspan(BAND_LO, BAND_HI, color="0.85", label=f"issue band {BAND_LO:g}-{BAND_HI:g} deg")
    axes["ang"].axhline(ex, color="k", ls="--", lw=1, label=f"experiment ~{ex:g} deg")
    axes["br"].axhspan(LIT_LO * 1e6, LIT_HI * 1e6, color="0.85",
                       label=f"phase-field / XFEM {LIT_LO * 1e6:g}-{LIT_HI * 1e6:g} us")
    axes["br"].axhline(BR_HI * 1e6, color="0.5", ls=":", lw=1, label=f"issue's limit {BR_HI * 1e6:g} us")
    axes["sp"].axhline(RAYLEIGH_KW, color="C3", ls=":", label=f"Rayleigh, steel {RAYLEIGH_KW:.0f} m/s")
    axes["sp"].axhline(RAYLEIGH_GLASS, color="C4", ls=":", label=f"Rayleigh, glass {RAYLEIGH_GLASS:.0f} m/s")
    titles = {"ang": ("Kalthoff-Winkler 2D: crack angle to the impact", "angle [deg]"),
              "ini": ("crack initiation", "time [us]"),
              "br": ("crack branching plate: branching time (none: not drawn)", "time [us]"),
              "sp": ("peak tip speed", "speed [m/s]"),
              "edge": ("time the crack reaches an edge", "time [us]")}
    for k, a in axes.items():
        a.set_title(titles[k][0], fontsize=10)
        a.set_xlabel("dx [mm]")
        a.set_ylabel(titles[k][1])
        a.set_xlim(1.8, 0.25)    # the studied range, finest on the right
        a.grid(alpha=0.3)


def plot(data, png):
    fig, ax = plt.subplots(2, 2, figsize=(11, 8))
    axes = {"ang": ax[0][0], "ini": ax[0][1], "br": ax[1][0], "sp": ax[1][1]}
    _frame(axes)
    for i, (setting, (krows, brows)) in enumerate(data.items()):
        _series(axes, setting, krows, brows, f"C{i}")
    for a in axes.values():
        a.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def plot_kept(data, png, kept):
    """the kept setting beside the thesis's: angle, initiation, branching time,
    peak tip speed and edge times against dx, with the literature bands"""
    fig, ax = plt.subplots(2, 3, figsize=(14, 7.5))
    axes = {"ang": ax[0][0], "ini": ax[0][1], "br": ax[0][2], "sp": ax[1][0], "edge": ax[1][1]}
    ax[1][2].axis("off")
    _frame(axes)
    for i, setting in enumerate(["thesis", kept]):
        if setting in data:
            _series(axes, setting, *data[setting], f"C{i}")
    for a in axes.values():
        a.legend(fontsize=7)
    fig.suptitle(f"kept setting '{kept}' and the thesis's setting 'thesis'", fontsize=11)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--doc", required=True)
    ap.add_argument("--notes", help="a Markdown file inserted after the summary (the findings)")
    ap.add_argument("--kept", help="the kept setting: a second plot of it beside 'thesis'")
    ap.add_argument("--title", default="Fracture convergence (generated by bench/fracture.sh)",
                    help="the report's title")
    ap.add_argument("--intro", help="a Markdown file inserted after the title")
    ap.add_argument("settings", nargs="+")
    a = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    commit = subprocess.run(["git", "-C", root, "describe", "--always", "--dirty"],
                            capture_output=True, text=True).stdout.strip()
    data = {s: (cases(a.out, s, "kalthoff"), cases(a.out, s, "branching")) for s in a.settings}
    png = os.path.splitext(a.doc)[0] + ".png"
    # the plots: the settings run at several resolutions (the scans are one dx each)
    plot({s: v for s, v in data.items() if not s.startswith("scan-")}, png)
    # the code the runs were made with (summarise.py's 'code:' line of each run)
    runs_code = run_info.runs_code([os.path.join(a.out, st) for st in a.settings])
    lines = [f"# {a.title}", ""]
    if a.intro and os.path.exists(a.intro):
        lines += [open(a.intro).read().rstrip(), ""]
    lines += [f"Runs made with code {runs_code}; report written at {commit}. Runs in bench/out/fracture/<setting>/, one per resolution, 1 MPI rank; "
             "measured with tools/crack_measure.py through the examples' summarise.py "
             "(examples/kalthoff-2d/README.md and examples/crack-branching/README.md say how). "
             "Settings: bench/fracture.sh. Acceptance (examples/common/acceptance.py, sources in "
             f"doc/references.rst): Kalthoff-Winkler {BAND_LO:g}-{BAND_HI:g} deg at {NRES} "
             f"resolutions at least, spread <= {SPREAD:g} deg, mirror-symmetric to {MIRROR:g} deg "
             f"(issue 12), and one unbranched crack from each notch, without short side "
             f"branches (the experiment); branching into two main branches between {BR_LO * 1e6:g} and "
             f"{BR_HI * 1e6:g} us (the issues' window, issues 12 and 26). Literature: "
             f"Kalthoff-Winkler about {A.EXP_KW_ANGLE.value:g} deg (experiment); branching between "
             f"{LIT_LO * 1e6:g} and {LIT_HI * 1e6:g} us (phase-field and XFEM studies cited by the "
             f"thesis); Rayleigh speeds {RAYLEIGH_KW:.0f} m/s (maraging steel) and "
             f"{RAYLEIGH_GLASS:.0f} m/s (glass).", "",
             f"![angles, times and speeds against dx]({os.path.basename(png)})", ""]
    if a.kept and a.kept in data:
        png_kept = os.path.splitext(a.doc)[0] + "-kept.png"
        plot_kept(data, png_kept, a.kept)
        lines += [f"The kept setting, `{a.kept}`, beside the thesis's (`thesis`), alone:", "",
                  f"![the kept setting against dx]({os.path.basename(png_kept)})", ""]
    # the acceptance of each setting (the criteria, over the resolutions run)
    lines += ["## Summary: the issue's criteria per setting", "",
              "| setting | Kalthoff angles [deg] | Kalthoff criteria not met | branching | "
              "branching criteria not met |", "|---|---|---|---|---|"]
    for s, (krows, brows) in data.items():
        if s.startswith("scan-"):
            continue
        kr, kb = kalthoff_verdict(krows)
        br, bb = branching_verdict(brows)
        lines.append(f"| `{s}` | {kr} | {'; '.join(kb) if kb else 'all met'} | {br} | "
                     f"{'; '.join(bb) if bb else 'all met'} |")
    lines += [""]
    if a.notes and os.path.exists(a.notes):
        lines += [open(a.notes).read().rstrip(), ""]
    # the one-resolution coefficient scans in one table
    scans = {s: v for s, v in data.items() if s.startswith("scan-")}
    if scans:
        lines += ["## Coefficient scan (Kalthoff-Winkler at 1 mm, crack branching at 0.5 mm)", "",
                  "`scan-A-AD-PHIC-EPS-G`: alpha, alpha_d, velocity filter phi_c and eps, "
                  "hourglass gamma, in both decks; h = 1.33 dx.", "",
                  "| alpha | alpha_d | filter | gamma | Kalthoff angle [deg] | Kalthoff peak tip "
                  "speed [m/s] | branching [us] | branches at the end | side branches | "
                  "right edge (xmax) [us] |", "|---:|---:|---|---:|---|---:|---:|---:|---:|---:|"]
        for s, (krows, brows) in scans.items():
            p = s.split("-")[1:]
            k = krows[0][1]["cracks"] if krows else {}
            up, lo = k.get("upper", {}), k.get("lower", {})
            c = list(brows[0][1]["cracks"].values())[0] if brows else {}
            edge = (c.get("edge_reached_time") or {}).get("xmax")
            lines.append(f"| {p[0]} | {p[1]} | {p[2]} {p[3]} | {p[4]} | "
                         f"{fmt(up.get('angle_deg'))} / {fmt(lo.get('angle_deg'))} | "
                         f"{fmt(up.get('speed_max'), '{:.0f}')} | "
                         f"{fmt(c.get('branching_time'), scale=1e6)} | {c.get('branches_final', '-')} | "
                         f"{c.get('side_branches_max', '-')} | {fmt(edge, scale=1e6)} |")
        lines += [""]
    for s, (krows, brows) in data.items():
        if s.startswith("scan-"):
            continue
        lines += [f"## Setting `{s}`", ""]
        if krows:
            lines += ["Kalthoff-Winkler 2D (16.5 m/s, 110 us):", ""] + kalthoff_table(krows) + [""]
        if brows:
            lines += ["Crack branching (glass, 1 MPa, 90 us):", ""] + branching_table(brows) + [""]
        if not krows and not brows:
            lines += ["(no finished runs)", ""]
    open(a.doc, "w").write("\n".join(lines))
    print(f"wrote {a.doc} and {png}")


if __name__ == "__main__":
    sys.exit(main())
