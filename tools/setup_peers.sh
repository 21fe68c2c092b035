#!/usr/bin/env bash
# Idempotent set-up of the peer-benchmark venv `.venv-peers` (make bench-peers).
# A separate venv WITHOUT system site packages: Exudyn and its numpy come from PyPI
# and must never touch `.venv`, whose numpy is Debian's (dolfinx is built against it).
# Both are pinned, so that a rerun gets the same peer: the peer reports' records and the
# checks against Exudyn's published numbers (studies/peers/exudyn_published.py, run by studies/peers/exudyn_static.py) name this
# version. A venv holding other versions is brought to the pins.
set -euo pipefail
cd "$(dirname "$0")/.."

EXUDYN_VERSION=1.13.6     # the newest on PyPI on 2026-11-27; the peer records so far were made with it
NUMPY_VERSION=2.4.6       # what pip chose for exudyn 1.13.6 (it requires numpy, unpinned)

venv=.venv-peers
if [ ! -x "$venv/bin/python" ]; then
  echo "setup_peers: creating $venv"
  rm -rf "$venv"
  /usr/bin/python3 -m venv "$venv"
fi

# has PACKAGE VERSION: the venv holds exactly that version
has() {
  "$venv/bin/python" - "$1" "$2" <<'PY' 2>/dev/null
import importlib.metadata as m, sys
sys.exit(0 if m.version(sys.argv[1]) == sys.argv[2] else 1)
PY
}
missing=""
has numpy "$NUMPY_VERSION" || missing="$missing numpy==$NUMPY_VERSION"
has exudyn "$EXUDYN_VERSION" || missing="$missing exudyn==$EXUDYN_VERSION"
if [ -n "$missing" ]; then
  echo "setup_peers: pip-installing into $venv:$missing"
  "$venv/bin/python" -m pip install -q $missing
fi
