#!/bin/bash
# Main case of the 2D cantilever (thesis section 3.1.1), about 1 minute on one core:
# dx = 1 mm (1030 particles), plane strain, P = 17.5 kN (alpha = 9.10), quadratic
# gradient, dynamic relaxation by kinetic damping (fix tlsph/relax) from a step load.
# Writes out/cantilever-2d.{log,dat,final.dump}, out/summary.txt and out/cantilever-2d.png.
#   bash run.sh [extra -var NAME VALUE pairs for in.cantilever-2d]
# Environment: LMP_TLSPH (default ../../build/lmp_tlsph), TLSPH_PYTHON, NP (MPI ranks).
set -eu
cd "$(dirname "$0")"
py="${TLSPH_PYTHON:-/usr/bin/python3}"
mkdir -p out
FORCE=1 ../common/run_case.sh in.cantilever-2d out cantilever-2d \
  -var dx 0.001 -var P 17500 -var plane strain -var grad quadratic -var cfl 0.16 \
  -var damp relax -var ramp 0 -var hold 4 -var tol 1e-6 -var final 1 "$@"
key=2d_$(sed -n 's/.*plane=\([a-z]*\).*/\1/p' out/cantilever-2d.dat | head -1)_P$(sed -n 's/.* P=\([0-9.]*\) .*/\1/p' out/cantilever-2d.dat | head -1)
"$py" ../common/summarise_run.py out/cantilever-2d --dim 2 --fe-key "$key" \
  --png out/cantilever-2d.png | tee out/summary.txt
echo "plot: out/cantilever-2d.png"
