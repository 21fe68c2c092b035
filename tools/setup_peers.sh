#!/usr/bin/env bash
# Idempotent set-up of the peer-benchmark venv `.venv-peers` (make bench-peers).
# A separate venv WITHOUT system site packages: Exudyn and its numpy come from PyPI
# and must never touch `.venv`, whose numpy is Debian's (dolfinx is built against it).
set -euo pipefail
cd "$(dirname "$0")/.."

venv=.venv-peers
if [ ! -x "$venv/bin/python" ]; then
  echo "setup_peers: creating $venv"
  rm -rf "$venv"
  /usr/bin/python3 -m venv "$venv"
fi

missing=""
"$venv/bin/python" -c "import numpy" 2>/dev/null || missing="$missing numpy"
"$venv/bin/python" -c "import exudyn" 2>/dev/null || missing="$missing exudyn"
if [ -n "$missing" ]; then
  echo "setup_peers: pip-installing into $venv:$missing"
  "$venv/bin/python" -m pip install -q $missing
fi
