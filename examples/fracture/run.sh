#!/bin/bash
# The main job (`make run`): the package's recommended fracture model on the
# thesis's two dynamic fracture benchmarks, one after the other, 1 MPI rank:
#   ../crack-branching   the glass plate under 1 MPa, dx = 0.333 mm (36,000
#                        particles), to 90 us: the crack branches and both
#                        branches run to the right edge
#   ../kalthoff-2d       Kalthoff-Winkler 2D, dx = 1 mm (20,000 particles), to
#                        110 us: two cracks at about 70 deg to the impact
# with a progress line every 5 s. Each example leaves its own outputs in its
# out/ (LAMMPS log and dumps, dump-image PNGs, montage, tip speed plot, the
# crack measured by tools/crack_measure.py, summary-NAME.txt against the thesis
# and the acceptance bands); this script gathers into out/ here:
#   summary.txt       both summaries, and the wall time of each run
#   overview.png      the final damage of both runs side by side (README's picture)
#   results.json, table.md   the numbers README shows and their table (report.py)
#   *.montage.png, *.speed.png   copies of the examples' montages and speed plots
# (the full-field dumps, NAME.full.dump, stay in the examples' out/)
# VARIANT=thesis: the thesis's method instead (crack-branching with h = 1.33 dx
# and h = 2 dx, Kalthoff-Winkler 2D at 1 mm), out/summary-thesis.txt.
# Environment: LMP_TLSPH, TLSPH_PYTHON, FORCE=0 to keep finished runs,
# PROGRESS=0 to silence the progress lines.
set -eu
cd "$(dirname "$0")"
py="${TLSPH_PYTHON:-/usr/bin/python3}"
export PROGRESS="${PROGRESS:-1}"
variant="${VARIANT:-recommended}"
mkdir -p out
start=$(date +%s)
case "$variant" in
  recommended)
    bash ../crack-branching/run.sh
    CASES=fine bash ../kalthoff-2d/run.sh
    runs=(../crack-branching/out/crack-branching ../kalthoff-2d/out/kalthoff-2d)
    summary=out/summary.txt ;;
  thesis)
    VARIANT=thesis bash ../crack-branching/run.sh
    NAME=kalthoff-2d-thesis CASES=fine bash ../kalthoff-2d/run.sh -var model thesis
    runs=(../crack-branching/out/crack-branching-thesis ../crack-branching/out/crack-branching-thesis-h2
          ../kalthoff-2d/out/kalthoff-2d-thesis)
    summary=out/summary-thesis.txt ;;
  *) echo "examples/fracture/run.sh: VARIANT must be recommended or thesis, not '$variant'" >&2
     exit 1 ;;
esac
{
  for r in "${runs[@]}"; do
    d=$(dirname "$r"); n=$(basename "$r")
    cat "$d/summary-$n.txt"; echo
    cp -f "$r.montage.png" "$r.speed.png" out/ 2>/dev/null || true
  done
  echo "wall time of this job: $(( $(date +%s) - start )) s (1 MPI rank)"
} > "$summary"
if [ "$variant" = recommended ]; then
  "$py" overview.py ../crack-branching/out/crack-branching ../kalthoff-2d/out/kalthoff-2d \
    -o out/overview.png || echo "overview.py failed (matplotlib?)"
  # the numbers README shows, and its table (report.py write README.md
  # out/results.json puts them there; examples/fracture/results.json is the
  # committed record, checked against README by ctest project.make_run_table)
  "$py" report.py extract ../crack-branching/out/crack-branching ../kalthoff-2d/out/kalthoff-2d \
    -o out/results.json && "$py" report.py table out/results.json > out/table.md \
    && { echo; cat out/table.md; } >> "$summary"
fi
cat "$summary"
echo "summary: examples/fracture/$summary; pictures: examples/fracture/out/*.png"
