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
REPEAT=${COMPARE_REPEAT:-3}
if [ "${COMPARE_QUICK:-0}" != 0 ]; then n2=60 n3=14 s2=20 s3=5 REPEAT=1; else n2=190 n3=34 s2=200 s3=30; fi
OUT="$HERE/out/compare"; mkdir -p "$OUT"
# case: name dim n nsteps gradient codes
cases=("2D $n2 2 $s2 quadratic tlsph smd" "3D $n3 3 $s3 quadratic tlsph smd"
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
      nbond=$(sed -n 's/.*bonds\/atom = *\([0-9.]*\).*/\1/p' "$log" | tail -1)
      echo "$name $code $r $natoms $ns $t $mem ${nbond:--}" >> "$OUT/times.txt"
      echo "compare: $name $code repeat $r: $t s" >&2
    done
  done
done
/usr/bin/python3 - "$OUT/times.txt" "$HERE/compare.md" "$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo '?')" <<'PY'
import sys, statistics, collections, datetime, platform, subprocess
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
t = collections.defaultdict(list); meta = {}
nbonds = {}
for name, code, r, natoms, ns, sec, mem, nb in rows:
    t[(name, code)].append(float(sec)); meta[(name, code)] = (int(natoms), int(ns), float(mem))
    if nb != "-":
        nbonds[(name, code)] = float(nb)


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
cpu = subprocess.run("lscpu | sed -n 's/^Model name: *//p'", shell=True, capture_output=True, text=True).stdout.strip()
label = {"tlsph": "tlsph (ours, plugin)", "tlsphd": "tlsph/damage (ours, plugin)",
         "smd": "smd/tlsph (MACHDYN)", "peri": "peri/pmb (PERI, horizon 3.015 dx)"}
out = ["# Side by side: one LAMMPS binary, alternating runs", "",
       "(2D, 3D: our quadratic gradient; 3D-damage: the linear gradient, tlsph/damage's default, for both of our rows; "
       "peri/pmb: bond-based peridynamics on the same particles, c = 18 K / (pi delta^4), s00 0.01, no bond breaks; "
       "a bond evaluation = one partner visited per particle and step, our bonds from the lattice within 2.66 dx, "
       "peri/pmb's from its fix (it also walks a half list of ~55 partners for its contact forces, not counted))", "",
       f"- date: {datetime.datetime.now():%Y-%m-%d %H:%M}, commit `{sys.argv[3]}`, machine: {cpu}, 1 rank",
       f"- {len(next(iter(t.values())))} repeat(s), median loop time; bench/in.compare (steel, dx = 1 mm, support 2.66 dx, "
       "alpha 1, gamma 1, dt 5e-8 s); memory: LAMMPS's 'Per MPI rank memory allocation' (avg)", "",
       "| block | code | particles | steps | loop time [s] | M particle-steps/s | speed-up of the first row over this row | bonds/particle | M bond-evaluations/s | memory [kB/particle] |",
       "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
for name in dict.fromkeys(k[0] for k in t):
    codes = [k[1] for k in t if k[0] == name]
    base = None
    for code in codes:
        natoms, ns, mem = meta[(name, code)]
        med = statistics.median(t[(name, code)])
        rate = natoms * ns / med / 1e6
        base = base or rate
        dim = 2 if name.startswith("2D") else 3
        nb = nbonds.get((name, code)) or lattice_bonds(dim, natoms)
        out.append(f"| {name} | {label[code]} | {natoms} | {ns} | {med:.3f} | {rate:.3f} | {base / rate:.2f} | "
                   f"{nb:.1f} | {rate * nb:.1f} | {mem * 1048.576 / natoms:.2f} |")
open(sys.argv[2], "w").write("\n".join(out) + "\n")
print("\n".join(out))
PY
