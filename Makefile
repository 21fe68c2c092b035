# The two commands a user needs: `make study` (the main job) and `make test`.
# Each runs the whole idempotent set-up first (Debian packages, venv, editable install).
PY := .venv/bin/python
export OMP_NUM_THREADS ?= 1
export OPENBLAS_NUM_THREADS ?= 1

.PHONY: setup test test-slow study bench bench-penalty bench-peers clean-venv

setup:
	@bash tools/setup.sh

test: setup
	$(PY) -m pytest -q -m "not slow" tests

test-slow: setup
	$(PY) -m pytest -q -m slow tests

study: setup
	$(PY) -m studies run all

bench: setup
	$(PY) -m studies.bench table3
	$(PY) -m studies.bench pendulum

bench-penalty: setup
	$(PY) -m studies.bench penalty

# Exudyn in a separate venv (.venv-peers), never in .venv
bench-peers: setup
	bash tools/setup_peers.sh && $(PY) -m studies.peers.compare

clean-venv:
	rm -rf .venv
