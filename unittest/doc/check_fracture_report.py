"""bench/fracture_report.py on a small fake run folder (ctest bench.fracture_report):
the report that `REPORT_ONLY=1 bash bench/fracture.sh all` regenerates
(doc/fracture-convergence.md) is written from <out>/<setting>/*.crack.json,
the LAMMPS logs and the summaries' 'code:' lines; this builds such a folder
with made-up measurements on both sides of every acceptance band of
examples/common/acceptance.py and checks the verdicts the report prints.

    check_fracture_report.py --root REPO --workdir DIR
Prints PASSED or FAILED (ctest matches PASSED).
"""
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples"))
from checks import verdict  # noqa: E402  (unittest/examples/checks.py)
from fake_runs import args, write_run  # noqa: E402  (unittest/doc/fake_runs.py)


def kalthoff(angle, speed=1700.0, diff=0.0, side=0):
    c = dict(angle_deg=angle, initiation_time=15e-6, speed_max=speed,
             edge_reached_time={"ymax": 80e-6}, branches_final=1, side_branches_max=side)
    lo = dict(c, angle_deg=angle - diff)
    return {"cracks": {"upper": c, "lower": lo}, "symmetry": {"angle_diff_deg": diff}}


def branching(t, nfin=2, side=0, two=80e-6):
    return {"cracks": {"crack": dict(initiation_time=13e-6, branching_time=t, branches_final=nfin,
                                     side_branches_max=side, two_branches_at_target_time=two,
                                     speed_max=1300.0, edge_reached_time={"xmax": 80e-6},
                                     branch_point_s=0.0135,
                                     branches_at_end=[{"tip": [0.0998, 0.0372], "edges": ["xmax"], "angle_deg": 28.46},
                                                      {"tip": [0.0998, 0.0028], "edges": ["xmax", "ymin"],
                                                       "angle_deg": -28.46}])}}


def write(d, name, j, code):
    write_run(d, name, code,
              "Loop time of 9.5 on 1 procs for 1500 steps with 20000 atoms\nTotal wall time: 0:00:12\n")
    json.dump(j, open(os.path.join(d, name + ".crack.json"), "w"))


def main():
    a, out = args()
    # setting 'good': in every band (the branching window's edge at 44.9 us, inside 25-45)
    for mm, ang in (("1.67", 68.0), ("1.33", 71.0), ("1", 72.0), ("0.5", 67.5)):
        write(os.path.join(out, "good"), f"kalthoff-{mm}", kalthoff(ang), "abc1234 fake")
    for mm, t in (("0.5", 44.9e-6), ("0.333", 25.1e-6)):
        write(os.path.join(out, "good"), f"branching-{mm}", branching(t), "abc1234 fake")
    # setting 'bad': each criterion missed once
    for mm, ang, sp, d in (("1.67", 72.04, 1700.0, 0.0), ("1", 65.0, 2900.0, 0.0),
                           ("0.5", 66.0, 1700.0, 2.5)):
        write(os.path.join(out, "bad"), f"kalthoff-{mm}", kalthoff(ang, sp, d, side=int(mm == "1")),
              "def5678 fake")
    write(os.path.join(out, "bad"), "branching-0.5", branching(45.5e-6), "def5678 fake")
    write(os.path.join(out, "bad"), "branching-0.333", branching(30e-6, nfin=3, side=1, two=None),
          "def5678 fake")
    doc = os.path.join(a.workdir, "report.md")
    p = subprocess.run([sys.executable, os.path.join(a.root, "bench", "fracture_report.py"),
                        "--out", out, "--doc", doc, "--kept", "good", "good", "bad"],
                       capture_output=True, text=True)
    print(p.stdout[-2000:], p.stderr[-2000:])
    if p.returncode != 0 or not os.path.exists(doc):
        print("FAILED: fracture_report.py exited with", p.returncode)
        return 1
    txt = open(doc).read()
    rows = {ln.split("|")[1].strip(): ln for ln in txt.splitlines() if ln.startswith("| `")}
    good, bad = rows.get("`good`", ""), rows.get("`bad`", "")
    checks = [
        ("good: Kalthoff in the band at 4 dx, all criteria met",
         "in the band at 4 dx" in good and good.count("all met") == 2),
        ("good: branching at 44.9 us is inside the 25-45 us window", "44.9 us, 2 at the end" in good),
        ("bad: 72.04 deg is outside 63-72", "angle 72.0 at 1.67 mm" in bad),
        ("bad: a tip at 2900 m/s is above the Rayleigh speed", "tip speed 2900 m/s at 1 mm" in bad),
        ("bad: a mirror difference of 2.5 deg fails", "mirror difference 2.5 at 0.5 mm" in bad),
        ("bad: 3 resolutions (4 asked)", "3 resolution(s) (4 asked)" in bad),
        ("bad: a Kalthoff crack with a short side branch fails (one crack per notch)",
         "branched at 1 mm (1 branch(es) at the end, 1 short side branch(es))" in bad
         and "branched" not in good),
        ("bad: branching at 45.5 us is outside the window", "branching at 45.5 us at 0.5 mm" in bad),
        ("bad: 3 branches, a side branch, not both at the right edge",
         "3 branches at the end at 0.333 mm" in bad and "1 side branches at 0.333 mm" in bad
         and "not two branches at the right edge at 0.333 mm" in bad),
        ("branching table: the branch point, where the branches end (lowest first, with their edges) "
         "and their angles", "| 13.5 | 80.0 | 99.8, 2.8 (xmax+ymin), -28.5; 99.8, 37.2 (xmax), +28.5 |" in txt),
        ("header: the runs' code and the acceptance source",
         "abc1234 fake (6 runs)" in txt and "examples/common/acceptance.py" in txt
         and "between 25 and 45 us" in txt),
        ("plots written", os.path.exists(os.path.join(a.workdir, "report.png"))
         and os.path.exists(os.path.join(a.workdir, "report-kept.png"))),
    ]
    return verdict(checks)


if __name__ == "__main__":
    sys.exit(main())
