#!/usr/bin/env bash
# The speed law of 'criterion tip' against theory (issue 26): a crack running
# steadily in the pure-shear strip of bench/in.toughness (plane strain glass,
# grips fixed, the strip pre-strained so that the energy released per unit
# crack advance is G0 = W D, whatever the crack's length) must run at
# v = c_R (1 - G_c / G0) (Freund's equation of motion, which the tip model
# applies to the G it measures). For G0 / G_c = 1.25, 1.5 and 2, dx = 0.5
# and 0.333 mm, the K fits (KFITS: kfit tip, the default, kfit offset, and
# kfit j, the size of K from the domain J-integral), the
# recommended model's coefficients (alpha 0.09, alpha_d 3.1, gamma 0,
# filter 0.65 / 0.1): the speed measured from the tip's position (least
# squares over 25-45 mm, the strip is 60 mm long and the pre-crack ends at
# 20 mm), the G the tip measured on its segments there (TLSPH_TIP_TRACE),
# and theory. Writes bench/speedlaw.md.
#   bash bench/speedlaw.sh          (LMP_TLSPH= another binary)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
LMP="${LMP_TLSPH:-$HERE/../build/lmp_tlsph}"
OUT="$HERE/out/speedlaw"
mkdir -p "$OUT"
rm -f "$OUT"/*
commit=$(git -C "$HERE/.." describe --always --dirty 2>/dev/null || echo unknown)
KFITS="${KFITS:-tip offset j}"
for kfit in $KFITS; do
  for dx in 0.0005 0.000333333333333; do
    for r in 1.25 1.5 2.0; do
      tag="$kfit-$dx-$r"
      G0=$(python3 -c "print(3.0 * $r)")
      (cd "$OUT" && TLSPH_TIP_TRACE=1 "$LMP" -in "$HERE/in.toughness" -var dx "$dx" -var crit tip \
        -var kfit "$kfit" -var G0 "$G0" -var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 \
        -var phic 0.65 -var eps 0.1 -var out "$tag" -log "$tag.log" -screen none > /dev/null)
    done
  done
done
KFITS="$KFITS" BENCH="$HERE" python3 - "$OUT" "$commit" > "$HERE/speedlaw.md" <<'PY'
import datetime, os, sys
sys.path.insert(0, os.environ["BENCH"])
from strip_speed import measure, energy_rates
out, commit = sys.argv[1], sys.argv[2]

print("# The speed law of `criterion tip` against theory (bench/speedlaw.sh)\n")
print("- date: %s, commit `%s`" % (datetime.datetime.now().strftime("%Y-%m-%d %H:%M"), commit))
print("- bench/in.toughness with `crit tip`: a pure-shear strip (60 mm, 5 mm between the grips, "
      "plane strain glass E 32 GPa, nu 0.2, G_c 3 J/m^2), pre-strained to G0 = W D, grips fixed; "
      "the recommended model's coefficients; h = 1.33 dx")
print("- v: least squares of the tip position (the furthest damaged particle on the crack line) "
      "over 25-45 mm; G measured: the mean of the G the tip measured at the start of its segments "
      "there; theory: v = c_R (1 - G_c / G0), c_R = 2119 m/s (the pair style's)\n")
print("- cuts: the energy the cut bonds dissipated over the same window: the fall of compute "
      "tlsph/energy's sum (strain, hourglass and viscous work, kinetic; the grips do no work) less the "
      "kinetic energy the velocity filter took out, per unit crack advance (least squares against the "
      "tip's position), over G_c; theory 1 (the tip model applies Freund's equation of motion, which "
      "gives the tip G_c); viscosity: the artificial viscosity's work per unit crack advance, over G_c\n")
print("| kfit | dx [mm] | G0 / G_c | v / c_R measured | theory | difference | G measured / G0 | segments | cuts / G_c | viscosity / G_c |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for kfit in os.environ["KFITS"].split():
    for dx in ("0.0005", "0.000333333333333"):
        for r in ("1.25", "1.5", "2.0"):
            tag = "%s-%s-%s" % (kfit, dx, r)
            v, g = measure("%s/%s" % (out, tag))
            gm = sum(g) / len(g) if g else float("nan")
            th = 1.0 - 1.0 / float(r)
            cut, visc = energy_rates("%s/%s" % (out, tag))
            print("| %s | %.3f | %s | %.3f | %.3f | %+.3f | %.2f | %d | %.3f | %.3f |" % (
                kfit, float(dx) * 1e3, r, v, th, v - th, gm / float(r), len(g), cut / 3.0, visc / 3.0))
PY
cat "$HERE/speedlaw.md"
