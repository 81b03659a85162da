#!/usr/bin/python3
"""Checks for the plugin tests (unittest/plugin/CMakeLists.txt).

  check_plugin.py load     --lmp LMP --plugin SO --input IN
      'plugin load' into a PLUGIN-enabled lmp runs the input and lists the styles
  check_plugin.py compare  --lmp LMP --plugin SO --launcher LMP_TLSPH --input IN
      lmp + plugin and lmp_tlsph print the same thermo numbers
  check_plugin.py mpi      --lmp LMP --plugin SO --input IN --mpiexec CMD...
      the plugin under 'mpirun -np 2' gives the serial thermo (to round-off)
  check_plugin.py python   --builddir DIR --launcher LMP_TLSPH --input IN
      tlsph.register() into Debian's python3-lammps gives lmp_tlsph's numbers
"""

import argparse
import math
import os
import shlex
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
PLUGIN_INPUT = os.path.join(HERE, "in.plugin")
# styles lammpsplugin_init must register (a subset: new styles may be added)
EXPECTED_STYLES = [
    ("pair", "tlsph"),
    ("fix", "tlsph/dt"),
    ("compute", "tlsph/stress/atom"),
    ("compute", "tlsph/strain/atom"),
    ("compute", "tlsph/energy"),
]
STEPS = 100


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def run(cmd, what):
    print("+ " + " ".join(shlex.quote(c) for c in cmd), flush=True)
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True, timeout=600)
    out = p.stdout
    if p.returncode != 0 or "ERROR" in out:
        print(out)
        fail("{} exited with {} (or printed ERROR)".format(what, p.returncode))
    if "Total wall time" not in out:
        print(out)
        fail(what + " did not finish the run")
    return out


def thermo(out, what):
    """Rows of the (last) thermo table: list of lists of floats, plus the header."""
    lines = out.splitlines()
    starts = [i for i, l in enumerate(lines) if l.split()[:1] == ["Step"]]
    if not starts:
        print(out)
        fail(what + ": no thermo output")
    header = lines[starts[-1]].split()
    rows = []
    for l in lines[starts[-1] + 1:]:
        if l.startswith("Loop time"):
            break
        rows.append([float(v) for v in l.split()])
    if not rows or int(rows[-1][0]) != STEPS:
        print(out)
        fail("{}: thermo does not reach step {}".format(what, STEPS))
    if not any(abs(v) > 0.0 for r in rows[1:] for v in r[2:3]):
        fail(what + ": potential energy stays zero, pair tlsph did nothing")
    print("{}: {}".format(what, "  ".join("{} {:.15g}".format(h, v) for h, v in zip(header, rows[-1]))))
    return header, rows


def compare(ref, new, rtol, what):
    (h1, r1), (h2, r2) = ref, new
    if h1 != h2 or len(r1) != len(r2):
        fail("{}: thermo tables differ in shape: {} x {} vs {} x {}".format(
            what, h1, len(r1), h2, len(r2)))
    worst = 0.0
    for a, b in zip(r1, r2):
        for col, x, y in zip(h1, a, b):
            scale = max(abs(x), abs(y), 1e-300)
            d = abs(x - y) / scale if x != y else 0.0
            worst = max(worst, d)
            if d > rtol:
                fail("{}: step {} {}: {!r} vs {!r} (relative difference {:.3g} > {:g})".format(
                    what, int(a[0]), col, x, y, d, rtol))
    print("{}: {} thermo rows agree, largest relative difference {:.3g} (tolerance {:g})".format(
        what, len(r1), worst, rtol))


def plugin_run(args, prefix=()):
    cmd = list(prefix) + [args.lmp, "-in", PLUGIN_INPUT, "-log", "none",
                          "-var", "plugin", args.plugin, "-var", "input", args.input]
    out = run(cmd, "lmp + plugin load")
    if "Currently loaded plugins" not in out:
        print(out)
        fail("'plugin list' printed nothing: is LAMMPS built with PLUGIN as a shared library?")
    listed = set()
    for l in out.splitlines():
        w = l.split()
        if len(w) == 5 and w[0].endswith(":") and w[2:4] == ["style", "plugin"]:
            listed.add((w[1], w[4]))
    missing = [s for s in EXPECTED_STYLES if s not in listed]
    if missing:
        print(out)
        fail("styles not registered by the plugin: {}".format(missing))
    print("registered by the plugin: " + ", ".join("{} {}".format(*s) for s in sorted(listed)))
    return out


def launcher_run(args):
    return run([args.launcher, "-in", args.input, "-log", "none"], "lmp_tlsph")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mode", choices=["load", "compare", "mpi", "python"])
    ap.add_argument("--lmp")
    ap.add_argument("--plugin")
    ap.add_argument("--launcher")
    ap.add_argument("--input", required=True)
    ap.add_argument("--builddir")
    ap.add_argument("--mpiexec", nargs=argparse.REMAINDER, default=[])
    args = ap.parse_args()

    if args.mode in ("load", "compare", "mpi"):
        for path in (args.lmp, args.plugin):
            if not path or not os.path.isfile(path):
                fail("not found: {} (run scripts/build-lammps-plugin.sh / build the plugin)".format(path))

    if args.mode == "load":
        thermo(plugin_run(args), "lmp + plugin")
    elif args.mode == "compare":
        ref = thermo(plugin_run(args), "lmp + plugin")
        new = thermo(launcher_run(args), "lmp_tlsph")
        # same styles, same input; the two LAMMPS binaries are compiled
        # separately, so allow round-off, but nothing more
        compare(ref, new, 1e-9, "lmp + plugin vs lmp_tlsph")
    elif args.mode == "mpi":
        ref = thermo(plugin_run(args), "lmp + plugin, 1 process")
        out = plugin_run(args, prefix=args.mpiexec)
        if " on 2 procs " not in out:
            print(out)
            fail("the mpirun run did not use 2 MPI processes")
        new = thermo(out, "lmp + plugin, mpirun")
        compare(ref, new, 1e-8, "1 process vs mpirun -np 2")
    elif args.mode == "python":
        ref = thermo(launcher_run(args), "lmp_tlsph")
        code = (
            "from lammps import lammps; import sys; sys.path.insert(0, {bd!r}); import tlsph\n"
            "lmp = lammps(cmdargs=['-log', 'none', '-screen', 'none'])\n"
            "tlsph.register(lmp)\n"
            "lmp.file({inp!r})\n"
            "print('RESULT', lmp.get_thermo('step'), repr(lmp.get_thermo('ke')), "
            "repr(lmp.get_thermo('pe')), lmp.get_natoms())\n"
            "lmp.close()\n").format(bd=args.builddir, inp=args.input)
        cmd = [sys.executable, "-c", code]
        print("+ " + sys.executable + " -c <tlsph.register + lmp.file>", flush=True)
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           universal_newlines=True, timeout=600)
        print(p.stdout)
        res = [l.split() for l in p.stdout.splitlines() if l.startswith("RESULT ")]
        if p.returncode != 0 or not res:
            fail("python3-lammps + tlsph.register failed (exit {})".format(p.returncode))
        step, ke, pe, natoms = float(res[-1][1]), float(res[-1][2]), float(res[-1][3]), int(res[-1][4])
        header, rows = ref
        want = dict(zip(header, rows[-1]))
        if int(step) != STEPS or natoms != 100:
            fail("python run: step {} natoms {} (expected {} and 100)".format(step, natoms, STEPS))
        for name, got in (("KinEng", ke), ("PotEng", pe)):
            exp = want[name]
            if not math.isclose(got, exp, rel_tol=1e-12, abs_tol=0.0):
                fail("python run: {} = {!r}, lmp_tlsph printed {!r}".format(name, got, exp))
        print("python3-lammps + tlsph.register: step {} KinEng {!r} PotEng {!r} match lmp_tlsph".format(
            int(step), ke, pe))
    print("PASS")


if __name__ == "__main__":
    main()
