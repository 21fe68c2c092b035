#!/usr/bin/env bash
# Idempotent set-up on a Debian (bookworm) machine, as root or with sudo:
#   1. Debian's FEniCSx / scientific stack for /usr/bin/python3, and Sphinx for the
#      documentation site (only what is missing),
#   2. a venv that sees those packages (--system-site-packages),
#   3. this project installed editable into it, with no dependencies from PyPI
#      (pip must never shadow Debian's numpy/scipy, or dolfinx breaks).
set -euo pipefail
cd "$(dirname "$0")/.."

packages="python3-dolfinx python3-gmsh python3-numba python3-mpi4py python3-pandas
python3-matplotlib python3-pytest python3-tqdm python3-venv python3-scipy openmpi-bin
python3-threadpoolctl python3-hypothesis python3-meshio python3-pytest-xdist python3-sympy
python3-sphinx python3-myst-parser furo python3-sphinx-argparse"

missing=""
for p in $packages; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "setup: installing Debian packages:$missing"
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q $missing
fi

if [ ! -x .venv/bin/python ] || ! .venv/bin/python -c "import numpy, scipy" 2>/dev/null; then
  echo "setup: creating .venv (system site packages)"
  rm -rf .venv
  /usr/bin/python3 -m venv --system-site-packages .venv
fi

# (Re)install editable when the package is not importable from the venv or the
# project metadata changed since the last install.
stamp=.venv/.ancf-installed
if ! .venv/bin/python -c "import ancf" 2>/dev/null || [ ! -f "$stamp" ] || [ pyproject.toml -nt "$stamp" ]; then
  echo "setup: installing the project (editable, --no-deps)"
  .venv/bin/python -m pip install -q --no-deps --no-build-isolation -e .
  touch "$stamp"
fi

# FElupe, the second continuum code (reference_fem backend "felupe"): pure Python,
# pinned, with --no-deps so pip never touches Debian's numpy/scipy. Versions checked
# to run on Debian bookworm's numpy 1.24 / scipy 1.10 (tests/test_felupe_install.py).
felupe_pins="felupe==9.1.0 tensortrax==0.29.0"
if ! .venv/bin/python - $felupe_pins <<'PY' 2>/dev/null
import sys
from importlib.metadata import version
for pin in sys.argv[1:]:
    name, wanted = pin.split("==")
    assert version(name) == wanted
PY
then
  echo "setup: installing $felupe_pins (--no-deps)"
  .venv/bin/python -m pip install -q --no-deps $felupe_pins
fi

# The solver's compiled code (numba), compiled once per clone into its cache (about 3 min
# on 2 cores) so that a first `ancf run` loads it in under a second; a no-op (about 2 s)
# while the code is unchanged. `.venv/bin/ancf warm` does the same by hand.
.venv/bin/ancf warm
