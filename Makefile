# `make demo` and `make test` work on a fresh machine: they create .venv and install into it.
PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed-stamp
# Where setup.py finds Voro++ (None: nowhere), rewritten only when that changes: Voro++
# installed, moved or removed since the last install rebuilds grainclass._voro.
VORO_FOUND := $(VENV)/.voro-found
KERNELS := $(wildcard src/grainclass/_kernels/*.py src/grainclass/_kernels/*/*.py) src/grainclass/_numba.py
KERNELS_STAMP := build/.kernels-stamp

# Seeds of the Poisson-Voronoi data set that `make figures` draws.
FIGURE_SEEDS ?= 100000
# One time step of a grain-growth simulation, one Surface Evolver file per grain.
GRAIN_GROWTH ?= tests/data/evolver/grain3d

.PHONY: all install voro FORCE demo figures test test-nojit test-lowest lint bench bench-prisms bench-voxels bench-parts fuzz reproduce-enumeration reproduce-voronoi reproduce-census bench-census voxel-study clean

all: lint test

$(VORO_FOUND): FORCE
	@mkdir -p $(VENV)
	@found="$$($(PYTHON) -c 'import setup; print(setup.find_voro())')" || exit 1; \
		[ "$$found" = "$$(cat $@ 2>/dev/null)" ] || echo "$$found" > $@

$(STAMP): pyproject.toml setup.py src/grainclass/_voro.cpp $(VORO_FOUND)
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -e '.[test]'
	# plantri, shipped inside passagemath-plantri's package, beside the venv's other commands.
	ln -sf "$$($(BIN)/python -c 'from grainclass.plantri import find_plantri; print(find_plantri())')" $(BIN)/plantri
	touch $(STAMP)

# numba's cache does not notice a change in a kernel inlined from another file (a batch kernel
# would go on calling the old one, in tests and benchmarks alike): whenever a kernel's source is
# newer than the last run, the caches go.
$(KERNELS_STAMP): $(KERNELS)
	find src -name '*.nbi' -delete -o -name '*.nbc' -delete
	rm -rf build/numba-cache build/lowest-numba-cache
	@mkdir -p build
	touch $@

install: $(STAMP) $(KERNELS_STAMP)

# The bundled examples classified and their tables printed; then the tour's other commands run
# on them, their output thrown away, so that numba compiles their kernels now (once per
# installation, into its cache beside the package) and each starts at once when run by hand.
demo: voro install
	@mkdir -p build
	$(BIN)/grainclass classify examples/polytopes.txt examples/plantri-10.pc -o build/demo.parquet
	$(BIN)/grainclass summarize build/demo.parquet --n 10
	@echo "Compiling the kernels of the other commands, once per installation:"
	$(BIN)/grainclass classify examples/bad-grains.txt -o build/demo-bad.parquet -q
	$(BIN)/grainclass summarize examples/plantri-10.pc examples/polytopes.txt -q > /dev/null
	$(BIN)/grainclass summarize examples/polytopes.txt --types -q > /dev/null
	$(BIN)/grainclass perturb examples/polytopes.txt --flips 1 --seed 1 -q > /dev/null
	$(BIN)/grainclass voronoi 200 --seed 1 -o build/demo-voronoi.parquet -q
	$(BIN)/grainclass classify tests/data/images/spparks/dump.potts20 --periodic xyz -o build/demo-potts.parquet -q
	$(BIN)/grainclass classify $(GRAIN_GROWTH) -o build/demo-evolver.parquet -q
	$(BIN)/grainclass voronoi 200 --seed 1 -o build/demo-voronoi.txt -q
	$(BIN)/grainclass draw build/demo-voronoi.txt --top 4 --flips --trees -o build/demo-draw.svg -q

# Every kind of `grainclass plot` for a fresh Poisson-Voronoi data set (edge-errors: perturbed
# with seed 1), and the evolution kind for the bundled grain-growth grains, into build/figures/
# (PNG, and the numbers drawn as CSV); and the data set's 12 most frequent types, drawn.
figures: voro install
	@mkdir -p build/figures
	$(BIN)/grainclass voronoi $(FIGURE_SEEDS) --seed 1 -o build/figures/pv.txt -q
	$(BIN)/grainclass classify build/figures/pv.txt -o build/figures/pv.parquet -q
	for kind in round classes faces-q round-q penalty ranks; do \
		$(BIN)/grainclass plot $$kind build/figures/pv.parquet --label Poisson-Voronoi -q \
			-o build/figures/$$kind.png --data build/figures/$$kind.csv || exit 1; \
	done
	$(BIN)/grainclass plot edge-errors build/figures/pv.txt --label Poisson-Voronoi --seed 1 -q \
		-o build/figures/edge-errors.png --data build/figures/edge-errors.csv
	$(BIN)/grainclass plot evolution $(GRAIN_GROWTH) --times 21000 --label grain-growth -q \
		--series flag --series triangles --series tetrahedron --series cube --series 0:m \
		-o build/figures/evolution.png --data build/figures/evolution.csv
	$(BIN)/grainclass draw build/figures/pv.parquet --top 12 -q \
		-o build/figures/types.svg --data build/figures/types.json
	@ls -l build/figures

# Voro++: its library and headers, which grainclass._voro is built against, and the voro++
# program, which the tests compare the cells with. Where either is missing, root installs them
# with apt-get; anyone else, or a system without apt-get, is told what to install.
HAS_VORO = $(PYTHON) -c 'import setup, sys; sys.exit(setup.find_voro() is None)' && \
	command -v voro++ >/dev/null
voro:
	@$(HAS_VORO) || { \
		if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
			apt-get update -qq && apt-get install -y -qq voro++-dev voro++ >/dev/null; \
		fi; \
		$(HAS_VORO) || { \
			echo "Voro++ (library and program) not found: apt-get install voro++-dev voro++ (Debian/Ubuntu), brew install voro++ (Homebrew) or conda install -c conda-forge voro (conda)" >&2; \
			exit 1; }; }

test: voro install
	$(BIN)/python -m pytest

# Coverage-style run of the kernels as plain Python (slow): catches code that only works jitted.
test-nojit: install
	NUMBA_DISABLE_JIT=1 $(BIN)/python -m pytest -m "not slow" -q -p no:cacheprovider --cov=grainclass --cov-report=term-missing:skip-covered

# The whole suite against the lowest versions pyproject.toml allows, in a venv of its own
# (build/lowest), so that its ranges are ranges that were tested.
test-lowest: voro $(KERNELS_STAMP)
	test -x build/lowest/bin/python || $(PYTHON) -m venv build/lowest
	build/lowest/bin/python -m pip install --quiet --disable-pip-version-check -c lowest-dependencies.txt -e '.[test]'
	NUMBA_CACHE_DIR=build/lowest-numba-cache build/lowest/bin/python -m pytest -q -p no:cacheprovider

lint: install
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -e '.[lint]'
	$(BIN)/python -m ruff check src tests scripts benchmarks
	$(BIN)/python -m ruff format --check src tests scripts benchmarks

# Speed and memory, measured in one run (plantri n = 14, 15, 16, three rounds; about fifteen minutes,
# and a tessellation of 10 million cells in parts, some minutes more).
# Before and after in one run: BENCH_ARGS='--compare-src DIR' times the grainclass of another
# checkout DIR (with its own make install) in turn with this one, in the same rounds, and gives
# for each figure ours, theirs and ours/theirs (about twice as long). Here for bench-prisms and
# bench-census too.
BENCH_ARGS ?=
bench: voro install
	$(BIN)/python benchmarks/bench.py $(BENCH_ARGS)

# One giant grain: the k-gonal prism for k = 1,000, 4,000 and 20,000 (a minute or two).
bench-prisms: install
	$(BIN)/python benchmarks/bench.py --prisms-only $(BENCH_ARGS)

# Label images alone: a 320^3 image against np.load + np.unique, a 1024^3 image's memory.
bench-voxels: install
	$(BIN)/python benchmarks/bench.py --voxels-only $(BENCH_ARGS)

# Mutation fuzzing of every reader from the seeds in tests/data (10^5 cases, minutes; not in CI):
# any exception that is not a typed error, a lost row, a case slower than 2 s. FUZZ_CASES=N.
# Then the CLI: every command stopped by SIGINT and SIGTERM at random moments, FUZZ_TRIALS runs
# each (some 20 minutes): the documented exit code, no traceback, nothing left behind.
FUZZ_CASES ?= 100000
FUZZ_TRIALS ?= 50
fuzz: install
	$(BIN)/python scripts/fuzz.py --cases $(FUZZ_CASES)
	$(BIN)/python scripts/fuzz_signals.py --trials $(FUZZ_TRIALS)

# voronoi 10,000,000 --parts 16 on a local Dask cluster against linear scaling from one process's
# voronoi 268402, and summarize of its folder (some minutes; BENCH_ARGS='--parts-seeds N').
bench-parts: voro install
	$(BIN)/python benchmarks/bench.py --parts-only $(BENCH_ARGS)

# The census (n = 16 and 17, several minutes) against plantri alone on the same parts.
bench-census: install
	$(BIN)/python benchmarks/bench.py --census-only --census-sizes 16 17 $(BENCH_ARGS)

# The paper's Table II, split-type table and all* round rows for n = 13 and 14 (seconds).
reproduce-enumeration: install
	$(BIN)/python scripts/reproduce_enumeration.py

# A fresh V-268402-like Poisson-Voronoi data set against the paper's V tables (a few minutes).
reproduce-voronoi: voro install
	$(BIN)/python scripts/reproduce_voronoi.py

# Every triangulation with n = 4..17 vertices on a local Dask cluster, checked against plantri
# and against the paper up to n = 14 (under four minutes on two cores; resumes if interrupted).
reproduce-census: install
	$(BIN)/python scripts/reproduce_census.py

# Label images of periodic Voronoi tessellations (CVT and Poisson, 2,000 seeds, 8 to 32 voxels
# across a grain) with their exact grains, and the naive voxel rule measured against them: the
# tables and figure of docs/voxels.md (some five minutes, 1.1 GB in VOXELS; not in make test).
VOXELS ?= build/voxels
voxel-study: voro install
	nice $(BIN)/python scripts/voxel_study.py study --out $(VOXELS) --jobs 2 \
		--plot $(VOXELS)/voxel-study.png

clean:
	rm -rf build .pytest_cache
	find src -name '*.nbi' -delete -o -name '*.nbc' -delete
