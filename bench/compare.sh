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
       "3D-damage $n3 3 $s3 linear tlsphd tlsph")
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
      echo "$name $code $r $natoms $ns $t $mem" >> "$OUT/times.txt"
      echo "compare: $name $code repeat $r: $t s" >&2
    done
  done
done
/usr/bin/python3 - "$OUT/times.txt" "$HERE/compare.md" "$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo '?')" <<'PY'
import sys, statistics, collections, datetime, platform, subprocess
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
t = collections.defaultdict(list); meta = {}
for name, code, r, natoms, ns, sec, mem in rows:
    t[(name, code)].append(float(sec)); meta[(name, code)] = (int(natoms), int(ns), float(mem))
cpu = subprocess.run("lscpu | sed -n 's/^Model name: *//p'", shell=True, capture_output=True, text=True).stdout.strip()
label = {"tlsph": "tlsph (ours, plugin)", "tlsphd": "tlsph/damage (ours, plugin)",
         "smd": "smd/tlsph (MACHDYN)"}
out = ["# Side by side: one LAMMPS binary, alternating runs", "",
       "(2D, 3D: our quadratic gradient; 3D-damage: the linear gradient, tlsph/damage's default, for both rows)", "",
       f"- date: {datetime.datetime.now():%Y-%m-%d %H:%M}, commit `{sys.argv[3]}`, machine: {cpu}, 1 rank",
       f"- {len(next(iter(t.values())))} repeat(s), median loop time; bench/in.compare (steel, dx = 1 mm, support 2.66 dx, "
       "alpha 1, gamma 1, dt 5e-8 s); memory: LAMMPS's 'Per MPI rank memory allocation' (avg)", "",
       "| block | code | particles | steps | loop time [s] | M particle-steps/s | speed-up of the first row over this row | memory [kB/particle] |",
       "|---|---|---:|---:|---:|---:|---:|---:|"]
for name in dict.fromkeys(k[0] for k in t):
    codes = [k[1] for k in t if k[0] == name]
    base = None
    for code in codes:
        natoms, ns, mem = meta[(name, code)]
        med = statistics.median(t[(name, code)])
        rate = natoms * ns / med / 1e6
        base = base or rate
        out.append(f"| {name} | {label[code]} | {natoms} | {ns} | {med:.3f} | {rate:.3f} | {base / rate:.2f} | {mem * 1048.576 / natoms:.2f} |")
open(sys.argv[2], "w").write("\n".join(out) + "\n")
print("\n".join(out))
PY
