"""The steady speed of a crack-tip-tracking crack in the pure-shear strip of
bench/in.toughness, and the G its tip measured, from a run's PREFIX.dat
(time strain G broken tip off etot filtered) and its log with TLSPH_TIP_TRACE
lines; the energy the cut bonds and the viscosity dissipated per crack area.
Used by bench/speedlaw.sh and bench/tipconst.sh. Plain Python."""
import re

WINDOW = (0.025, 0.045)    # tip positions [m] over which the speed is fitted


def fit(t, y):
    """least squares slope of y(t)"""
    n = len(t)
    mt, my = sum(t) / n, sum(y) / n
    return sum((a - mt) * (b - my) for a, b in zip(t, y)) / sum((a - mt) ** 2 for a in t)


def window_columns(prefix, cols):
    """the columns cols of PREFIX.dat (time strain G broken tip off etot
    filtered strain viscous kinetic), over the rows whose tip is in the window"""
    out = [[] for _ in cols]
    for line in open(prefix + ".dat"):
        if line.startswith("#"):
            continue
        c = line.split()
        if WINDOW[0] < float(c[4]) < WINDOW[1]:
            for k, col in enumerate(cols):
                out[k].append(float(c[col]))
    return out


def measure(prefix):
    """(v / c_R over the window, or nan; the mean G / G_c... as measured at the
    segments' starts in the window, the list of those G) for the run PREFIX"""
    log = open(prefix + ".log").read()
    cR = float(re.search(r"c_R ([0-9.e+]+)", log).group(1))
    t, y = window_columns(prefix, (0, 4))
    v = fit(t, y) / cR if len(t) > 2 else float("nan")
    g = [float(l.split()[7]) for l in log.splitlines()
         if l.startswith("tip-trace") and WINDOW[0] < float(l.split()[3]) < WINDOW[1]]
    return v, g


def energy_rates(prefix):
    """per unit crack advance over the window [J/m^2] (least squares slopes
    against the tip's position; per unit thickness, the strip's is 1), from
    PREFIX.dat: (the energy the cut bonds dissipated: the fall of compute
    tlsph/energy's sum less the velocity filter's share; the artificial
    viscosity's work)"""
    a, e, f, w = window_columns(prefix, (4, 6, 7, 9))
    if len(a) < 3:
        return float("nan"), float("nan")
    return -fit(a, e) - fit(a, f), fit(a, w)
