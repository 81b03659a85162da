#!/usr/bin/env bash
# The cost of one neighbor rebuild of the /kk styles against one ordinary
# step, on the Kokkos host backend (make kokkos LAMMPS, Serial, 1 rank):
# bench/in.gpu (3D tlsph/damage/kk, FP64) at n^3 particles, its ordinary
# steps and its steps with a neighbor build each (check no), with the bond
# cache built on the device (the default: the partners resolved and the
# bond math run in Kokkos kernels; x0c set on the host) and on the host
# (TLSPH_KK_HOST_CACHE=1: the whole cache built on the host and uploaded), alternating, REPEAT times,
# medians; in the device model (TLSPH_KK_DEVICE_MODEL=1), so that the copy
# ledger gives the bytes each rebuild moves to the device. Writes
# bench/rebuild.md (doc/kokkos-cuda.md cites it).
#   bash bench/rebuild.sh            N=30 (27,000 particles), REPEAT=3
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(dirname "$HERE")"
LMP=$(bash "$ROOT/scripts/build-lammps-plugin.sh" kokkos | tail -n1)
N=${N:-30}
REPEAT=${REPEAT:-3}
NS=${NS:-20}
NR=${NR:-10}
OUT="$HERE/out/rebuild"; mkdir -p "$OUT"
COMMIT=$(git -C "$ROOT" describe --always --dirty)
: > "$OUT/runs.txt"
for r in $(seq "$REPEAT"); do
  for mode in device host; do
    env=(TLSPH_KK_DEVICE_MODEL=1)
    [ "$mode" = host ] && env+=(TLSPH_KK_HOST_CACHE=1)
    (cd "$OUT" && env "${env[@]}" "$LMP" -k on -sf kk -pk kokkos newton off neigh full comm device \
       -in "$HERE/in.gpu" -var n "$N" -var nsteps "$NS" -var nrebuild "$NR" \
       -log "$mode.$r.log" -screen none)
    echo "$mode $r $OUT/$mode.$r.log" >> "$OUT/runs.txt"
  done
done
python3 - "$OUT/runs.txt" "$COMMIT" "$N" "$NS" "$NR" "$REPEAT" "$(python3 -c "import sys; sys.path.insert(0, \"$HERE\"); import machine; print(machine.cpu_model())")" > "$HERE/rebuild.md" <<'PY'
import re, statistics, sys
runs, commit, n, ns, nr, rep, cpu = sys.argv[1:8]
by = {}
for line in open(runs):
    mode, r, log = line.split()
    s = open(log).read()
    loops = re.findall(r"^Loop time of (\S+) on \d+ procs for (\d+) steps with (\d+) atoms", s, re.M)
    reports = s.split("tlsph/kk copies: run of ")
    # bytes uploaded in the rebuild run (the third run's report)
    up = 0.0
    last = reports[-1] if len(reports) > 3 else ""
    for m in re.finditer(r"^tlsph/kk copies: own (\S+) (\d+) (\d+) (\S+)$", last, re.M):
        if int(m.group(2)) > 0:
            up += float(m.group(4))
    (_, _, nat), (t, s1, _), (tr, s2, _) = [(float(a), int(b), int(c)) for a, b, c in loops]
    step = t / s1
    reb = (tr - step * s2) / s2
    parts = re.findall(r"^tlsph/kk bond cache: .*partners resolved (\S+) ms, .*; "
                       r"uploads (\S+) ms, bond math (\S+) ms", s, re.M)
    br = [float(x) for x in parts[-1]] if parts else [float("nan")] * 3
    by.setdefault(mode, []).append((step, reb, up / s2, nat, br))
nat = by["device"][0][3]
print("# Neighbor rebuild against ordinary step, /kk styles, Kokkos host backend\n")
print("Made by `bash bench/rebuild.sh` at commit %s: bench/in.gpu (3D tlsph/damage/kk, FP64), "
      "n = %s (%d particles), %s ordinary steps and %s steps with a neighbor build each, "
      "1 rank, Kokkos Serial (make kokkos LAMMPS, -O2), device model (copy ledger), "
      "alternating, %s repeats, medians. CPU: %s.\n" % (commit, n, nat, ns, nr, rep, cpu or "?"))
print("| bond cache built | ms per ordinary step | ms per rebuild (over a step) | rebuild / step | MB to the device per rebuild | of the rebuild: partner resolution / uploads / bond math kernel [ms] |")
print("|---|---|---|---|---|---|")
for mode, label in (("device", "on the device (Kokkos kernels)"), ("host", "on the host, uploaded (TLSPH_KK_HOST_CACHE=1)")):
    v = by[mode]
    st = statistics.median(x[0] for x in v) * 1e3
    rb = statistics.median(x[1] for x in v) * 1e3
    mb = statistics.median(x[2] for x in v)
    br = [statistics.median(x[4][k] for x in v) for k in range(3)]
    parts = "%.2f / %.2f / %.2f" % tuple(br) if mode == "device" else "(host build, not split)"
    print("| %s | %.2f | %.2f | %.2f | %.3f | %s |" % (label, st, rb, rb / st, mb, parts))
print("\nThe rebuild time includes LAMMPS's own neighbor build, exchange and borders "
      "(on the host in this LAMMPS version for a fix with per-atom data) and x0c (host); "
      "with the device build the partner resolution (tag -> index map, closest images, "
      "order) and the bond math are Kokkos kernels, here on the host backend (Serial, one "
      "core), whose copies are memcpy's. On a GPU the ordinary step is far cheaper, so the "
      "ratio is larger there (scripts/gpu-check.sh measures it).")
PY
cat "$HERE/rebuild.md"
