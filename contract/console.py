"""What every command line of the harness shares: output paths checked before a run
(never a traceback after the solve), file names made from scene names (always inside
the folder the user gave), an interrupt as one line (exit status 130), and a progress
bar on the terminal (never in a record).
"""
from __future__ import annotations

import os
import re
import sys
import tempfile
import time
from pathlib import Path

from .errors import SceneError

INTERRUPTED = 130


def safe_name(name: str) -> str:
    """A file name from a scene name: letters, digits, '.', '_' and '-' kept, every other
    run of characters (separators, NUL, spaces) made one '_', runs of dots dropped, no
    leading or trailing dot or '_': it cannot leave the folder it is put in."""
    s = re.sub(r"[^A-Za-z0-9._-]+", "_", name)
    s = re.sub(r"_+", "_", re.sub(r"\.{2,}", "", s)).strip("._")
    return s or "scene"


def _writable_dir(d: Path, flag: str) -> None:
    """Make the folder d (with its parents) and prove that a file can be written in it,
    by writing and removing one (permission bits do not tell, e.g. for root or on a
    read-only file system)."""
    probe = d
    while not probe.exists() and probe.parent != probe:
        probe = probe.parent
    if probe.exists() and not probe.is_dir():
        raise SceneError(f"{flag}: cannot create {d}: {probe} is a file, not a folder")
    try:
        d.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=d, prefix=".write-check-"):
            pass
    except OSError as e:
        raise SceneError(f"{flag}: cannot write in {d} ({e.strerror or e})") from None


def check_output_file(path: str | Path | None, flag: str) -> Path | None:
    """A file the run will write: not a folder, in a folder that exists or can be made."""
    if path is None:
        return None
    p = Path(path)
    if p.is_dir():
        raise SceneError(f"{flag}: {p} is a folder; give a file name")
    if p.exists() and not os.access(p, os.W_OK):
        raise SceneError(f"{flag}: cannot overwrite {p} (permission denied)")
    _writable_dir(p.parent, flag)
    return p


def check_output_dir(path: str | Path | None, flag: str) -> Path | None:
    """A folder the run will write into: a folder (or creatable), not a file."""
    if path is None:
        return None
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise SceneError(f"{flag}: {p} is a file; give a folder")
    _writable_dir(p, flag)
    return p


def import_modules(names) -> None:
    """Import the user's modules named by ``--import`` (each registers its laws in
    ``mechanics.laws`` or its elements in ``ancf.elements`` on import); a module that
    cannot be found is a :class:`SceneError` naming the flag."""
    import importlib
    for name in names or ():
        try:
            importlib.import_module(name)
        except ModuleNotFoundError as e:
            if e.name and name.startswith(e.name):
                raise SceneError(f"--import: no module named {name!r} (a module on the Python path, "
                                 f"e.g. examples.cubic_slope)") from None
            raise


def by_interrupt(e: BaseException) -> bool:
    """Is ``e`` a Ctrl-C in disguise? A KeyboardInterrupt raised while compiled code
    (numba) runs comes out as a SystemError whose cause is the interrupt."""
    while e is not None:
        if isinstance(e, KeyboardInterrupt):
            return True
        e = e.__cause__ or e.__context__
    return False


def command(prog: str, run, errors: tuple[type[BaseException], ...] = (SceneError,),
            interrupt_note: str = "") -> int:
    """Run a command's body ``run()`` the way every command line of the harness ends:
    its exit status, or one line and 2 for a bad scene or option (``errors``), or one
    line and 130 on Ctrl-C (also when it arrives inside compiled code)."""
    try:
        return run()
    except errors as e:
        print(f"{prog}: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        pass
    except BrokenPipeError:   # the reader went away (`... | head`): stop quietly, as cat does
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 141
    except SystemError as e:
        if not by_interrupt(e):
            raise
    print(f"{prog}: interrupted{interrupt_note}", file=sys.stderr)
    return INTERRUPTED


class Progress:
    """A tqdm bar of simulated time with steps and Newton iterations, drawn on stderr
    when it is a terminal (or when forced), at most every 0.5 s; ``close()`` removes it.
    Called as ``progress(t, result)`` by the time loop."""

    def __init__(self, t_end: float, enabled: bool = True, force: bool = False):
        self.bar = None
        if enabled and (force or sys.stderr.isatty()):
            from tqdm import tqdm
            self.bar = tqdm(total=t_end, unit="s", unit_scale=False, leave=False, mininterval=0.5,
                            bar_format="{l_bar}{bar}| t = {n:.4g} / {total:.4g} s [{elapsed}<{remaining}{postfix}]",
                            file=sys.stderr, dynamic_ncols=True)
        self._last = 0.0

    def __call__(self, t: float, res) -> None:
        if self.bar is None:
            return
        now = time.perf_counter()
        if now - self._last < 0.5:
            return
        self._last = now
        self.bar.n = t
        self.bar.set_postfix_str(f"steps {res.steps}, Newton {res.newton_iterations}", refresh=False)
        self.bar.refresh()

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
