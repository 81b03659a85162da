"""Shared helpers of the laminate decks' analysis scripts (examples/laminate-beam,
examples/laminate-plate): read a TLSPH final-state dump, evaluate the stored
CalculiX reference at the particles' reference positions, and read the run's
bookkeeping (steps, loop time) from the LAMMPS log.

The comparison is made at identical material points: the FE field is sampled at
each particle's reference position X = x - u (laminate_reference.sample, the
20-node interpolation of the stored FE solution), never at the nearest node.
"""

import os
import re
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "laminate-common"))
import laminate_reference as ref  # noqa: E402,F401  (re-exported)


def read_final_dump(path):
    """(ids, types, X, u) from 'write_dump ... id type x y z ux uy uz'; X = x - u."""
    with open(path) as f:
        lines = f.readlines()
    i = next(k for k, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
    cols = lines[i].split()[2:]
    data = np.loadtxt(lines[i + 1:], ndmin=2)
    c = {name: k for k, name in enumerate(cols)}
    ucols = [k for k, name in enumerate(cols) if name.startswith("c_") and "[" in name]
    x = data[:, [c["x"], c["y"], c["z"]]]
    u = data[:, ucols[:3]]
    return data[:, c["id"]].astype(int), data[:, c["type"]].astype(int), x - u, u


def read_log(path):
    """steps, loop time [s], CPU use [%], ranks and atoms of the last run of a LAMMPS log."""
    out = {}
    if not os.path.exists(path):
        return out
    with open(path) as f:
        text = f.read()
    for m in re.finditer(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) "
                         r"atoms", text):
        out.update(loop=float(m.group(1)), np=int(m.group(2)), steps=int(m.group(3)),
                   atoms=int(m.group(4)))
    m = list(re.finditer(r"^([0-9.]+)% CPU use", text, re.M))
    if m:
        out["cpu"] = float(m[-1].group(1))
    m = list(re.finditer(r"^Total wall time: (\d+):(\d+):(\d+)", text, re.M))
    if m:
        h, mi, s = (int(v) for v in m[-1].groups())
        out["wall"] = 3600 * h + 60 * mi + s
    return out


def read_dat(path):
    """header dict (key=value words of the first line) and the data rows of a fix print file"""
    head, rows = {}, []
    with open(path) as f:
        for line in f:
            if line.startswith("# laminate"):
                for w in line.split():
                    if "=" in w:
                        k, v = w.split("=", 1)
                        head[k] = v
            elif line.strip() and not line.startswith("#"):
                rows.append([float(v) for v in line.split()])
    return head, np.array(rows)


def rel(a, b):
    """relative difference (a - b)/|b|"""
    return (a - b) / abs(b) if b != 0 else float("nan")


def pct(x):
    return f"{100 * x:+.2f} %"
