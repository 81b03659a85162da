#!/bin/bash
# Which sets the branching: the horizon delta = h (a length of the model, it also
# sets s_c) or the number of spacings per horizon m = h/dx (a property of the
# discretisation)?  Runs the deck at two more spacings with h = 1.33 dx and
# h = 2 dx, so that each horizon is met with both m:
#
#   dx [mm]   m = 1.33        m = 2
#   0.500     delta 0.667     delta 1.000
#   0.333     delta 0.444 (*) delta 0.667 (*)   (*) the make-run cases (run.sh)
#   0.222     delta 0.296     delta 0.444
#
# and, at the deck's dx, two ratios between them: h = 1.5 dx and 1.67 dx.
# Every case runs to 90 us and is measured with the same physical lengths
# (summarise.py --dx: initiation at 1 mm of crack, branches 1 mm apart over
# 3.33 mm).  Writes out/hz-*.{log,dump,crack.*,montage.png,...},
# out/summary-hz-*.txt and the table out/study-horizon.md.
# About 15 minutes on 2 cores (NP=2 default here); FORCE=0 keeps finished runs.
set -eu
cd "$(dirname "$0")"
py="${TLSPH_PYTHON:-/usr/bin/python3}"
export NP="${NP:-2}"
mkdir -p out
dx3=0.000333333333333
dx2=0.000222222222222
dx5=0.0005
cases=(
  "hz-dx0.500-m1.33 $dx5 1.33"
  "hz-dx0.500-m2 $dx5 2.0"
  "hz-dx0.333-m1.33 $dx3 1.33"
  "hz-dx0.333-m2 $dx3 2.0"
  "hz-dx0.222-m1.33 $dx2 1.33"
  "hz-dx0.222-m2 $dx2 2.0"
  "hz-dx0.333-m1.5 $dx3 1.5"
  "hz-dx0.333-m1.67 $dx3 1.67"
)
names=()
for c in "${cases[@]}"; do
  set -- $c
  name=$1 dx=$2 hdx=$3
  names+=("$name")
  FORCE="${FORCE:-1}" ../common/run_case.sh in.crack-branching out "$name" \
    -var model thesis -var dx "$dx" -var hdx "$hdx" -var tend 90e-6 -var timg 10e-6 || true
  "$py" summarise.py out/"$name" --dx "$dx" --label "$name (dx $dx, h $hdx dx)" \
    > out/summary-"$name".txt || echo "summarise failed for $name" >&2
done

"$py" - "${names[@]}" > out/study-horizon.md <<'EOF'
import json, sys
sys.path.insert(0, '../common')
from run_info import log_info
rows = ['| dx [mm] | h/dx | horizon [mm] | s_c | particles | initiation | branching (persistent 2) | '
        'branches at the end | max speed | side branches | right edge | steps | wall [s] |',
        '|---:|---:|---:|---:|---:|---|---|---:|---:|---:|---|---:|---:|']
us = lambda t: 'none' if t is None else f'{t * 1e6:.1f} us'
for name in sys.argv[1:]:
    p = 'out/' + name
    try:
        d = json.load(open(p + '.crack.json'))
    except OSError:
        rows.append(f'| {name}: no result |' + ' |' * 12)
        continue
    info = log_info(p + '.log')
    c = d['cracks']['crack']
    dx = d['dx']
    hdx = float(name.split('-m')[1])
    at = c.get('two_branches_at_target_time')
    edge = (f'both branches, {us(at)}' if at is not None else
            f'single crack, {us(c["target_reached_time"])}' if c['target_reached_time'] is not None
            else f'not reached ({c.get("branches_at_target_final", 0)} branch(es) there)')
    vmax = c['speed_max']
    rows.append(f'| {dx * 1e3:.3f} | {hdx:g} | {hdx * dx * 1e3:.3f} | {info.get("sc", float("nan")):.3g} | '
                f'{d["n_particles"]} | {us(c["initiation_time"])} | {us(c["branching_time"])} | '
                f'{c["branches_final"]} | {"n/a" if vmax is None else f"{vmax:.0f} m/s"} | '
                f'{c["side_branches_max"]} | {edge} | {info.get("steps", "")} | {info.get("wall_s", "")} |'
                + (f' STOPPED: {info["error"]}' if 'error' in info else ''))
print('\n'.join(rows))
EOF
cat out/study-horizon.md

# the last damage snapshot of each case, in one figure
"$py" - "${names[@]}" <<'PYEOF' || echo "study-horizon.sh: figure failed" >&2
import glob, sys
import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt
import matplotlib.image as mpimg
names = sys.argv[1:]
ncol = 2
nrow = (len(names) + ncol - 1) // ncol
fig, axs = plt.subplots(nrow, ncol, figsize=(12, 2.2 * nrow), squeeze=False)
for ax in axs.flat:
    ax.axis('off')
for ax, name in zip(axs.flat, names):
    pngs = sorted(glob.glob(f'out/{name}.damage.*.png'))
    if not pngs:
        continue
    ax.imshow(mpimg.imread(pngs[-1]))
    dx, m = name.split('-dx')[1].split('-m')
    ax.set_title(f'dx = {dx} mm, h = {m} dx (horizon {float(dx) * float(m):.3g} mm), '
                 f'step {int(pngs[-1].split(".")[-2])}', fontsize=9)
fig.suptitle('damage phi, the last snapshot (every 10 us) before 90 us; blue 0, yellow 0.3, red >= 0.6', fontsize=10)
fig.tight_layout()
fig.savefig('out/study-horizon.png', dpi=80)
print('figure: out/study-horizon.png')
PYEOF
