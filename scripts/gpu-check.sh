#!/usr/bin/env bash
# The device check (doc/kokkos-cuda.md, "The device check"): ONE command on
# the GPU machine, from the root of the checkout with gpu-bundle/ in it
# (make gpu-bundle here first), finishing in at most 7 minutes:
#
#   bash scripts/gpu-check.sh [--out DIR] [--budget S] [--sizes "0.25 1 4 16"]
#
#   1. the machine: nvidia-smi, the driver and glibc against what the bundle
#      needs (MANIFEST; stops with a message when either is too old), the
#      versions of the bundle's LAMMPS and Kokkos (env.txt)
#   2. the /kk tests of CI on GPU 0 (unittest/kokkos/check_kokkos.py --gpu
#      --max-ranks 1; the references are the CPU styles of the same binary):
#      forces (2D/3D, isotropic/orthotropic, both hourglass forms and
#      gradient orders, newton on/off), a restart written on the GPU read by
#      the CPU styles and back, damage (a shortened crack-branching run: the
#      same broken-bond set and damage as the CPU style, energies), transfers
#      (an ordinary step copies nothing between host and device: the atom
#      style's DualView ledger), cache (the bond cache built on the GPU equals
#      the host build, every rebuild compared) (tests.txt)
#   3. speed: 3D tlsph/damage/kk, FP64, bench/in.gpu at about 0.25, 1, 4 and
#      16 M particles, newton off (the two smallest also newton on, and
#      with the bond cache in rows instead of the sliced layout): ns per
#      particle-step of the
#      ordinary steps, and the time of one neighbor rebuild (bond cache
#      built on the GPU from the bond fix's partner rows); a size is listed
#      as skipped when the budget (330 s from the start, --budget) is spent,
#      when the last run's time scaled by the particle count would overrun
#      it, or when a run was cut at it (speed.csv)
#   4. the device's copy bandwidth (bin/gpu_bandwidth), the roofline ceiling
#      (bandwidth.txt)
#   3a. the thesis's 3D Kalthoff-Winkler deck with -sf kk: time to solution
#      against the 2 CPU cores of the build machine (kalthoff3d.txt)
#   2b. a kernel profile of the step with Nsight Compute where the machine
#      has it (ncu.txt)
#   summary.md: the tables; logs.tar.xz: every LAMMPS log. At most 8 files,
#   in DIR (default: $OUT when set, else gpu-check-out/).
#
#   bash scripts/gpu-check.sh --host [--lmp PATH]   the same script on the
#      host twin (make gpu-bundle-host; Kokkos Serial, MPI STUBS), small sizes,
#      no GPU steps: what CI runs (ctest gpu.check_host), so that the script
#      and its decks are tested on every commit.
#
# Tolerances: on the host backend the /kk styles are bitwise the CPU styles
# up to summation order (1e-12, as in CI). On the GPU nvcc contracts
# multiply-adds into FMAs (its default; g++ for x86-64 emits none) and the
# math library differs: 1e-10 relative to the largest value for forces,
# stress, energies and states (--tol), while the broken-bond sets and the
# damage must still be identical.
set -uo pipefail
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)
REPO=$(cd "$HERE/.." && pwd -P)
MODE=gpu LMP="" OUTD=${OUT:-$REPO/gpu-check-out} BUDGET=330 SIZES=""
while [ $# -gt 0 ]; do
  case "$1" in
    --host) MODE=host ;;
    --lmp) LMP=$2; shift ;;
    --out) OUTD=$2; shift ;;
    --budget) BUDGET=$2; shift ;;
    --sizes) SIZES=$2; shift ;;
    *) echo "gpu-check.sh: unknown option '$1' (allowed: --host --lmp PATH --out DIR --budget S --sizes LIST)" >&2; exit 2 ;;
  esac
  shift
done
T0=$(date +%s)
elapsed() { echo $(( $(date +%s) - T0 )); }
mkdir -p "$OUTD"
OUTD=$(cd "$OUTD" && pwd -P)
WORK=$(mktemp -d /tmp/tlsph-gpu-check.XXXXXX)
trap 'rm -rf "$WORK"' EXIT
say() { printf 'gpu-check.sh [%4ds] %s\n' "$(elapsed)" "$*" >&2; }
fail=0

# --- 1. the machine --------------------------------------------------------
{
  echo "# gpu-check.sh $(date -u +%Y-%m-%dT%H:%MZ), mode $MODE, checkout $(git -C "$REPO" describe --always --dirty 2>/dev/null || echo '?')"
  echo "## machine"; uname -a; nproc; free -g | head -2
  echo "glibc $(getconf GNU_LIBC_VERSION 2>/dev/null)"
  python3 -c 'import sys; print("python", sys.version.split()[0])'
  python3 -c 'import numpy; print("numpy", numpy.__version__)' 2>/dev/null || echo "numpy: not installed (not needed)"
} > "$OUTD/env.txt"
if [ "$MODE" = gpu ]; then
  BUNDLE="$REPO/gpu-bundle/tlsph-gpu-bundle.tar.xz"
  [ -f "$BUNDLE" ] || { echo "gpu-check.sh: no $BUNDLE: run 'make gpu-bundle' on the build machine first" >&2; exit 2; }
  tar -C "$WORK" -xJf "$BUNDLE"
  B="$WORK/tlsph-gpu"
  LMP=${LMP:-$B/bin/lmp}
  cat "$B/MANIFEST" >> "$OUTD/env.txt"
  need_glibc=$(sed -n 's/^glibc_min //p' "$B/MANIFEST")
  have_glibc=$(getconf GNU_LIBC_VERSION | awk '{print $2}')
  if [ "$(printf '%s\n%s\n' "$need_glibc" "$have_glibc" | sort -V | head -n1)" != "$need_glibc" ]; then
    echo "gpu-check.sh: this machine's glibc is $have_glibc, the bundle needs $need_glibc or newer: build on the machine with gpu-bundle/tlsph-gpu-sources.tar.xz (fallback-build.sh), then --lmp" >&2
    exit 3
  fi
  if ! command -v nvidia-smi >/dev/null; then
    echo "gpu-check.sh: no nvidia-smi: no NVIDIA driver on this machine" >&2; exit 3
  fi
  { echo "## nvidia-smi"; nvidia-smi; nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv; } >> "$OUTD/env.txt" 2>&1
  need_drv=$(sed -n 's/^driver_min //p' "$B/MANIFEST")
  have_drv=$(nvidia-smi --query-gpu=driver_version --format=csv,noheader | head -n1 | cut -d. -f1)
  if [ -z "$have_drv" ] || [ "$have_drv" -lt "$need_drv" ]; then
    echo "gpu-check.sh: driver ${have_drv:-none}, the bundle's CUDA runtime needs R$need_drv or newer" >&2; exit 3
  fi
  KFLAGS=(-k on g 1); TOL=1e-10; GPU=(--gpu)
  [ -n "$SIZES" ] || SIZES="0.25 1 4 16"
else
  LMP=${LMP:-$REPO/gpu-bundle/host/bin/lmp}
  [ -x "$LMP" ] || { echo "gpu-check.sh: no host twin $LMP: make gpu-bundle-host" >&2; exit 2; }
  KFLAGS=(-k on t 1); TOL=1e-12; GPU=()
  [ -n "$SIZES" ] || SIZES="0.0005 0.002"
fi
{ echo "## lmp -h (head)"; "$LMP" -h 2>&1 | sed -n '1,/^Installed packages/p' | grep -E 'LAMMPS|KOKKOS|OS:|Compiler|C\+\+|Accelerator' ; "$LMP" -h 2>&1 | grep -A3 '^Installed packages' | grep -v '^ *$'; } >> "$OUTD/env.txt"
say "machine checked: $MODE, lmp $LMP"

# --- 2. the /kk tests ------------------------------------------------------
: > "$OUTD/tests.txt"
for c in forces restart damage transfers cache; do
  mkdir -p "$WORK/t_$c"
  say "test $c"
  if python3 "$REPO/unittest/kokkos/check_kokkos.py" --lmp "$LMP" --case "$c" --workdir "$WORK/t_$c" \
       --max-ranks 1 --tol "$TOL" "${GPU[@]}" > "$WORK/t_$c.txt" 2>&1; then
    r=passed
  else
    r=FAILED; fail=1
  fi
  { echo "### $c: $r"; cat "$WORK/t_$c.txt"; echo; } >> "$OUTD/tests.txt"
  say "test $c: $r"
done

# --- 2b. a kernel profile (Nsight Compute, where the machine has it) -------
# The step's kernels on 0.25 M particles of bench/in.gpu (newton off, the
# default layout): duration, DRAM and L1/L2 throughput against the device's
# peak, SM throughput, occupancy (ncu.txt; the summary lists them). Needs
# access to the GPU's performance counters; without it ncu says so.
if [ "$MODE" = gpu ]; then
  NCU=$(command -v ncu || ls /usr/local/cuda/bin/ncu /usr/local/cuda-*/bin/ncu 2>/dev/null | head -n1)
  if [ -n "$NCU" ] && [ "$(elapsed)" -lt $((BUDGET - 200)) ]; then
    say "kernel profile ($NCU)"
    (cd "$WORK" && timeout 90 "$NCU" --section SpeedOfLight --section Occupancy --section LaunchStats \
       --kernel-name-base demangled --kernel-name regex:"force_kernel|break_kernel|deformation_kernel|damage_step|smooth_kernel|FixNVE" \
       --launch-skip 8 --launch-count 10 --csv "$LMP" "${KFLAGS[@]}" -sf kk \
       -pk kokkos newton off neigh full comm device -in "$REPO/bench/in.gpu" -var n 63 -var nsteps 3 \
       -var nrebuild 1 -log ncu_lammps.log -screen none) > "$OUTD/ncu.txt" 2>&1
    echo "(ncu exit $?)" >> "$OUTD/ncu.txt"
  else
    echo "no kernel profile: ${NCU:-no ncu on this machine}${NCU:+ (budget)}" > "$OUTD/ncu.txt"
  fi
fi

# --- 3a. the thesis's 3D Kalthoff-Winkler deck: time to solution ---------
# examples/kalthoff-3d at the thesis resolution (dx = 1 mm) with the thesis's
# model, -sf kk, to its end (100 us): wall time, against 943 s measured on
# the 2 shared cores of the build machine (examples/kalthoff-3d/README.md);
# the copy report of the run (its fixes without a Kokkos variant: fix move
# of the impactor, fix halt, fix ave/time). Host twin: dx 2.5 mm to 2 us.
K3D=(-var model thesis -var tdump 1 -var tfull 0 -var timg 0 -var out k3d)
[ "$MODE" = host ] && K3D+=(-var dx 0.0025 -var tend 2e-6)
if [ "$(elapsed)" -lt $((BUDGET - 150)) ]; then
  say "the 3D Kalthoff-Winkler deck (thesis model, -sf kk)"
  t1=$(date +%s.%N)
  (cd "$WORK" && timeout 150 "$LMP" "${KFLAGS[@]}" -sf kk -pk kokkos newton off neigh full comm device \
     -in "$REPO/examples/kalthoff-3d/in.kalthoff-3d" "${K3D[@]}" -log kalthoff3d.log -screen none) > /dev/null 2>&1
  st=$?
  t2=$(date +%s.%N)
  python3 - "$WORK/kalthoff3d.log" "$st" "$t1" "$t2" > "$OUTD/kalthoff3d.txt" <<'K3DPARSE'
import re, sys
log, st, t1, t2 = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
s = open(log).read() if log else ""
loops = re.findall(r"^Loop time of (\S+) on \d+ procs for (\d+) steps with (\d+) atoms", s, re.M)
print("3D Kalthoff-Winkler, thesis model, -sf kk: exit %d, wall %.1f s (LAMMPS start to end)" % (st, t2 - t1))
if loops:
    t, n, nat = float(loops[-1][0]), int(loops[-1][1]), int(loops[-1][2])
    print("main run: %d steps, %d particles, loop time %.2f s, %.2f ns per particle-step"
          % (n, nat, t, t / max(1, n * nat) * 1e9))
print("reference: 943 s wall on the 2 shared cores of the build machine (2 MPI ranks, "
      "examples/kalthoff-3d/README.md)")
for line in re.findall(r"^tlsph/kk (?:copies: (?:host-fix|comm-host|host-code|atom) .*|bond cache: .*)$", s, re.M)[-8:]:
    print(line)
K3DPARSE
  [ "$st" = 0 ] || { [ "$st" = 124 ] && echo "cut at 150 s" >> "$OUTD/kalthoff3d.txt" || fail=1; }
else
  echo "3D Kalthoff-Winkler: skipped (budget)" > "$OUTD/kalthoff3d.txt"
fi

# --- 3. speed --------------------------------------------------------------
echo "size_M,natoms,newton,layout,nsteps,loop_s,ns_per_particle_step,rebuild_steps,rebuild_loop_s,ms_per_rebuild,status" > "$OUTD/speed.csv"
# A run's wall time is mostly its set-up on one host core (the partner
# search, the first bond cache), which grows with the particles: a size is
# skipped when the last run's time scaled by the particle count would not
# end before the budget (a run started anyway would be cut and wasted).
# Each size runs newton off with the default bond layout (sliced, chunks of
# 32 particles on a GPU); the two smallest also newton on, and newton off
# with rows (TLSPH_KK_SLICE=1), and with the partner rows read as columns
# (TLSPH_KK_PK_COLUMNS=1): side-by-side comparisons (the
# larger sizes' set-up on the host takes most of a run's time: 4 M
# particles about 100 s).
last_t="" last_n=""
speed_run() {    # speed_run M NEWTON SLICE ("" = default) [PK_COLUMNS]
  local m=$1 newton=$2 sl=$3 pc=${4:-} n left pred tag ns t1 st lay
  n=$(python3 -c "print(max(4, round(($m * 1e6) ** (1.0 / 3.0))))")
  lay=${sl:-default}${pc:+ + columns}
  left=$((BUDGET + 40 - $(elapsed)))
  pred=0
  [ -n "$last_t" ] && pred=$(python3 -c "print(int($last_t * $n ** 3 / $last_n ** 3) + 1)")
  if [ "$(elapsed)" -ge "$BUDGET" ] || [ "$pred" -gt "$left" ]; then
    echo "$m,,$newton,$lay,,,,,,,skipped (budget ${BUDGET}s: about ${pred}s needed; ${left}s left)" >> "$OUTD/speed.csv"
    say "speed $m M particles, newton $newton, layout $lay: skipped (about ${pred}s needed, ${left}s left)"
    return
  fi
  tag="speed_${m}M_${newton}${sl:+_slice$sl}${pc:+_columns}"
  say "speed $m M particles (n = $n), newton $newton, layout $lay"
  ns=100; [ "$MODE" = host ] && ns=10
  t1=$(date +%s)
  (cd "$WORK" && TLSPH_KK_SLICE=$sl TLSPH_KK_PK_COLUMNS=$pc timeout "$left" "$LMP" "${KFLAGS[@]}" -sf kk \
     -pk kokkos newton "$newton" neigh full comm device -in "$REPO/bench/in.gpu" \
     -var n "$n" -var nsteps "$ns" -var nrebuild 5 -log "$tag.log" -screen none) > /dev/null 2>&1
  st=$?
  last_t=$(( $(date +%s) - t1 )) last_n=$n
  python3 - "$WORK/$tag.log" "$m" "$newton" "$st" >> "$OUTD/speed.csv" <<'PARSE'
import re, sys
log, m, newton, st = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
try:
    s = open(log).read()
except OSError:
    s = ""
loops = [(float(a), int(b), int(c)) for a, b, c in
         re.findall(r"^Loop time of (\S+) on \d+ procs for (\d+) steps with (\d+) atoms", s, re.M)]
lay = re.findall(r"layout: chunks of (\d+) particles: the last cache \S+ records for \S+ bonds on "
                 r"rank 0 = (\S+) % padding", s)
layout = ("C=%s (%s%% pad)" % lay[-1]) if lay else "?"
if "(partner rows read as columns)" in s:
    layout += " + columns"
if st == 124:
    print("%s,,%s,%s,,,,,,,skipped (timed out at the budget)" % (m, newton, layout))
    sys.exit(0)
if st != 0 or len(loops) != 3:
    err = re.findall(r"^ERROR.*$", s, re.M)
    print("%s,,%s,%s,,,,,,,FAILED (exit %d%s)" % (m, newton, layout, st,
                                                 ": " + err[0].replace(",", ";") if err else ""))
    sys.exit(0)
(_, _, nat), (t, ns, _), (tr, nr, _) = loops
per = t / (nat * ns) * 1e9
reb = (tr - t / ns * nr) / nr * 1e3
print("%s,%d,%s,%s,%d,%.4f,%.3f,%d,%.4f,%.2f,ok" % (m, nat, newton, layout, ns, t, per, nr, tr, reb))
PARSE
  tail -n1 "$OUTD/speed.csv" | grep -q ',FAILED' && fail=1
}
k=0
for m in $SIZES; do
  speed_run "$m" off ""
  if [ $k -lt 2 ]; then
    speed_run "$m" on ""
    speed_run "$m" off 1
    speed_run "$m" off "" 1
  fi
  k=$((k + 1))
done

# --- 4. bandwidth ----------------------------------------------------------
if [ "$MODE" = gpu ]; then
  "$B/bin/gpu_bandwidth" > "$OUTD/bandwidth.txt" 2>&1 || fail=1
else
  echo "no GPU (host twin): bandwidth not measured" > "$OUTD/bandwidth.txt"
fi

# --- summary ---------------------------------------------------------------
python3 - "$OUTD" "$MODE" "$(elapsed)" "$fail" <<'SUMMARY' > "$OUTD/summary.md"
import csv, os, re, sys
d, mode, secs, fail = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
print("# gpu-check.sh summary (%s, %s s)\n" % (mode, secs))
env = open(os.path.join(d, "env.txt")).read()
for k in ("commit", "glibc_min", "driver_min"):
    m = re.search(r"^%s (.*)$" % k, env, re.M)
    if m:
        print("- %s: %s" % (k, m.group(1)))
print("\n## tests\n")
for m in re.finditer(r"^### (\S+): (\S+)$", open(os.path.join(d, "tests.txt")).read(), re.M):
    print("- %s: %s" % (m.group(1), m.group(2)))
print("\n## speed (3D tlsph/damage/kk, FP64)\n")
print("| M particles | atoms | newton | bond layout | ns / particle-step | ms / rebuild | status |")
print("|---|---|---|---|---|---|---|")
for r in csv.DictReader(open(os.path.join(d, "speed.csv"))):
    print("| %s | %s | %s | %s | %s | %s | %s |" % (r["size_M"], r["natoms"], r["newton"], r["layout"],
          r["ns_per_particle_step"], r["ms_per_rebuild"], r["status"]))
print("\n## 3D Kalthoff-Winkler, time to solution\n")
for line in open(os.path.join(d, "kalthoff3d.txt")):
    print("    " + line.rstrip())
try:
    if os.path.exists(os.path.join(d, "ncu.txt")):
        print("\n## kernel profile (ncu, 0.25 M particles)\n")
        rows = {}
        want = ("Duration", "DRAM Throughput", "Memory Throughput", "L1/TEX Cache Throughput",
                "L2 Cache Throughput", "Compute (SM) Throughput", "Achieved Occupancy",
                "Registers Per Thread", "Block Size")
        text = open(os.path.join(d, "ncu.txt")).read()
        for r in csv.reader(l for l in text.splitlines() if l.startswith('"')):
            if len(r) < 15 or r[0] == "ID":
                continue
            name = r[4]
            short = None
            for pat in (r"force_kernel\w*<[^>]*>", r"break_kernel<[^>]*>", r"deformation_kernel<[^>]*>",
                        r"FixNVEKokkos", r"PairTLSPHDamageKokkos", r"\w*Kokkos\w*"):
                short = short or re.search(pat, name)
            key = (r[0], short.group(0) if short else name[:40])
            if r[12] in want:
                rows.setdefault(key, {})[r[12]] = r[14] + (" " + r[13] if r[13] and r[13] != "%" else "%" if r[13] == "%" else "")
        if rows:
            print("| launch | kernel | " + " | ".join(want) + " |")
            print("|---" * (len(want) + 2) + "|")
            for (i, k), v in sorted(rows.items(), key=lambda kv: int(kv[0][0])):
                print("| %s | %s | %s |" % (i, k, " | ".join(v.get(w, "") for w in want)))
        else:
            for line in text.splitlines()[-6:]:
                print("    " + line)
except Exception as e:    # the profile is extra: never lose the summary over it
    print("(ncu.txt not parsed: %s)" % e)
print("\n## bandwidth\n")
for line in open(os.path.join(d, "bandwidth.txt")):
    print("    " + line.rstrip())
print("\nverdict: %s" % ("FAILED" if fail != "0" else "all passed"))
SUMMARY
(cd "$WORK" && find . -name '*.log' | tar -cf - -T - | xz -6 > "$OUTD/logs.tar.xz")
cat "$OUTD/summary.md"
exit $fail
