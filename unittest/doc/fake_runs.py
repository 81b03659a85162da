"""Shared by the bench report checks (check_fracture_report.py,
check_branch_g.py): their command line and a made-up run's log and summary."""
import argparse
import os


def args():
    """--root REPO --workdir DIR; returns (args, DIR/out)"""
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True)
    ap.add_argument("--workdir", required=True)
    a = ap.parse_args()
    return a, os.path.join(a.workdir, "out")


def write_run(d, name, code, log="Total wall time: 0:00:01\n"):
    """d/name.log (its text: log) and d/summary-name.txt with the 'code:' line of summarise.py"""
    os.makedirs(d, exist_ok=True)
    open(os.path.join(d, name + ".log"), "w").write(log)
    open(os.path.join(d, "summary-" + name + ".txt"), "w").write(f"x\ncode: {code}\n")
