"""What the tutorial checks (check_*.py) share: running a tutorial deck the way
its page in doc/ shows it (mpirun -np 2 lmp_tlsph -in DECK, in an empty
working directory), reading the package's material file, and the verdict
(unittest/examples/checks.py: one line per check, then PASSED or FAILED)."""

import argparse
import math
import os
import re
import shutil
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "examples"))
from checks import verdict  # noqa: E402,F401


def arg_parser(example):
    """the command line every tutorial check takes: --mpiexec --np --lmp
    --example (the tutorial's folder, `example`) --workdir --python"""
    ap = argparse.ArgumentParser()
    ap.add_argument("--mpiexec", required=True)
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--lmp", required=True)
    ap.add_argument("--example", required=True, help=example)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--python", default=sys.executable)
    return ap


def mpi_cmd(mpiexec, np):
    """mpiexec -np NP, with Open MPI's --oversubscribe (and --allow-run-as-root as root)"""
    cmd = [mpiexec]
    v = subprocess.run([mpiexec, "--version"], capture_output=True, text=True)
    if re.search(r"Open MPI|OpenRTE|open-mpi\.org", v.stdout + v.stderr):
        cmd += ["--oversubscribe"]
        if hasattr(os, "geteuid") and os.geteuid() == 0:
            cmd += ["--allow-run-as-root"]
    return cmd + ["-np", str(np)]


def fresh_dir(path):
    """an empty working directory (the outputs of an earlier run removed)"""
    if os.path.isdir(path):
        shutil.rmtree(path)
    os.makedirs(path)
    return path


def run(cmd, cwd, timeout=600):
    """run a command; on failure print its output's tail and FAILED, return False"""
    print("$ " + " ".join(cmd), flush=True)
    p = subprocess.run(cmd, capture_output=True, text=True, cwd=cwd, timeout=timeout)
    if p.returncode != 0:
        print(p.stdout[-3000:], p.stderr[-3000:])
        print("FAILED: exit status", p.returncode)
        return False
    return True


def material(name, path=None):
    """the keyword/value pairs of one material of potentials/tlsph_materials.tlsph"""
    if path is None:
        path = os.path.join(here, "..", "..", "potentials", "tlsph_materials.tlsph")
    for line in open(path):
        w = line.split("#")[0].split()
        if w and w[0] == name:
            return {w[k]: float(w[k + 1]) for k in range(1, len(w) - 1, 2)}
    raise KeyError(f"material {name} not in {path}")


def wave_speed(m):
    """longitudinal wave speed sqrt((lambda + 2 mu) / rho) of an isotropic material"""
    E, nu, rho = m["E"], m["nu"], m["rho"]
    return math.sqrt(E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) / rho)
