#!/usr/bin/env bash
# Fracture convergence study (issue 12): the Kalthoff-Winkler 2D deck at the
# resolutions KDX and the crack-branching deck at BDX, for each named model
# setting, then the report doc/fracture-convergence.md with its plots
# (bench/fracture_report.py): crack angles, initiation, branching, peak tip
# speed and edge times against dx, with the literature bands drawn.
#
#   bash bench/fracture.sh [SETTING ...]        default: thesis
#   KDX="1.67 1.0" BDX="0.5" bash bench/fracture.sh thesis gamma1   (a subset)
#   REPORT_ONLY=1 bash bench/fracture.sh ...    the report from finished runs
#   bash bench/fracture.sh all                  every setting of the report in
#                                               doc/fracture-convergence.md
# The report inserts bench/fracture-notes.md (the findings, written from its
# tables) after its summary.
#
# Settings (the variables each passes to both decks; the decks' own defaults
# are the thesis's coefficients per benchmark):
#   thesis     nothing: h = 1.33 dx, the thesis's viscosity, hourglass and
#              filter values of each benchmark
#   h2         -var hdx 2.0 (the crack-branching example's branching setting)
#   gamma1     -var gamma 1.0 (hourglass control on in both)
#   conservative  -var gamma 1.0 -var hg conservative
#   family4    -var famdx 4: pair_style tlsph/damage family 4 dx (bond family
#              of 4 spacings for the damage, s_c from Gc with horizon 2 dx;
#              forces with h = 1.33 dx)
#   common     one coefficient set for both decks, each value a thesis value
#              of one of them: alpha 0.09, filter 0.65 0.1, gamma 0 (Kalthoff),
#              alpha_d 0.4 (crack branching); h = 1.33 dx
#   linear     kcoef with 'damping linear' (alpha_i grows with phi')
#   load2      a diagnostic, not a model setting: the glass plate at 2 MPa
#              instead of the benchmark's 1 MPa (thesis coefficients);
#              load-X the same at X MPa
#   scan-A-AD-PHIC-EPS-G  alpha A, alpha_d AD, filter PHIC EPS, gamma G in
#              both decks (the coefficient scan: run it at one dx per deck,
#              KDX=1.0 BDX=0.5)
#   calibrated the thesis's setting with the fracture energy each
#              discretisation dissipates made equal to the material's G_c:
#              the decks give the pair style G_c / gmodel, gmodel = the
#              model's fracture energy per unit G_c given, measured by the
#              pure-shear strip (bench/toughness.sh, doc/toughness.md):
#              1.70 for the steel (nu 0.3), 1.47 for the glass (nu 0.2)
#   h2-calibrated  the same with h = 2 dx (gmodel 0.81 steel, 0.75 glass)
#   kcoef      one coefficient set for both decks: the Kalthoff deck's
#              (alpha 0.09, alpha_d 3.1, gamma 0, filter 0.65 0.1), h = 1.33 dx
#   tip        crack-tip tracking (pair_style tlsph/damage criterion tip,
#              experimental): K_I, K_II from the crack-face displacement
#              jump, maximum tangential stress direction, Freund's speed,
#              branching at G >= 2 G_c by +-15 deg ('branch 15'); the
#              kcoef coefficients in both decks, h = 1.33 dx, G_c as given
#   tip-yoffe  tip, but a tip with G >= 2 G_c branches only where the hoop
#              stress on the circle of radius 2h about it has two maxima,
#              one each side of its line (Yoffe's instability), and the
#              branches take those directions ('branch yoffe')
#   tip-yoffe-offset  tip-yoffe with the tips' K from the fit that also
#              finds the tip's effective position ('kfit offset')
#   tip-yoffe-j  tip-yoffe with the size of the tips' K from the domain
#              J-integral, the mode ratio from the displacement jump ('kfit j')
#   tip-yoffe-i  the same with the mode ratio from the interaction
#              integrals ('kfit interaction')
#   tip-yoffe-jin  tip-yoffe-j with the inertia term of the dynamic
#              J-integral ('jinertia yes'); bench/kfit_inertia.sh
#   tip-yoffe-iin  tip-yoffe-i with it
#   tip-ts-RC  tip-yoffe-is with the branching rule on the T-stress
#              ('branch tstress r_c', r_c = RC mm): a tip with G >= 2 G_c
#              branches where its two-term field's hoop stress at r_c has a
#              maximum each side of its line
#   tip-tsd-RC  tip-ts-RC with the running tip's field ('branch
#              tstress/dynamic r_c'): the hoop stress of the singular field
#              of a tip at its speed v = c_R (1 - G_c / G), K from G at that
#              speed (Freund's A_I, A_II), plus T
#   SETTING-vV  SETTING with the Kalthoff-Winkler impact at V m/s (-var v0
#              V; the deck's 16.5, the 3D deck's 30); bench/kw_speed.sh
#   SETTING-kr  SETTING with 'kratio running': the tips' K_II / K_I
#              corrected for their speed (the static readings' factors of a
#              running tip, tlsph_crack.h running_ratio_factors)
#   tip-tsdj-RC  tip-tsd-RC with the recommended model's fit, 'kfit j'
#              (K's ratio from the faces' opening, T from J's ring)
#   tip-yoffe-js  tip-yoffe-j (the recommended model) with 'tipdir segment'
#   tip-yoffe-is  tip-yoffe-i with the kink that leaves each segment's end
#              in mode I by the T-stress ('tipdir segment'); tip-yoffe-iins
#              the same with 'jinertia yes'
#   tip-ystep-j, -jin, -i, -iin  the same four with 'branch yoffe/step':
#              the branching condition tested at every step, not only
#              where a segment starts
#   tipc-NAME-VALUE  tip-yoffe with one constant of the tip model set to
#              VALUE (NAME: seg = tipseg, or sample, disc, hoopr, window,
#              split = pair_style tlsph/damage tipparam NAME); bench/tipconst.sh
#   tipjc-NAME-VALUE  the same for tip-yoffe-j (kfit j, the recommended
#              model from e469aee to c7dc05f); bench/tipconst.sh with KFIT=j
#   tipjkc-NAME-VALUE  the same for tip-yoffe-j-kr (the recommended model
#              since c7dc05f); bench/tipconst.sh with KFIT=jkr
#   tip-nobranch  the same without branching
#   tipg-j     tip-yoffe-j without branching, the tips' G/G_c at every step
#              into <case>.tips (-var tips 1): bench/branch_g.sh
#   tipg-jin   the same with J's inertia term ('jinertia yes')
#   tipg-j-seg-N  tipg-j with segments of N h (tipseg N)
#   tipg-i     tipg-j with the mode ratio from the interaction integrals
#              ('kfit interaction')
#   tipg-is    tipg-i with tipdir segment (the kink by the T-stress)
#   tip-thesis    tip with each deck's own (thesis) coefficients
#   tip-hoop   tip-nobranch with the direction of the largest hoop stress
#              at 2h ('tipdir hoop', segments of h)
# Runs are resumable: a finished case (its log ends with the wall time) is
# kept unless FORCE=1. Wall time: the 0.5 mm Kalthoff case is 80,000
# particles (about 15 min on a free core at 6db5ae1, 62 s with the tip
# models at 700ccf0), the 0.333 mm plate 36,000 (3-5 min; 20 s).
# Output: bench/out/fracture/<setting>/{kalthoff,branching}-<dx mm>.*
set -uo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(dirname "$HERE")"
PY="${TLSPH_PYTHON:-/usr/bin/python3}"
OUT="${FRACTURE_OUT:-$HERE/out/fracture}"    # FRACTURE_OUT: elsewhere (exploratory runs)
# (set but empty: none of that deck)
KDX="${KDX-1.67 1.33 1.11 1.0 0.833 0.667 0.5}"
BDX="${BDX-0.5 0.333}"
settings=("$@")
[ ${#settings[@]} -eq 0 ] && settings=(thesis)

# 'all': the settings of doc/fracture-convergence.md, each at its resolutions
SCANS="scan-0.03-0.4-0.5-0.5-1.0 scan-0.03-0.4-0.5-0.5-0.0 scan-0.03-0.4-0.65-0.1-0.0
  scan-0.03-3.1-0.5-0.5-0.0 scan-0.03-3.1-0.65-0.1-0.0 scan-0.09-0.3-0.65-0.1-0.0
  scan-0.09-0.4-0.5-0.5-0.0 scan-0.09-0.4-0.65-0.1-0.0 scan-0.09-0.5-0.65-0.1-0.0
  scan-0.09-0.7-0.65-0.1-0.0 scan-0.09-1.0-0.65-0.1-0.0 scan-0.09-1.5-0.65-0.1-0.0
  scan-0.09-2.0-0.65-0.1-0.0 scan-0.09-3.1-0.5-0.5-0.0 scan-0.09-3.1-0.65-0.1-0.0
  scan-0.09-3.1-0.65-0.1-1.0 scan-0.09-0.4-0.65-0.1-0.02 scan-0.09-0.4-0.65-0.1-0.05
  scan-0.09-0.4-0.65-0.1-0.1 scan-0.09-0.3-0.65-0.1-0.05"
if [ "${settings[0]}" = all ]; then
  # shellcheck disable=SC2086
  {
    NO_REPORT=1 bash "$0" thesis h2 common calibrated tip-yoffe-j-kr tip-yoffe-j tip-yoffe-i tip-yoffe tip tip-nobranch tip-thesis
    KDX="1.67 1.0" BDX="0.5" NO_REPORT=1 bash "$0" tip-hoop
    KDX="1.67 1.0" NO_REPORT=1 bash "$0" family4 linear h2-calibrated
    KDX="" NO_REPORT=1 bash "$0" load2 load-1.25 load-1.5 load-1.75
    KDX="1.0" BDX="0.5" NO_REPORT=1 bash "$0" $SCANS
  }
  # shellcheck disable=SC2206
  settings=(thesis h2 common calibrated tip-yoffe-j-kr tip-yoffe-j tip-yoffe-i tip-yoffe tip tip-nobranch tip-thesis tip-hoop family4 linear h2-calibrated load2 load-1.25 load-1.5 load-1.75 $SCANS)
  KDX="" BDX=""
fi

vars_of() {    # setting [kalthoff|branching]
  case "$1" in
    calibrated) [ "${2:-}" = kalthoff ] && echo "-var gmodel 1.70" || echo "-var gmodel 1.47" ;;
    h2-calibrated) [ "${2:-}" = kalthoff ] && echo "-var hdx 2.0 -var gmodel 0.81" \
                                            || echo "-var hdx 2.0 -var gmodel 0.75" ;;
    thesis) ;;
    h2) echo "-var hdx 2.0" ;;
    gamma1) echo "-var gamma 1.0" ;;
    conservative) echo "-var gamma 1.0 -var hg conservative" ;;
    family4) echo "-var famdx 4" ;;
    common) echo "-var alpha 0.09 -var alpha_d 0.4 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    kcoef) echo "-var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    tip) echo "-var crit tip -var branch 15 -var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    tip-yoffe) echo "-var crit tip -var branch yoffe -var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    tip-yoffe-offset) echo "-var crit tip -var branch yoffe -var kfit offset -var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    tipc-*|tipjc-*|tipjkc-*)    # tipc-NAME-VALUE, tipjc-, tipjkc-: tip-yoffe, tip-yoffe-j, tip-yoffe-j-kr with one constant changed
      local pre nm val kf=""
      IFS=- read -r pre nm val <<< "$1"
      [ "$pre" = tipjc ] && kf="-var kfit j "
      [ "$pre" = tipjkc ] && kf="-var kfit j -var kratio running "
      case "$nm" in
        seg) echo "-var crit tip -var branch yoffe ${kf}-var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1 -var tipseg $val" ;;
        sample|disc|hoopr|window|split) echo "-var crit tip -var branch yoffe ${kf}-var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1 -var t$nm $val" ;;
        *) echo "bench/fracture.sh: unknown tip constant '$nm' in '$1' (seg sample disc hoopr window split)" >&2; return 1 ;;
      esac ;;
    tip-yoffe-j) echo "-var crit tip -var branch yoffe -var kfit j -var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    tip-yoffe-jin) echo "-var crit tip -var branch yoffe -var kfit j -var jin yes -var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    tip-yoffe-iin) echo "-var crit tip -var branch yoffe -var kfit interaction -var jin yes -var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    tip-ystep-*)    # tip-ystep-j|jin|i|iin: as tip-yoffe-*, the branching tested at every step
      local kf jn=no
      case "${1#tip-ystep-}" in j) kf=j ;; jin) kf=j; jn=yes ;; i) kf=interaction ;; iin) kf=interaction; jn=yes ;;
        *) echo "bench/fracture.sh: unknown setting '$1' (tip-ystep-j, -jin, -i, -iin)" >&2; return 1 ;; esac
      echo "-var crit tip -var branch yoffe/step -var kfit $kf -var jin $jn -var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    *-v[0-9]*)    # SETTING-vV: SETTING with the Kalthoff-Winkler impact at V m/s (the deck's v0)
      echo "$(vars_of "${1%-v*}" "${2:-}") -var v0 ${1##*-v}" ;;
    *-kr)    # SETTING-kr: SETTING with the tips' K_II / K_I read at their speed ('kratio running')
      echo "$(vars_of "${1%-kr}" "${2:-}") -var kratio running" ;;
    tip-tsdj-*) echo "$(vars_of "tip-tsd-${1#tip-tsdj-}" | sed 's/-var kfit interaction /-var kfit j /')" ;;
    tip-yoffe-js) echo "$(vars_of tip-yoffe-j) -var tipdir segment" ;;
    tip-tsd-*) echo "$(vars_of "tip-ts-${1#tip-tsd-}" | sed 's/-var branch tstress /-var branch tstress\/dynamic /')" ;;
    tip-ts-*) echo "-var crit tip -var branch tstress -var brc $("$PY" -c "print(float('${1#tip-ts-}') * 1e-3)") -var kfit interaction -var tipdir segment -var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    tip-yoffe-is) echo "$(vars_of tip-yoffe-i) -var tipdir segment" ;;
    tip-yoffe-iins) echo "$(vars_of tip-yoffe-iin) -var tipdir segment" ;;
    tipg-is) echo "$(vars_of tipg-i) -var tipdir segment" ;;
    tip-yoffe-i) echo "-var crit tip -var branch yoffe -var kfit interaction -var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    tipg-j-seg-*) echo "$(vars_of tipg-j) -var tipseg ${1#tipg-j-seg-}" ;;
    tipg-i) vars_of tipg-j | sed 's/-var kfit j /-var kfit interaction /' ;;
    tipg-j|tipg-jin) echo "-var crit tip -var branch 0 -var kfit j -var jin $([ "$1" = tipg-jin ] && echo yes || echo no) -var tips 1 -var ttips 1e-12 -var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    tip-nobranch) echo "-var crit tip -var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    tip-thesis) echo "-var crit tip -var branch 15" ;;
    tip-hoop) echo "-var crit tip -var tipdir hoop -var tipseg 1 -var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    linear) echo "-var damping linear -var alpha 0.09 -var alpha_d 3.1 -var gamma 0.0 -var phic 0.65 -var eps 0.1" ;;
    load2) echo "-var sigma0 2.0e6" ;;
    load-*) echo "-var sigma0 ${1#load-}e6" ;;    # load-1.5: 1.5 MPa (diagnostic)
    scan-*)    # scan-ALPHA-ALPHAD-PHIC-EPS-GAMMA
      local a
      IFS=- read -r _ a[0] a[1] a[2] a[3] a[4] <<< "$1"
      echo "-var alpha ${a[0]} -var alpha_d ${a[1]} -var phic ${a[2]} -var eps ${a[3]} -var gamma ${a[4]}" ;;
    *) echo "bench/fracture.sh: unknown setting '$1' (allowed: thesis calibrated h2-calibrated h2 gamma1 conservative family4 common kcoef linear tip tip-yoffe tip-yoffe-offset tip-yoffe-j tip-yoffe-jin tip-yoffe-i tip-yoffe-iin tip-yoffe-is tip-yoffe-iins tip-ts-RC SETTING-kr SETTING-vV tip-ystep-j tip-ystep-jin tip-ystep-i tip-ystep-iin tipg-j tipg-jin tipg-j-seg-N tipg-i tipg-is tip-nobranch tip-thesis tip-hoop tipc-NAME-VALUE tipjc-NAME-VALUE tipjkc-NAME-VALUE load2 load-X scan-A-AD-PHIC-EPS-G)" >&2
       return 1 ;;
  esac
}

# dx in mm as written (1.67 means 5/3 mm, 1.33 4/3, 1.11 10/9, 0.833 5/6,
# 0.667 2/3, 0.333 1/3, 0.286 2/7, 0.222 2/9: the lattice must fit the
# plates exactly) -> metres
dx_m() {
  case "$1" in
    1.67) echo 0.00166666666666667 ;; 1.33) echo 0.00133333333333333 ;;
    1.11) echo 0.00111111111111111 ;; 0.833) echo 0.000833333333333333 ;;
    0.667) echo 0.000666666666666667 ;; 0.333) echo 0.000333333333333333 ;;
    0.286) echo 0.000285714285714286 ;; 0.222) echo 0.000222222222222222 ;;
    *) "$PY" -c "print(float('$1') * 1e-3)" ;;
  esac
}

run_deck() {    # example deck setting dxmm extra...
  local ex=$1 deck=$2 setting=$3 mm=$4; shift 4
  local dir="$OUT/$setting" name
  name="$(basename "$ex" | sed 's/-2d$//; s/crack-branching/branching/')-$mm"
  mkdir -p "$dir"
  if [ -z "${REPORT_ONLY:-}" ]; then
    (cd "$ROOT/examples/$ex" && FORCE="${FORCE:-0}" ../common/run_case.sh "$deck" "$dir" "$name" \
       -var dx "$(dx_m "$mm")" -var timg 0 "$@") || echo "  $name: LAMMPS stopped with an error"
  fi
  if [ -f "$dir/$name.log" ] && { [ -n "${FORCE:-}" ] || [ ! -f "$dir/$name.crack.json" ]; }; then
    (cd "$ROOT/examples/$ex" && "$PY" summarise.py "$dir/$name" --label "$setting $name" \
       > "$dir/summary-$name.txt" 2>&1) || echo "  $name: summarise.py failed"
  fi
}

for s in "${settings[@]}"; do
  vk=$(vars_of "$s" kalthoff) || exit 1
  vb=$(vars_of "$s" branching) || exit 1
  # every setting is defined against the decks' thesis model (-var model
  # thesis); the decks' default, model recommended, is setting tip-yoffe
  # shellcheck disable=SC2086
  for mm in $KDX; do run_deck kalthoff-2d in.kalthoff-2d "$s" "$mm" -var tend 110e-6 -var model thesis $vk; done
  # shellcheck disable=SC2086
  for mm in $BDX; do run_deck crack-branching in.crack-branching "$s" "$mm" -var tend 90e-6 -var model thesis $vb; done
done
[ -n "${NO_REPORT:-}" ] && exit 0
"$PY" "$HERE/fracture_report.py" --out "$OUT" --doc "$ROOT/doc/fracture-convergence.md" --kept tip-yoffe-j-kr \
  --notes "$HERE/fracture-notes.md" "${settings[@]}"
