"""The benchmarks' acceptance criteria, the thesis's numbers and the
experiment's, in one place, each with its source.

Every script that judges a benchmark run or prints the thesis's numbers beside
it takes them from here: examples/crack-branching/summarise.py,
examples/kalthoff-2d/summarise.py, examples/kalthoff-3d/summarise.py,
bench/fracture_report.py, unittest/examples/check_kalthoff.py and
check_branching.py; tools/sync_status.py writes the table of doc/references.rst
from it (ctest doc.status_sync fails when that table is out of date).

Each entry is a Ref(value, unit, source): value is a number, a (low, high)
pair or a short text; source names where it comes from:
  * "thesis 3.2.1.1" etc.: a section, figure or table of the thesis
    (doc/references.rst, "The thesis");
  * "references: ..." : doc/references.rst (the project's reference values,
    "computed" where it says so);
  * "issue N": the acceptance criteria of the project's issue N.
Times are in seconds, speeds in m/s, angles in degrees, lengths in m.

Plain Python (no numpy): `python3 acceptance.py` prints every entry.
"""

from collections import namedtuple

Ref = namedtuple("Ref", "value unit source")

# --------------------------------------------------------------------------
# Rayleigh speeds (the upper limit of a crack tip's speed)
# --------------------------------------------------------------------------
RAYLEIGH_STEEL = Ref(2803.0, "m/s", "references: Kalthoff-Winkler, maraging steel, plane strain / 3D (computed)")
RAYLEIGH_STEEL_PLANE_STRESS = Ref(2769.0, "m/s", "references: Kalthoff-Winkler, maraging steel, plane stress (computed)")
RAYLEIGH_GLASS = Ref(2125.0, "m/s", "references: crack branching, glass, plane strain (computed)")
RAYLEIGH_GLASS_PLANE_STRESS = Ref(2112.0, "m/s", "references: crack branching, glass, plane stress (computed)")

# --------------------------------------------------------------------------
# Acceptance criteria
# --------------------------------------------------------------------------
# Kalthoff-Winkler 2D (16.5 m/s)
KW_ANGLE_BAND = Ref((63.0, 72.0), "deg",
                    "issue 3 (at dx = 1 mm); issue 12 (at >= 4 resolutions from 1.67 to 0.5 mm); "
                    "issue 26 (at every resolution)")
KW_MIRROR_DEG = Ref(2.0, "deg", "issue 3, issue 12: the two cracks mirror-symmetric to within this angle")
KW_SPREAD_DEG = Ref(5.0, "deg", "issue 12, issue 26: spread of the angle over the resolutions")
KW_MIN_RESOLUTIONS = Ref(4, "", "issue 12: the band at this many resolutions at least (1.67 ... 0.5 mm)")
KW_SPEED = Ref("below the Rayleigh speed", "", "issue 3, issue 12")
KW_IMPACTOR = Ref("no cracking under the impactor", "", "issue 3 (tension-only criterion), issue 12")
# Kalthoff-Winkler 3D (30 m/s)
KW3D_ANGLE = Ref("the 2D band, 63-72 deg", "", "issue 12 (coarse resolution); issue 26 (1.25 and 1.0 mm, "
                 "no side branches)")

# dynamic crack branching (glass, 1 MPa)
BR_INITIATION_BEFORE = Ref(15e-6, "s", "issue 3")
BR_WINDOW = Ref((25e-6, 45e-6), "s",
                "issue 12 and issue 26: one branching into two main branches in this window "
                "(issue 3 had 25-40 us, the literature band below)")
BR_MAIN_BRANCHES = Ref(2, "", "issue 3, issue 12: two main branches, both reaching the right edge")
BR_SPURIOUS = Ref("no spurious (side) branches", "", "issue 3, issue 12")
BR_SPEED = Ref("not above the Rayleigh speed, 2125 m/s", "", "issue 3")
BR_RESOLUTIONS = Ref([0.5e-3, 0.333e-3], "m", "issue 12: at these two resolutions at least "
                     "(issue 26: 0.5, 0.333, 0.286, 0.222 mm)")

# large-deflection cantilever and laminates
CANTILEVER_TIP = Ref(0.02, "", "issue 2: static tip deflection within 2 % of the elastica at dx = 1 mm")
CANTILEVER_HOURGLASS = Ref(0.01, "", "issue 2: hourglass energy below 1 % of the strain energy")
LAMINATE_U3 = Ref(0.02, "", "issue 4: u3 within 2 % of the converged FE reference")
LAMINATE_U12 = Ref(0.03, "", "issue 4: u1, u2 within 3 % of the converged FE reference")

# --------------------------------------------------------------------------
# The experiment and the literature
# --------------------------------------------------------------------------
EXP_KW_ANGLE = Ref(70.0, "deg", "Kalthoff & Winkler 1988 (thesis Table 3.3): about 70 deg")
HOOP_MODE_II = Ref(70.5, "deg", "references: maximum-hoop-stress kink angle, pure mode II (computed)")
LIT_KW_ANGLES = Ref("XFEM ~58; discrete model 65-70; peridynamics 65-70; TLSPH (Islam & Peng) ~77",
                    "deg", "thesis Table 3.3")
LIT_BRANCHING_BAND = Ref((25e-6, 40e-6), "s",
                         "issue 3, issue 12: the phase-field and XFEM studies the thesis cites "
                         "(references: Borden et al. 2012 and the COMSOL phase-field example near "
                         "33 us; 30-35 us at 1 MPa)")
LIT_KW3D = Ref("Raymond et al. 2014 (SPH, 30 m/s): 69.8 deg, 1200 m/s average; Ren et al. 2019 "
               "(phase field, 25 m/s): initiation 12.7 us; Partmann et al. 2023 (peridynamics, "
               "33 m/s): 64 deg", "", "thesis Table 3.4")

# --------------------------------------------------------------------------
# The thesis's numbers
# --------------------------------------------------------------------------
# Kalthoff-Winkler 2D, dx = 1 mm (thesis 3.2.1.1, Figs. 3.7-3.11)
THESIS_KW_ANGLE = Ref(68.0, "deg", "thesis 3.2.1.1 (dx = 1.0 mm)")
THESIS_KW_ANGLES = Ref({1.67: 52.0, 1.33: 69.0, 1.11: 66.0, 1.0: 68.0}, "deg (dx in mm)",
                       "thesis 3.2.1.1, convergence study")
THESIS_KW_INITIATION = Ref(24e-6, "s", "thesis 3.2.1.1 (dx = 1.0 mm; 30 us at 1.67 mm, 26 us at 1.33 and 1.11 mm)")
THESIS_KW_INITIATION_COARSE = Ref(30e-6, "s", "thesis 3.2.1.1 (dx = 1.67 mm)")
THESIS_KW_EDGE = Ref(98e-6, "s", "thesis 3.2.1.1 (dx = 1.0 mm: both cracks at the side edges)")
THESIS_KW_EDGE_COARSE = Ref(110e-6, "s", "thesis 3.2.1.1 (dx = 1.67 mm: the lower, far edge)")
THESIS_KW_SPEED = Ref(1581.0, "m/s", "thesis 3.2.1.1, Fig. 3.11 (peak; 56.46 % of its 2800 m/s)")
THESIS_KW_PARTICLES = Ref(20300, "", "thesis 3.2.1.1")
# Kalthoff-Winkler 3D, 30 m/s (thesis 3.2.1.2, Figs. 3.12-3.13, Table 3.4)
THESIS_KW3D_ANGLE = Ref("65 deg, rising to 70", "", "thesis 3.2.1.2")
THESIS_KW3D_KINK = Ref(65.0, "deg", "thesis 3.2.1.2 (initially)")
THESIS_KW3D_INITIATION = Ref(14e-6, "s", "thesis 3.2.1.2, Table 3.4")
THESIS_KW3D_EDGE = Ref(76e-6, "s", "thesis 3.2.1.2 (both cracks at the side edges)")
THESIS_KW3D_SPEED = Ref(2236.0, "m/s", "thesis 3.2.1.2, Fig. 3.13 (maximum)")
THESIS_KW3D_PARTICLES = Ref(203000, "", "thesis 3.2.1.2")
# dynamic crack branching, dx = 0.333 mm (thesis 3.2.2, Figs. 3.15-3.16)
THESIS_BR_INITIATION = Ref(8e-6, "s", "thesis 3.2.2 (approximately)")
THESIS_BR_BRANCHING = Ref(33e-6, "s", "thesis 3.2.2 (around)")
THESIS_BR_EDGE = Ref(56e-6, "s", "thesis 3.2.2 (both branches at the right edge)")
THESIS_BR_PARTICLES = Ref(36000, "", "thesis 3.2.2")


def us(v):
    """seconds -> 'N us' text (as the tables print the thesis's times)"""
    return f"{v * 1e6:g} us"


def in_band(v, band):
    """v within the (low, high) pair band.value (inclusive); False for None"""
    lo, hi = band.value
    return v is not None and lo <= v <= hi


def entries():
    """(name, Ref) of every entry of this module, in the order written"""
    return [(k, v) for k, v in globals().items() if isinstance(v, Ref)]


def fmt_value(r):
    """an entry's value as text, in the units the tables use (us for seconds, mm for m)"""
    v, u = r.value, r.unit
    if u == "s":
        f = (lambda x: f"{x * 1e6:g}")
        u = "us"
    elif u == "m":
        f = (lambda x: f"{x * 1e3:g}")
        u = "mm"
    elif u == "" and isinstance(v, float) and v < 1:
        return f"{v * 100:g} %"
    else:
        f = (lambda x: f"{x:g}")
    if isinstance(v, tuple):      # a band
        return " - ".join(f(x) for x in v) + (f" {u}" if u else "")
    if isinstance(v, list):       # a list of values
        return ", ".join(f(x) for x in v) + (f" {u}" if u else "")
    if isinstance(v, dict):
        return ", ".join(f"{k:g}: {f(x)}" for k, x in v.items()) + (f" {u}" if u else "")
    if isinstance(v, str):
        return v
    return f(v) + (f" {u}" if u else "")


if __name__ == "__main__":
    for k, r in entries():
        print(f"{k:30s} {fmt_value(r):40s} {r.source}")
