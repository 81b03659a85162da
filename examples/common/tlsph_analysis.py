"""Readers and small numerical helpers shared by the example analyses.

read_dat(path)   the fix print file of a cantilever deck: columns by name,
                 plus the key=value metadata of its first line
read_log(path)   LAMMPS log: loop time, steps, ranks, final line, error
read_dump(path)  a write_dump custom file: columns by name
hourglass_indicator(dump, dx, dim)
                 max over nearest-neighbour bonds of |F_i X_ij - x_ij| / dx:
                 O(dx / bending radius) for a smooth field, O(1) for a
                 zig-zag (hourglass) pattern that F cannot see
min_distance(dump)  smallest current distance between two free particles
richardson(h, f)    observed order and extrapolated value from three
                    resolutions with a constant refinement ratio
settle_time(t, f, f_ref, tol)  first time after which |f/f_ref - 1| <= tol
Case(outdir, name, dim, L)      one run of run_case.sh: data, log, error, final dump
"""

import math
import os
import re

import numpy as np


def read_dat(path):
    meta = {}
    names = None
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                body = line[1:].strip()
                if "=" in body:
                    for k, v in re.findall(r"(\w+)=(\S+)", body):
                        try:
                            meta[k] = float(v)
                        except ValueError:
                            meta[k] = v
                elif body.startswith("step"):
                    names = body.split("(")[0].split()
                continue
            parts = line.split()
            if not parts:
                continue
            try:
                rows.append([float(p) for p in parts])
            except ValueError:
                continue
    if not rows:
        return {"meta": meta, "n": 0}
    width = min(len(r) for r in rows)
    a = np.array([r[:width] for r in rows])
    out = {"meta": meta, "n": len(a)}
    for k, name in enumerate(names[:width]):
        out[name] = a[:, k]
    return out


def read_log(path):
    info = {"loop_time": None, "steps": None, "nprocs": None, "error": None, "finished": False,
            "cpu_use": None, "cpu_time": None}
    try:
        with open(path, errors="replace") as f:
            text = f.read()
    except OSError:
        return info
    m = re.findall(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps", text)
    if m:
        info["loop_time"] = sum(float(x[0]) for x in m)
        info["nprocs"] = int(m[-1][1])
        info["steps"] = sum(int(x[2]) for x in m)
    # "99.9% CPU use with 1 MPI tasks": CPU time / wall time of the loop, per task;
    # on a shared machine the CPU time is the fairer cost measure
    cu = re.findall(r"([0-9.]+)% CPU use with (\d+) MPI tasks", text)
    if cu and info["loop_time"]:
        info["cpu_use"] = float(cu[-1][0]) / 100.0
        info["cpu_time"] = info["loop_time"] * info["cpu_use"] * int(cu[-1][1])
    e = re.search(r"^ERROR.*$", text, re.M)
    if e:
        info["error"] = e.group(0)
    info["finished"] = "Total wall time" in text
    return info


def read_screen_error(path):
    """the ERROR line of a run's screen output (an MPI abort leaves the log short)"""
    try:
        with open(path, errors="replace") as f:
            for line in f:
                if line.startswith("ERROR"):
                    return line.strip()
    except OSError:
        pass
    return None


def read_dump(path):
    with open(path) as f:
        lines = f.readlines()
    k = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    names = lines[k].split()[2:]
    a = np.loadtxt(lines[k + 1:], ndmin=2)
    a = a[np.argsort(a[:, 0])]
    return {n: a[:, j] for j, n in enumerate(names)}


def _positions(d, dim):
    x = np.c_[d["x"], d["y"], d["z"]][:, :dim]
    u = np.c_[d["c_d[1]"], d["c_d[2]"], d["c_d[3]"]][:, :dim]
    return x, x - u


def hourglass_indicator(d, dx, dim):
    """(max, mean, reference position of the max) of |F_i X_ij - x_ij| / dx
    over nearest-neighbour bonds; needs F in the dump (c_F[1..9])."""
    from scipy.spatial import cKDTree

    if "c_F[1]" not in d:
        return None
    x, X = _positions(d, dim)
    F = np.stack([d[f"c_F[{k}]"] for k in range(1, 10)], axis=1).reshape(-1, 3, 3)[:, :dim, :dim]
    # 1.05 dx: the layers through the depth placed for the exact second
    # moment (yplace moment) are up to 1.02 dx apart (5 layers)
    pairs = cKDTree(X).query_pairs(1.05 * dx, output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    Xij = X[j] - X[i]
    xij = x[j] - x[i]
    ei = np.linalg.norm(np.einsum("nab,nb->na", F[i], Xij) - xij, axis=1)
    ej = np.linalg.norm(np.einsum("nab,nb->na", F[j], -Xij) + xij, axis=1)
    e = np.maximum(ei, ej) / dx
    k = np.argmax(e)
    return float(e.max()), float(e.mean()), X[i[k]]


def min_distance(d, dim):
    """over the free particles (reference x > 0): with the clamp's first
    column on the clamped face (clamp face) the first free column is dx/2
    from it by construction"""
    from scipy.spatial import cKDTree

    x, X = _positions(d, dim)
    x = x[X[:, 0] > 1e-9]
    dist, _ = cKDTree(x).query(x, k=2)
    return float(dist[:, 1].min())


def richardson(h, f):
    """h decreasing by a constant ratio r; returns (order p, extrapolated f0)
    from the last three values, or (nan, nan) when not monotone."""
    h = list(h)
    f = list(f)
    if len(f) < 3:
        return float("nan"), float("nan")
    f1, f2, f3 = f[-3:]
    r = h[-3] / h[-2]
    d1, d2 = f1 - f2, f2 - f3
    if d1 == 0 or d2 == 0 or d1 * d2 < 0:
        return float("nan"), float("nan")
    p = math.log(d1 / d2) / math.log(r)
    return p, f3 - d2 / (r ** p - 1.0)


def settle_time(t, f, f_ref, tol):
    """first index after which |f/f_ref - 1| <= tol for good (None if never)"""
    err = np.abs(np.asarray(f) / f_ref - 1.0)
    bad = np.nonzero(err > tol)[0]
    if len(bad) == 0:
        return 0
    k = bad[-1] + 1
    return int(k) if k < len(err) else None


class Case:
    """one run: its fix print data, log, screen error and final dump"""

    def __init__(self, outdir, name, dim, L):
        self.name = name
        self.dim = dim
        base = os.path.join(outdir, name)
        self.exists = os.path.exists(base + ".dat")
        if not self.exists:
            return
        self.dat = read_dat(base + ".dat")
        self.log = read_log(base + ".log")
        self.error = read_screen_error(base + ".screen") or self.log["error"]
        self.dump = read_dump(base + ".final.dump") if os.path.exists(base + ".final.dump") else None
        m = self.dat["meta"]
        self.dx = m.get("dx")
        self.T1 = m.get("T1")
        self.unstable = self.error is not None and "det(F)" in self.error
        d = self.dat
        self.v = -d["tip_uy"][-1] / L if d["n"] else float("nan")
        self.u = -d["tip_ux"][-1] / L if d["n"] else float("nan")
        self.resid = d["resid"][-1] if d["n"] else float("nan")
        self.hg_ratio = d["E_hourglass"][-1] / d["E_strain"][-1] if d["n"] else float("nan")
        self.min_detF = d["min_detF"].min() if d["n"] else float("nan")
        self.min_dist = d["min_dist/dx"].min() if "min_dist/dx" in d else float("nan")
        self.steps = int(d["step"][-1]) if d["n"] else 0
        self.loop = self.log["loop_time"]
        self.cpu = self.log["cpu_time"]
        if self.dump is not None:
            self.min_dist_final = min_distance(self.dump, dim) / self.dx
            hg = hourglass_indicator(self.dump, self.dx, dim)
            self.hg_ind = hg[0] if hg else float("nan")
            self.hg_where = hg[2] if hg else None
        else:
            self.min_dist_final = float("nan")
            self.hg_ind = float("nan")
            self.hg_where = None

    @property
    def converged(self):
        return self.exists and not self.error and self.resid < 1e-4

    def status(self):
        if not self.exists:
            return "not run"
        if self.unstable:
            t = self.dat["t/T1"][-1] if self.dat["n"] else float("nan")
            m = re.search(r"at step (\d+)", self.error)
            step = f"step {m.group(1)}, " if m else ""
            return f"unstable (det F < 0 at {step}t = {t:.2f} T1)"
        if self.error:
            return "error: " + self.error[:60]
        if self.dat["meta"].get("damp") == "none":
            return "ok"
        if self.resid > 1e-4:
            return f"not converged (resid {self.resid:.1e})"
        return "ok"
