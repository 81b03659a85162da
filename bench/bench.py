#!/usr/bin/env python3
"""Throughput and memory benchmark of pair_style tlsph (driven by bench/run.sh).

Runs bench/in.bench (a 2D and a 3D steel block with a smooth non-uniform
velocity field) as separate lmp_tlsph processes, every configuration once per
repeat, configurations interleaved inside a repeat so that the machine load
hits them alike; the figure of a configuration is its fastest repeat. Reads
from each log the "Loop time" of the second (timed) run, the timing breakdown
(Pair, Comm) and the "Per MPI rank memory allocation" line. Ratios between
configurations come from the same invocation. Optionally (bench/memprobe.so
and Debian's python3-lammps present) reads LAMMPS's memory accounting split by
owner (pair style, bond fix, atoms) from a serial instance.

Writes a Markdown report to --out and prints it. See doc/bench.md.
"""

import argparse
import ctypes
import datetime
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from machine import cpu_model  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
INPUT = os.path.join(HERE, "in.bench")
BRANCHING = os.path.join(HERE, "in.branching")

# quoted in the issue for LAMMPS MACHDYN smd/tlsph on these machines, per core
# (same kernel support, linear elastic); NOT measured by this harness
QUOTED = {
    "machdyn": {2: 0.55e6, 3: 0.2e6},
    "target": {2: 4.0e6, 3: 1.0e6},
}


def sh(cmd):
    try:
        return subprocess.run(cmd, shell=True, capture_output=True, text=True,
                              timeout=30).stdout.strip()
    except Exception:    # noqa: BLE001 (informational only)
        return ""


def loadavg():
    try:
        with open("/proc/loadavg") as f:
            return " ".join(f.read().split()[:3])
    except OSError:
        return "?"


# ----------------------------------------------------------------------------
# configurations


class Case:
    def __init__(self, key, dim, n, np, nsteps, grad="quadratic", alpha=1.0, gamma=1.0,
                 mat="iso"):
        self.key, self.dim, self.n, self.np, self.nsteps = key, dim, n, np, nsteps
        self.grad, self.alpha, self.gamma, self.mat = grad, alpha, gamma, mat
        self.natoms = n ** dim
        self.input = INPUT
        self.runs = []    # parsed logs, one per repeat

    def label(self):
        terms = []
        terms.append("visc" if self.alpha > 0 else "no visc")
        terms.append("hg" if self.gamma != 0 else "no hg")
        if self.mat != "iso":
            terms.append("orthotropic law")
        return f"{self.dim}D {self.grad}, {', '.join(terms)}"

    def varargs(self, nwarm):
        return ["-var", "dim", str(self.dim), "-var", "n", str(self.n),
                "-var", "grad", self.grad, "-var", "alpha", str(self.alpha),
                "-var", "gamma", str(self.gamma), "-var", "mat", self.mat,
                "-var", "nwarm", str(nwarm),
                "-var", "nsteps", str(self.nsteps)]

    def best(self):
        """The repeat with the shortest Loop time (wall clock)."""
        ok = [r for r in self.runs if r.get("loop")]
        return min(ok, key=lambda r: r["loop"]) if ok else None

    def best_cpu(self):
        """Shortest CPU time per rank over the repeats (Loop time x CPU use)."""
        ok = [r["cpu_s"] for r in self.runs if r.get("cpu_s")]
        return min(ok) if ok else None

    def rate(self, seconds):
        """particle-steps per second for a loop of `seconds`."""
        b = self.best()
        return self.natoms * b["steps"] / seconds if b and seconds else None


class BranchingCase(Case):
    """The crack-branching plate (bench/in.branching), tlsph/damage or tlsph."""

    def __init__(self, key, damage, np, nsteps):
        super().__init__(key, 2, 0, np, nsteps)
        self.damage = damage
        self.natoms = 300 * 120    # 100 mm x 40 mm at dx = 0.333 mm
        self.input = BRANCHING

    def label(self):
        return ("tlsph/damage + pre-crack + velocity filter" if self.damage
                else "tlsph, same particles")

    def varargs(self, nwarm):
        return ["-var", "damage", str(self.damage), "-var", "nwarm", str(nwarm),
                "-var", "nsteps", str(self.nsteps)]


def make_cases(a):
    cases = []
    for dim, n, ns in ((2, a.n2, a.steps2), (3, a.n3, a.steps3)):
        cases.append(Case(f"{dim}d-np1", dim, n, 1, ns))
        cases.append(Case(f"{dim}d-np2", dim, n, 2, ns))
        cases.append(Case(f"{dim}d-linear", dim, n, 1, ns, grad="linear"))
        cases.append(Case(f"{dim}d-novisc", dim, n, 1, ns, alpha=0.0))
        cases.append(Case(f"{dim}d-nohg", dim, n, 1, ns, gamma=0.0))
        cases.append(Case(f"{dim}d-stress", dim, n, 1, ns, alpha=0.0, gamma=0.0))
        cases.append(Case(f"{dim}d-ortho", dim, n, 1, ns, mat="ortho"))
    for np in (1, 2):
        for damage in (1, 0):
            cases.append(BranchingCase(f"branch-{'damage' if damage else 'tlsph'}-np{np}",
                                       damage, np, a.steps_branch))
    return cases


# ----------------------------------------------------------------------------
# one LAMMPS run and its log

RE_LOOP = re.compile(r"^Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")
RE_CPU = re.compile(r"^([0-9.]+)% CPU use")
RE_SECT = re.compile(r"^(Pair|Neigh|Comm|Output|Modify|Other)\s*\|(.*)$")
RE_MEM = re.compile(r"^Per MPI rank memory allocation \(min/avg/max\) = ([0-9.eE+-]+) \| "
                    r"([0-9.eE+-]+) \| ([0-9.eE+-]+) Mbytes")


def parse_log(text):
    """Blocks of the log, one per `run`: loop time, sections, memory line."""
    runs, cur, mem = [], None, None
    for line in text.splitlines():
        m = RE_MEM.match(line)
        if m:
            mem = tuple(float(v) for v in m.groups())
            continue
        m = RE_LOOP.match(line)
        if m:
            cur = {"loop": float(m.group(1)), "np": int(m.group(2)), "steps": int(m.group(3)),
                   "atoms": int(m.group(4)), "sect": {}, "mem": mem, "cpu": None}
            runs.append(cur)
            mem = None
            continue
        if cur is None:
            continue
        m = RE_CPU.match(line)
        if m:
            cur["cpu"] = float(m.group(1))
            continue
        m = RE_SECT.match(line)
        if m:
            fields = [f.strip() for f in m.group(2).split("|")]
            # min | avg | max | %varavg | %total   (Other: only avg and %total)
            avg = fields[1] if len(fields) > 1 else ""
            tot = fields[-1]
            cur["sect"][m.group(1)] = (float(avg) if avg else 0.0, float(tot) if tot else 0.0)
    return runs


def run_case(case, a, rep):
    log = os.path.join(a.outdir, f"{case.key}.rep{rep}.log")
    lmp = [a.lmp, "-in", case.input, "-log", log, "-screen", "none"] + case.varargs(a.nwarm)
    if case.np > 1:
        cmd = [a.mpirun, "--allow-run-as-root", "--bind-to", "none", "-np", str(case.np)] + lmp
    else:
        cmd = lmp
    env = dict(os.environ, OMP_NUM_THREADS="1")
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=a.outdir)
    wall = time.time() - t0
    res = {"rep": rep, "wall": wall, "load": loadavg(), "loop": None}
    text = ""
    if os.path.exists(log):
        with open(log) as f:
            text = f.read()
    runs = parse_log(text)
    if p.returncode != 0 or len(runs) < 2:
        tail = "\n".join((text or p.stdout + p.stderr).splitlines()[-8:])
        res["error"] = f"rc {p.returncode}, {len(runs)} run blocks\n{tail}"
        return res
    r = runs[1]    # the timed second run
    res.update(r)
    if r["cpu"] is not None:
        res["cpu_s"] = r["loop"] * r["cpu"] / 100.0    # CPU seconds per rank in the loop
    if r["atoms"] != case.natoms:
        res["error"] = f"expected {case.natoms} atoms, log says {r['atoms']}"
    return res


# ----------------------------------------------------------------------------
# memory accounting from a serial python instance (optional)


def memory_probe(a, dim, n, grad):
    """Split of LAMMPS's memory accounting after the warm-up run, or None."""
    if not a.probe or not os.path.exists(a.probe):
        return None, "bench/memprobe.so not built"
    code = r"""
import ctypes, json, sys
sys.path.insert(0, sys.argv[1])
from lammps import lammps
import tlsph
lmp = lammps(cmdargs=["-log", "none", "-screen", "none"] + sys.argv[4:])
tlsph.register(lmp)
lmp.file(sys.argv[3])
lib = ctypes.CDLL(sys.argv[2])
lib.tlsph_memprobe.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double)]
out = (ctypes.c_double * 13)()
rc = lib.tlsph_memprobe(lmp.lmp, out)
print("MEMPROBE", json.dumps({"rc": rc, "v": list(out)}))
lmp.close()
"""
    import json
    pydir = os.path.join(ROOT, "python")
    args = ["-var", "dim", str(dim), "-var", "n", str(n), "-var", "grad", grad,
            "-var", "nwarm", "2", "-var", "nsteps", "2"]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    try:
        p = subprocess.run([sys.executable, "-c", code, pydir, a.probe, INPUT] + args,
                           capture_output=True, text=True, env=env, cwd=a.outdir, timeout=300)
    except subprocess.TimeoutExpired:
        return None, "memory probe timed out"
    for line in p.stdout.splitlines():
        if line.startswith("MEMPROBE "):
            d = json.loads(line[9:])
            if d["rc"] != 0:
                return None, "memory probe: no pair style"
            keys = ["atom", "neighbor", "comm", "update", "force", "modify", "pair", "bondfix",
                    "nlocal", "nghost", "nmax", "nbonds", "sizeof_bond"]
            return dict(zip(keys, d["v"])), ""
    err = (p.stderr or p.stdout).strip().splitlines()[-1:] or ["no output"]
    return None, "memory probe failed: " + err[0]


# ----------------------------------------------------------------------------
# report


def fmt_rate(x):
    return f"{x / 1e6:.3f} M" if x is not None else "n/a"


def report(a, cases, probes, started, finished, uptime_before, uptime_after, total_wall):
    by = {c.key: c for c in cases}
    L = []
    commit, dirty = a.commit, a.dirty
    built = datetime.datetime.fromtimestamp(a.mtime0).strftime("%Y-%m-%d %H:%M:%S")
    L.append("# tlsph benchmark results")
    L.append("")
    L.append(f"- date: {started} (finished {finished}, {total_wall:.0f} s)")
    L.append(f"- commit at the start: `{commit}`" + (" (working tree has uncommitted changes "
                                                     "under src/)" if dirty else ""))
    if a.built_after and a.built_after != commit:
        L.append(f"- **the binary predates HEAD**: built after commit `{a.built_after}` (the newest "
                 f"commit older than the binary), before `{commit}`; `make build` first to "
                 "benchmark HEAD")
    L.append(f"- machine: {os.cpu_count()} cores, {cpu_model()}")
    L.append(f"- load before: `{uptime_before}`")
    L.append(f"- load after:  `{uptime_after}`")
    cut = (f" (cut from {a.cut[1]} by the {a.budget:.0f} s time budget)" if a.cut else "")
    L.append(f"- binary: `{a.lmp_orig}` (built {built}, run from a copy taken at the start); "
             f"mode: "
             f"{'QUICK (smoke test)' if a.quick else 'full'}, {a.repeat} repeat(s){cut}, figure = "
             f"fastest repeat; warm-up `run {a.nwarm}` untimed, timed = Loop time of the second "
             f"run")
    if os.path.exists(a.lmp_orig) and os.path.getmtime(a.lmp_orig) != a.mtime0:
        L.append("- note: the build was updated while the benchmark ran; all figures are from "
                 "the copy taken at the start")
    L.append("- other processes share the cores: wall-clock figures are noisy (see the load "
             "and the CPU-use column). *CPU time* = Loop time x LAMMPS's \"CPU use\" = the "
             "process CPU seconds per rank spent in the loop, which time-slicing by other "
             "processes does not inflate; ratios come from configurations interleaved in this "
             "one invocation")
    L.append("")

    # 1. throughput
    L.append("## 1. Throughput (quadratic gradient, alpha 1, gamma 1)")
    L.append("")
    L.append("| case | particles | ranks | steps | loop time [s] | particle-steps/s (wall) "
             "| per core (wall) | CPU time/rank [s] | per CPU-second | Pair % | Comm % "
             "| CPU use % | speed-up vs 1 rank (wall) |")
    L.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for dim in (2, 3):
        base = by[f"{dim}d-np1"].best()
        for key in (f"{dim}d-np1", f"{dim}d-np2"):
            c = by[key]
            b = c.best()
            if not b:
                L.append(f"| {dim}D block | {c.natoms} | {c.np} | {c.nsteps} | failed "
                         "| | | | | | | | |")
                continue
            rate = c.rate(b["loop"])
            cpu_s = c.best_cpu()
            cpu_rate = c.rate(cpu_s * c.np) if cpu_s else None
            su = (base["loop"] / b["loop"]) if base else None
            su_s = f"{su:.2f} (efficiency {100 * su / c.np:.0f} %)" if su else "n/a"
            cpu = b["cpu"] if b["cpu"] is not None else "?"
            L.append(f"| {dim}D block | {c.natoms} | {c.np} | {b['steps']} | {b['loop']:.3f} "
                     f"| {fmt_rate(rate)} | {fmt_rate(rate / c.np)} "
                     f"| {f'{cpu_s:.3f}' if cpu_s else 'n/a'} | {fmt_rate(cpu_rate)} "
                     f"| {b['sect'].get('Pair', (0, 0))[1]:.1f} "
                     f"| {b['sect'].get('Comm', (0, 0))[1]:.1f} | {cpu} | {su_s} |")
    L.append("")
    L.append("Per CPU-second = particle-steps / (CPU time per rank x ranks): the throughput a "
             "dedicated core would give; with 2 ranks it includes MPI waiting (Open MPI polls, "
             "so waiting burns CPU). Pair/Comm % are LAMMPS's shares of the loop time "
             "(fastest repeat).")
    L.append("")

    # 2. cost of the terms
    L.append("## 2. Cost of the terms (1 rank; ratio = time / time of the full quadratic case "
             "of the same dimension, same invocation)")
    L.append("")
    L.append("| case | gradient | alpha | gamma | loop time [s] | wall ratio | CPU time [s] "
             "| CPU ratio | particle-steps per CPU-second | Pair % |")
    L.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    names = {"np1": "full", "linear": "linear gradient", "novisc": "no viscosity",
             "nohg": "no hourglass", "stress": "stress only"}
    for dim in (2, 3):
        basec = by[f"{dim}d-np1"]
        base, base_cpu = basec.best(), basec.best_cpu()
        for suffix in names:
            c = by[f"{dim}d-{suffix}"]
            b, cpu_s = c.best(), c.best_cpu()
            if not b:
                L.append(f"| {dim}D {names[suffix]} | {c.grad} | {c.alpha:g} | {c.gamma:g} "
                         "| failed | | | | | |")
                continue
            wr = f"{b['loop'] / base['loop']:.3f}" if base else "n/a"
            cr = f"{cpu_s / base_cpu:.3f}" if cpu_s and base_cpu else "n/a"
            L.append(f"| {dim}D {names[suffix]} | {c.grad} | {c.alpha:g} | {c.gamma:g} "
                     f"| {b['loop']:.3f} | {wr} | {f'{cpu_s:.3f}' if cpu_s else 'n/a'} | {cr} "
                     f"| {fmt_rate(c.rate(cpu_s))} | {b['sect'].get('Pair', (0, 0))[1]:.1f} |")
    L.append("")
    for dim in (2, 3):
        t = {s: by[f"{dim}d-{s}"].best_cpu() for s in names}
        if all(t.values()):
            full = t["np1"]
            L.append(f"- {dim}D (CPU time): viscosity {100 * (full - t['novisc']) / full:.0f} % "
                     f"of the full step, hourglass {100 * (full - t['nohg']) / full:.0f} %, both "
                     f"{100 * (full - t['stress']) / full:.0f} % (stress-only step = "
                     f"{100 * t['stress'] / full:.0f} %); the linear gradient takes "
                     f"{100 * t['linear'] / full:.0f} % of the quadratic step")
    L.append("")

    # 3. memory
    L.append("## 3. Memory per particle")
    L.append("")
    L.append("\"LAMMPS line\": the \"Per MPI rank memory allocation\" of the timed run (avg x "
             "ranks / particles). The split comes from LAMMPS's own accounting, read from a "
             "serial instance after a short run (bench/memprobe.cpp: `pair->memory_usage()`, "
             "the bond fix's `memory_usage()`, `atom->memory_usage()`). Per-atom arrays are "
             "sized by `atom->nmax`, which LAMMPS grows in chunks, hence above the particle "
             "count; \"bond cache (min.)\" is entries x the bytes per bond of the lean layout, without the "
             "headroom the pair keeps.")
    L.append("")
    L.append("| case | particles | LAMMPS line, 1 rank [MB] | bytes/particle (1 rank) "
             "| bytes/particle (2 ranks) | pair style | of it bond cache (min.) "
             "| bond fix (partners) | atom arrays | atom->nmax |")
    L.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for dim in (2, 3):
        for grad in ("quadratic", "linear"):
            key = f"{dim}d-np1" if grad == "quadratic" else f"{dim}d-linear"
            c = by[key]
            b = c.best()
            b2 = by[f"{dim}d-np2"].best() if grad == "quadratic" else None
            line1 = b["mem"][1] if b and b.get("mem") else None
            per1 = line1 * 1024 * 1024 / c.natoms if line1 else None
            per2 = (b2["mem"][1] * b2["np"] * 1024 * 1024 / c.natoms
                    if b2 and b2.get("mem") else None)
            pr, why = probes.get((dim, grad), (None, "not run"))
            if pr:
                N = pr["nlocal"]
                cache_min = pr["nbonds"] * pr["sizeof_bond"] / N
                cols = (f"{pr['pair'] / N:.0f} | {cache_min:.0f} ({pr['nbonds'] / N:.1f} bonds "
                        f"x {pr['sizeof_bond']:.0f} B) | {pr['bondfix'] / N:.0f} | "
                        f"{pr['atom'] / N:.0f} | {pr['nmax']:.0f}")
            else:
                cols = f"n/a ({why}) | | | |"
            L.append(f"| {dim}D {grad} | {c.natoms} | "
                     f"{f'{line1:.1f}' if line1 else 'n/a'} | "
                     f"{f'{per1:.0f}' if per1 else 'n/a'} | "
                     f"{f'{per2:.0f}' if per2 else '-'} | {cols} |")
    L.append("")

    # 4. quoted figures
    L.append("## 4. For scale: figures QUOTED from the issue, not measured here")
    L.append("")
    L.append("LAMMPS MACHDYN (`pair_style smd/tlsph`, same kernel support, linear elastic) is "
             "not installed on this machine, so it was not run: its figures are the ones stated "
             "in the issue (\"measured on these machines\"), as are the targets. Only the "
             "tlsph rows were measured by this harness (1 rank, full quadratic case).")
    L.append("")
    L.append("| per core, particle-steps/s | 2D | 3D |")
    L.append("|---|---:|---:|")
    wall, cpu = {}, {}
    for dim in (2, 3):
        c = by[f"{dim}d-np1"]
        b = c.best()
        wall[dim] = c.rate(b["loop"]) if b else None
        cpu[dim] = c.rate(c.best_cpu())
    L.append(f"| tlsph, measured here, wall clock (1 rank) | {fmt_rate(wall[2])} "
             f"| {fmt_rate(wall[3])} |")
    L.append(f"| tlsph, measured here, per CPU-second (1 rank) | {fmt_rate(cpu[2])} "
             f"| {fmt_rate(cpu[3])} |")
    L.append(f"| MACHDYN smd/tlsph (QUOTED, not measured here) | "
             f"{fmt_rate(QUOTED['machdyn'][2])} | {fmt_rate(QUOTED['machdyn'][3])} |")
    L.append(f"| target (QUOTED from the issue) | {fmt_rate(QUOTED['target'][2])} | "
             f"{fmt_rate(QUOTED['target'][3])} |")

    def r(x, y):
        return f"{x / y:.2f}x" if x and y else "n/a"
    L.append(f"| tlsph (per CPU-second) / quoted MACHDYN | {r(cpu[2], QUOTED['machdyn'][2])} | "
             f"{r(cpu[3], QUOTED['machdyn'][3])} |")
    L.append(f"| tlsph (per CPU-second) / target | {r(cpu[2], QUOTED['target'][2])} | "
             f"{r(cpu[3], QUOTED['target'][3])} |")
    L.append("")

    # 5. orthotropic law
    L.append("## 5. Cost of the orthotropic law (1 rank, the blocks of section 1)")
    L.append("")
    L.append("The same steel block, its material given once as isotropic (E, nu) and once as an "
             "orthotropic ply with the same constants (E1 = E2 = E3, G = E/2(1+nu)) at theta = "
             "30 deg: the motion is the same, only the law's cost differs (6x6 stiffness "
             "instead of two Lame constants, every particle testing its type's law).")
    L.append("")
    L.append("| case | loop time [s] | CPU time [s] | particle-steps per CPU-second "
             "| extra cost (wall) | extra cost (CPU) |")
    L.append("|---|---:|---:|---:|---:|---:|")
    for dim in (2, 3):
        ref_c, c = by[f"{dim}d-np1"], by[f"{dim}d-ortho"]
        b, rb = c.best(), ref_c.best()
        cpu_s, rcpu = c.best_cpu(), ref_c.best_cpu()
        if not b or not rb:
            L.append(f"| {dim}D orthotropic | failed | | | | |")
            continue
        L.append(f"| {dim}D isotropic | {rb['loop']:.3f} | {f'{rcpu:.3f}' if rcpu else 'n/a'} "
                 f"| {fmt_rate(ref_c.rate(rcpu))} | - | - |")
        L.append(f"| {dim}D orthotropic | {b['loop']:.3f} | {f'{cpu_s:.3f}' if cpu_s else 'n/a'} "
                 f"| {fmt_rate(c.rate(cpu_s))} | {100 * (b['loop'] / rb['loop'] - 1):+.1f} % "
                 f"| {(f'{100 * (cpu_s / rcpu - 1):+.1f} %') if cpu_s and rcpu else 'n/a'} |")
    L.append("")

    # 6. damage
    L.append("## 6. Cost of the damage machinery (crack-branching plate, bench/in.branching)")
    L.append("")
    L.append("The plate of examples/crack-branching (36,000 particles, dx = 0.333 mm, 1 MPa "
             "traction) without output: `tlsph/damage` with its pre-crack, fix "
             "tlsph/velocity/filter and the damage compute, beside `tlsph` on the same "
             "particles (no pre-crack, no filter). Timed: steps "
             f"{a.nwarm}-{a.nwarm + a.steps_branch} (the deck's dt ~ 35 ns: 0-40 us covers "
             "initiation, ~15 us, and 25 us of propagation). Extra cost = damage / tlsph - 1, "
             "same ranks, same invocation.")
    L.append("")
    L.append("| case | ranks | steps | loop time [s] | particle-steps/s (wall) | CPU time/rank [s] "
             "| per CPU-second | extra cost (wall) | extra cost (CPU) |")
    L.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for np in (1, 2):
        ref = by[f"branch-tlsph-np{np}"]
        for key in (f"branch-tlsph-np{np}", f"branch-damage-np{np}"):
            c = by[key]
            b, cpu_s = c.best(), c.best_cpu()
            if not b:
                L.append(f"| {c.label()} | {np} | {c.nsteps} | failed | | | | | |")
                continue
            rb, rcpu = ref.best(), ref.best_cpu()
            ew = f"{100 * (b['loop'] / rb['loop'] - 1):+.0f} %" if rb and c is not ref else "-"
            ec = (f"{100 * (cpu_s / rcpu - 1):+.0f} %" if cpu_s and rcpu and c is not ref
                  else "-")
            L.append(f"| {c.label()} | {np} | {b['steps']} | {b['loop']:.3f} "
                     f"| {fmt_rate(c.rate(b['loop']))} | {f'{cpu_s:.3f}' if cpu_s else 'n/a'} "
                     f"| {fmt_rate(c.rate(cpu_s * np) if cpu_s else None)} | {ew} | {ec} |")
    L.append("")

    # raw repeats
    L.append("## Raw repeats: loop time [s] (CPU use %, 1-min load average after the run)")
    L.append("")
    L.append("| case | " + " | ".join(f"repeat {i + 1}" for i in range(a.repeat)) + " |")
    L.append("|---|" + "---:|" * a.repeat)
    for c in cases:
        cells = []
        for res in c.runs:
            if res.get("loop"):
                cells.append(f"{res['loop']:.3f} ({res.get('cpu', '?')} %, "
                             f"{res['load'].split()[0]})")
            else:
                cells.append("FAILED")
        L.append(f"| {c.key} ({c.label()}, {c.np} rank{'s' if c.np > 1 else ''}) | "
                 + " | ".join(cells) + " |")
    L.append("")
    errors = [(c.key, res["error"]) for c in cases for res in c.runs if res.get("error")]
    if errors:
        L.append("## Errors")
        L.append("")
        for key, e in errors:
            L.append(f"- {key}: ```{e}```")
        L.append("")
    return "\n".join(L), errors


# ----------------------------------------------------------------------------


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lmp", default=os.environ.get("LMP_TLSPH",
                                                   os.path.join(ROOT, "build", "lmp_tlsph")))
    ap.add_argument("--mpirun", default=os.environ.get("MPIRUN", "mpirun"))
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=None)
    ap.add_argument("--outdir", default=os.path.join(HERE, "out"))
    ap.add_argument("--out", default=os.path.join(HERE, "results.md"))
    ap.add_argument("--probe", default=None, help="bench/memprobe.so (optional)")
    ap.add_argument("--budget", type=float, default=float(os.environ.get("BENCH_BUDGET", 900)),
                    help="seconds; no new repeat is started that would end past it (0: off)")
    ap.add_argument("--n2", type=int, default=190)
    ap.add_argument("--n3", type=int, default=34)
    a = ap.parse_args()
    if a.quick:
        a.steps2, a.steps3, a.nwarm, a.steps_branch = 60, 10, 5, 100
        a.repeat = a.repeat or 1
    else:
        a.steps2, a.steps3, a.nwarm, a.steps_branch = 300, 50, 10, 1150
        a.repeat = a.repeat or 3
    os.makedirs(a.outdir, exist_ok=True)
    if not os.access(a.lmp, os.X_OK):
        sys.exit(f"bench: {a.lmp} not found or not executable (make build, or set LMP_TLSPH)")

    started = datetime.datetime.now().strftime("%Y-%m-%d %H:%M:%S %Z").strip()
    uptime_before = sh("uptime")
    print(f"bench: {uptime_before}", flush=True)
    t0 = time.time()

    # snapshot the binary (and the plugin the memory probe loads): the build
    # directory may be rebuilt while this runs, a snapshot keeps one build
    import shutil
    a.lmp_orig = a.lmp
    a.commit = sh(f"git -C {ROOT} rev-parse --short HEAD") or "?"
    a.dirty = sh(f"git -C {ROOT} status --porcelain -- src CMakeLists.txt launcher")
    # the newest commit older than the binary: what it was most likely built from
    a.built_after = sh(f"git -C {ROOT} log -1 --format=%h --before=@{int(os.path.getmtime(a.lmp))}")
    a.mtime0 = os.path.getmtime(a.lmp)
    snap = os.path.join(a.outdir, "lmp_tlsph.snapshot")
    shutil.copy2(a.lmp, snap)
    a.lmp = snap
    plugin = os.environ.get("TLSPH_PLUGIN") or os.path.join(os.path.dirname(a.lmp_orig),
                                                            "tlsphplugin.so")
    if os.path.exists(plugin):
        shutil.copy2(plugin, os.path.join(a.outdir, "tlsphplugin.snapshot.so"))
        os.environ["TLSPH_PLUGIN"] = os.path.join(a.outdir, "tlsphplugin.snapshot.so")
    cases = make_cases(a)
    a.cut = None
    for rep in range(a.repeat):
        # keep the whole run inside the time budget: skip a repeat that, at
        # the pace of the previous ones, would end past it (plus the probes)
        elapsed = time.time() - t0
        if rep > 0 and a.budget > 0 and elapsed * (rep + 1) / rep + 15 > a.budget:
            a.cut = (rep, a.repeat)
            print(f"bench: stopping after {rep} repeat(s): another would pass the "
                  f"{a.budget:.0f} s budget (BENCH_BUDGET)", flush=True)
            a.repeat = rep
            break
        for c in cases:
            res = run_case(c, a, rep)
            c.runs.append(res)
            if res.get("loop"):
                rate = c.natoms * res["steps"] / res["loop"]
                print(f"bench: repeat {rep + 1}/{a.repeat} {c.key:12s} loop {res['loop']:8.3f} s "
                      f"{rate / 1e6:7.3f} M particle-steps/s  cpu {res['cpu']}%  "
                      f"load {res['load']}", flush=True)
            else:
                print(f"bench: repeat {rep + 1}/{a.repeat} {c.key:12s} FAILED: "
                      f"{res.get('error', '')}", flush=True)

    probes = {}
    for dim, n in ((2, a.n2), (3, a.n3)):
        for grad in ("quadratic", "linear"):
            probes[(dim, grad)] = memory_probe(a, dim, n, grad)
            pr, why = probes[(dim, grad)]
            print(f"bench: memory probe {dim}D {grad}: "
                  + (f"pair {pr['pair'] / pr['nlocal']:.0f} B/particle" if pr else why),
                  flush=True)

    finished = datetime.datetime.now().strftime("%Y-%m-%d %H:%M:%S")
    uptime_after = sh("uptime")
    text, errors = report(a, cases, probes, started, finished, uptime_before, uptime_after,
                          time.time() - t0)
    with open(a.out, "w") as f:
        f.write(text + "\n")
    print()
    print(text)
    print(f"bench: report written to {a.out}; logs in {a.outdir}")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
