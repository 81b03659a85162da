"""What the example checks (check_*.py) share: their command line (--lmp,
--example, --workdir), printing a list of named checks and the verdict that
ctest matches (PASS_REGULAR_EXPRESSION "PASSED")."""

import argparse
import os
import subprocess


def example_args(example, more=None):
    """parse --lmp LMP --example DIR --workdir DIR (and what more(ap) adds); makes workdir"""
    ap = argparse.ArgumentParser()
    ap.add_argument("--lmp", required=True)
    ap.add_argument("--example", required=True, help="examples/" + example)
    ap.add_argument("--workdir", required=True)
    if more:
        more(ap)
    a = ap.parse_args()
    os.makedirs(a.workdir, exist_ok=True)
    return a


def deck_vars(pairs):
    """NAME VALUE pairs (a --vars list) as LAMMPS '-var NAME VALUE' words; None if odd"""
    if len(pairs) % 2:
        print("FAILED: --vars needs NAME VALUE pairs")
        return None
    return [w for k in range(0, len(pairs), 2) for w in ("-var", pairs[k], pairs[k + 1])]


def verdict(checks):
    """checks: [(name, bool)]; prints one line each, then PASSED or FAILED; returns the exit code"""
    ok = True
    for name, good in checks:
        print(("ok    " if good else "FAIL  ") + name)
        ok &= bool(good)
    print("PASSED" if ok else "FAILED")
    return 0 if ok else 1


def run_lammps(cmd, cwd=None):
    """run a LAMMPS command line; on failure print its output's tail and FAILED, return False"""
    p = subprocess.run(cmd, capture_output=True, text=True, cwd=cwd)
    if p.returncode != 0:
        print(p.stdout[-2000:], p.stderr[-2000:])
        print("FAILED: LAMMPS exited with", p.returncode)
        return False
    return True
