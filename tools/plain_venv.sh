#!/usr/bin/env bash
# The install without root: a plain venv (no system site packages) holding this project
# and its dependencies from PyPI (numpy, scipy, numba, FElupe, ...), then the quick tests
# in it; what needs DOLFINx, or the committed records' package versions, skips with the
# reason. Any Python 3.11 or newer (PYTHON=...; default: the first python3 on PATH).
# CI (.ci/run) runs it after `make test`, so that the route cannot rot.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-python3}
venv=${PLAIN_VENV:-.venv-plain}
"$PY" -c 'import sys; assert sys.version_info >= (3, 11), f"Python 3.11 or newer, got {sys.version}"'
t0=$(date +%s)
if [ ! -x "$venv/bin/python" ]; then
  "$PY" -m venv "$venv"
fi
"$venv/bin/python" -m pip install -q --disable-pip-version-check ".[continuum,study,test]"
echo "plain venv: installed in $(( $(date +%s) - t0 )) s ($("$venv/bin/python" -c 'import numpy, scipy, numba, felupe; print("numpy", numpy.__version__, "scipy", scipy.__version__, "numba", numba.__version__, "felupe", felupe.__version__)'))"
"$venv/bin/python" -m ancf warm
"$venv/bin/python" -m pytest -q -m "not slow and not mpi" -n 2 --dist loadfile -p no:cacheprovider tests
