"""numba's disk cache is keyed by the package's source (ancf.compiled_cache).

numba checks a cached function against its own file only, so a compiled caller of an
edited module runs the old code from its cache. Two small modules show it, in fresh
processes as a user would meet it: b.g() calls a.f(); a.f is edited; the cached b.g
still returns the old sum, unless the cache directory is named by the source digest.
"""
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import numba
import pytest

import ancf
from ancf import compiled_cache

A = "from numba import njit\n\n\n@njit(cache=True)\ndef f():\n    return {}\n"
B = "from numba import njit\nfrom .a import f\n\n\n@njit(cache=True)\ndef g():\n    return f() + 10\n"


def _package(root: Path) -> Path:
    pkg = root / "pkg"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text(A.format(1))
    (pkg / "b.py").write_text(B)
    return pkg


def _g(root: Path, keyed: bool) -> int:
    """b.g() in a fresh process; keyed: the cache directory named by the digest."""
    code = textwrap.dedent(f"""
        import sys
        sys.path.insert(0, {str(root)!r})
        if {keyed}:
            from ancf.compiled_cache import configure
            configure({str(root / 'pkg')!r})
        from pkg.b import g
        print(g())
    """)
    env_py = sys.executable
    out = subprocess.run([env_py, "-c", code], capture_output=True, text=True, check=True, cwd=root)
    return int(out.stdout.split()[-1])


def test_a_compiled_caller_sees_an_edited_callee(tmp_path, monkeypatch):
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    results = {}
    for keyed in (False, True):
        root = tmp_path / ("keyed" if keyed else "plain")
        root.mkdir()
        pkg = _package(root)
        first = _g(root, keyed)                 # compiles, writes the caches
        (pkg / "a.py").write_text(A.format(2))
        results[keyed] = (first, _g(root, keyed))
    assert results[True] == (11, 12)
    # numba's own behaviour, the reason for the keyed directory (if this fails, numba
    # has learnt to invalidate dependents and compiled_cache may go)
    assert results[False] == (11, 11)


def _edits_keep_or_change_the_digest(tmp_path, pick) -> None:
    copy = tmp_path / "ancf"
    for name in ("ancf", *compiled_cache.COMPILED_FROM):
        shutil.copytree(compiled_cache.PACKAGE.parent / name, tmp_path / name,
                        ignore=shutil.ignore_patterns("__pycache__"))
    d0 = compiled_cache.source_digest(copy)
    assert d0 == compiled_cache.source_digest(compiled_cache.PACKAGE)
    modules = [p for name in ("ancf", *compiled_cache.COMPILED_FROM) for p in sorted((tmp_path / name).glob("*.py"))]
    assert any(p.parent.name == "mechanics" for p in modules)
    for p in pick(modules):
        text = p.read_text()
        p.write_text(text + "\n# a comment\n\n")
        assert compiled_cache.source_digest(copy) == d0, p.name
        p.write_text(text + "\n_EDITED = 1\n")
        front = p.parent.name == "ancf" and p.name in compiled_cache.FRONT_END
        assert (compiled_cache.source_digest(copy) == d0) == front, p.name
        p.write_text(text)
    assert compiled_cache.source_digest(copy) == d0
    assert numba.config.CACHE_DIR == str(compiled_cache.cache_dir())
    assert Path(numba.config.CACHE_DIR).name == f"numba-{d0}-{compiled_cache.toolchain()}"
    assert ancf.__version__


def test_the_digest_covers_code_and_not_comments_kernel_step_rules_and_front_end(tmp_path):
    """A kernel module, the step rules of mechanics and the command line: an edit of code
    starts a new cache (but in the front end); a comment or a blank line does not."""
    names = {("ancf", "kernels.py"), ("mechanics", "alpha_family.py"), ("ancf", "cli.py")}
    _edits_keep_or_change_the_digest(tmp_path, lambda ms: [p for p in ms if (p.parent.name, p.name) in names])


@pytest.mark.slow(guard="test_the_digest_covers_code_and_not_comments_kernel_step_rules_and_front_end")
def test_the_digest_covers_the_code_of_every_module_and_names_the_cache(tmp_path):
    """An edit of code in any module (the front end's aside) starts a new cache; a
    comment, a docstring or a blank line does not."""
    _edits_keep_or_change_the_digest(tmp_path, lambda ms: ms)


def test_prune_keeps_another_toolchains_cache_and_drops_this_ones_earlier_code():
    """Two venvs of one clone (Debian's numba and PyPI's) keep their own compiled code: the
    warm-up's prune removes the earlier code of its own toolchain only."""
    from ancf.warm import prune

    current = compiled_cache.cache_dir()
    other = current.parent / f"numba-{'0' * 16}-{'f' * 8}"
    earlier = current.parent / f"numba-{'0' * 16}-{compiled_cache.toolchain()}"
    for d in (other, earlier):
        d.mkdir(parents=True, exist_ok=True)
    try:
        gone = prune()
        assert earlier in gone and not earlier.exists()
        assert other.exists() and other not in gone and current.exists()
    finally:
        shutil.rmtree(other, ignore_errors=True)
        shutil.rmtree(earlier, ignore_errors=True)
