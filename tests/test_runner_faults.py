"""The study runner under faults, as a hostile user tries it (issue 22, item 6): ``kill -9``
of the runner (its pool workers and the resource tracker must not outlive it), two
runners on one study at once (the second waits, says so, and reuses the first's records)
and Ctrl-C early (while the pool starts) and late (while cases run): the command returns
130 only once every finished record is on disk and no worker is left.

Each runs ``python -m studies run`` in its own session, so that every process it started
can be found (same session id) and none is missed or left behind: on a catalog of 12
Table 3 cells (about 0.3 s each) where a whole run is needed, and on one of 12 pendulums
at a fine step (``LONG``: about 2 s each, 12 s in all on two workers) where the run is to
be stopped: an interrupt that did not end it shows as a run that goes on (the bound is a
multiple of the measured case time, so a busy machine slows both sides alike).
"""
from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from studies.engine.store import RecordStore

ROOT = Path(__file__).resolve().parents[1]
CASES = 12


LONG = -1   # count for the long catalog
STOP_S = 10.0   # an interrupt while the pool starts ends the run within this


def _catalog(tmp_path: Path, count: int) -> Path:
    p = tmp_path / "cases.toml"
    if count == LONG:
        p.write_text("""
[faults]
module = "paper.figure5"
laws = ["neo-hookean", "mooney-rivlin", "yeoh"]
elements = ["HB2n-12", "HB3n-12"]
elements_count = 32
formulations = ["plane-stress", "paper"]
dt = 2e-5
rho_inf = 0.5
t_end = 0.5
""")
        return p
    p.write_text(f"""
[faults]
module = "paper.table3"
laws = ["yeoh", "neo-hookean"]
elements = ["HB3n-12", "HB2n-12"]
formulations = ["plane-stress", "paper", "plane-strain"]
counts = {{ HB3n-12 = {count}, HB2n-12 = {count} }}
settings = {{ paper = {{ quadrature = [2, 2], clamp = "all" }}, plane-strain = {{ quadrature = [3, 2], clamp = "face" }}, plane-stress = {{ quadrature = [3, 2], clamp = "face" }} }}
""")
    return p


def _start(tmp_path: Path, count: int, out: Path | None = None,
           executor: str = "pool") -> tuple[subprocess.Popen, Path]:
    """The runner in a new session, SIGINT at its default (a background `make test` would
    start it ignored, and Python would then never raise KeyboardInterrupt). The lock does
    not depend on the executor: the tests of it run serially (no worker start-ups)."""
    out = out or tmp_path / "out"
    cmd = [sys.executable, "-m", "studies", "run", "faults", "--catalog", str(_catalog(tmp_path, count)),
           "--out", str(out), "--no-progress", "--workers", "2", "--executor", executor]

    def child():
        os.setsid()
        signal.signal(signal.SIGINT, signal.SIG_DFL)
    p = subprocess.Popen(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         preexec_fn=child)
    return p, out / "data" / "faults.jsonl"


def _session(sid: int) -> dict[int, str]:
    """{pid: command line} of the live (not zombie) processes of session ``sid``."""
    found = {}
    for d in Path("/proc").iterdir():
        if not d.name.isdigit():
            continue
        try:
            stat = (d / "stat").read_text()
            fields = stat[stat.rindex(")") + 2:].split()
            if int(fields[3]) == sid and fields[0] != "Z":
                found[int(d.name)] = (d / "cmdline").read_bytes().replace(b"\0", b" ").decode()
        except (OSError, ValueError, IndexError):
            continue
    return found


def _maps(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/maps").read_text()
    except OSError:
        return ""


def _workers(sid: int) -> dict[int, str]:
    return {pid: cmd for pid, cmd in _session(sid).items() if "spawn_main" in cmd}


def _wait(cond, timeout: float, what: str, p: subprocess.Popen | None = None):
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        got = cond()
        if got:
            return got
        if p is not None and p.poll() is not None:
            pytest.fail(f"the runner ended before {what}: {p.returncode}\n{p.stderr.read()[-2000:]}")
        time.sleep(0.02)
    pytest.fail(f"no {what} within {timeout} s")


def _records(data: Path) -> int:
    return len(data.read_text().splitlines()) if data.exists() else 0


def _gone(sid: int, timeout: float) -> dict[int, str]:
    """Wait up to ``timeout`` for the session to empty; what is left."""
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout and _session(sid):
        time.sleep(0.05)
    return _session(sid)


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads /proc")
def test_kill_9_of_the_runner_takes_its_workers_and_the_resource_tracker_with_it(tmp_path):
    p, data = _start(tmp_path, count=LONG)
    try:
        # both workers in a case: the solver's compiled code (llvmlite) loaded
        workers = _wait(lambda: len(_workers(p.pid)) == 2 and all("llvmlite" in _maps(w) for w in _workers(p.pid))
                        and _workers(p.pid), 60, "two workers in a case", p)
        assert any("resource_tracker" in c for c in _session(p.pid).values())
        os.kill(p.pid, signal.SIGKILL)            # the runner alone, not its process group
        p.wait()
        left = _gone(p.pid, timeout=10)           # they stayed 74 s and more
        assert not left, f"outlived the runner: {left}"
        assert not set(workers) & set(_session(p.pid))
    finally:
        for pid in _session(p.pid):
            os.kill(pid, signal.SIGKILL)
        p.wait()
    store = RecordStore(data)
    assert len(store.read()) < CASES and store.skipped_lines == 0


def test_a_runner_waits_while_another_holds_the_study_and_says_so(tmp_path):
    """Deterministic half: this test holds the study's lock; the runner waits (one line on
    stderr naming the holder's pid), computes nothing meanwhile, and goes on once free."""
    out = tmp_path / "out"
    store = RecordStore(out / "data" / "faults.jsonl")
    with store.lock():
        p, data = _start(tmp_path, count=4, out=out, executor="serial")
        line = p.stderr.readline()
        assert f"another runner (pid {os.getpid()})" in line and "waiting" in line, line
        time.sleep(0.5)
        assert not data.exists() and p.poll() is None
    stdout, stderr = p.communicate(timeout=120)
    assert p.returncode == 0, stderr
    assert "the other runner is done" in stderr
    assert f"{CASES} cases, 0 reused, {CASES} computed" in stdout


@pytest.mark.slow(guard="test_a_runner_waits_while_another_holds_the_study_and_says_so")
def test_two_runners_at_once_compute_each_case_once(tmp_path):
    out = tmp_path / "out"
    a, data = _start(tmp_path, count=8, out=out, executor="serial")
    b, _ = _start(tmp_path, count=8, out=out, executor="serial")
    runs = [x.communicate(timeout=180) for x in (a, b)]
    assert a.returncode == 0 and b.returncode == 0, runs
    computed = [int(re.search(r"faults: \d+ cases, \d+ reused, (\d+) computed", o).group(1)) for o, _ in runs]
    assert sorted(computed) == [0, CASES], runs           # one ran them all, the other reused them
    assert len(data.read_text().splitlines()) == CASES and len(RecordStore(data).read()) == CASES


# Ctrl-C at a terminal signals the whole process group; `kill -INT PID` the runner alone
TARGETS = ["group", "runner"]


def _interrupt(p: subprocess.Popen, target: str) -> tuple[str, str]:
    if target == "group":
        os.killpg(p.pid, signal.SIGINT)
    else:
        os.kill(p.pid, signal.SIGINT)
    out, err = p.communicate(timeout=60)
    return out, err


def _stopped(p: subprocess.Popen, target: str, data: Path, within: float = STOP_S) -> None:
    """Interrupt ``p``; it must end (not run on to the end of its cases) cleanly."""
    t0 = time.monotonic()
    out, err = _interrupt(p, target)
    took = time.monotonic() - t0
    assert took < within, f"the interrupt did not end the run: it went on for {took:.1f} s"
    _assert_clean_interrupt(p, err, data)


def _assert_clean_interrupt(p: subprocess.Popen, err: str, data: Path) -> None:
    assert p.returncode == 130, err[-3000:]
    assert err.strip().splitlines()[-1].startswith("studies: interrupted") and "Traceback" not in err, err[-3000:]
    assert not _workers(p.pid), "a pool worker outlived the interrupted command"
    lines = _records(data)
    time.sleep(1.0)
    assert _records(data) == lines, "a record was written after the command returned"
    assert not _gone(p.pid, timeout=5)
    store = RecordStore(data)
    assert len(store.read()) == lines and store.skipped_lines == 0, [
        (r.get("case_id"), r.get("pid"), r.get("run")) for r in map(json.loads, data.read_text().splitlines())]


@pytest.mark.parametrize("target", [pytest.param(t, marks=pytest.mark.slow(guard="test_ctrl_c_while_the_pool_starts_ends_the_run"))
                                    if t == "group" else t for t in TARGETS])
def test_ctrl_c_while_the_pool_starts_ends_the_run(tmp_path, target):
    """Early: the study's lock is held (the runner is in the scheduler) and the pool's
    workers are being spawned; once this was ignored and the run went on to the end."""
    p, data = _start(tmp_path, count=LONG)
    lock = data.with_suffix(".lock")
    _wait(lambda: lock.exists() and lock.read_text().strip() == str(p.pid), 60, "the study's lock", p)
    time.sleep(0.2)
    _stopped(p, target, data)
    assert _records(data) < CASES


@pytest.mark.slow(guard="test_ctrl_c_while_the_pool_starts_ends_the_run")
@pytest.mark.parametrize("target", ["group", "runner"])
def test_ctrl_c_while_cases_run_keeps_every_finished_record_and_leaves_no_worker(tmp_path, target):
    """Late: records are on disk and both workers are in a case; the command returns 130
    with every finished record on disk and no worker alive, and nothing writes afterwards."""
    p, data = _start(tmp_path, count=LONG)
    _wait(lambda: _records(data) >= 1, 120, "a record", p)
    _wait(lambda: len(_workers(p.pid)) == 2, 30, "two live workers", p)
    case_s = next(iter(RecordStore(data).read().values()))["elapsed_s"]
    # the rest of the run is 11 cases on 2 workers, 5.5 case times; stopping takes well under one
    _stopped(p, target, data, within=max(3.0, 2.5 * case_s))
    have = RecordStore(data).read()
    assert 1 <= len(have) < CASES and all(r["status"] == "converged" for r in have.values())
