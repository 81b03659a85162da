#!/usr/bin/env bash
# The instruction count of bench/in.manytips's run loop (valgrind callgrind,
# collecting inside Verlet::run only, STEPS steps, default 40) for tlsph,
# tlsph/damage criterion tension (no tips) and criterion tip with kfit j (the
# recommended model, 110 standing tips): a deterministic measure of the work
# the tips add, beside bench/manytips.sh's loop times, which this shared
# machine's noise moves by more than that work (issue 26, "Cost and scale").
# Under valgrind the SIMD step runs the instruction set valgrind offers, not
# necessarily the one of a plain run. Writes bench/manytips-ir.md.
#   bash bench/manytips_ir.sh          (LMP_TLSPH= another binary)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
LMP="${LMP_TLSPH:-$HERE/../build/lmp_tlsph}"
OUT="$HERE/out/manytips-ir"
STEPS="${STEPS:-40}"
command -v valgrind > /dev/null || { echo "bench/manytips_ir.sh: valgrind is not installed (apt-get install valgrind)" >&2; exit 1; }
mkdir -p "$OUT"
for m in tlsph tension tipj; do
  model=$m; [ $m = tipj ] && model=tip
  valgrind --tool=callgrind --callgrind-out-file="$OUT/cg.$m" "--toggle-collect=LAMMPS_NS::Verlet::run(int)" \
    "$LMP" -in "$HERE/in.manytips" -var model "$model" -var kfit j -var steps "$STEPS" \
    -log "$OUT/$m.log" -screen none > "$OUT/$m.txt" 2>&1 &
done
wait
commit=$(git -C "$HERE/.." describe --always --dirty 2>/dev/null || echo unknown)
python3 - "$OUT" "$commit" "$STEPS" > "$HERE/manytips-ir.md" <<'PY'
import re, sys, datetime
out, commit, steps = sys.argv[1], sys.argv[2], int(sys.argv[3])
ir = {}
for m in ("tlsph", "tension", "tipj"):
    ir[m] = int(re.search(r"Collected : (\d+)", open(out + "/" + m + ".txt").read()).group(1))
isa = re.search(r"SIMD step \((\w+)", open(out + "/tlsph.log").read())
print("# Instructions of the many-tips run loop (bench/manytips_ir.sh)\n")
print("- date: %s, commit `%s`, valgrind callgrind, collecting in Verlet::run only, %d steps, 1 rank; "
      "SIMD step under valgrind: %s\n" % (datetime.datetime.now().strftime("%Y-%m-%d %H:%M"), commit, steps,
                                         isa.group(1) if isa else "?"))
print("| model | instructions per step | / tlsph |")
print("|---|---:|---:|")
names = {"tlsph": "tlsph", "tension": "tlsph/damage criterion tension (no tips)",
         "tipj": "tlsph/damage criterion tip branch yoffe kfit j, 110 tips standing (1 MPa)"}
for m in ("tlsph", "tension", "tipj"):
    print("| %s | %.3g | %.3f |" % (names[m], ir[m] / steps, ir[m] / ir["tlsph"]))
PY
cat "$HERE/manytips-ir.md"
