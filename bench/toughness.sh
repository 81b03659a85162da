#!/usr/bin/env bash
# The fracture energy the damage model dissipates, against the G_c it is
# given: the pure-shear strip of bench/in.toughness (2D plane strain) at
# several resolutions, h/dx, Poisson ratios and bond families, loaded slowly
# (onset of growth: the model's static fracture energy) and at fixed strain
# (steady crack speed: the model's dynamic fracture energy Gamma(v)); then the
# report doc/toughness.md with doc/toughness.png (bench/toughness_report.py).
#
#   bash bench/toughness.sh            every case (about 6 min on 2 cores)
#   REPORT_ONLY=1 bash bench/toughness.sh
# Runs are resumable (a finished case is kept unless FORCE=1).
# Output: bench/out/toughness/<case>.{log,dat,screen}
set -uo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(dirname "$HERE")"
PY="${TLSPH_PYTHON:-/usr/bin/python3}"
OUT="$HERE/out/toughness"
mkdir -p "$OUT"

D05=0.0005; D033=0.000333333333333; D025=0.00025; D1=0.001
STEEL="-var E 190e9 -var nu 0.3 -var rho 8000 -var Gc 22130 -var rate 40"
# name | variables of bench/in.toughness (ramp cases: name starts with 'ramp-';
# fixed-strain cases: 'run-', with G0)
CASES=(
  "ramp-h1.33-nu0.2-dx1|-var dx $D1"
  "ramp-h1.33-nu0.2-dx0.5|-var dx $D05"
  "ramp-h1.33-nu0.2-dx0.333|-var dx $D033"
  "ramp-h1.33-nu0.2-dx0.25|-var dx $D025"
  "ramp-h1.33-nu0.2-dx0.5-rate1|-var dx $D05 -var rate 1 -var tend 500e-6"
  "ramp-h1.33-nu0.2-dx0.5-Gc1.5|-var dx $D05 -var Gc 1.5"
  "ramp-h1.33-nu0.0-dx0.5|-var dx $D05 -var nu 0.0"
  "ramp-h1.33-nu0.3-dx0.5|-var dx $D05 -var nu 0.3"
  "ramp-h1.33-nu0.3-dx0.333|-var dx $D033 -var nu 0.3"
  "ramp-h1.33-steel-dx0.5|-var dx $D05 $STEEL"
  "ramp-h1.5-nu0.2-dx0.5|-var dx $D05 -var hdx 1.5"
  "ramp-h2-nu0.2-dx0.5|-var dx $D05 -var hdx 2"
  "ramp-h2-nu0.2-dx0.333|-var dx $D033 -var hdx 2"
  "ramp-h2-nu0.3-dx0.5|-var dx $D05 -var hdx 2 -var nu 0.3"
  "ramp-h1.33-fam4-nu0.2-dx0.5|-var dx $D05 -var famdx 4"
  # calibrated: G_c / 1.47 given (the glass at h = 1.33 dx), G_c / 0.75 (h = 2 dx)
  "ramp-h1.33-nu0.2-dx0.5-cal|-var dx $D05 -var Gc $("$PY" -c 'print(3/1.47)')"
  "ramp-h1.33-nu0.2-dx0.333-cal|-var dx $D033 -var Gc $("$PY" -c 'print(3/1.47)')"
  "ramp-h2-nu0.2-dx0.333-cal|-var dx $D033 -var hdx 2 -var Gc $("$PY" -c 'print(3/0.75)')"
)
# fixed strain: G0 = f x the model's onset fracture energy (4.41 J/m^2 at
# h = 1.33 dx, 2.26 J/m^2 at h = 2 dx, both for G_c = 3 J/m^2 given)
for f in 1.1 1.25 1.5 2 3; do
  CASES+=("run-h1.33-nu0.2-dx0.5-f$f|-var dx $D05 -var G0 $("$PY" -c "print(round($f*4.41, 4))")")
  CASES+=("run-h2-nu0.2-dx0.5-f$f|-var dx $D05 -var hdx 2 -var G0 $("$PY" -c "print(round($f*2.26, 4))")")
done
# the lattice turned against the crack line (lattice orient x oa ob 0): theta =
# atan(ob/oa) = 0, 18.4, 26.6, 33.7, 45 deg; ramp loading, the crack runs 10 mm
for o in "1 0" "3 1" "2 1" "3 2" "1 1"; do
  set -- $o
  CASES+=("orient-h1.33-o$1$2|-var dx $D05 -var oa $1 -var ob $2")
  CASES+=("orient-h2-o$1$2|-var dx $D05 -var hdx 2 -var oa $1 -var ob $2")
  CASES+=("orient-fam4-o$1$2|-var dx $D05 -var famdx 4 -var oa $1 -var ob $2")
done
for f in 1.25 2; do
  CASES+=("run-h1.33-nu0.2-dx0.333-f$f|-var dx $D033 -var G0 $("$PY" -c "print(round($f*4.41, 4))")")
done

if [ -z "${REPORT_ONLY:-}" ]; then
  run() {    # "name|vars"
    local name=${1%%|*} vars=${1#*|}
    # shellcheck disable=SC2086
    FORCE="${FORCE:-0}" "$ROOT/examples/common/run_case.sh" "$HERE/in.toughness" "$OUT" "$name" $vars \
      > /dev/null || echo "  $name: LAMMPS stopped with an error"
  }
  # two at a time
  for ((i = 0; i < ${#CASES[@]}; i += 2)); do
    run "${CASES[$i]}" &
    [ $((i + 1)) -lt ${#CASES[@]} ] && run "${CASES[$((i + 1))]}" &
    wait
  done
fi
names=()
for c in "${CASES[@]}"; do names+=("${c%%|*}"); done
"$PY" "$HERE/toughness_report.py" --out "$OUT" --doc "$ROOT/doc/toughness.md" "${names[@]}"
