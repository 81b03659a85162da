"""What the example checks (check_*.py) share: their command line (--lmp,
--example, --workdir), printing a list of named checks and the verdict that
ctest matches (PASS_REGULAR_EXPRESSION "PASSED")."""

import argparse
import os


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


def verdict(checks):
    """checks: [(name, bool)]; prints one line each, then PASSED or FAILED; returns the exit code"""
    ok = True
    for name, good in checks:
        print(("ok    " if good else "FAIL  ") + name)
        ok &= bool(good)
    print("PASSED" if ok else "FAILED")
    return 0 if ok else 1
