"""bench/branch_g.py, kcheck_kink.py, kcheck_seg.py, kcheck_t.py and kcheck_3d.py on made-up runs (ctest bench.branch_g):

* branch_g.py: two fake settings, one whose Kalthoff-Winkler tips stay below
  the plate's G before 45 us (a threshold exists: "yes") and one whose tips
  go above it ("no"); the Kalthoff-Winkler tips grow three straight segments
  at 70, 80 and 60 deg, so the kinks between them are 10 and 20 deg (mean 15);
* kcheck_kink.py: the maximum tangential stress kink of a kinked tip's
  theory (tan(theta/2) -> about -theta) and a fake log's row;
* kcheck_seg.py: tipdir segment's kink, and the turn that zeroes K_II / K_I
  at a second segment's end, from three fake runs on a known line;
* kcheck_t.py: T / sigma against theory and the error's trend with dx.
* kcheck_3d.py: K_I against Tada and 2D, T, and the mixed ratio against 2D; an unfinished run left out.

    check_branch_g.py --root REPO --workdir DIR
Prints PASSED or FAILED (ctest matches PASSED).
"""
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fake_runs import args, write_run  # noqa: E402  (unittest/doc/fake_runs.py)


def kalthoff_tips(path, gval):
    """a tip that rests 5 records, grows 3 segments of 10 steps, then stops"""
    x, y, L = 0.05, 0.025, 0.05
    rows = [(i * 1e-7, x, y, L, 0.5) for i in range(5)]
    t = 5e-7
    for ang in (70.0, 80.0, 60.0):
        for _ in range(10):
            x += 1e-4 * math.cos(math.radians(ang))
            y += 1e-4 * math.sin(math.radians(ang))
            L += 1e-4
            rows.append((t, x, y, L, gval))
            t += 1e-7
    for _ in range(5):
        rows.append((t, x, y, L, gval))
        t += 1e-7
    with open(path, "w") as f:
        f.write("# fake\n")
        for r in rows:
            f.write("%.6e %.9e %.9e %.9e %.5g %.9e %.9e %.9e %.5g\n" % (r + (r[1], -r[2], r[3], r[4])))


def plate_tips(path, gmax45):
    """G rises linearly to gmax45 at 40 us, then stays"""
    with open(path, "w") as f:
        f.write("# fake\n")
        for i in range(901):
            t = i * 1e-7
            g = gmax45 * min(t, 40e-6) / 40e-6
            f.write("%.6e 0.05 0.02 0.05 %.5g 0\n" % (t, g))


def main():
    a, out = args()
    for st, gk in (("sep", 2.0), ("nosep", 3.0)):
        d = os.path.join(out, st)
        for mm in ("1", "0.5"):
            write_run(d, f"kalthoff-{mm}", "abc1234 fake")
            kalthoff_tips(os.path.join(d, f"kalthoff-{mm}.tips"), gk)
        write_run(d, "branching-0.5", "abc1234 fake")
        plate_tips(os.path.join(d, "branching-0.5.tips"), 2.5)
    doc = os.path.join(a.workdir, "branch-g.md")
    p = subprocess.run([sys.executable, os.path.join(a.root, "bench", "branch_g.py"), "--out", out,
                        "--doc", doc, "sep", "nosep"], capture_output=True, text=True)
    problems = []
    if p.returncode != 0:
        problems.append("branch_g.py failed: " + p.stderr[-500:])
        txt = ""
    else:
        txt = open(doc).read()
    rows = {ln.split("|")[1].strip(): ln for ln in txt.splitlines() if ln.startswith("| `")}
    want = {"`sep`": ("| yes |", "| 15.0-15.0 |"), "`nosep`": ("| no |", "| 15.0-15.0 |")}
    for st, (verdict, kink) in want.items():
        r = rows.get(st, "")
        if verdict not in r or kink not in r:
            problems.append(f"summary row of {st}: expected '{verdict}' and kinks '{kink}', got '{r}'")
    if "abc1234 fake (6 runs)" not in txt:
        problems.append("the runs' code and count (6 runs of abc1234) not in the report")
    # kcheck_kink.py: the theory's kink, and a fake run's row
    sys.path.insert(0, os.path.join(a.root, "bench"))
    import kcheck_kink as K
    for th, back in ((10.0, -9.9), (20.0, -18.9), (40.0, -33.3)):
        got = math.degrees(K.mts_kink(math.tan(math.radians(th) / 2)))
        if abs(got - back) > 0.05:
            problems.append(f"mts_kink at {th} deg: {got:.2f}, expected {back}")
    kd = os.path.join(a.workdir, "kink")
    os.makedirs(kd, exist_ok=True)
    open(os.path.join(kd, "kink-j-biaxial-20-4.5-0.001.log"), "w").write(
        "Step Time ...\n   12000 0.001 300000 0 282000 67000 -24.0 0.0256 0.002 60\nTotal wall time: 0:00:30\n")
    open(os.path.join(kd, "runs.txt"), "w").write("kink-j-biaxial-20-4.5-0.001.log abc1234 0123456789ab\n")
    kdoc = os.path.join(a.workdir, "kcheck-kink.md")
    p = subprocess.run([sys.executable, os.path.join(a.root, "bench", "kcheck_kink.py"), "--out", kd,
                        "--doc", kdoc], capture_output=True, text=True)
    ktxt = open(kdoc).read() if p.returncode == 0 else ""
    row = "| j | 1 | biaxial | 20 | 4.5 | 0.30 | 0.940 | 0.955 | 0.238 | 0.176 | -24.0 | -18.9 | 1.27 |"
    if row not in ktxt:
        problems.append(f"kcheck_kink.py: row '{row}' not in its report ({p.stderr[-300:]})")
    if "abc1234 (binary md5 0123456789ab): 1 runs" not in ktxt:
        problems.append("kcheck_kink.py: the run's commit not in its report")
    # kcheck_seg.py: the segment kink, and the turn that zeroes K_II / K_I
    # from three fake second segments on the line r = 0.1 + 0.01 turn
    import kcheck_seg as S
    KI, KII, T = 300000.0, 30000.0, -1.0e6
    if abs(S.segment_kink(KI, KII, 2.0e6) - K.mts_kink(KII / KI)) > 1e-15:
        problems.append("kcheck_seg.py: with T > 0 the segment kink is not the local one")
    ks = math.degrees(S.segment_kink(KI, KII, T))
    kse = math.degrees(K.mts_kink(KII / (KI - 2 * T * math.sqrt(8 * S.S / math.pi))))
    if abs(ks - kse) > 1e-9 or not -11.25 < ks < 0:
        problems.append(f"kcheck_seg.py: segment kink {ks}, expected {kse}")
    sd = os.path.join(a.workdir, "seg")
    os.makedirs(sd, exist_ok=True)
    row = lambda kI, kII, kink, t: f"   12000 0.001 300000 0 {kI} {kII} {kink} 0.03 0.001 60 {t}\n"
    end = "Total wall time: 0:00:30\n"
    open(os.path.join(sd, "seg-I-10-one.log"), "w").write("Step ...\n" + row(KI, KII, -11.25, T) + end)
    for name, turn in (("0", 0.0), ("-11.25", -11.25), (f"{ks:.2f}", float(f"{ks:.2f}"))):
        r = 0.1 + 0.01 * turn
        open(os.path.join(sd, f"seg-I-10-{name}.log"), "w").write("Step ...\n" + row(1e5, r * 1e5, 0, T) + end)
    sdoc = os.path.join(a.workdir, "kcheck-seg.md")
    p = subprocess.run([sys.executable, os.path.join(a.root, "bench", "kcheck_seg.py"), "--out", sd,
                        "--doc", sdoc], capture_output=True, text=True)
    stxt = open(sdoc).read() if p.returncode == 0 else ""
    rf, rs = 0.1 + 0.01 * -11.25, 0.1 + 0.01 * float(f"{ks:.2f}")
    want = (f"| I | 10 | 0.100 | -1.000 | {T * math.sqrt(2 * math.pi * S.S) / KI:.2f} | -11.25 | {ks:.2f} | "
            f"-10.00 | 0.100 | {rf:.3f} | {rs:.3f} | 1.12 | {ks / -10:.2f} |")
    if want not in stxt:
        problems.append(f"kcheck_seg.py: row '{want}' not in its report ({p.stderr[-300:]}{stxt[-400:]})")
    # kcheck_t.py: T / sigma of both tips against -1 (uniaxial) and 0
    # (biaxial), and the error's trend, from fake relaxed runs
    td = os.path.join(a.workdir, "tstress")
    os.makedirs(td, exist_ok=True)
    for mode, dx, t in (("I", "0.001", -0.95e6), ("I", "0.0005", -0.98e6), ("biaxial", "0.001", 0.02e6),
                        ("biaxial", "0.0005", -0.03e6)):
        open(os.path.join(td, f"t-{mode}-{dx}.log"), "w").write(
            f"Step ...\n   8000 0.0008 137000 0 137000 0 5e-9 0.097 59 {t} {t}\nTotal wall time: 0:00:07\n")
    tdoc = os.path.join(a.workdir, "kcheck-t.md")
    p = subprocess.run([sys.executable, os.path.join(a.root, "bench", "kcheck_t.py"), "--out", td,
                        "--doc", tdoc], capture_output=True, text=True)
    ttxt = open(tdoc).read() if p.returncode == 0 else ""
    for want in ("| I | 1 | -0.9500 | -0.9500 | -1 | +0.0500 |", "| I | 0.5 | -0.9800 | -0.9800 | -1 | +0.0200 |",
                 "`I`: |error| 0.0500, 0.0200 at the finer dx: it falls with dx",
                 "`biaxial`: |error| 0.0200, 0.0300: it does not fall steadily with dx"):
        if want not in ttxt:
            problems.append(f"kcheck_t.py: '{want}' not in its report ({p.stderr[-300:]})")
    # kcheck_3d.py: K_I against Tada and 2D, T, and the mixed ratio against 2D, from fake
    # relaxed runs (a run that did not finish is left out)
    kd = os.path.join(a.workdir, "k3d")
    os.makedirs(kd, exist_ok=True)
    for g, mode, ki, kii, t in (("2d", "I", 130000, 0, -0.97e6), ("2d", "mixed", 140000, 147000, 0),
                                ("p8", "I", 131300, 0, -0.96e6), ("p8", "mixed", 140000, 140000, 0)):
        open(os.path.join(kd, f"k3-{g}-{mode}.log"), "w").write(
            f"Step ...\n   10000 0.001 {ki} {kii} {ki} {kii} 5e-9 0.097 59 {t} {t}\nTotal wall time: 0:00:07\n")
    open(os.path.join(kd, "k3-s4-I.log"), "w").write("Step ...\n   10000 0.001 1 0 1 0 5e-9 0.097 59 0 0\n")
    kdoc = os.path.join(a.workdir, "kcheck-3d.md")
    p = subprocess.run([sys.executable, os.path.join(a.root, "bench", "kcheck_3d.py"), "--out", kd,
                        "--doc", kdoc], capture_output=True, text=True)
    ktxt = open(kdoc).read() if p.returncode == 0 else ""
    k0 = 1.0e6 * math.sqrt(math.pi * 0.005) * (1 - 0.025 * 0.125 ** 2 + 0.06 * 0.125 ** 4) * \
        math.sqrt(1 / math.cos(math.pi * 0.125 / 2))
    for want in (f"| 2D plane strain | {130000 / k0:.4f} | 1.0000 | -0.9700 | 1.0500 | 1.0000 |",
                 f"| 3D, 8 layers, periodic faces (plane strain) | {131300 / k0:.4f} | 1.0100 | -0.9600 | "
                 "1.0000 | 0.9524 |",
                 "| 3D, 4 layers (4 mm), free faces | - | - | - | - | - |"):
        if want not in ktxt:
            problems.append(f"kcheck_3d.py: '{want}' not in its report ({p.stderr[-300:]}{ktxt[-400:]})")
    for pr in problems:
        print("problem:", pr)
    print("FAILED" if problems else "PASSED")


if __name__ == "__main__":
    main()
