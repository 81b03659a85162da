#!/usr/bin/env bash
# make fuzz: a bounded-time libFuzzer run of the package's input parsers
# (pair_style arguments, inline pair_coeff, material files; doc/fuzz.md).
#   bash scripts/fuzz-parser.sh [SECONDS]      (default 300; make fuzz FUZZ_TIME=...)
# Builds the harness (fuzz/, clang++ with -fsanitize=fuzzer,address,undefined)
# into build-fuzz/ (first time about 3 min on 2 cores), writes the seed corpus,
# runs one fuzzer process for SECONDS and fails (exit 1) when it stopped on a
# finding: a crash, a sanitizer report, a leak, a timeout (-timeout=10 s per
# input), memory over -rss_limit_mb, or a process exit in an input (an error
# path the harness does not catch). Findings are in build-fuzz/artifacts/;
# replay one with  build-fuzz/tlsph_fuzz_parser FILE  (TLSPH_FUZZ_VERBOSE=1
# prints each command and error). The grown corpus stays in build-fuzz/corpus
# for the next run.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
TIME="${1:-${FUZZ_TIME:-300}}"
B="${FUZZ_BUILD:-$ROOT/build-fuzz}"
JOBS="${JOBS:-2}"
RSS_MB="${FUZZ_RSS_MB:-2048}"
[[ "$TIME" =~ ^[0-9]+$ ]] || { echo "fuzz-parser.sh: SECONDS must be an integer, got '$TIME'" >&2; exit 2; }

src=$(bash "$ROOT/scripts/setup.sh")

# clang++ and libFuzzer (Debian: clang, libclang-rt-14-dev)
fuzzer_lib() {
  command -v clang++ >/dev/null 2>&1 || return 1
  local lib
  lib="$(clang++ -print-resource-dir)/lib/linux/libclang_rt.fuzzer-x86_64.a"
  [ -f "$lib" ]
}
if ! fuzzer_lib; then
  SUDO=()
  [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1 && SUDO=(sudo -E)
  echo "fuzz-parser.sh: installing clang and libclang-rt-14-dev (libFuzzer)" >&2
  "${SUDO[@]}" apt-get install -y -q --no-install-recommends clang libclang-rt-14-dev >&2 ||
    { "${SUDO[@]}" apt-get update -q >&2 &&
      "${SUDO[@]}" apt-get install -y -q --no-install-recommends clang libclang-rt-14-dev >&2; }
  fuzzer_lib || { echo "fuzz-parser.sh: clang++ with libFuzzer not found" >&2; exit 2; }
fi

if ! grep -qxF "LAMMPS_SOURCE_DIR:PATH=$src" "$B/CMakeCache.txt" 2>/dev/null; then
  CXX=clang++ cmake -S "$ROOT/fuzz" -B "$B" -G Ninja -DLAMMPS_SOURCE_DIR="$src"
fi
nice ninja -C "$B" -j"$JOBS"

rm -rf "$B/seeds" "$B/artifacts" "$B/tmp"
mkdir -p "$B/corpus" "$B/artifacts" "$B/tmp"
export TLSPH_FUZZ_TMPDIR="$B/tmp"    # the material file of each input
/usr/bin/python3 "$ROOT/fuzz/seeds.py" "$B/seeds" >/dev/null

# one process, one job. Leak detection stays on: libFuzzer checks each input
# whose allocations outlive it (the harness keeps Open MPI's start-up
# allocations out of it, fuzz_parser.cpp)
export ASAN_OPTIONS="abort_on_error=0:detect_stack_use_after_return=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cd "$B"
echo "fuzz-parser.sh: fuzzing for ${TIME} s (log: $B/fuzz.log)"
set +e
nice ./tlsph_fuzz_parser corpus seeds -dict="$ROOT/fuzz/tlsph.dict" \
  -max_total_time="$TIME" -timeout=10 -rss_limit_mb="$RSS_MB" -max_len=4096 \
  -artifact_prefix=artifacts/ -print_final_stats=1 -print_pcs=0 > fuzz.log 2>&1
rc=$?
set -e
grep -E "^#[0-9]+ +(INITED|DONE)" fuzz.log | tail -n 2 || true
grep -E "^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb|new_units_added)" \
  fuzz.log || true
n=$(find artifacts -type f | wc -l)
if [ "$rc" -ne 0 ] || [ "$n" -ne 0 ]; then
  grep -E "ERROR: |runtime error|SUMMARY|libFuzzer: " fuzz.log | head -n 20 || true
  echo "fuzz-parser.sh: FAILED (exit $rc, $n finding(s) in $B/artifacts: $(ls artifacts | tr '\n' ' '))"
  exit 1
fi
echo "fuzz-parser.sh: PASSED (${TIME} s, no finding; corpus: $(ls corpus | wc -l) inputs)"
