#!/usr/bin/env python3
"""Compare the outputs of two check_kokkos.py work directories (by hand).

  compare_runs.py DIR_A DIR_B [--tol 1e-12]

For every text dump (*.dump, any depth) and every log (*.log) present under
the same relative path in both: the dumps must have the same atom IDs and
columns, and each column must agree to TOL relative to its largest absolute
value; the logs' thermo rows (all thermo blocks, in order) likewise, per
column. Used for doc/kokkos.md ("Loading the /kk styles as a plugin"): the
runs of a LAMMPS with the package compiled in against the same runs with
tlsphkkplugin.so loaded into a LAMMPS without it.
"""
import argparse
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "lammps", "mpi"))
from run_mpi import read_dump  # noqa: E402
from check_kokkos import thermo_rows  # noqa: E402


def col_rel(a, b):
    """max |a-b| / max |a| over two equal-length lists (0 when both are 0)"""
    scale = max((abs(x) for x in a), default=0.0)
    diff = max((abs(x - y) for x, y in zip(a, b)), default=0.0)
    if math.isnan(diff):
        return math.inf
    return diff / scale if scale > 0 else diff


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--tol", type=float, default=1e-12)
    args = ap.parse_args()
    files = []
    for root, _, names in os.walk(args.a):
        for n in names:
            if n.endswith(".dump") or n.endswith(".log"):
                rel = os.path.relpath(os.path.join(root, n), args.a)
                if os.path.exists(os.path.join(args.b, rel)):
                    files.append(rel)
    files.sort()
    problems, worst, identical, nvalues = [], 0.0, 0, 0
    for rel in files:
        pa, pb = os.path.join(args.a, rel), os.path.join(args.b, rel)
        if rel.endswith(".dump"):
            ca, ra = read_dump(pa)
            cb, rb = read_dump(pb)
            if ca != cb or sorted(ra) != sorted(rb):
                problems.append("%s: different columns or atom IDs" % rel)
                continue
            ids = sorted(ra)
            pairs = [([ra[i][k] for i in ids], [rb[i][k] for i in ids]) for k in range(len(ca))]
        else:
            ta = thermo_rows(open(pa, errors="replace").read())
            tb = thermo_rows(open(pb, errors="replace").read())
            if [c for c, _ in ta] != [c for c, _ in tb]:
                problems.append("%s: different thermo rows (%d, %d)" % (rel, len(ta), len(tb)))
                continue
            if not ta:
                continue
            pairs = []
            ncol = len(ta[0][1])
            # per thermo block column (same header throughout a block)
            for k in range(ncol):
                pairs.append(([v[k] for _, v in ta], [v[k] for _, v in tb]))
        rel_max = max((col_rel(x, y) for x, y in pairs), default=0.0)
        nvalues += sum(len(x) for x, _ in pairs)
        if all(x == y for x, y in pairs):
            identical += 1
        worst = max(worst, rel_max)
        if not rel_max <= args.tol:
            problems.append("%s: relative difference %.3g" % (rel, rel_max))
    print("%d files compared (%d dumps, %d logs), %d values; %d identical; largest relative "
          "difference %.3g (limit %.0e)"
          % (len(files), sum(f.endswith(".dump") for f in files),
             sum(f.endswith(".log") for f in files), nvalues, identical, worst, args.tol))
    if not files:
        problems.append("no common files")
    if problems:
        print("FAILED:\n  " + "\n  ".join(problems))
        return 1
    print("all equal to the limit")
    return 0


if __name__ == "__main__":
    sys.exit(main())
