#!/bin/bash
# Full studies of the 2D cantilever (README.md, "Studies"). Each case writes
# out/studies/<name>.{log,dat,screen}; finished cases are skipped, so the
# script can be interrupted and resumed (FORCE=1 reruns everything).
#   bash studies.sh [convergence] [hourglass] [speed] [courant] [analyse]   (default: all)
# About 25 min of CPU on one core of the development machine (2026-11),
# most of it in the dx = 0.5 mm convergence runs and the ramped dynamics.
set -u
cd "$(dirname "$0")"
# The tables of results.md / README.md were measured with the layout before
# 2026-12 (cell-centre layers through the depth, clamp columns behind the face):
# the studies keep it. LAYOUT="moment face" runs the deck's present default
# (into out/studies-moment-face); doc/pareto.md compares the two.
read -r yplace clamp <<< "${LAYOUT:-uniform cell}"
run_layout() { ../common/run_case.sh "$@" -var yplace "$yplace" -var clamp "$clamp"; }
run=run_layout
deck="in.cantilever-2d"
out="out/studies"
[ "$yplace $clamp" = "uniform cell" ] || out="out/studies-$yplace-$clamp"
py="${TLSPH_PYTHON:-/usr/bin/python3}"
parts="${*:-convergence hourglass speed courant analyse}"

# dynamic relaxation to the static state: kinetic damping, step load, stop when
# the net force on the free particles is below 1e-6 P (at most 4 T1)
mmof() { awk "BEGIN{print $1*1000}"; }
dr() { "$run" "$deck" "$out" "$@" -var damp relax -var ramp 0 -var hold 4 -var tol 1e-6 -var final 1; }

main() {
for part in $parts; do
  case "$part" in
  convergence)
    # thesis load (alpha 9.10 plane strain, 10.0 plane stress): Courant 0.16;
    # alpha = 1 and the linear regime (P/100): Courant 0.3, the static state
    # does not depend on it (checked in 'courant')
    series=("strain 17500 0.16" "stress 17500 0.16" "stress 1750 0.3" "strain 175 0.3" "stress 175 0.3")
    for grad in quadratic linear; do
      g=${grad:0:1}
      for dx in 0.002 0.001; do
        for s in "${series[@]}"; do
          set -- $s
          dr ${g}_$1_P$2_dx$(mmof $dx) -var grad $grad -var plane $1 -var P $2 -var cfl $3 -var dx $dx
        done
      done
      # dx = 0.5 mm: every quadratic series; linear only plane stress (CPU budget)
      for s in "${series[@]}"; do
        set -- $s
        [ $grad = linear ] && [ $1 = strain -o $2 = 1750 ] && continue
        dr ${g}_$1_P$2_dx0.5 -var grad $grad -var plane $1 -var P $2 -var cfl $3 -var dx 0.0005
      done
    done
    ;;
  hourglass)
    # hourglass coefficient gamma at the thesis load (plane stress, alpha = 10,
    # dx = 1 mm): gamma = 1 is the default (convergence runs), 0 and 3 here
    for gamma in 0 3; do
      dr hg_gamma${gamma}_stress_P17500_dx1 -var grad quadratic -var plane stress -var dx 0.001 \
        -var P 17500 -var cfl 0.16 -var gamma $gamma
    done
    ;;
  speed)
    # speed against error at dx = 1 mm, thesis case (quadratic, plane strain)
    common=(-var P 17500 -var plane strain -var grad quadratic -var cfl 0.16)
    "$run" "$deck" "$out" speed_relax "${common[@]}" -var dx 0.001 -var damp relax -var ramp 0 -var hold 4
    "$run" "$deck" "$out" speed_viscous "${common[@]}" -var dx 0.001 -var damp viscous -var ramp 0 -var hold 6
    # plain dynamics, load ramped over Tr T1, then held; at dx = 1 mm Tr = 2 and
    # Tr = 5 held for 20 T1 (the long-hold stability check), the whole sweep
    # Tr = 2, 5, 10, 20 at dx = 2 mm (8 times cheaper)
    "$run" "$deck" "$out" speed_none_ramp2 "${common[@]}" -var dx 0.001 -var damp none -var ramp 2 -var hold 4
    "$run" "$deck" "$out" speed_none_ramp5 "${common[@]}" -var dx 0.001 -var damp none -var ramp 5 -var hold 20 -var final 1
    for tr in 2 5 10 20; do
      "$run" "$deck" "$out" speed2_none_ramp$tr "${common[@]}" -var dx 0.002 -var damp none -var ramp $tr -var hold 4
    done
    "$run" "$deck" "$out" speed2_relax "${common[@]}" -var dx 0.002 -var damp relax -var ramp 0 -var hold 4
    "$run" "$deck" "$out" speed2_viscous "${common[@]}" -var dx 0.002 -var damp viscous -var ramp 0 -var hold 6
    ;;
  courant)
    # stability against the Courant number at the thesis load, plane stress
    # (alpha = 10), and a check that the static state does not depend on C
    for c in 0.16 0.25 0.3 0.4 0.5 0.7 1.0; do
      [ $c != 0.16 ] && "$run" "$deck" "$out" courant_${c}_dx1 -var dx 0.001 -var P 17500 \
        -var plane stress -var cfl $c -var damp relax -var ramp 0 -var hold 4 -var tol 1e-6
      "$run" "$deck" "$out" courant_${c}_dx1_none -var dx 0.001 -var P 17500 -var plane stress \
        -var cfl $c -var damp none -var ramp 2 -var hold 3
    done
    "$run" "$deck" "$out" courant_0.16_P175_dx1 -var dx 0.001 -var P 175 -var plane strain \
      -var cfl 0.16 -var damp relax -var ramp 0 -var hold 4 -var tol 1e-6
    ;;
  analyse)
    if [ "$out" = out/studies ]; then "$py" analyse.py
    else "$py" analyse.py --out "$out" --results "$out"; fi
    "$py" ../common/summarise_run.py $out/q_strain_P17500_dx1 --dim 2 --fe-key 2d_strain_P17500 --png final_state_dx1.png
    ;;
  *) echo "unknown part '$part' (convergence, speed, courant, analyse)" >&2; exit 1 ;;
  esac
done
}

# the whole script is parsed before it runs: editing it meanwhile is safe
main "$@"
exit
