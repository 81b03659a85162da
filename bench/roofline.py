#!/usr/bin/env python3
"""Roofline of the TLSPH step from the measurements of bench/roofline.sh.

    roofline.py --out bench/out/roofline --doc doc

Flops and bytes per particle-step of each pass are counted from the source
(src/USER-TLSPH/tlsph_particle.h, pair_tlsph.cpp, pair_tlsph_step.h) for the
production path (newton on: the stress term scattered, the viscous and
hourglass pair forces computed once per pair by the leading end, compact
packed rows), with the bonds per particle of the benchmark block counted
exactly (the lattice offsets within the support 2h = 2.66 dx, clipped by the
block's faces). Conventions: a multiply, an add or a divide is one flop, a
fused multiply-add two; a byte is counted once per pass for every per-particle
array the pass reads or writes (the partners' rows are reused from the
cache: a particle's row is read by all its ~20 / ~80 partners in a
spatially sorted order), and once per bond for the streamed bond arrays;
writes are counted once (STREAM's convention). The counts are estimates
to about +-15 %; the conclusions below do not depend on that margin.
"""

import argparse
import datetime
import itertools
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from machine import commit, cpu_model  # noqa: E402


def bonds_per_particle(dim, n, support=2.66):
    """mean number of partners within `support` (in dx) of an n^dim lattice block"""
    r = int(support) + 1
    total = 0
    for off in itertools.product(range(-r, r + 1), repeat=dim):
        if not any(off) or sum(o * o for o in off) >= support * support:
            continue
        pairs = 1
        for o in off:
            pairs *= max(n - abs(o), 0)
        total += pairs
    return total / n ** dim


def counts(dim, nb):
    """flops and bytes per particle-step of the two passes, quadratic
    gradient, viscosity and hourglass on, newton on (see module doc)"""
    D = dim
    lead = nb / 2.0                    # each pair computed once, by its leading end
    row = 8 * (2 * D * D + 1)          # compact packed row: F, K, alpha
    # deformation pass, per bond: X = x0c_j - x0c_i (D), du = (x_j - x_i) - X
    # (2D), F += du (x) g (D^2 FMA)
    fl_def_bond = D + 2 * D + 2 * D * D
    # per particle: F = I + Fa (D^2), Green-Lagrange 3x3 (63), isotropic SVK
    # stress and energy (46), det (14), P = F S (54), F^-1 and K = J F^-T (46),
    # fown = V P sum g (3 D^2); 3x3 algebra also in 2D
    fl_def_part = D * D + 63 + 46 + 14 + 54 + 46 + 3 * D * D
    by_def_bond = 4 + 8 * D            # partner index, g_ij
    # nbond, bond start, x_i, x0c_i, vfrac, type, sumg (read); F, P, psi,
    # packed row, fown (written)
    by_def_part = 4 + 4 + 24 + 24 + 8 + 4 + 24 + 72 + 72 + 8 + row + 24
    # force pass, every bond: t = V_i P_i g_ij (D^2 FMA + D), f_j -= t (D)
    fl_frc_bond = 2 * D * D + 2 * D
    # leading bonds: X (D), separation, r2, 1/(r2 (r2 + eps2)) (3D + 3),
    # viscous coefficient (3D + 17), (K_i + K_j) X (3 D^2) and its tallies (2D),
    # hourglass coefficient (3 D^2 + 3D + 9), its force and tallies (2D), the
    # partner's share f_j, f_hg_j, f_visc_j (4D)
    fl_frc_lead = D + (3 * D + 3) + (3 * D + 17) + (3 * D * D + 2 * D) + \
        (3 * D * D + 3 * D + 9) + 2 * D + 4 * D
    fl_frc_part = 20                   # own force, material averages, tallies
    by_frc_bond = 4 + 8 * D
    by_frc_lead = 16                   # the two kernel weights (viscous, hourglass)
    # f_hg, f_visc (zeroed, then updated), f (read, written), fown, P_i, the
    # packed row, x, v, x0c, vfrac, type, nbond, nlead, bond start
    by_frc_part = 144 + 48 + 24 + 72 + row + 24 + 24 + 24 + 8 + 4 + 4 + 4 + 4
    return {
        "deformation": {"flops": nb * fl_def_bond + fl_def_part,
                        "bytes": nb * by_def_bond + by_def_part},
        "forces": {"flops": nb * fl_frc_bond + lead * fl_frc_lead + fl_frc_part,
                   "bytes": nb * by_frc_bond + lead * by_frc_lead + by_frc_part},
    }


def simd_counts(dim, nb, own):
    """flops and bytes per particle-step of the two passes of the SIMD step
    (tlsph_ell_vec.h: ell_deformation_stencil with ell_stress_lanes, and
    ell_force_stencil; quadratic gradient, viscosity and hourglass on, one
    material). own: the fraction of particles whose chunk streams its own
    bond blocks (the others read a shared pattern, from the cache, and
    stream no bond data). Same conventions as counts(); the partners'
    columns are reused from the cache, the particles' own columns and the
    per-atom arrays the passes write by LAMMPS index are streamed."""
    D = dim
    NB = 5 if D == 2 else 9            # quadratic basis
    lead = nb / 2.0                    # pair forces once per bond, by the earlier end
    packed = 2 * D * D + 1 + D * NB    # F, K, alpha, R = V P Q
    # deformation, per bond: dx, X, du (3D), F += du (x) g (D^2 FMA)
    fl_def_bond = 3 * D + 2 * D * D
    # per particle: F = I + Fa, Green-Lagrange, SVK stress and energy, det, P = F S,
    # F^-1 and K = J F^-T (as counts()), R = V P Q (D NB (D FMA + 1)), V P s (3 D^2)
    fl_def_part = D * D + 63 + 46 + 14 + 54 + 46 + D * NB * (2 * D + 1) + 3 * D * D
    by_def_bond = own * (4 + 8 * D)    # partner index (one int per lane and slot), g
    # own columns x, x0 (read), Q, s, V (read), packed row and V P s (written),
    # the per-atom F, P, psi, e_hg, fown (written, by LAMMPS index)
    by_def_part = 8 * (2 * D + D * NB + D + 1) + 8 * (packed + D) + 8 * (9 + 9 + 1 + 1 + 3)
    # forces, every bond (the stress term gathered): s = (X_i - X_j)/h (2D), the
    # basis (NB - D products), R_j p (D NB FMA), a -= c_ij (...) (2D)
    fl_frc_bond = 2 * D + (NB - D) + 2 * D * NB + 2 * D
    # once per bond: as counts() (the same pair terms), plus the partner's
    # accumulators (2D subtractions)
    fl_frc_lead = D + (3 * D + 3) + (3 * D + 17) + (3 * D * D + 2 * D) + \
        (3 * D * D + 3 * D + 9) + 2 * D + 2 * D
    fl_frc_part = 6 * D                # the sums into f, f_hg, f_visc
    by_frc_bond = own * (4 + 8)        # partner index, c_ij
    by_frc_lead = own * 16             # the viscous and hourglass weights
    # own columns x, v, x0, F, K, alpha, V, V P s, the accumulators (zeroed,
    # read); f (read, written), f_hg, f_visc (written), the type
    by_frc_part = 8 * (3 * D + 2 * D * D + 1 + 1 + D + 2 * 2 * D) + 48 + 24 + 24 + 4
    return {
        "deformation": {"flops": nb * fl_def_bond + fl_def_part,
                        "bytes": nb * by_def_bond + by_def_part},
        "forces": {"flops": nb * fl_frc_bond + lead * fl_frc_lead + fl_frc_part,
                   "bytes": nb * by_frc_bond + lead * by_frc_lead + by_frc_part},
    }


def simd_own_fraction(log):
    """the fraction of particles that stream their own bond blocks, from the
    SIMD step's line in the log: those with bonds of their own less those
    that read the blocks of a translated copy (523b015: the same end of
    another row; a few owners' blocks, read again and again, from the
    cache, like a pattern)"""
    m = re.search(r"SIMD step \((\w+), up to \d+ lanes\): (\d+) particles in \d+ chunks; (\d+) read "
                  r"their bonds from \d+ shared pattern\(s\), (\d+) their own"
                  r"(?: \(\d+ of them alone in a chunk; (\d+) from the blocks of a translated copy\))?",
                  open(log).read())
    if not m:
        return None, None
    shared = int(m.group(5)) if m.group(5) else 0
    return m.group(1), (int(m.group(4)) - shared) / int(m.group(2))


def read_kv(path):
    out = {}
    with open(path) as f:
        for line in f:
            k, v = line.split()
            out[k] = float(v)
    return out


PERF_HZ = 2000.0    # perf record -F of roofline.sh (cpu-clock: one sample per 0.5 ms of CPU)


def perf_samples(path, is_dfm, is_frc):
    """CPU seconds of the deformation and force passes (the symbols the two
    predicates pick) and of the whole process, from a perf report with
    sample counts"""
    dfm = frc = tot = 0
    with open(path) as f:
        for line in f:
            m = re.match(r"\s*[0-9.]+%\s+(\d+)\s+\[(.)\]\s+(.*)", line)
            if not m:
                continue
            n, sym = int(m.group(1)), m.group(3)
            tot += n
            if is_dfm(sym):
                dfm += n
            elif is_frc(sym):
                frc += n
    return dfm / PERF_HZ, frc / PERF_HZ, tot / PERF_HZ


def perf_pass_seconds(path):
    """the scalar step's passes (all their template variants)"""
    return perf_samples(path, lambda s: "compute_deformation" in s or "particle_stress" in s,
                        lambda s: "particle_force_bonds" in s or "compute_forces" in s)


def perf_simd_seconds(path):
    """the SIMD step's passes (the ell_* kernels)"""
    return perf_samples(path, lambda s: "ell_" in s and "::deformation<" in s,
                        lambda s: "ell_" in s and "::forces<" in s)[:2]


def loop_info(log):
    with open(log) as f:
        text = f.read()
    loops = re.findall(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms",
                       text)
    t, steps, n = loops[-1]
    cpu = re.findall(r"([0-9.]+)% CPU use", text)
    allsteps = sum(int(x[1]) for x in loops)
    return float(t), int(steps), int(n), float(cpu[-1]) / 100 if cpu else 1.0, allsteps


def callgrind_pass(path):
    """inclusive instructions of the two passes in a callgrind_annotate listing"""
    dfm = frc = 0
    with open(path) as f:
        for line in f:
            m = re.match(r"\s*([0-9,]+)\s", line)
            if not m:
                continue
            ir = int(m.group(1).replace(",", ""))
            if "compute_deformation<" in line:
                dfm += ir
            elif "compute_forces<" in line:
                frc += ir
    return dfm, frc


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=os.path.join(HERE, "out", "roofline"))
    ap.add_argument("--doc", default=os.path.join(ROOT, "doc"))
    a = ap.parse_args()
    c = read_kv(os.path.join(a.out, "ceilings.txt"))
    bw, bw3 = c["triad_gb_per_s"], c["triad_l3_gb_per_s"]
    peak_s, peak_v = c["scalar_gflops"], c.get("avx2_fma_gflops", float("nan"))
    # clock estimate: Zen 3 (and most AVX2 cores) retire two 256-bit FMAs per cycle
    ghz = peak_v / 16.0

    rows = []
    for dim, n in ((2, 190), (3, 34)):
        nb = bonds_per_particle(dim, n)
        cnt = counts(dim, nb)
        with open(os.path.join(a.out, f"perf-{dim}.steps")) as f:
            p1, p2 = (int(x) for x in f.read().split())
        t, steps, natoms, cpu_use, _ = loop_info(os.path.join(a.out, f"perf-{dim}-{p2}.log"))
        rate = natoms * steps / t                       # particle-steps per second, timed loop
        # CPU time of a pass per particle-step: the difference of the samples of
        # two runs that differ only in the number of timed steps (set-up and
        # warm-up cancel)
        d1, f1, _ = perf_pass_seconds(os.path.join(a.out, f"perf-{dim}-{p1}.txt"))
        d2, f2, _ = perf_pass_seconds(os.path.join(a.out, f"perf-{dim}-{p2}.txt"))
        dfm, frc = d2 - d1, f2 - f1
        npass = natoms * (p2 - p1)
        with open(os.path.join(a.out, f"cg-{dim}.steps")) as f:
            n1, n2, ncg = (int(x) for x in f.read().split())
        d1, f1 = callgrind_pass(os.path.join(a.out, f"cg-{dim}-{n1}.txt"))
        d2, f2 = callgrind_pass(os.path.join(a.out, f"cg-{dim}-{n2}.txt"))
        ncg_atoms = ncg ** dim
        ins = {"deformation": (d2 - d1) / (n2 - n1) / ncg_atoms,
               "forces": (f2 - f1) / (n2 - n1) / ncg_atoms}
        pass_ns = {"deformation": 1e9 * dfm / npass, "forces": 1e9 * frc / npass}
        for pas in ("deformation", "forces"):
            fl, by = cnt[pas]["flops"], cnt[pas]["bytes"]
            ns = pass_ns[pas]
            ai = fl / by
            bound_s = max(fl / peak_s, by / bw)        # ns: scalar code from DRAM
            bound_v = max(fl / peak_v, by / bw)        # ns: perfect SIMD from DRAM
            rows.append({"dim": dim, "pass": pas, "nb": nb, "flops": fl, "bytes": by, "ai": ai,
                         "ns": ns, "gflops": fl / ns, "gbs": by / ns, "bound_s": bound_s,
                         "bound_v": bound_v, "ins": ins[pas], "ipc": ins[pas] / (ns * ghz),
                         "rate": rate})
    # the SIMD step (roofline.sh, 2b)
    peak_512 = c.get("avx512_fma_gflops", float("nan"))
    srows = []
    for dim, n in ((2, 190), (3, 34)):
        fn = os.path.join(a.out, f"perf-simd-{dim}.steps")
        if not os.path.exists(fn):
            continue
        nb = bonds_per_particle(dim, n)
        with open(fn) as f:
            p1, p2 = (int(x) for x in f.read().split())
        log2 = os.path.join(a.out, f"perf-simd-{dim}-{p2}.log")
        isa, own = simd_own_fraction(log2)
        if own is None:
            continue
        cnt = simd_counts(dim, nb, own)
        t, steps, natoms, _, _ = loop_info(log2)
        rate = natoms * steps / t
        d1, f1 = perf_simd_seconds(os.path.join(a.out, f"perf-simd-{dim}-{p1}.txt"))
        d2, f2 = perf_simd_seconds(os.path.join(a.out, f"perf-simd-{dim}-{p2}.txt"))
        npass = natoms * (p2 - p1)
        pass_ns = {"deformation": 1e9 * (d2 - d1) / npass, "forces": 1e9 * (f2 - f1) / npass}
        peak = peak_512 if isa == "avx512" else peak_v
        for pas in ("deformation", "forces"):
            fl, by = cnt[pas]["flops"], cnt[pas]["bytes"]
            ns = pass_ns[pas]
            srows.append({"dim": dim, "pass": pas, "nb": nb, "own": own, "isa": isa, "flops": fl,
                          "bytes": by, "ai": fl / by, "ns": ns, "gflops": fl / ns, "gbs": by / ns,
                          "bound": max(fl / peak, by / bw), "bound_f": fl / peak, "bound_m": by / bw,
                          "rate": rate, "peak": peak})
    # ------------------------------------------------------------ report
    try:    # the commit the measurements were made with (roofline.sh writes it)
        with open(os.path.join(a.out, "commit.txt")) as f:
            run_commit = f.read().strip()
    except OSError:
        run_commit = commit()
    stamp = (f"commit {run_commit}, {cpu_model()}, {os.cpu_count()} cores (shared), "
             f"{datetime.date.today().isoformat()}")
    md = ["# Roofline of the TLSPH step (generated by bench/roofline.sh, bench/roofline.py)", "",
          f"Measured: {stamp}; 1 rank, bench/in.bench blocks (2D 190 x 190, 3D 34^3 particles, "
          "steel, dx = 1 mm, h = 1.33 dx, quadratic gradient, alpha 1, gamma 1, newton on).", "",
          "## Ceilings of one core (bench/roofline.cpp)", "",
          "| ceiling | value |", "|---|---:|",
          f"| STREAM-like triad, arrays of {c['triad_array_mib']:.0f} MiB (DRAM) | {bw:.1f} GB/s |",
          f"| the same triad in the last-level cache (3 x 2 MiB) | {bw3:.1f} GB/s |",
          f"| scalar multiply-add peak (SSE2 code, as the package is built) | {peak_s:.1f} GFLOP/s |",
          f"| AVX2 FMA peak (256-bit, two pipes) | {peak_v:.1f} GFLOP/s |",
          (f"| AVX-512 FMA peak (512-bit) | {peak_512:.1f} GFLOP/s |" if peak_512 == peak_512
           else "| AVX-512 FMA peak (512-bit) | - (no AVX-512 on this CPU) |"),
          f"| clock inferred from the FMA peak (16 flops per cycle) | {ghz:.2f} GHz |", "",
          "## The scalar step (simd no) against the ceilings", "",
          "Flops and bytes per particle-step counted from the source (bench/roofline.py: "
          "conventions, +-15 %); time per particle-step of a pass = its CPU time in the perf "
          "samples (perf, cpu-clock at 2 kHz), the difference of two run lengths; instructions per particle-step of a pass from "
          "callgrind (inclusive, the difference of two run lengths); IPC = instructions / "
          "(time x inferred clock). Bound = max(flops / peak, bytes / DRAM bandwidth): "
          "the shortest time this pass could take on this core, for scalar code and for "
          "perfectly vectorised code.", "",
          "| case | pass | bonds/particle | flops | bytes | flop/byte | measured ns | GFLOP/s | "
          "GB/s | instructions | IPC | bound, scalar [ns] | bound, AVX2 [ns] | measured / bound (scalar) |",
          "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        md.append(f"| {r['dim']}D | {r['pass']} | {r['nb']:.1f} | {r['flops']:.0f} | "
                  f"{r['bytes']:.0f} | {r['ai']:.2f} | {r['ns']:.0f} | {r['gflops']:.2f} | "
                  f"{r['gbs']:.2f} | {r['ins']:.0f} | {r['ipc']:.2f} | {r['bound_s']:.0f} | "
                  f"{r['bound_v']:.0f} | {r['ns'] / r['bound_s']:.1f}x |")
    md.append("")
    for dim in (2, 3):
        rs = [r for r in rows if r["dim"] == dim]
        step = 1e9 / rs[0]["rate"]
        bs = sum(r["bound_s"] for r in rs)
        bv = sum(r["bound_v"] for r in rs)
        passes = sum(r["ns"] for r in rs)
        md.append(f"- {dim}D: measured {rs[0]['rate'] / 1e6:.2f} M particle-steps/s ({step:.0f} ns "
                  f"per particle-step, the two passes {passes:.0f} ns = "
                  f"{100 * passes / step:.0f} %); the two passes' bound {bs:.0f} ns (scalar) / "
                  f"{bv:.0f} ns (AVX2), i.e. at most {1e3 / bs:.1f} / {1e3 / bv:.1f} M "
                  "particle-steps/s from the passes alone, before integration and communication.")
    md.append("")
    if srows:
        md += ["## The SIMD step (the default) against the ceilings", "",
               "The same blocks with the SIMD step (tlsph_ell.h, tlsph_ell_vec.h; the kernels of "
               "the instruction set named, chosen at run time). Flops and bytes per particle-step "
               "counted from its kernels (bench/roofline.py, simd_counts: the same conventions; the "
               "flops are those of the scalar math plus R = V P Q and the gathered stress term, "
               "each bond's stress term computed at both ends, its pair forces at one); bytes: "
               "only the particles whose chunk has its own bond blocks stream bond data (the "
               "others read one pattern shared by the whole lattice interior, or the blocks of a "
               "translated copy, from the cache; 'own bond blocks' counts the rest), "
               "and every particle streams its own columns and the per-atom arrays the passes "
               "write. Time per pass: the perf samples of the ell_* kernels, the difference of two "
               "run lengths. Bound = max(flops / the kernels' FMA peak, bytes / DRAM bandwidth).",
               "",
               "| case | kernels | pass | bonds/particle | own bond blocks | flops | bytes | flop/byte | "
               "measured ns | GFLOP/s | GB/s | bound: flops [ns] | bound: bytes [ns] | measured / bound |",
               "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
        for r in srows:
            md.append(f"| {r['dim']}D | {r['isa']} | {r['pass']} | {r['nb']:.1f} | {100 * r['own']:.0f} % | "
                      f"{r['flops']:.0f} | {r['bytes']:.0f} | {r['ai']:.2f} | {r['ns']:.1f} | "
                      f"{r['gflops']:.2f} | {r['gbs']:.2f} | {r['bound_f']:.1f} | {r['bound_m']:.1f} | "
                      f"{r['ns'] / r['bound']:.1f}x |")
        md.append("")
        for dim in (2, 3):
            rs = [r for r in srows if r["dim"] == dim]
            if not rs:
                continue
            step = 1e9 / rs[0]["rate"]
            b = sum(r["bound"] for r in rs)
            passes = sum(r["ns"] for r in rs)
            md.append(f"- {dim}D, SIMD step: measured {rs[0]['rate'] / 1e6:.2f} M particle-steps/s "
                      f"({step:.0f} ns per particle-step, the two passes {passes:.0f} ns = "
                      f"{100 * passes / step:.0f} %); the two passes' bound {b:.0f} ns, i.e. at most "
                      f"{1e3 / b:.1f} M particle-steps/s from the passes alone; the passes run at "
                      f"{passes / b:.1f}x their bound.")
        md.append("")
    with open(os.path.join(a.doc, "roofline.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))

    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    ais = [0.05 * 1.05 ** k for k in range(160)]       # dense: the roof has a kink
    ax.plot(ais, [min(peak_v, x * bw) for x in ais], "k-", lw=1.2, label=f"DRAM triad {bw:.1f} GB/s")
    ax.plot(ais, [min(peak_v, x * bw3) for x in ais], "k--", lw=0.8,
            label=f"L3 triad {bw3:.1f} GB/s")
    ax.axhline(peak_v, color="C3", lw=1, label=f"AVX2 FMA peak {peak_v:.0f} GFLOP/s")
    ax.axhline(peak_s, color="C1", lw=1, label=f"scalar peak {peak_s:.1f} GFLOP/s")
    for r in rows:
        ax.plot(r["ai"], r["gflops"], "o" if r["pass"] == "forces" else "s", ms=8,
                color="C0" if r["dim"] == 2 else "C2",
                label=f"{r['dim']}D {r['pass']} ({r['gflops']:.2f} GFLOP/s, IPC {r['ipc']:.1f})")
    for r in srows:
        ax.plot(r["ai"], r["gflops"], "^" if r["pass"] == "forces" else "v", ms=8,
                color="C4" if r["dim"] == 2 else "C5",
                label=f"{r['dim']}D {r['pass']}, SIMD step ({r['gflops']:.2f} GFLOP/s)")
    if peak_512 == peak_512:
        ax.axhline(peak_512, color="C6", lw=1, label=f"AVX-512 FMA peak {peak_512:.0f} GFLOP/s")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(0.1, 30)
    ax.set_ylim(0.3, 200)
    ax.set_xlabel("arithmetic intensity [flop / byte]")
    ax.set_ylabel("GFLOP/s (one core)")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
    ax.set_title(f"TLSPH step passes on one core\n({stamp})", fontsize=7.5)
    fig.tight_layout()
    fig.savefig(os.path.join(a.doc, "roofline.png"), dpi=110)


if __name__ == "__main__":
    main()
