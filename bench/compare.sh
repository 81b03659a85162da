#!/usr/bin/env bash
# Side by side (doc/bench.md, "Side by side"): our styles, loaded with
# `plugin load`, and MACHDYN's smd/tlsph, run by ONE LAMMPS binary (built from
# the same Debian source with PLUGIN, PERI and MACHDYN, cached:
# scripts/build-lammps-plugin.sh bench), on the same particles
# (bench/in.compare), alternating, COMPARE_REPEAT (3) repeats, medians.
# Writes bench/compare.md and prints it.
#   bash bench/compare.sh          (make bench-compare)
#   COMPARE_QUICK=1 bash bench/compare.sh   smoke: small blocks, 1 repeat
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(dirname "$HERE")"
PLUGIN="${TLSPH_PLUGIN:-$ROOT/build/tlsphplugin.so}"
[ -f "$PLUGIN" ] || { echo "compare: $PLUGIN not found: run 'make build' first" >&2; exit 1; }
LMP=$(bash "$ROOT/scripts/build-lammps-plugin.sh" bench | tail -n1)
# the compile flags of both sides, read back from their build.ninja files (the
# FLAGS of the file that holds each code's pair style): the optimisation
# options (-O*, -f*, -m*, -g*, -DNDEBUG) must be the same, else no comparison
flags_in() {    # build.ninja source-file-name
  awk -v f="$2" 'index($0, "build ") == 1 && index($0, "/" f ".o:") {s=1} s && /^  FLAGS = /{sub(/^  FLAGS = /, ""); print; exit}' "$1"
}
opt_of() { tr ' ' '\n' <<<"$1" | grep -E '^-(O|f|m|g)|^-DNDEBUG$' | grep -v '^-fPIC$' | tr '\n' ' ' | sed 's/ $//'; }
OURS_NINJA="$(dirname "$PLUGIN")/build.ninja"
LMP_NINJA="$(dirname "$(dirname "$LMP")")/build/build.ninja"
OURS_FLAGS=$(flags_in "$OURS_NINJA" pair_tlsph.cpp)
LMP_FLAGS=$(flags_in "$LMP_NINJA" pair_smd_tlsph.cpp)
[ -n "$OURS_FLAGS" ] && [ -n "$LMP_FLAGS" ] ||
  { echo "compare: cannot read the compile flags from $OURS_NINJA and $LMP_NINJA" >&2; exit 1; }
if [ "$(opt_of "$OURS_FLAGS")" != "$(opt_of "$LMP_FLAGS")" ]; then
  echo "compare: the plugin is compiled with '$(opt_of "$OURS_FLAGS")', the LAMMPS with '$(opt_of "$LMP_FLAGS")': not a fair comparison (scripts/build-lammps-plugin.sh bench takes the plugin's flags; rebuild one of them)" >&2
  exit 1
fi
CXX_VER=$(g++ --version | head -1)
REPEAT=${COMPARE_REPEAT:-3}
if [ "${COMPARE_QUICK:-0}" != 0 ]; then n2=60 n3=14 s2=20 s3=5 REPEAT=1; else n2=190 n3=34 s2=200 s3=30; fi
OUT="$HERE/out/compare"; mkdir -p "$OUT"
# case: name dim n nsteps gradient codes
cases=("2D $n2 2 $s2 quadratic tlsph tlsph0 smd" "3D $n3 3 $s3 quadratic tlsph tlsph0 smd"
       "3D-damage $n3 3 $s3 linear tlsphd tlsph peri")
: > "$OUT/times.txt"
for r in $(seq "$REPEAT"); do
  for c in "${cases[@]}"; do
    set -- $c; name=$1 n=$2 dim=$3 ns=$4 grad=$5; shift 5
    for code in "$@"; do
      log="$OUT/$name-$code-$r.log"
      (cd "$OUT" && "$LMP" -in "$HERE/in.compare" -var code "$code" -var dim "$dim" -var n "$n" \
         -var nsteps "$ns" -var grad "$grad" -var plugin "$PLUGIN" -log none -echo none > "$log" 2>&1) ||
        { tail -5 "$log" >&2; echo "compare: $name $code failed (log $log)" >&2; exit 1; }
      t=$(grep "Loop time" "$log" | tail -1 | awk '{print $4}')
      natoms=$(grep "Loop time" "$log" | tail -1 | awk '{print $(NF-1)}')
      mem=$(grep "Per MPI rank memory" "$log" | tail -1 | awk '{print $(NF-1)}')
      # bonds per particle: peri/pmb's fix reports them; ours are the lattice
      # partners within the support 2h = 2.66 dx (counted in the report below)
      # partners per particle as each code reports them: peri/pmb's fix
      # ('bonds/atom'), smd/tlsph ('average # of neighbors/particle'), our
      # bond fix ('TLSPH bonds: N reference partners in total')
      nbond=$(sed -n 's/.*bonds\/atom = *\([0-9.]*\).*/\1/p' "$log" | tail -1)
      [ -n "$nbond" ] || nbond=$(sed -n 's/.*average # of neighbors\/particle in group tlsph = *\([0-9.e+-]*\).*/\1/p' "$log" | tail -1)
      if [ -z "$nbond" ]; then
        nb=$(sed -n 's/^TLSPH bonds: \([0-9]*\) reference partners.*/\1/p' "$log" | tail -1)
        [ -n "$nb" ] && nbond=$(awk -v a="$nb" -v b="$natoms" 'BEGIN{printf "%.3f", a / b}')
      fi
      # neighbor-list builds in the timed run (0 expected) and its CPU use
      nneigh=$(sed -n 's/^Neighbor list builds = *\([0-9]*\).*/\1/p' "$log" | tail -1)
      cpu=$(sed -n 's/^\([0-9.]*\)% CPU use.*/\1/p' "$log" | tail -1)
      echo "$name $code $r $natoms $ns $t $mem ${nbond:--} ${nneigh:--} ${cpu:--}" >> "$OUT/times.txt"
      echo "compare: $name $code repeat $r: $t s" >&2
    done
  done
done
# the instruction set of our SIMD step, as the plugin logged it
SIMD=$(sed -n 's/^pair tlsph: SIMD step (\([a-z0-9]*\),.*/\1/p' "$OUT"/2D-tlsph-1.log | head -1)
export COMPARE_SIMD="${SIMD:-none}"
/usr/bin/python3 - "$OUT/times.txt" "$HERE/compare.md" "$(git -C "$ROOT" describe --always --dirty 2>/dev/null || echo '?')" \
  "$OURS_FLAGS" "$LMP_FLAGS" "$CXX_VER" "$(opt_of "$OURS_FLAGS")" <<'PY'
import os, sys, statistics, collections, datetime, platform, subprocess
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
t = collections.defaultdict(list); meta = {}
nbonds = {}; nneigh = collections.defaultdict(set); cpuse = collections.defaultdict(list)
for name, code, r, natoms, ns, sec, mem, nb, nn, cpu in rows:
    t[(name, code)].append(float(sec)); meta[(name, code)] = (int(natoms), int(ns), float(mem))
    if nb != "-":
        nbonds[(name, code)] = float(nb)
    nneigh[(name, code)].add(nn)
    if cpu != "-":
        cpuse[(name, code)].append(float(cpu) / 100.0 * float(sec))
ours_flags, lmp_flags, cxx, opt = sys.argv[4:8]


def lattice_bonds(dim, natoms, support=2.66):
    """mean partners within `support` dx of an n^dim lattice block (our bonds)"""
    import itertools
    n = round(natoms ** (1.0 / dim))
    total = 0
    for off in itertools.product(range(-3, 4), repeat=dim):
        if any(off) and sum(o * o for o in off) < support * support:
            p = 1
            for o in off:
                p *= max(n - abs(o), 0)
            total += p
    return total / n ** dim
sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[2])))  # bench/
from machine import cpu_model  # noqa: E402
cpu = cpu_model()
label = {"tlsph": "tlsph (ours, plugin, SIMD step)", "tlsph0": "tlsph (ours, plugin, simd no)",
         "tlsphd": "tlsph/damage (ours, plugin, SIMD step)",
         "smd": "smd/tlsph (MACHDYN)", "peri": "peri/pmb (PERI, horizon 3.015 dx)"}
out = ["# Side by side: one LAMMPS binary, alternating runs", "",
       "(2D, 3D: our quadratic gradient; 3D-damage: the linear gradient, tlsph/damage's default, for both of our rows; "
       "peri/pmb: bond-based peridynamics on the same particles, c = 18 K / (pi delta^4), s00 0.01, no bond breaks; "
       "a bond evaluation = one partner visited per particle and step, our bonds from the lattice within 2.66 dx, "
       "peri/pmb's from its fix (it also walks a half list of ~55 partners for its contact forces, not counted))", "",
       f"- date: {datetime.datetime.now():%Y-%m-%d %H:%M}, commit `{sys.argv[3]}`, CPU: {cpu}, 1 rank",
       f"- compiler: {cxx}; optimisation flags of both sides: `{opt}` (compare.sh stops when they differ)",
       f"  - our plugin (build.ninja, pair_tlsph.cpp): `{ours_flags}`",
       f"  - our SIMD step (pair_style tlsph's default 'simd auto') ran its {os.environ.get('COMPARE_SIMD')} code: "
       "pair_tlsph_simd.cpp compiles its kernels for AVX-512, AVX2 + FMA and the baseline with function "
       "attributes and picks one at run time, so our 'SIMD step' rows use vector instructions that the "
       "other codes, built for the baseline x86-64 (no -march), do not; the 'simd no' row is our scalar "
       "step, built like them",
       f"  - the LAMMPS with MACHDYN and PERI (build.ninja, pair_smd_tlsph.cpp; "
       "scripts/build-lammps-plugin.sh bench): " f"`{lmp_flags}`",
       f"- {len(next(iter(t.values())))} repeat(s), median loop time (wall) and the CPU time of the same runs (loop time x LAMMPS's "
       "'% CPU use'); bench/in.compare (steel, dx = 1 mm, support 2.66 dx, "
       "alpha 1, gamma 1, dt 5e-8 s); memory: LAMMPS's 'Per MPI rank memory allocation' (avg); "
       "neighbor-list builds: LAMMPS's count for the timed run; bonds/particle: as each code reports it "
       "(our bond fix's reference partners, smd/tlsph's 'average # of neighbors/particle', peri/pmb's 'bonds/atom')", "",
       "| block | code | particles | steps | loop time [s] | CPU time [s] | neighbor builds | M particle-steps/s | speed-up of the first row over this row | bonds/particle | M bond-evaluations/s | memory [kB/particle] |",
       "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
for name in dict.fromkeys(k[0] for k in t):
    codes = [k[1] for k in t if k[0] == name]
    base = None
    for code in codes:
        natoms, ns, mem = meta[(name, code)]
        med = statistics.median(t[(name, code)])
        rate = natoms * ns / med / 1e6
        base = base or rate
        dim = 2 if name.startswith("2D") else 3
        # a code that printed no count: the lattice's partners within 2.66 dx, marked
        nb = nbonds.get((name, code))
        nbs = f"{nb:.1f}" if nb else f"{lattice_bonds(dim, natoms):.1f} (lattice, not reported)"
        nb = nb or lattice_bonds(dim, natoms)
        cput = f"{statistics.median(cpuse[(name, code)]):.3f}" if cpuse[(name, code)] else "-"
        nn = "/".join(sorted(nneigh[(name, code)]))
        out.append(f"| {name} | {label[code]} | {natoms} | {ns} | {med:.3f} | {cput} | {nn} | {rate:.3f} | "
                   f"{base / rate:.2f} | {nbs} | {rate * nb:.1f} | {mem * 1048.576 / natoms:.2f} |")
open(sys.argv[2], "w").write("\n".join(out) + "\n")
print("\n".join(out))
PY
