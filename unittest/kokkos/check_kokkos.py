#!/usr/bin/env python3
"""pair_style tlsph/kk and atom_style peri/kk against the CPU styles (ctest kokkos.*).

All runs use one LAMMPS, built by scripts/build-lammps-plugin.sh kokkos with
the KOKKOS, PERI and PLUGIN packages and this package compiled in (Kokkos host
backend; or kokkos-omp with --threads N): the CPU styles without -k, the /kk styles with -k on -sf kk and
explicit /kk style names (-var kk /kk), so a missing /kk style is an error,
not a silent fall-back to the CPU style.

  --case forces    in.forces (run 0 on a deformed, moving body with two types):
                   2D/3D, isotropic/orthotropic plies, thesis/conservative
                   hourglass, linear/quadratic gradient. The forces, the stress
                   compute, the energies and the pressure of tlsph/kk equal those
                   of tlsph with the same newton setting (on: the scatter form,
                   off: the gather form), and the gather form's the scatter
                   form's, to TOL relative to the largest value.
  --case mpi       ../lammps/mpi/run_mpi.py with the /kk styles: -np 1, 2, 4 (and
                   -np 2 newton off) give the same final state (atoms migrate), and
                   for the laminate its restart test (files written and read by /kk).
  --case damage    in.damage (a shortened crack-branching plate, bonds breaking,
                   velocity filter): tlsph/damage/kk equals tlsph/damage with
                   the same newton setting to TOL (state and damage after 500 steps),
                   has the same damage per particle with the other setting and on
                   2 ranks (x, v to DAMAGE_XTOL), and a restart written mid-crack by /kk continues
                   under the CPU style (and back) as the CPU-written one does, to TOL.
  --case restart   a restart written by /kk is read by the CPU styles, and one
                   written by the CPU styles is read by /kk; each continued run equals
                   the CPU-written, CPU-read one to TOL (the /kk step is bitwise the
                   CPU newton-off step, used here as the CPU reference).
  --case transfers in.transfers with the settings of a GPU run (-pk kokkos comm
                   device newton off neigh full): an ordinary step of tlsph/kk,
                   and of tlsph/damage/kk with the velocity filter and the
                   time-step fix, copies no per-atom array and none of the
                   styles' own arrays between host and device (the 'tlsph/kk
                   copies' report the bond fix logs after each run; two runs of
                   different length, their difference per step must be zero).
                   A GPU build counts the real copies; on a host backend the
                   device model (TLSPH_KK_DEVICE_MODEL=1) runs the GPU's paths
                   on one memory and counts what they would copy, on 1 rank and
                   on 2 (GPU-aware MPI), with thermo output equal to the plain
                   host backend's. A fix without a Kokkos variant must be
                   reported (negative control).
  --case cache     the bond cache built on the device equals the host build
                   (TLSPH_KK_CACHE_CHECK=1 compares every device build with a
                   host build; a neighbor build every step; 2D both styles,
                   3D damage; 1 and 2 ranks).
  --case plugin    (with --plugin) `plugin list` after `plugin load` of the /kk
                   plugin: every style of the CPU plugin (--cpu-plugin, loaded
                   alone in another run) and the /kk pair and fix styles.

--plugin PATH (tlsphkkplugin.so, scripts/build-kk-plugin.sh): every run, CPU and
/kk, first does `plugin load PATH` (a wrapper input: plugin load, then include
the case's input), so the styles come from the plugin; for a LAMMPS without
the package compiled in (build-lammps-plugin.sh kokkos-stock) or one with it
(kokkos: the plugin's styles override the built-in ones). The runs have
TLSPH_KK_PLUGIN_TRACE=1, and every /kk run must log that its pair style's
compute() and its atom style's grow() come from PATH ("(this plugin)"),
never "not from this plugin".
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "lammps", "mpi"))
from run_mpi import read_dump  # noqa: E402

MATERIALS = os.path.join(HERE, "..", "..", "potentials", "tlsph_materials.tlsph")
TOL = 1e-12
# newton on (scatter) and 2 ranks sum the same terms in another order: the
# round-off grows over the 500 steps of the breaking run (as in run_mpi.py)
DAMAGE_XTOL = 1e-8
# On a GPU (--gpu) nvcc contracts multiply-adds into FMAs and the math library
# differs: every step rounds differently from the CPU, as a changed summation
# order does. A one-step comparison (forces, cache) keeps --tol; a comparison
# after many steps (damage, restart) is held against the same deck's round-off
# yardstick, the difference between two CPU runs that differ only in their
# summation order (newton on and off), measured in the same check: the limit
# is max(--tol, ROUNDOFF_FACTOR x yardstick). Measured on an H200 (commits
# a5b9619, 55cf580; bench/gpu-check/): the GPU runs differ from the CPU runs
# by 0.9 to 1.4 times the yardstick (the breaking run's velocities 3.7e-10 to
# 4.3e-10 against 3.7e-10, the laminate restart's forces 1.2e-9 to 1.4e-9
# against 1.1e-9); the factor is the margin for the spread of one sample.
# Broken-bond sets and damage stay exact.
ROUNDOFF_FACTOR = 10.0
GPU = False


def roundoff_limit(tol, yardstick):
    """the limit of a many-step comparison: tol, and on a GPU at least
    ROUNDOFF_FACTOR x the CPU's own newton on/off difference"""
    if GPU and yardstick is not None and math.isfinite(yardstick):
        return max(tol, ROUNDOFF_FACTOR * yardstick)
    return tol
KK = ["-k", "on", "-sf", "kk", "-var", "kk", "/kk"]


def lmp_run(args, tag, inp, extra, kk, np=1, env_extra=None):
    cmd = []
    if np > 1:
        cmd = [args.mpiexec, "--oversubscribe"]
        if hasattr(os, "geteuid") and os.geteuid() == 0:
            cmd += ["--allow-run-as-root"]
        cmd += ["-np", str(np)]
    kkflags = []
    if kk:
        kkflags = (["-k", "on", "g", "1"] if args.gpu else ["-k", "on", "t", str(args.threads)]) + KK[2:]
    if args.plugin:
        inp = plugin_input(args, inp)
    cmd += [args.lmp] + kkflags + ["-in", inp, "-log", tag + ".log", "-screen",
                                               "none", "-var", "out", tag] + list(extra)
    # the CPU styles' scalar step (TLSPH_SIMD=no: pair_style tlsph's default
    # 'simd' value): the /kk kernels are its twins, bitwise on the host
    # backend; the SIMD step is checked against the scalar step by the
    # lammps.Simd.* tests
    env = dict(os.environ, OMP_NUM_THREADS=str(args.threads), OMP_PROC_BIND="false",
               TLSPH_SIMD="no")
    if args.plugin:
        env["TLSPH_KK_PLUGIN_TRACE"] = "1"
    env.update(env_extra or {})
    p = subprocess.run(cmd, cwd=args.workdir, capture_output=True, text=True,
                       timeout=args.timeout, env=env)
    log = open(os.path.join(args.workdir, tag + ".log")).read() \
        if os.path.exists(os.path.join(args.workdir, tag + ".log")) else ""
    out = p.stdout + p.stderr + log
    problems = []
    if p.returncode != 0:
        problems.append("exit code %d" % p.returncode)
    m = re.search(r"^ERROR.*$", out, re.M)
    if m:
        problems.append(m.group(0))
    if re.search(r"\bnan\b|\bNaN\b|-nan", out):
        problems.append("NaN in output")
    if args.plugin:
        problems += plugin_origin_problems(args, out, kk)
    if problems:
        print("\n".join(out.splitlines()[-20:]))
    return out, problems


def plugin_input(args, inp):
    """a wrapper input in the workdir: plugin load, then the case's input"""
    wrapper = os.path.join(args.workdir, "kkplugin_" + os.path.basename(inp))
    with open(wrapper, "w") as fp:
        fp.write("plugin load %s\ninclude %s\n" % (args.plugin, inp))
    return wrapper


def plugin_origin_problems(args, out, kk):
    """with --plugin: the /kk objects' code must come from the plugin"""
    problems = []
    if "Loading plugin: Total Lagrangian SPH, KOKKOS by" not in out:
        problems.append("the plugin did not register pair tlsph/kk")
    m = re.search(r"^.*not from this plugin.*$", out, re.M)
    if m:
        problems.append("code not from the plugin: " + m.group(0))
    if kk:
        so = os.path.realpath(args.plugin)
        for what in (r"pair LAMMPS_NS::PairTLSPH(?:Damage)?Kokkos<Kokkos::Serial>: compute\(\)",
                     r"atom style LAMMPS_NS::AtomVecPeriKokkos: grow\(\)"):
            pat = r"tlsph kk plugin: %s from (\S+) \(this plugin\)" % what
            found = [f for f in re.findall(pat, out) if os.path.realpath(f) == so]
            if not found:
                problems.append("no log line '%s from %s (this plugin)'" % (what, so))
    return problems


def case_plugin(args):
    """plugin list: the /kk plugin registers all the CPU plugin's styles and the /kk ones"""
    if not args.plugin:
        return ["--case plugin needs --plugin"]
    listed = {}
    for tag, so in (("list_kk", args.plugin), ("list_cpu", args.cpu_plugin)):
        if not so:
            continue
        inp = os.path.join(args.workdir, tag + ".in")
        with open(inp, "w") as fp:
            fp.write("plugin load %s\nplugin list\n" % so)
        p = subprocess.run([args.lmp, "-in", inp, "-log", tag + ".log", "-echo", "none"],
                           cwd=args.workdir, capture_output=True, text=True, timeout=args.timeout)
        out = p.stdout + p.stderr
        listed[tag] = set(re.findall(r"^\s*\d+: (\w+) style plugin (\S+)$", out, re.M))
        print("%s: %d styles in 'plugin list' (exit %d)" % (tag, len(listed[tag]), p.returncode))
        if p.returncode != 0 or not listed[tag]:
            print(out[-3000:])
            return ["%s: plugin load/list failed" % tag]
    problems = []
    want = {("pair", n) for n in ("tlsph/kk", "tlsph/kk/device", "tlsph/kk/host", "tlsph/damage/kk",
                                  "tlsph/damage/kk/device", "tlsph/damage/kk/host")}
    want |= {("fix", n + s) for n in ("tlsph/dt/kk", "tlsph/velocity/filter/kk")
             for s in ("", "/device", "/host")}
    want |= listed.get("list_cpu", set())
    missing = sorted(want - listed["list_kk"])
    print("kk plugin: %d styles, expected at least %d (%d of the CPU plugin): %s"
          % (len(listed["list_kk"]), len(want), len(listed.get("list_cpu", ())),
             "ok" if not missing else "missing " + " ".join("%s %s" % m for m in missing)))
    if missing:
        problems.append("styles missing from the kk plugin: %s" % missing)
    return problems


def thermo(log):
    """the last thermo line as {column: value}"""
    lines = log.splitlines()
    k = max(i for i, l in enumerate(lines) if l.split()[:1] == ["Step"])
    return dict(zip(lines[k].split(), (float(x) for x in lines[k + 1].split())))


def rel_diff(a, b, keys):
    scale = max(abs(a[i][k]) for i in a for k in keys)
    diff = max(abs(a[i][k] - b[i][k]) for i in a for k in keys)
    return diff, scale, (diff / scale if scale > 0 else diff)


def case_forces(args):
    inp = os.path.join(HERE, "in.forces")
    matrix = [("2", "iso", "thesis", "linear"), ("2", "iso", "conservative", "quadratic"),
              ("3", "iso", "thesis", "quadratic"), ("3", "ortho", "thesis", "linear"),
              ("3", "ortho", "conservative", "quadratic")]
    problems = []
    for dim, law, hg, grad in matrix:
        name = "%sd_%s_%s_%s" % (dim, law, hg, grad)
        extra = ["-var", "dim", dim, "-var", "law", law, "-var", "hg", hg, "-var", "grad", grad]
        runs = {}
        for tag, kk, newton in (("cpu_on", False, "on"), ("cpu_off", False, "off"),
                                ("kk_on", True, "on"), ("kk_off", True, "off")):
            t = "%s_%s" % (name, tag)
            log, prob = lmp_run(args, t, inp, extra + ["-var", "newton", newton], kk)
            problems += ["%s: %s" % (t, p) for p in prob]
            if prob:
                break
            cols, rows = read_dump(os.path.join(args.workdir, t + ".dump"))
            runs[tag] = (thermo(log), cols, rows)
        if len(runs) < 4:
            continue
        cols = runs["kk_on"][1]
        force = [cols.index(c) for c in ("fx", "fy", "fz")]
        stress = [cols.index(c) for c in ("c_sig[1]", "c_sig[2]", "c_sig[4]")]
        # the same form (newton on: scatter, off: gather) and the other one
        for kk, ref in (("kk_on", "cpu_on"), ("kk_off", "cpu_off"), ("kk_on", "cpu_off")):
            th, _, rows = runs[ref]
            kk_rows = runs[kk][2]
            if sorted(rows) != sorted(kk_rows):
                problems.append("%s: different atom IDs" % name)
                continue
            for what, keys in (("force", force), ("stress", stress)):
                diff, scale, rel = rel_diff(rows, kk_rows, keys)
                ok = rel <= TOL and math.isfinite(rel)
                print("%-34s %-6s vs %-7s %-6s max|diff| %.3e of %.3e: %.2e %s"
                      % (name, kk, ref, what, diff, scale, rel, "ok" if ok else "FAIL"))
                if not ok:
                    problems.append("%s: %s vs %s differs by %.3g" % (name, what, ref, rel))
            kth = runs[kk][0]
            pscale = max(abs(th[k]) for k in ("Pxx", "Pyy", "Pxy"))
            worst = 0.0
            for k in ("PotEng", "c_e[1]", "c_e[2]", "Press", "Pxx", "Pyy", "Pxy"):
                scale = pscale if k.startswith("P") and k != "PotEng" else abs(th[k])
                rel = abs(th[k] - kth[k]) / scale if scale > 0 else abs(th[k] - kth[k])
                worst = max(worst, rel) if math.isfinite(rel) else math.inf
                if not (rel <= TOL):
                    problems.append("%s: %s vs %s differs by %.3g" % (name, k, ref, rel))
            print("%-34s %-6s vs %-7s energies, pressure: largest relative difference %.2e %s"
                  % (name, kk, ref, worst, "ok" if worst <= TOL else "FAIL"))
    return problems


def case_mpi(args):
    # a launcher that gives run_mpi.py's lmp the /kk styles
    wrapper = os.path.join(args.workdir, "lmp_kk.sh")
    kkflags = " ".join(["-k", "on", "t", str(args.threads)] + KK[2:])
    with open(wrapper, "w") as fp:
        if args.plugin:
            # -in FILE becomes a wrapper input in the current directory (one
            # per rank, renamed into place): plugin load, then include FILE
            fp.write('#!/bin/bash\na=()\nwhile [ $# -gt 0 ]; do\n'
                     '  if [ "$1" = -in ] && [ $# -ge 2 ]; then\n'
                     '    w="kkplugin_$(basename "$2")"\n'
                     '    printf "plugin load %%s\\ninclude %%s\\n" "%s" "$2" > "$w.$$" && mv -f "$w.$$" "$w"\n'
                     '    a+=(-in "$w"); shift 2\n'
                     '  else a+=("$1"); shift; fi\ndone\n'
                     'exec "%s" %s "${a[@]}"\n' % (args.plugin, args.lmp, kkflags))
        else:
            fp.write('#!/bin/sh\nexec "%s" %s "$@"\n' % (args.lmp, kkflags))
    os.chmod(wrapper, 0o755)
    problems = []
    mpi = os.path.join(HERE, "..", "lammps", "mpi")
    for case, extra in (("2d", []), ("laminate_3d",
                                     ["--restart-input", os.path.join(mpi, "in.laminate_3d_restart")])):
        wd = os.path.join(args.workdir, "mpi_" + case)
        os.makedirs(wd, exist_ok=True)
        shutil.copy(MATERIALS, wd)
        cmd = [sys.executable, os.path.join(mpi, "run_mpi.py"), "--mpiexec", args.mpiexec,
               "--lmp", wrapper, "--input", os.path.join(mpi, "in." + case), "--workdir", wd,
               "--np", "1", "2", "4"] + extra
        print("$ " + " ".join(cmd))
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=4 * args.timeout)
        print(p.stdout + p.stderr)
        if p.returncode != 0:
            problems.append("run_mpi.py %s failed (exit %d)" % (case, p.returncode))
    return problems


def case_restart(args):
    mpi = os.path.join(HERE, "..", "lammps", "mpi")
    first, second = os.path.join(mpi, "in.laminate_3d"), os.path.join(mpi, "in.laminate_3d_restart")
    half = "150"
    problems = []
    finals = {}
    for writer in ("cpu", "kk"):
        rfile = "half_" + writer
        _, prob = lmp_run(args, "first_" + writer, first,
                          ["-var", "newton", "off", "-var", "steps", half, "-var", "restart", rfile],
                          writer == "kk")
        problems += ["first_%s: %s" % (writer, p) for p in prob]
        if prob:
            continue
        for reader in ("cpu", "kk"):
            t = "%s_to_%s" % (writer, reader)
            _, prob = lmp_run(args, t, second,
                              ["-var", "newton", "off", "-var", "file", rfile, "-var", "steps", half],
                              reader == "kk")
            problems += ["%s: %s" % (t, p) for p in prob]
            if not prob:
                finals[t] = read_dump(os.path.join(args.workdir, t + ".final.dump"))
    if "cpu_to_cpu" not in finals:
        return problems + ["no CPU-written, CPU-read reference"]
    cols, ref = finals["cpu_to_cpu"]
    quantities = (("position", ("xu", "yu", "zu")), ("velocity", ("vx", "vy", "vz")),
                  ("force", ("fx", "fy", "fz")))
    # the round-off yardstick (ROUNDOFF_FACTOR): the same two halves on the
    # CPU with newton on, against newton off
    yard = {}
    if GPU:
        _, prob = lmp_run(args, "first_cpu_on", first,
                          ["-var", "newton", "on", "-var", "steps", half, "-var", "restart",
                           "half_cpu_on"], False)
        if not prob:
            _, prob = lmp_run(args, "cpu_on_to_cpu_on", second,
                              ["-var", "newton", "on", "-var", "file", "half_cpu_on", "-var",
                               "steps", half], False)
        problems += ["yardstick (CPU, newton on): %s" % p for p in prob]
        if not prob:
            _, rows = read_dump(os.path.join(args.workdir, "cpu_on_to_cpu_on.final.dump"))
            for what, keys in quantities:
                yard[what] = rel_diff(ref, rows, [cols.index(k) for k in keys])[2]
                print("%-10s vs cpu_to_cpu %-8s %.2e (the round-off yardstick: CPU, newton on "
                      "against off)" % ("cpu_on", what, yard[what]))
    for t in ("kk_to_cpu", "cpu_to_kk", "kk_to_kk"):
        if t not in finals:
            continue
        _, rows = finals[t]
        if sorted(rows) != sorted(ref):
            problems.append("%s: different atom IDs" % t)
            continue
        for what, keys in quantities:
            diff, scale, rel = rel_diff(ref, rows, [cols.index(k) for k in keys])
            lim = roundoff_limit(TOL, yard.get(what))
            ok = rel <= lim and math.isfinite(rel)
            print("%-10s vs cpu_to_cpu %-8s max|diff| %.3e of %.3e: %.2e %s"
                  % (t, what, diff, scale, rel, "ok" if ok else "FAIL (limit %.1e)" % lim))
            if not ok:
                problems.append("%s: %s differs by %.3g" % (t, what, rel))
    return problems


def thermo_rows(log):
    """all thermo rows of a LAMMPS log text, every block in order: [(columns, [values])]"""
    rows, cols = [], None
    for line in log.splitlines():
        w = line.split()
        if w[:1] == ["Step"]:
            cols = w
            continue
        if cols and len(w) == len(cols):
            try:
                rows.append((tuple(cols), [float(x) for x in w]))    # numbers only
                continue
            except ValueError:
                pass
        cols = None    # the thermo block has ended
    return rows


def thermo_column(log, name):
    """all values of a thermo column"""
    return [v[c.index(name)] for c, v in thermo_rows(log) if name in c]


def case_damage(args):
    for f in ("in.damage", "in.damage_fixes", "in.damage_final", "in.damage_restart"):
        shutil.copy(os.path.join(HERE, f), args.workdir)
    problems, finals, energies = [], {}, {}
    runs = (("cpu_off", False, "off", 1), ("cpu_on", False, "on", 1), ("kk", True, "off", 1),
            ("kk_on", True, "on", 1), ("kk_np2", True, "off", 2))
    for tag, kk, newton, np in runs:
        if np > args.max_ranks:
            print("%-8s skipped (%d ranks, --max-ranks %d)" % (tag, np, args.max_ranks))
            continue
        log, prob = lmp_run(args, tag, "in.damage", ["-var", "newton", newton] + args.options,
                            kk, np)
        problems += ["%s: %s" % (tag, p) for p in prob]
        if prob:
            continue
        broken = thermo_column(log, "v_broken")
        print("%-8s broken bonds %s (the pre-crack, then the growing crack)"
              % (tag, " ".join("%d" % b for b in broken)))
        if not broken or not broken[-1] > broken[0]:
            problems.append("%s: no bond broke during the run: the test does not exercise "
                            "breaking" % tag)
        finals[tag] = read_dump(os.path.join(args.workdir, tag + ".final.dump"))
        energies[tag] = {c: thermo_column(log, c) for c in ("c_e[1]", "c_e[2]", "c_e[3]", "c_e[4]")}
    # the energy balance every 100 steps (compute tlsph/energy: strain, hourglass
    # and viscous work tallied by the bond fix, kinetic): /kk against the CPU
    # style with the same newton setting
    def energy_diff(ref, got):
        scale = max(abs(x) for x in ref) if ref else 0.0
        diff = max((abs(a - b) for a, b in zip(ref, got)), default=math.inf)
        return diff, scale, (diff / scale if scale > 0 else diff)

    # the round-off yardstick (ROUNDOFF_FACTOR): CPU newton on against off
    yard = {}
    if GPU and "cpu_on" in energies and "cpu_off" in energies:
        for c, ref in energies["cpu_off"].items():
            yard[c] = energy_diff(ref, energies["cpu_on"][c])[2]
        for what, keys in (("position", ("x", "y")), ("velocity", ("vx", "vy")),
                           ("force", ("fx", "fy"))):
            if "cpu_on" in finals and "cpu_off" in finals:
                cols = finals["cpu_off"][0]
                yard[what] = rel_diff(finals["cpu_off"][1], finals["cpu_on"][1],
                                      [cols.index(k) for k in keys])[2]
        print("round-off yardstick (CPU, newton on against off): " +
              ", ".join("%s %.2e" % kv for kv in sorted(yard.items())))
    for kk, cpu in (("kk", "cpu_off"), ("kk_on", "cpu_on")):
        if kk not in energies or cpu not in energies:
            continue
        for c, ref in energies[cpu].items():
            got = energies[kk][c]
            diff, scale, rel = energy_diff(ref, got)
            lim = roundoff_limit(TOL, yard.get(c))
            ok = len(ref) == len(got) and len(ref) > 1 and rel <= lim
            print("%-10s vs %-10s %-8s (%d thermo rows) max|diff| %.3e of %.3e: %.2e %s"
                  % (kk, cpu, c, len(ref), diff, scale, rel,
                     "ok" if ok else "FAIL (limit %.1e)" % lim))
            if not ok:
                problems.append("%s vs %s: %s differs by %.3g" % (kk, cpu, c, rel))
    # restarts mid-crack, across the variants (all with newton off)
    for writer in ("cpu", "kk"):
        _, prob = lmp_run(args, "first_" + writer, "in.damage",
                          ["-var", "newton", "off", "-var", "steps", "250", "-var", "restart",
                           "half_" + writer] + args.options, writer == "kk")
        problems += ["first_%s: %s" % (writer, p) for p in prob]
        if prob:
            continue
        for reader in ("cpu", "kk"):
            if writer == "kk" and reader == "kk":
                continue
            t = "%s_to_%s" % (writer, reader)
            _, prob = lmp_run(args, t, "in.damage_restart",
                              ["-var", "newton", "off", "-var", "file", "half_" + writer,
                               "-var", "steps", "250"], reader == "kk")
            problems += ["%s: %s" % (t, p) for p in prob]
            if not prob:
                finals[t] = read_dump(os.path.join(args.workdir, t + ".final.dump"))

    def check(a, b, tol_state, exact_damage=True):
        if a not in finals or b not in finals:
            return
        cols, ra = finals[a]
        _, rb = finals[b]
        if sorted(ra) != sorted(rb):
            problems.append("%s vs %s: different atom IDs" % (a, b))
            return
        for what, keys, tol in (("position", ("x", "y"), tol_state),
                                ("velocity", ("vx", "vy"), tol_state),
                                ("force", ("fx", "fy"), tol_state * 100),
                                ("damage", ("c_dmg[1]", "c_dmg[3]"), 0.0 if exact_damage else TOL)):
            diff, scale, rel = rel_diff(ra, rb, [cols.index(k) for k in keys])
            if what != "damage":
                tol = roundoff_limit(tol, yard.get(what))
            ok = rel <= tol and math.isfinite(rel)
            print("%-10s vs %-10s %-8s max|diff| %.3e of %.3e: %.2e %s"
                  % (b, a, what, diff, scale, rel, "ok" if ok else "FAIL (limit %.0e)" % tol))
            if not ok:
                problems.append("%s vs %s: %s differs by %.3g" % (b, a, what, rel))

    check("cpu_off", "kk", TOL)
    check("cpu_on", "kk_on", TOL)
    check("cpu_on", "kk", DAMAGE_XTOL)
    check("kk", "kk_np2", DAMAGE_XTOL)
    check("cpu_to_cpu", "kk_to_cpu", TOL)
    check("cpu_to_cpu", "cpu_to_kk", TOL)
    return problems


def copy_blocks(log):
    """the 'tlsph/kk copies' report of each run in a log: [(nsteps, where, {name: (to device,
    to host, MB)})], where = 'device', 'model' or 'host'"""
    runs = []
    for line in log.splitlines():
        m = re.match(r"^tlsph/kk copies: run of (\d+) steps on (the device model|the device|"
                     r"a host backend)", line)
        if m:
            where = {"the device": "device", "the device model": "model",
                     "a host backend": "host"}[m.group(2)]
            runs.append((int(m.group(1)), where, {}))
            continue
        m = re.match(r"^tlsph/kk copies: (\S+) (\S+) (\d+) (\d+) (\S+)$", line)
        if m and runs:
            runs[-1][2][m.group(1) + " " + m.group(2)] = (int(m.group(3)), int(m.group(4)),
                                                          float(m.group(5)))
    return runs


def per_step_copies(runs, n1, n2):
    """{name: (to device, to host, MB)} per ordinary step: the difference of the
    two timed runs (same set-up and output, n1 and n2 steps) over n2 - n1"""
    (_, _, a), (_, _, b) = runs[1], runs[2]
    out = {}
    for name in sorted(set(a) | set(b)):
        ca, cb = a.get(name, (0, 0, 0.0)), b.get(name, (0, 0, 0.0))
        out[name] = tuple((cb[k] - ca[k]) / float(n2 - n1) for k in range(3))
    return out


def transfer_run(args, tag, style, n1, n2, np, model, extra=()):
    """in.transfers: the copy reports of its three runs, their last thermo row
    and the problems found"""
    inp = os.path.join(HERE, "in.transfers")
    flags = ["-pk", "kokkos", "comm", "device", "newton", "off", "neigh", "full"]
    if np > 1:
        # one memory: MPI reads device buffers as it reads host ones (GPU-aware)
        flags += ["gpu/aware", "on"]
    env = {"TLSPH_KK_DEVICE_MODEL": "1"} if model else {"TLSPH_KK_DEVICE_MODEL": "0"}
    out, p = lmp_run(args, tag, inp, flags + ["-var", "style", style, "-var", "n1", str(n1),
                                              "-var", "n2", str(n2)] + list(extra),
                     True, np=np, env_extra=env)
    problems = ["%s: %s" % (tag, q) for q in p]
    runs = copy_blocks(out)
    if len(runs) != 3 or [r[0] for r in runs] != [5, n1, n2]:
        problems.append("%s: expected the copy reports of 3 runs (5, %d, %d steps), found %s"
                        % (tag, n1, n2, [r[0] for r in runs]))
        return None, None, problems
    builds = re.findall(r"^Neighbor list builds = (\d+)$", out, re.M)
    if len(builds) != 3 or builds[1:] != ["0", "0"]:
        problems.append("%s: the two timed runs must build no neighbor list (found %s)"
                        % (tag, builds))
    rows = thermo_rows(out)
    return runs, (rows[-1] if rows else None), problems


def case_transfers(args):
    """an ordinary step of tlsph/kk and tlsph/damage/kk (with nve/kk, the
    velocity filter and the time-step fix) copies no per-atom array and none
    of the styles' own arrays between host and device. On a GPU build the
    atom style's ledger of the DualView protocol counts the copies; on a host
    backend the device model (TLSPH_KK_DEVICE_MODEL=1, tlsph_kk_copies.h)
    runs the GPU's paths on one memory and counts what they would copy: the
    styles' own uploads and downloads, the host accesses of their host code,
    fixes LAMMPS runs on the host, communication through the host. 1 rank (a
    GPU bundle's configuration) and 2 ranks (GPU-aware MPI). The model's
    thermo output must equal the plain host backend's (only the paths
    differ). A negative control: a fix without a Kokkos variant (addforce)
    must be reported as copying every step."""
    problems = []
    n1, n2 = 10, 30
    for style in ("tlsph", "damage"):
        plain_row = None
        if not args.gpu:
            plain, plain_row, p = transfer_run(args, "transfers_%s_host" % style, style, n1, n2,
                                               1, False)
            problems += p
            if plain and any(r[1] != "host" for r in plain):
                problems.append("%s: the plain host backend reports %s, not 'a host backend'"
                                % (style, [r[1] for r in plain]))
        for np in (1, 2):
            if np > args.max_ranks:
                continue
            tag = "transfers_%s_np%d" % (style, np)
            runs, row, p = transfer_run(args, tag, style, n1, n2, np, True)
            problems += p
            if not runs:
                continue
            kinds = set(r[1] for r in runs)
            if kinds != ({"device"} if args.gpu else {"model"}):
                problems.append("%s: the runs report %s, expected the device model (or a GPU)"
                                % (tag, sorted(kinds)))
                continue
            # the set-up must have counted something (the bond cache goes to
            # the device): else the ledger is not counting at all
            if not runs[0][2]:
                problems.append("%s: the warm-up run reports no copies: the ledger counts "
                                "nothing" % tag)
            if np == 1 and not args.gpu and row != plain_row:
                problems.append("%s: last thermo row %s differs from the plain host backend's %s"
                                % (tag, row, plain_row))
            per = per_step_copies(runs, n1, n2)
            print("%s (%s): copies per ordinary step (runs of %d and %d steps):"
                  % (tag, sorted(kinds)[0], n1, n2))
            clean = True
            for name, c in per.items():
                bad = c[0] != 0 or c[1] != 0
                print("  %-40s to device %6.2f  to host %6.2f  %8.4f MB  %s"
                      % (name, c[0], c[1], c[2], "FAIL" if bad else "ok"))
                if bad:
                    clean = False
                    problems.append("%s: an ordinary step copies %s (%.2f to the device, %.2f "
                                    "to the host per step)" % (tag, name, c[0], c[1]))
            if clean:
                print("  nothing: every copy is in the set-up and the thermo output")
    # the negative control: the check must see a fix that runs on the host
    runs, _, p = transfer_run(args, "transfers_control", "tlsph", n1, n2, 1, True,
                              ["-var", "extra", "addforce"])
    problems += p
    # ... and the pair style warns about it (it declares no atom data: on a
    # GPU its force would be lost)
    log = open(os.path.join(args.workdir, "transfers_control.log")).read() \
        if os.path.exists(os.path.join(args.workdir, "transfers_control.log")) else ""
    if not re.search(r"^WARNING: pair tlsph/kk: fix extra \(addforce\) has no Kokkos variant", log, re.M):
        problems.append("control: no warning that fix addforce works on stale host copies")
    else:
        print("control: the pair style warns that fix extra (addforce) works on stale host copies")
    if runs:
        per = per_step_copies(runs, n1, n2)
        seen = [n for n, c in per.items() if n.startswith("host-fix extra/addforce:")
                and c[1] >= 1]
        print("control (fix addforce, no Kokkos variant): %s" %
              ("reported: " + ", ".join("%s %s" % (n, per[n][:2]) for n in seen) if seen
               else "NOT reported"))
        if not seen:
            problems.append("control: a fix without a Kokkos variant (addforce) that runs every "
                            "step was not reported as copying")
    return problems


def case_cache(args):
    """the bond cache built on the device (the partners resolved and the bond
    math run in Kokkos kernels) equals the host build: with
    TLSPH_KK_CACHE_CHECK=1 every device build is compared with a host build of
    the same cache (the partner indices, slots, row starts and counts
    exactly; g, w, Q, sum g, frozen corrections; the run stops on a
    difference above 1e-12, --tol on a GPU). A neighbor build every step:
    in.transfers (2D, tlsph/kk and tlsph/damage/kk with pre-crack and frozen
    corrections) and bench/in.gpu (3D tlsph/damage/kk), 1 and 2 ranks (atoms
    migrate). Each run must report device builds."""
    problems = []
    env = {"TLSPH_KK_CACHE_CHECK": "1" if TOL == 1e-12 else repr(TOL)}
    flags = ["-pk", "kokkos", "newton", "off", "neigh", "full"]
    runs = [("cache_tlsph", os.path.join(HERE, "in.transfers"),
             ["-var", "style", "tlsph", "-var", "check", "no", "-var", "n1", "5", "-var", "n2", "5"]),
            ("cache_damage", os.path.join(HERE, "in.transfers"),
             ["-var", "style", "damage", "-var", "check", "no", "-var", "n1", "5", "-var", "n2", "5"]),
            ("cache_3d", os.path.join(HERE, "..", "..", "bench", "in.gpu"),
             ["-var", "n", "10", "-var", "nsteps", "5", "-var", "nrebuild", "5"])]
    for tag, inp, extra in runs:
        for np in (1, 2):
            if np > args.max_ranks:
                continue
            t = "%s_np%d" % (tag, np)
            out, p = lmp_run(args, t, inp, flags + extra + (["-pk", "kokkos", "gpu/aware", "on"]
                                                            if np > 1 else []),
                             True, np=np, env_extra=env)
            problems += ["%s: %s" % (t, q) for q in p]
            rep = re.findall(r"^tlsph/kk bond cache: (\d+) device builds, (\d+) host builds"
                             r"(?: \(per device build[^)]*\))?(?:; layout: [^,]*)?, the device builds checked against the host build: largest relative "
                             r"difference (\S+)$", out, re.M)
            dev = sum(int(r[0]) for r in rep)
            worst = max((float(r[2]) for r in rep), default=math.inf)
            print("%-18s %d device-built bond caches, each equal to the host build within %.3g "
                  "(relative) %s" % (t, dev, worst, "ok" if dev > 5 and worst <= TOL else "FAIL"))
            if dev <= 5:
                problems.append("%s: only %d device builds (a neighbor build every step expected)"
                                % (t, dev))
            if not (worst <= TOL):
                problems.append("%s: device-built bond cache differs from the host build by %.3g"
                                % (t, worst))
    return problems


def main():
    global TOL, DAMAGE_XTOL, GPU
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lmp", required=True, help="the KOKKOS-enabled lmp (build-lammps-plugin.sh kokkos)")
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--case", required=True, choices=["forces", "mpi", "restart", "damage", "plugin", "transfers", "cache"])
    ap.add_argument("--gpu", action="store_true", help="the /kk runs on GPU 0 (-k on g 1); "
                    "scripts/gpu-check.sh")
    ap.add_argument("--tol", type=float, default=TOL, help="relative tolerance of the /kk "
                    "results against the CPU styles' (default %(default)g, the host backend's "
                    "bitwise-equal arithmetic up to summation order; on a GPU see gpu-check.sh)")
    ap.add_argument("--max-ranks", type=int, default=2, help="skip the runs on more MPI ranks "
                    "(1: a LAMMPS with MPI STUBS, the GPU bundle)")
    ap.add_argument("--plugin", help="tlsphkkplugin.so: every run loads it first (see above)")
    ap.add_argument("--cpu-plugin", help="--case plugin: tlsphplugin.so, whose styles the "
                    "kk plugin must register too")
    ap.add_argument("--options", action="store_true",
                    help="damage case with the pair_style tlsph/damage options family (4 dx) "
                         "and damping linear (the restarts take them from the file)")
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--threads", type=int, default=1,
                    help="Kokkos threads of the /kk runs (-k on t N; >1 needs an OpenMP "
                         "Kokkos, build-lammps-plugin.sh kokkos-omp)")
    args = ap.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    shutil.copy(MATERIALS, args.workdir)
    args.options = ["-var", "family", "0.004", "-var", "damping", "linear"] if args.options else []
    for a in ("plugin", "cpu_plugin"):
        if getattr(args, a):
            setattr(args, a, os.path.abspath(getattr(args, a)))
    GPU = args.gpu
    if args.tol != TOL:
        # the breaking run's state tolerance grows with TOL as from 1e-12 to 1e-8
        DAMAGE_XTOL = max(DAMAGE_XTOL, args.tol * 1e4)
        TOL = args.tol
    problems = {"forces": case_forces, "mpi": case_mpi, "restart": case_restart,
                "damage": case_damage, "plugin": case_plugin,
                "transfers": case_transfers, "cache": case_cache}[args.case](args)
    if problems:
        print("FAILED:\n  " + "\n  ".join(problems))
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
