#!/bin/bash
# Main case of the 3D cantilever (thesis section 3.1.2) at reduced resolution,
# about 1-2 minutes on one core: dx = 2 mm (1,325 particles), P = 17.5 kN
# (alpha = 1), quadratic gradient, kinetic damping (fix tlsph/relax) from a step
# load. The thesis resolution dx = 1 mm (10,300 particles) is in studies.sh
# (about 10 min of CPU): bash run.sh -var dx 0.001 -var cfl 0.3 -var tol 1e-5
# Writes out/cantilever-3d.{log,dat,final.dump}, out/summary.txt, out/cantilever-3d.png.
# Environment: LMP_TLSPH (default ../../build/lmp_tlsph), TLSPH_PYTHON, NP (MPI ranks).
set -eu
cd "$(dirname "$0")"
py="${TLSPH_PYTHON:-/usr/bin/python3}"
mkdir -p out
FORCE=1 ../common/run_case.sh in.cantilever-3d out cantilever-3d \
  -var dx 0.002 -var P 17500 -var grad quadratic -var cfl 0.16 \
  -var damp relax -var ramp 0 -var hold 4 -var tol 1e-6 -var final 1 "$@"
"$py" ../common/summarise_run.py out/cantilever-3d --dim 3 --fe-key 3d_P17500 \
  --png out/cantilever-3d.png | tee out/summary.txt
echo "plot: out/cantilever-3d.png"
