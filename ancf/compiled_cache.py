"""numba's disk cache, in a directory named by a digest of the package's source.

numba checks a cached function against the time stamp of its own file only. A compiled
function that calls compiled code of another module (the step loop and the static loop
inline :func:`ancf.kinematics.section.kernels.assemble_fused`) is loaded from its cache after that other
module has changed, and runs the old code. Measured: after an edit of
``ancf/kinematics/section/kernels.py`` the step loop kept running the old assembly until its cache files
were removed (``tests/test_compiled_cache.py`` shows the same with two small modules).

So :func:`configure` (called by ``ancf/__init__.py``, before any compiled function is
defined) points numba at ``<base>/numba-<digest>-<toolchain>``, the digest taken over the code of
every module of the package (but its front end: the command line, the compiled-code
loader, the output writers) and of ``mechanics`` (whose step rules the step loop
compiles), comments and docstrings left out by the records' normaliser
(:func:`contract.source.normalised`): an edit of code anywhere starts a fresh
cache (one compilation), and an unchanged package loads its compiled code as before; the
toolchain (:func:`toolchain`: interpreter, numba, numpy) keeps the caches of two venvs of
one clone apart. ``<base>`` is ``$NUMBA_CACHE_DIR``
if set, else the package's ``__pycache__``, else (not writable) ``~/.cache/ancf``.
numba has one cache directory per process, so other packages' cached functions defined
after this call are stored there too.
"""
from __future__ import annotations

import hashlib
import os
from pathlib import Path

from contract.source import normalised

PACKAGE = Path(__file__).resolve().parent
# the sibling packages whose functions ancf's compiled code compiles or inlines
# (the time loop's step rules are compiled into the step loop)
COMPILED_FROM = ("mechanics",)
# front-end modules that no compiled code imports (the command line, the warm-up, the scene
# checks): an edit of them keeps the cache
FRONT_END = ("__main__.py", "cli.py", "output.py", "warm.py", "compiled_cache.py", "admission.py")


def _sources(package: Path) -> list[tuple[str, bytes]]:
    """(name, bytes) of every module the digest covers, in a fixed order."""
    out = []
    siblings = [package.parent / name for name in COMPILED_FROM if (package.parent / name).is_dir()]
    for d in [package, *siblings]:
        for p in sorted(Path(d).rglob("*.py")):
            if d == package and p.parent == package and p.name in FRONT_END:
                continue
            out.append((d.name + "/" + p.relative_to(d).as_posix(), p.read_bytes()))
    return out


def source_digest(package: Path = PACKAGE) -> str:
    """sha256 over the names and normalised code of the modules of ``package`` (but its
    front end, :data:`FRONT_END`) and of its sibling packages named in
    :data:`COMPILED_FROM` (16 hex digits).

    Parsing every module costs a quarter of a second at each import, so the digest is kept
    in a memo file named by a hash of the files' raw bytes (``<package>/__pycache__/
    digest-<raw>``): unchanged files read it back; any edit, even of a comment, parses
    again once (and finds the same digest if only comments or docstrings changed)."""
    package = Path(package)
    sources = _sources(package)
    raw = hashlib.sha256(b"".join(name.encode() + b"\0" + text + b"\0" for name, text in sources)).hexdigest()
    memo = package / "__pycache__" / f"digest-{raw[:24]}"
    try:
        digest = memo.read_text().strip()
        if len(digest) == 16:
            return digest
    except OSError:
        pass
    h = hashlib.sha256()
    for name, text in sources:
        h.update(name.encode() + b"\0" + normalised(text).encode() + b"\0")
    digest = h.hexdigest()[:16]
    try:
        memo.parent.mkdir(exist_ok=True)
        tmp = memo.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(digest + "\n")
        os.replace(tmp, memo)
    except OSError:
        pass                      # a read-only install computes it each time
    return digest


def _writable(d: Path) -> bool:
    try:
        d.mkdir(parents=True, exist_ok=True)
    except OSError:
        return False
    return os.access(d, os.W_OK)


def toolchain() -> str:
    """The interpreter, numba and numpy this process compiles with, and the machine (8 hex
    digits): two venvs of one clone (Debian's packages and PyPI's) never load each other's
    compiled code, nor overwrite each other's cache."""
    import platform
    import sys

    import numba
    import numpy

    text = (f"python {sys.version_info[0]}.{sys.version_info[1]} numba {numba.__version__} "
            f"numpy {numpy.__version__} {platform.machine()}")
    return hashlib.sha256(text.encode()).hexdigest()[:8]


def cache_dir(package: Path = PACKAGE) -> Path:
    """Where numba caches the package's compiled code (see the module docstring):
    ``numba-<source digest>-<toolchain>``."""
    name = f"numba-{source_digest(package)}-{toolchain()}"
    for base in (os.environ.get("NUMBA_CACHE_DIR"), Path(package) / "__pycache__", Path.home() / ".cache" / "ancf"):
        if base and _writable(Path(base) / name):
            return Path(base) / name
    return Path(package) / "__pycache__" / name      # numba then warns that it cannot cache


def configure(package: Path = PACKAGE) -> Path:
    """Point numba's cache at :func:`cache_dir` and return it."""
    import numba

    d = cache_dir(package)
    numba.config.CACHE_DIR = str(d)
    return d
