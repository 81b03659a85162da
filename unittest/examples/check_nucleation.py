"""Crack nucleation of crack-tip tracking (pair_coeff strength, pair_style
tlsph/damage criterion tip; issue 26, "Nucleation and interaction"), against
what the theory of each scene says; ctest examples.nucleation.hole,
examples.nucleation.plate and examples.nucleation.beam. The decks log every nucleation ("a crack
nucleates at (x, y) ... direction (tx, ty)") and every tip that stops.

--case hole: examples/nucleation/in.hole-plate, an 80 x 80 mm plate with a
  central hole of radius R = 10 mm under a step traction sigma = 10 MPa on
  its left and right edges. The two waves reach the hole at t_a =
  (W/2 - R) / c_L; the hoop stress is highest at the hole's top and bottom
  (Kirsch: 3 sigma static, about twice that as the two waves pass).
  With sigma_t = 4 sigma, at dx = 1 and 0.5 mm:
    * the first cracks are born on the hole's edge (within 1.5 dx of it),
      near its top and bottom: within 25 deg of the axis normal to the load
      (the lattice's staircase edge puts the peak beside the top: 16 and
      11 deg at 1 and 0.5 mm), and that angle falls with dx;
    * after the waves reach the hole and before they have crossed it
      twice (t_a < t < t_a + 4 R / c_L);
    * radial at birth (normal to the hoop stress: within 5 deg);
    * mirror images about the load's axis (same step, positions and
      directions mirrored);
    * they run normal to the load: each tip of the first cracks that stops
      at the plate's edge does so on the top or bottom edge, |x| < W / 4.
  With sigma_t = 10 sigma (above the elastodynamic peak of about 6.6 sigma),
  at dx = 1 mm, 30 us: nothing nucleates.
--case hole3d: the same deck in 3D (-var nz 4: a plate 4 mm thick, free
  faces, through-thickness cracks), dx = 1 mm, the same checks as the hole
  at that dx (the stress averaged through the thickness).
--case plate: examples/crack-branching with its pre-crack removed (notch
  none), a 100 x 40 mm glass plate under a step traction sigma0 = 1 MPa on
  its top and bottom edges. The two waves meet on the mid-line y = Ly/2 at
  t_m = (Ly/2 - dx) / c_L (from the loaded rows), where the stress jumps to
  2 sigma0 (1D: the stress of a bar with both ends loaded at once never
  exceeds 2 sigma0). With sigma_t = 3 sigma0, dx = 0.5 mm, 40 us: nothing
  nucleates. With sigma_t = 1.5 sigma0, at dx = 1 and 0.5 mm: the first
  cracks are born on the mid-line (within one dx; those more than 5 mm from
  the free left and right edges, where the plane strain wave is not 1D: at
  0.5 mm a crack is also born on the left edge 1.75 mm off the line), along it (within 2 deg),
  after t_m and within 1 us of it (the discrete wave front's rise), and that
  delay falls with dx.

--case beam: examples/nucleation/in.beam-3pb, an un-notched beam (span
  S = 60 mm, depth H = 15 mm) in three-point bending, the load point moved
  down at 0.25 m/s, sigma_t = 40 MPa, at dx = 1 and 0.5 mm. Beam theory: the
  largest tension is the bending stress on the bottom face at mid-span; the
  deck reports the Timoshenko beam's bending stress from the measured
  deflection of the bottom face, 6 E' H w / (S^2 (1 + Phi)). Checks:
    * the first crack is born alone, on the bottom face (first row) at
      mid-span (within dx), across the beam (along y within 2 deg);
    * not before the beam's bending stress reaches sigma_t, and by 1.35
      sigma_t: the strength is read on the particle's kernel disc, whose
      centroid lies about 0.6 h inside the face, where the linear bending
      stress is lower by 1.2 h / H (9 % at dx = 1 mm), so the beam stress at
      nucleation exceeds sigma_t by an amount that falls with dx (checked);
    * it runs up to the top face near the load (|x| < H / 4 there).

    check_nucleation.py --lmp LMP --root DIR --workdir DIR --case hole|hole3d|plate|beam
Prints PASSED or FAILED (ctest matches PASSED) and exits 0 / 1.
"""

import argparse
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import run_lammps, verdict  # noqa: E402

NUC = re.compile(r"step (\d+) t (\S+): a crack nucleates at \(([-0-9.e+]+), ([-0-9.e+]+)\) \(atom \d+\), "
                 r"principal stress (\S+) >= strength (\S+), direction \(([-0-9.e+]+), ([-0-9.e+]+)\), "
                 r"length (\S+): tips (\d+) and (\d+)")
STOP = re.compile(r"step (\d+) tip (\d+) stops at \(([-0-9.e+]+), ([-0-9.e+]+)\), outside the body")

E, NU, RHO = 32e9, 0.2, 2450.0
CL = math.sqrt(E * (1 - NU) / ((1 + NU) * (1 - 2 * NU)) / RHO)    # plane strain P-wave speed


def nucleations(log):
    text = open(log).read()
    out = []
    for m in NUC.finditer(text):
        out.append(dict(step=int(m.group(1)), t=float(m.group(2)), x=float(m.group(3)), y=float(m.group(4)),
                        s1=float(m.group(5)), tx=float(m.group(7)), ty=float(m.group(8)),
                        tips=(int(m.group(10)), int(m.group(11)))))
    stops = {int(m.group(2)): (float(m.group(3)), float(m.group(4))) for m in STOP.finditer(text)}
    return out, stops


def run(a, deck, tag, args):
    log = os.path.join(a.workdir, tag + ".log")
    cmd = [os.path.abspath(a.lmp), "-in", deck, "-log", log, "-screen", "none"] + args
    return log if run_lammps(cmd, cwd=a.workdir) else None


class LammpsFailed(Exception):
    pass


def first_cracks(a, deck, tag, args, checks):
    """Run a deck; its nucleations, the tips that stopped and the cracks of
    the first step that nucleated (empty, with a failed check, if none)."""
    log = run(a, deck, tag, args)
    if log is None:
        raise LammpsFailed(tag)
    nuc, stops = nucleations(log)
    if not nuc:
        checks.append((f"{tag}: a crack nucleates", False))
        return log, nuc, stops, []
    return log, nuc, stops, [n for n in nuc if n["step"] == nuc[0]["step"]]


def hole(a, nz=0):
    deck = os.path.join(a.root, "examples", "nucleation", "in.hole-plate")
    W, R, load = 0.08, 0.01, 10e6
    ta = (W / 2 - R) / CL
    checks, off = [], {}
    for dx in ((0.001, 0.0005) if nz == 0 else (0.001,)):
        tag = f"hole-{dx}" + (f"-nz{nz}" if nz else "")
        _, nuc, stops, first = first_cracks(a, deck, tag, ["-var", "dx", str(dx), "-var", "st", "40e6",
                                                           "-var", "nz", str(nz), "-var", "out", tag], checks)
        if not first:
            continue
        t1 = first[0]["t"]
        print(f"dx {dx}: {len(nuc)} nucleations, the first at t = {t1 * 1e6:.2f} us (t_a {ta * 1e6:.2f} us): " +
              ", ".join(f"({n['x'] * 1e3:.2f}, {n['y'] * 1e3:.2f}) mm dir ({n['tx']:.3f}, {n['ty']:.3f})"
                        for n in first))
        angs, radial, edge = [], [], []
        for n in first:
            r = math.hypot(n["x"], n["y"])
            edge.append(R < r <= R + 1.5 * dx)
            angs.append(math.degrees(math.atan2(abs(n["x"]), abs(n["y"]))))    # from the y axis
            # the crack line against the radius (both unsigned)
            c = abs(n["tx"] * n["x"] + n["ty"] * n["y"]) / r
            radial.append(math.degrees(math.acos(min(1.0, c))))
        off[dx] = max(angs)
        mirror = all(any(m["step"] == n["step"] and abs(m["x"] - n["x"]) <= 1e-9 and abs(m["y"] + n["y"]) <= 1e-9
                         and abs(abs(m["tx"]) - abs(n["tx"])) <= 1e-4 and abs(abs(m["ty"]) - abs(n["ty"])) <= 1e-4
                         and (m["tx"] * m["ty"]) * (n["tx"] * n["ty"]) <= 1e-12 for m in first) for n in first)
        firsttips = [t for n in first for t in n["tips"]]
        ends = [stops[t] for t in firsttips if t in stops and abs(stops[t][1]) > R + 2 * dx]
        runs = bool(ends) and all(abs(y) >= W / 2 - 2 * dx and abs(x) < W / 4 for x, y in ends)
        print(f"  angles from the axis normal to the load {', '.join(f'{v:.1f}' for v in angs)} deg, from radial "
              f"{', '.join(f'{v:.1f}' for v in radial)} deg; ends at the plate's edge: " +
              ", ".join(f"({x * 1e3:.1f}, {y * 1e3:.1f})" for x, y in ends))
        checks += [(f"dx {dx}: the first cracks on the hole's edge", all(edge)),
                   (f"dx {dx}: within 25 deg of the top and bottom ({off[dx]:.1f} deg)", off[dx] <= 25.0),
                   (f"dx {dx}: after the waves reach the hole, before they cross it twice ({t1 * 1e6:.2f} us in "
                    f"{ta * 1e6:.2f}-{(ta + 4 * R / CL) * 1e6:.2f} us)", ta < t1 < ta + 4 * R / CL),
                   (f"dx {dx}: radial at birth (within 5 deg: {max(radial):.2f})", max(radial) <= 5.0),
                   (f"dx {dx}: mirror images about the load's axis ({len(first)} cracks)",
                    mirror and len(first) % 2 == 0),
                   (f"dx {dx}: the first cracks run to the top and bottom edges ({len(ends)} tips there)", runs)]
    if len(off) == 2:
        checks.append((f"the angle from the top falls with dx ({off[0.001]:.1f} -> {off[0.0005]:.1f} deg)",
                       off[0.0005] < off[0.001]))
    if nz:
        return verdict(checks)
    log = run(a, deck, "hole-strong", ["-var", "dx", "0.001", "-var", "st", str(10 * load), "-var", "out",
                                       "hole-strong"])
    if log is None:
        return 1
    nuc, _ = nucleations(log)
    checks.append((f"sigma_t = 10 sigma: nothing nucleates in 30 us ({len(nuc)} cracks)", not nuc))
    return verdict(checks)


def plate(a):
    ex = os.path.join(a.root, "examples", "crack-branching")
    deck = os.path.join(ex, "in.crack-branching")
    Lx, Ly, s0 = 0.1, 0.04, 1e6
    common = ["-var", "here", ex, "-var", "notch", "none", "-var", "timg", "0", "-var", "tfull", "0"]
    checks = []
    log = run(a, deck, "plate-strong", common + ["-var", "dx", "0.0005", "-var", "strength", str(3 * s0),
                                                 "-var", "tend", "40e-6", "-var", "out", "plate-strong"])
    if log is None:
        return 1
    nuc, _ = nucleations(log)
    checks.append((f"sigma_t = 3 sigma0: nothing nucleates in 40 us ({len(nuc)} cracks)", not nuc))
    delay = {}
    for dx in (0.001, 0.0005):
        _, _, _, first = first_cracks(a, deck, f"plate-{dx}", common + [
            "-var", "dx", str(dx), "-var", "strength", str(1.5 * s0), "-var", "tend", "12e-6", "-var", "out",
            f"plate-{dx}"], checks)
        if not first:
            continue
        tm = (Ly / 2 - dx) / CL
        delay[dx] = first[0]["t"] - tm
        print(f"dx {dx}: the first cracks at t = {first[0]['t'] * 1e6:.3f} us (t_m {tm * 1e6:.3f} us): " +
              ", ".join(f"({n['x'] * 1e3:.2f}, {n['y'] * 1e3:.2f}) mm dir ({n['tx']:.4f}, {n['ty']:.4f})"
                        for n in first))
        inner = [n for n in first if 0.005 <= n["x"] <= Lx - 0.005]
        checks += [(f"dx {dx}: on the mid-line (within dx), {len(inner)} of {len(first)} more than 5 mm from the "
                    f"free side edges", bool(inner) and all(abs(n["y"] - Ly / 2) <= dx for n in inner)),
                   (f"dx {dx}: along it (within 2 deg)",
                    all(abs(n["ty"]) <= math.sin(math.radians(2.0)) for n in first)),
                   (f"dx {dx}: after the waves meet, within 1 us ({delay[dx] * 1e6:.3f} us)", 0.0 < delay[dx] <= 1e-6)]
    if len(delay) == 2:
        checks.append((f"the delay falls with dx ({delay[0.001] * 1e6:.3f} -> {delay[0.0005] * 1e6:.3f} us)",
                       delay[0.0005] < delay[0.001]))
    return verdict(checks)


def beam(a):
    deck = os.path.join(a.root, "examples", "nucleation", "in.beam-3pb")
    H, st = 0.015, 40e6
    checks, excess = [], {}
    for dx in (0.001, 0.0005):
        log, nuc, stops, first = first_cracks(a, deck, f"beam-{dx}", ["-var", "dx", str(dx), "-var", "out",
                                                                     f"beam-{dx}"], checks)
        if not first:
            continue
        n = first[0]
        # the thermo rows: step time w sigma_beam
        rows = []
        for l in open(log):
            c = l.split()
            if len(c) == 4 and re.match(r"^\d+$", c[0]):
                rows.append([float(v) for v in c])
        before = [r for r in rows if r[0] <= n["step"]]
        after = [r for r in rows if r[0] >= n["step"]]
        # the beam stress at the nucleation step, between the thermo rows around it
        if before and after and after[0][0] > before[-1][0]:
            f = (n["step"] - before[-1][0]) / (after[0][0] - before[-1][0])
            sb = before[-1][3] + f * (after[0][3] - before[-1][3])
        else:
            sb = before[-1][3] if before else float("nan")
        excess[dx] = sb / st
        top = [stops[t] for t in n["tips"] if t in stops and stops[t][1] > H / 2]
        print(f"dx {dx}: the first crack at step {n['step']}, t = {n['t'] * 1e6:.1f} us, at ({n['x'] * 1e3:.2f}, "
              f"{n['y'] * 1e3:.2f}) mm, dir ({n['tx']:.4f}, {n['ty']:.4f}); beam stress then {sb / 1e6:.2f} MPa = "
              f"{sb / st:.3f} sigma_t; its tip stops at " + ", ".join(f"({x * 1e3:.2f}, {y * 1e3:.2f})" for x, y in top))
        checks += [(f"dx {dx}: the first crack alone, on the bottom face at mid-span",
                    len(first) == 1 and n["y"] <= dx and abs(n["x"]) <= dx),
                   (f"dx {dx}: across the beam (within 2 deg)", abs(n["tx"]) <= math.sin(math.radians(2.0))),
                   (f"dx {dx}: when the beam stress is sigma_t to 1.35 sigma_t ({sb / st:.3f})",
                    1.0 <= sb / st <= 1.35),
                   (f"dx {dx}: it runs to the top face near the load",
                    len(top) == 1 and top[0][1] >= H - 2 * dx and abs(top[0][0]) < H / 4)]
    if len(excess) == 2:
        checks.append((f"the beam stress's excess at nucleation falls with dx ({excess[0.001]:.3f} -> "
                       f"{excess[0.0005]:.3f})", excess[0.0005] < excess[0.001]))
    return verdict(checks)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--lmp", required=True)
    ap.add_argument("--root", required=True)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--case", required=True, choices=["hole", "hole3d", "plate", "beam"])
    a = ap.parse_args()
    os.makedirs(a.workdir, exist_ok=True)
    try:
        return {"hole": hole, "hole3d": lambda a: hole(a, nz=4), "plate": plate, "beam": beam}[a.case](a)
    except LammpsFailed:
        return 1


if __name__ == "__main__":
    sys.exit(main())
