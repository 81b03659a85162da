#!/usr/bin/env bash
# The tips' mode ratio against theory (issue 26): bench/in.kcheck with
# -var mode mixed (the central crack 2a = 10 mm in the 80 x 80 mm glass
# plate under remote tension and remote shear of 1 MPa together, relaxed;
# by superposition K_I = K_II = the reference of bench/kcheck.md) at dx =
# DXS, for each fit of KFITS (default: kfit j, the mode ratio from the
# faces' opening, and kfit interaction, from the interaction integrals),
# two runs at a time. Writes bench/kcheck-mixed.md.
#   bash bench/kcheck_mixed.sh        (LMP_TLSPH= another binary; REPORT_ONLY=1:
#                                      the table from the logs there are)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
LMP="${LMP_TLSPH:-$HERE/../build/lmp_tlsph}"
OUT="$HERE/out/kcheck-mixed"
mkdir -p "$OUT"
DXS="${DXS:-0.001 0.0005 0.000333333333333333}"
KFITS="${KFITS:-j interaction}"
for dx in $DXS; do
  [ -n "${REPORT_ONLY:-}" ] && break
  chunk=$(python3 -c "print(round(1.0e-3 / $dx * 1000))")
  pids=()
  for kfit in $KFITS; do
    (cd "$OUT" && "$LMP" -in "$HERE/in.kcheck" -var dx "$dx" -var mode mixed -var kfit "$kfit" \
      -var chunk "$chunk" -var nchunk 8 -log "$OUT/k-$kfit-$dx.log" -screen none > /dev/null) &
    pids+=($!)
  done
  for p in "${pids[@]}"; do wait "$p"; done
  echo "kcheck_mixed: dx $dx done" >&2
done
commit=$(git -C "$HERE/.." describe --always --dirty 2>/dev/null || echo unknown)
/usr/bin/python3 - "$OUT" "$commit" "$HERE/kcheck-mixed.md" "$KFITS" $DXS <<'PY'
import datetime, math, sys
out, commit, rep, kfits, dxs = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4].split(), sys.argv[5:]
a, b, load = 0.005, 0.04, 1.0e6
lam = a / b
F = (1 - 0.025 * lam ** 2 + 0.06 * lam ** 4) * math.sqrt(1 / math.cos(math.pi * lam / 2))
K0 = load * math.sqrt(math.pi * a) * F
L = ["# The tips' mode ratio against theory (bench/kcheck_mixed.sh)", "",
     f"- date: {datetime.datetime.now():%Y-%m-%d %H:%M}, commit `{commit}`",
     "- bench/in.kcheck -var mode mixed: the central crack 2a = 10 mm in the 80 x 80 mm glass plate (2D plane strain, "
     "h = 1.33 dx, gamma 0, nothing grows) under remote tension and remote shear of 1 MPa together, relaxed "
     "(fix tlsph/relax, 8 report intervals); by superposition K_I = K_II = "
     f"{K0:.1f} Pa m^0.5 (Tada's finite-width factor {F:.4f}, as bench/kcheck.md); both fits take the size of K "
     "from the domain J-integral (ring 2h-4h), kfit j the ratio K_II/K_I from the faces' opening, kfit interaction "
     "from the interaction integrals over the same ring", "",
     "| kfit | dx [mm] | K_I / reference | K_II / reference | K_II / K_I | change of K_II / K_I over the last interval |",
     "|---|---:|---:|---:|---:|---:|"]
for kfit in kfits:
    for dx in dxs:
        rows = []
        try:
            lines = open(f"{out}/k-{kfit}-{dx}.log").read().splitlines()
        except OSError:
            lines = []
        on = False
        for l in lines:
            w = l.split()
            if w[:2] == ["Step", "Time"]:
                on = True
                continue
            if on:
                try:
                    rows.append([float(v) for v in w])
                except ValueError:
                    on = False
        if len(rows) < 2:
            L.append(f"| {kfit} | {1e3 * float(dx):.3f} | run failed | | | |")
            continue
        k1, k2 = rows[-1][2], rows[-1][3]
        r, rp = k2 / k1, rows[-2][3] / rows[-2][2]
        L.append(f"| {kfit} | {1e3 * float(dx):.3f} | {k1 / K0:.4f} | {k2 / K0:.4f} | {r:.4f} | {100 * (r / rp - 1):+.3f} % |")
open(rep, "w").write("\n".join(L) + "\n")
print("\n".join(L))
PY
