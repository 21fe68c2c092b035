# The two commands a user needs: `make study` (the main job) and `make test`.
# Each runs the whole idempotent set-up first (Debian packages, venv, editable install).
PY := .venv/bin/python
export OMP_NUM_THREADS ?= 1
export OPENBLAS_NUM_THREADS ?= 1

.PHONY: setup test test-full test-slow test-guards study study-full audit loops bench bench-spatial bench-penalty bench-peers external-exudyn docs clean-venv

# The idempotent set-up every target runs first (tools/setup.sh): Debian's packages, the
# venv .venv with the system's site packages, this project installed editable, FElupe pinned,
# the solver's compiled code in its cache (`ancf warm`)
setup:
	@bash tools/setup.sh

# The quick tier: two workers (pytest-xdist, Debian's python3-pytest-xdist), each test file on
# one worker (a file's module-scoped fixtures run once); TEST_WORKERS=0: serially. Then the
# tests marked mpi, alone: ranks that wait on each other at every global sum starve beside
# another worker on 2 cores. Both phases run; the target fails if either did.
# Every test marked slow names the quick test that guards its property in this tier
# (tests/conftest.py refuses a slow test without one); `make test-full` runs the slow ones.
TEST_WORKERS ?= 2
XDIST = $(if $(filter 0,$(TEST_WORKERS)),,-n $(TEST_WORKERS) --dist loadfile)
test: setup
	@status=0; \
	$(PY) -m pytest -q -m "not slow and not mpi" $(XDIST) tests || status=$$?; \
	$(PY) -m pytest -q -m "mpi and not slow" tests || status=$$?; \
	exit $$status

# The full tier: what make test leaves out (fuzz at 10 to 25 times the budget, every element
# and law of the contract cases, the studies' tiny runs, the examples' claims, cold compiles).
# (pytest's exit 5, "no tests collected", is not a failure of the mpi phase when no slow
# test launches ranks.)
test-full: setup
	@status=0; \
	$(PY) -m pytest -q -m "slow and not mpi" $(XDIST) tests || status=$$?; \
	$(PY) -m pytest -q -m "slow and mpi" tests || [ $$? -eq 5 ] || status=1; \
	exit $$status

# another name of test-full
test-slow: test-full

# each test of the full tier with the quick test that guards its property (runs nothing)
test-guards: setup
	@$(PY) -m pytest -q --guards tests || [ $$? -eq 5 ]

# The main job: the paper's tables and figures and the studies that answer the three demands
# (accuracy against cost, hard cases, effects); every finished record reused. Its cold time
# (no records) and its time with every record reused are in the record of `make loops`.
study: setup
	$(PY) -m studies run all
	$(PY) -m studies audit

# every report rebuilt from its records and compared (no solver runs; the stamp of the last
# full audit answers at once while records, report code and reports are unchanged)
audit: setup
	$(PY) -m studies audit

# The rest, after the main job: the studies marked full (the paper's sensitivity and Yeoh
# hypotheses, the fixed quadrature rules' cost, the formulation comparison, the 3D width map,
# the law card, the two continuum codes' agreement, the manufactured solutions, the cold
# first run, the 3D pendulum), every element's card (the built-in ones and the examples'), and
# the converged 3D cantilever gold (2 to 4 min per law; RANKS=N: on N MPI ranks).
RANKS ?= 1
MPIEXEC := mpiexec --oversubscribe --allow-run-as-root -x PYTHONPATH -x OMP_NUM_THREADS -x OPENBLAS_NUM_THREADS
CARDS = all
CARD_IMPORTS = --import examples.transversely_cubic --import examples.cubic_slope --import examples.sextic_section
study-full: study
	$(PY) -m studies run full
	$(PY) -m studies card $(CARDS) $(CARD_IMPORTS)
	$(if $(filter 1,$(RANKS)),,$(MPIEXEC) -n $(RANKS)) $(PY) -m studies continuum gold --3d --out reports/data/solid3d
	$(PY) -m studies audit

# The five loops a user waits on, in a fresh clone of the committed tree (set-up, first
# run, make test, verify, make study cold and with every record reused; about 25 min):
# reports/data/loops.json, quoted in README.md
loops: setup
	$(PY) -m studies loops

# timings of the paper's cells (Table 3, the pendulum of Table 4) and of the compiled kernels
# (reports/kernels.md)
bench: setup
	$(PY) -m studies bench table3
	$(PY) -m studies bench pendulum
	$(PY) -m studies bench kernels

# what 1 % and 0.1 % cost in 3D: the spatial ANCF elements beside the 3D continuum on the
# end-force cantilever and half a turn of torsion, timed side by side (experiments/spatial_cost)
bench-spatial: setup
	$(PY) experiments/spatial_cost/bench.py

# the penalty sweep: every element x law x penalised formulation x mesh from 10 to 1e5 C10
# (reports/penalty.md)
bench-penalty: setup
	$(PY) -m studies bench penalty

# The pendulum beside a peer, Exudyn's ANCF cable, installed in a separate venv (.venv-peers,
# never in .venv): the same pendulum side by side, Exudyn against its own published numbers,
# and the work-precision diagrams of two pendulums with every registered element that runs
# plane stress, but one tagged locking (reports/peers*.md)
bench-peers: setup
	bash tools/setup_peers.sh && $(PY) -m studies peers compare --report
	$(PY) -m studies peers published --report && $(PY) -m studies peers compare --report-only
	$(PY) -m studies peers work-precision --scene pendulum
	$(PY) -m studies peers work-precision --scene thick

# Exudyn through the external-solver protocol (in .venv-peers), its cable
# (studies/peers/exudyn.toml) and its geometrically exact beam (exudyn-beam2d.toml): the
# benchmark suite's and the dynamic benchmarks' cases each takes and each one's element card
# (the sections that need only runs); records in reports/external/data, verdicts in
# reports/external/*benchmarks@<solver>.md, cards in reports/external/cards/
external-exudyn: setup
	bash tools/setup_peers.sh
	for d in exudyn exudyn-beam2d; do \
		$(PY) -m studies external studies/peers/$$d.toml benchmarks dynamic-benchmarks --out reports/external || exit 1; \
	done
	$(PY) -m studies card --solver studies/peers/exudyn.toml --solver studies/peers/exudyn-beam2d.toml --out reports/external

# The documentation site (Sphinx with MyST Markdown and furo, Debian's packages):
# docs/ -> docs/_build/html; every warning is an error; the reference pages and the results
# are drawn from the code, this Makefile and reports/ at every build
docs: setup
	$(PY) -m sphinx -W --keep-going -b html docs docs/_build/html

# remove the venv (the next target makes it again)
clean-venv:
	rm -rf .venv
