# tlsph: set-up, build, main example, tests. On a fresh Debian 12 (as root):
#   make run     installs what is missing, builds, runs the main example
#   make test    same set-up and build, then the whole test suite (ctest)
# Caches (LAMMPS source, PLUGIN-enabled LAMMPS) live outside the checkout, in
# $(TLSPH_CACHE) (default ~/.cache/tlsph): a second run is fast.

BUILD        ?= build
MAIN_EXAMPLE ?= fracture
VARIANT      ?= recommended
JOBS         ?= 2
PYTHON       ?= /usr/bin/python3
CMAKE_ARGS   ?=
FUZZ_TIME    ?= 300

SHELL := /bin/bash
BUILD_ABS = $(abspath $(BUILD))

# exported to the scripts, the examples and the tests
export TLSPH_BUILD = $(BUILD_ABS)
export TLSPH_PYTHON = $(PYTHON)
export LMP_TLSPH = $(BUILD_ABS)/lmp_tlsph
export TLSPH_PLUGIN = $(BUILD_ABS)/tlsphplugin.so

.PHONY: all setup configure build run test test-sanitize fuzz bench bench-instructions bench-compare bench-scaling bench-phases \
        bench-pareto bench-roofline bench-kokkos kokkos kokkos-cuda kokkos-stock kk-plugin clean \
        gpu-bundle gpu-bundle-host gpu-check-host

all: build

setup:
	bash scripts/setup.sh >/dev/null

# setup.sh prints the matching LAMMPS source tree as its only stdout line;
# cmake runs when the build dir is new, the source tree changed or CMAKE_ARGS
# are given (later CMakeLists.txt edits re-run it through ninja anyway)
configure:
	@set -e; src="$$(bash scripts/setup.sh)"; \
	if [ ! -f "$(BUILD)/build.ninja" ] || [ -n "$(CMAKE_ARGS)" ] || \
	   ! grep -qxF "LAMMPS_SOURCE_DIR:PATH=$$src" "$(BUILD)/CMakeCache.txt" 2>/dev/null; then \
	  echo "cmake -S . -B $(BUILD) -G Ninja -DLAMMPS_SOURCE_DIR=$$src $(CMAKE_ARGS)"; \
	  cmake -S . -B "$(BUILD)" -G Ninja -DLAMMPS_SOURCE_DIR="$$src" \
	        -DTLSPH_PYTHON=$(PYTHON) $(CMAKE_ARGS); \
	fi

build: configure
	ninja -C "$(BUILD)" -j$(JOBS)

run: build
	@set -e; ex=examples/$(MAIN_EXAMPLE); \
	if [ -f "$$ex/run.sh" ]; then echo "running $$ex/run.sh (VARIANT=$(VARIANT))"; VARIANT=$(VARIANT) bash "$$ex/run.sh"; \
	elif [ -f "$$ex/Makefile" ]; then $(MAKE) -C "$$ex"; \
	else echo "make run: no $$ex/run.sh (or Makefile): main example '$(MAIN_EXAMPLE)' missing" >&2; exit 1; fi

test: build
	ctest --test-dir "$(BUILD)" --output-on-failure --parallel $(JOBS)

# the unit tests, the shortened example decks and a plugin load/run/clear leak
# check under AddressSanitizer + UndefinedBehaviorSanitizer, in build-sanitize/
# (30-45 min the first time on 2 cores; not part of `make test`, see README)
test-sanitize: setup
	JOBS=$(JOBS) bash scripts/test-sanitize.sh

# a bounded-time libFuzzer run of the pair_style / pair_coeff / material-file
# parsers, FUZZ_TIME seconds (clang, in build-fuzz/; doc/fuzz.md; not part of
# `make test`: the instrumented build takes about 3 min)
fuzz: setup
	JOBS=$(JOBS) bash scripts/fuzz-parser.sh $(FUZZ_TIME)

# a LAMMPS with KOKKOS (host, Kokkos Serial: Debian's libtrilinos-kokkos-dev),
# PERI and PLUGIN from the same Debian source, cached in $(TLSPH_CACHE) and
# keyed by version; prints its lmp (doc/kokkos.md; about 25 min the first time
# on 2 shared cores). Our styles: `plugin load build/tlsphplugin.so`, without -k
kokkos:
	@TLSPH_JOBS=$(JOBS) bash scripts/build-lammps-plugin.sh kokkos

# the same with the Kokkos CUDA backend for NVIDIA GPUs: native sm_90 (Hopper,
# + compute_90 PTX) and sm_80 (Ampere) code, CUDA toolkit in /usr/local/cuda
# (TLSPH_CUDA_HOME), Kokkos 3.4.01 from Debian's trilinos source (downloaded
# once, 166 MB) patched for CUDA 13; our package compiled in (rebuilt
# incrementally on every call); prints its lmp. It only compiles without a GPU
# (doc/kokkos-cuda.md; about 50 min the first time on 2 shared cores)
kokkos-cuda:
	@TLSPH_JOBS=$(JOBS) bash scripts/build-lammps-plugin.sh kokkos-cuda

# the /kk styles as a plugin (doc/kokkos.md, "Loading the /kk styles as a
# plugin"): kokkos-stock builds the same KOKKOS LAMMPS without our package
# (cached like kokkos; about 12 min the first time on 2 cores),
# kk-plugin the whole package as $(BUILD)/kkplugin/tlsphkkplugin.so for it
# (about 1 min the first time here, then incremental); each prints its path
kokkos-stock:
	@TLSPH_JOBS=$(JOBS) bash scripts/build-lammps-plugin.sh kokkos-stock

kk-plugin: setup
	@TLSPH_JOBS=$(JOBS) bash scripts/build-kk-plugin.sh "$(BUILD_ABS)/kkplugin"

# the GPU bundle (doc/kokkos-cuda.md): a static LAMMPS with KOKKOS/CUDA for
# sm_90 (+ PTX), PERI and our package, MPI STUBS, packed into gpu-bundle/
# (git-ignored, <= 48 MiB with its fallback sources) to travel with the
# checkout to a GPU machine, where `bash scripts/gpu-check.sh` runs the
# device check; gpu-bundle-host builds its host twin (Kokkos Serial) and
# gpu-check-host runs the check against it, as CI does
gpu-bundle: setup
	@TLSPH_JOBS=$(JOBS) bash scripts/gpu-bundle.sh cuda

gpu-bundle-host: setup
	@TLSPH_JOBS=$(JOBS) bash scripts/gpu-bundle.sh host

gpu-check-host: gpu-bundle-host
	bash scripts/gpu-check.sh --host

# tlsph/kk against tlsph on the host, side by side in the make-kokkos LAMMPS
# (bench/kokkos.md; a few minutes)
bench-kokkos:
	@bash bench/kokkos.sh

bench: build
	@if [ -f bench/run.sh ]; then bash bench/run.sh; \
	else echo "make bench: bench/run.sh not present yet" >&2; exit 1; fi

# instruction counts per step (valgrind callgrind): the cost comparisons that
# load on a shared machine blurs (doc/bench.md, "Instruction counts")
bench-instructions: build
	bash bench/instructions.sh

# side by side with MACHDYN's smd/tlsph in one LAMMPS binary (builds that
# LAMMPS once, cached in $(TLSPH_CACHE)); doc/bench.md, "Side by side"
bench-compare: build
	bash bench/compare.sh

# two MPI ranks against one on the 2D block, alternating pairs
# (bench/scaling.md; doc/bench.md, the table of the goals of issue 24)
bench-scaling: build
	bash bench/scaling.sh

# speed per phase of the step: simd no against the SIMD step per
# instruction set (bench/phases.md; doc/bench.md, "Speed per phase")
bench-phases: build
	bash bench/phases.sh

# speed against error of the benchmarks (doc/pareto.md, doc/pareto-*.png;
# about an hour of one core; resumable, FORCE=1 reruns)
bench-pareto: build
	bash bench/pareto.sh

# the step against this CPU's ceilings (doc/roofline.md, doc/roofline.png;
# needs perf and valgrind)
bench-roofline: build
	bash bench/roofline.sh

clean:
	rm -rf "$(BUILD)"
