#!/usr/bin/env bash
# Speed per phase of the step (doc/bench.md, "Speed per phase"): the blocks
# of bench/in.bench (2D 190 x 190, 3D 34^3, quadratic gradient, alpha 1,
# gamma 1) with pair_style tlsph's step as it was before the SIMD work
# (simd no: the scalar step) and the SIMD step for each instruction set this
# CPU runs (portable: the layout, order and patterns without vector
# instructions; avx2; avx512), in ONE invocation, alternating, PHASES_REPEAT
# (3) repeats, medians. Writes bench/phases.md and prints it.
#   bash bench/phases.sh            (make bench-phases)
#   PHASES_QUICK=1 bash bench/phases.sh   smoke: small blocks, 1 repeat
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(dirname "$HERE")"
LMP="${LMP_TLSPH:-$ROOT/build/lmp_tlsph}"
[ -x "$LMP" ] || { echo "phases: $LMP not found: run 'make build' first" >&2; exit 1; }
REPEAT=${PHASES_REPEAT:-3}
if [ "${PHASES_QUICK:-0}" != 0 ]; then n2=60 n3=14 s2=20 s3=5 REPEAT=1; else n2=190 n3=34 s2=200 s3=30; fi
OUT="$HERE/out/phases"; mkdir -p "$OUT"
: > "$OUT/times.txt"
# the instruction sets this CPU runs (the plugin refuses the others)
isas="no portable"
for isa in avx2 avx512; do
  if "$LMP" -in "$HERE/in.bench" -var n 12 -var nwarm 1 -var nsteps 1 -var simd $isa \
       -log none -echo none > "$OUT/probe-$isa.log" 2>&1; then
    isas="$isas $isa"
  fi
done
for r in $(seq "$REPEAT"); do
  for c in "2D 2 $n2 $s2" "3D 3 $n3 $s3"; do
    set -- $c; name=$1 dim=$2 n=$3 ns=$4
    for isa in $isas; do
      log="$OUT/$name-$isa-$r.log"
      (cd "$OUT" && "$LMP" -in "$HERE/in.bench" -var dim "$dim" -var n "$n" -var nsteps "$ns" \
         -var simd "$isa" -log none -echo none > "$log" 2>&1) ||
        { tail -5 "$log" >&2; echo "phases: $name simd $isa failed (log $log)" >&2; exit 1; }
      t=$(grep "Loop time" "$log" | tail -1 | awk '{print $4}')
      natoms=$(grep "Loop time" "$log" | tail -1 | awk '{print $(NF-1)}')
      mem=$(grep "Per MPI rank memory" "$log" | tail -1 | awk '{print $(NF-1)}')
      cpu=$(sed -n 's/^\([0-9.]*\)% CPU use.*/\1/p' "$log" | tail -1)
      layout=$(sed -n 's/^pair tlsph: SIMD step (.*): \(.*\)$/\1/p' "$log" | tail -1 | tr ' ' '_')
      echo "$name $isa $r $natoms $ns $t $mem ${cpu:--} ${layout:--}" >> "$OUT/times.txt"
      echo "phases: $name simd $isa repeat $r: $t s" >&2
    done
  done
done
/usr/bin/python3 - "$OUT/times.txt" "$HERE/phases.md" \
  "$(git -C "$ROOT" describe --always --dirty 2>/dev/null || echo '?')" "$(g++ --version | head -1)" <<'PY'
import os, sys, statistics, collections, datetime, subprocess
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
t = collections.defaultdict(list); meta = {}; cpu = collections.defaultdict(list); layout = {}
for name, isa, r, natoms, ns, sec, mem, c, lay in rows:
    t[(name, isa)].append(float(sec)); meta[(name, isa)] = (int(natoms), int(ns), float(mem))
    if c != "-":
        cpu[(name, isa)].append(float(c) / 100.0 * float(sec))
    if lay != "-":
        layout[name] = lay.replace("_", " ")
sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[2])))  # bench/
from machine import cpu_model  # noqa: E402
model = cpu_model()
what = {"no": "scalar step (simd no): the step before this work",
        "portable": "SIMD step, portable (order, columns, chunks, patterns; baseline instructions)",
        "avx2": "SIMD step, AVX2 + FMA (4 lanes)", "avx512": "SIMD step, AVX-512 (8 lanes)"}
out = ["# Speed per phase of pair_style tlsph's step (bench/phases.sh)", "",
       f"- date: {datetime.datetime.now():%Y-%m-%d %H:%M}, commit `{sys.argv[3]}`, CPU: {model}, 1 rank, "
       f"compiler: {sys.argv[4]}, the plugin's flags (CMakeLists.txt: -O3 -DNDEBUG; the SIMD kernels "
       "compiled per instruction set with function attributes)",
       f"- bench/in.bench blocks (steel, dx = 1 mm, h = 1.33 dx, quadratic gradient, alpha 1, gamma 1, "
       f"newton on), {len(next(iter(t.values())))} repeat(s) alternating in one invocation, median loop "
       "time; CPU time = loop time x LAMMPS's '% CPU use'; memory: LAMMPS's per-rank figure", ""]
for name in dict.fromkeys(k[0] for k in t):
    if name in layout:
        out.append(f"- {name} layout of the SIMD step: {layout[name]}")
out += ["", "| block | step | particles | steps | loop time [s] | CPU time [s] | M particle-steps/s | "
        "speed-up over simd no | memory [kB/particle] |", "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
for name in dict.fromkeys(k[0] for k in t):
    base = None
    for isa in [k[1] for k in t if k[0] == name]:
        natoms, ns, mem = meta[(name, isa)]
        med = statistics.median(t[(name, isa)])
        rate = natoms * ns / med / 1e6
        base = base or rate
        cput = f"{statistics.median(cpu[(name, isa)]):.3f}" if cpu[(name, isa)] else "-"
        out.append(f"| {name} | {what[isa]} | {natoms} | {ns} | {med:.3f} | {cput} | {rate:.3f} | "
                   f"{rate / base:.2f} | {mem * 1048.576 / natoms:.2f} |")
open(sys.argv[2], "w").write("\n".join(out) + "\n")
print("\n".join(out))
PY
