"""The tutorials' code blocks run as written (docs/tutorials/*.md).

Each page runs in a fresh process, in a scratch directory that holds links to the
repository's `scenes/` and `examples/`, its blocks in order:

- a ```python block is executed, every block of a page in one namespace (a later block
  reads what an earlier one made);
- a ```sh block runs in bash (-e, pipefail), with `.venv/bin/python` and `.venv/bin/ancf`
  meaning this interpreter (`python -m ancf`), whichever venv runs the tests;
- a ```{code-block} with a `:caption:` naming a file is that file's text: it is written
  into the scratch directory (a module the reader saves, a scene);
- a block preceded by `<!-- not run: why -->` is shown, not run (the main job, a cluster
  launch); a python or sh block without that marker always runs.

So a tutorial that stops working fails here, naming page and line.
"""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

from .conftest import HAS_FENICSX, tiered

ROOT = Path(__file__).resolve().parents[1]
TUTORIALS = ROOT / "docs" / "tutorials"
PAGES = sorted(p for p in TUTORIALS.glob("*.md") if p.name != "index.md")
# pages whose runs include the default continuum backend (DOLFINx)
CONTINUUM_PAGES = {"first-scene", "your-law"}
SLOW_PAGES = {"your-element", "your-law", "first-scene"}
FENCE = re.compile(r"^(`{3,})\s*(\{[a-z-]+\})?\s*([A-Za-z0-9_-]*)(.*)$")
NOT_RUN = re.compile(r"<!--\s*not run:\s*(.+?)\s*-->")
RUNS = ("python", "sh")
# a page's whole run, its scenes tiny; the bound catches a tutorial grown expensive
PAGE_BUDGET_S = 180.0


def blocks(path: Path) -> list[dict]:
    """The fenced blocks of a Markdown page: {line, directive, lang, options, code, skip}."""
    lines = path.read_text(encoding="utf-8").splitlines()
    out, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        ticks, directive, lang = m.group(1), m.group(2) or "", m.group(3)
        if directive in ("{code-block}", "{code}"):
            lang = m.group(3) or m.group(4).strip()
        start, j, options = i + 1, i + 1, {}
        while directive and j < len(lines) and re.match(r"^:[a-z-]+:", lines[j]):
            key, _, value = lines[j][1:].partition(":")
            options[key] = value.strip()
            j += 1
        body = []
        while j < len(lines) and not lines[j].startswith(ticks):
            body.append(lines[j])
            j += 1
        previous = next((lines[k] for k in range(i - 1, -1, -1) if lines[k].strip()), "")
        skip = NOT_RUN.search(previous)
        out.append({"line": start, "directive": directive, "lang": lang, "options": options,
                    "code": "\n".join(body).strip("\n") + "\n", "skip": skip.group(1) if skip else None})
        i = j + 1
    return out


def steps(path: Path) -> list[dict]:
    """What the page runs, in order: python / sh blocks and files to write."""
    out = []
    for b in blocks(path):
        if b["skip"]:
            continue
        caption = b["options"].get("caption")
        if b["directive"] in ("{code-block}", "{code}") and caption:
            out.append({"kind": "file", "name": caption, "code": b["code"], "line": b["line"]})
        elif b["lang"] in RUNS and b["directive"] in ("", "{code-block}", "{code}"):
            out.append({"kind": b["lang"], "code": b["code"], "line": b["line"]})
    return out


DRIVER = r'''
import json, os, subprocess, sys, time, traceback
page, steps = json.load(sys.stdin)
namespace = {"__name__": "__tutorial__"}
python = sys.executable
for s in steps:
    where = f"{page}:{s['line']}"
    print(f"--- {where} ({s['kind']})", flush=True)
    t0 = time.perf_counter()
    if s["kind"] == "file":
        os.makedirs(os.path.dirname(s["name"]) or ".", exist_ok=True)
        with open(s["name"], "w") as f:
            f.write(s["code"])
        continue
    if s["kind"] == "python":
        try:
            exec(compile(s["code"], where, "exec"), namespace)
        except BaseException:
            traceback.print_exc()
            print(f"FAILED: {where}", flush=True)
            sys.exit(1)
    else:
        code = s["code"].replace(".venv/bin/python", python).replace(".venv/bin/ancf", python + " -m ancf")
        run = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", code])
        if run.returncode:
            print(f"FAILED: {where} (exit {run.returncode})", flush=True)
            sys.exit(1)
    print(f"--- {where}: {time.perf_counter() - t0:.1f} s", flush=True)
'''


def test_the_tutorials_have_runnable_blocks():
    """Every tutorial page runs something, and every block it does not run says why."""
    assert PAGES, "no tutorial pages"
    for page in PAGES:
        assert any(s["kind"] in RUNS for s in steps(page)), f"{page.name}: no block runs"
        for b in blocks(page):
            if b["lang"] in RUNS and b["skip"] is not None:
                assert b["skip"].strip(), f"{page.name}:{b['line']}: 'not run' without a reason"


# the element, law and first-scene tutorials (about 15, 4 and 8 s: their compiles and runs) run in the full tier;
# the other tutorials keep the steps' runner in the quick one
@pytest.mark.parametrize("page", tiered(PAGES, lambda p: p.stem in SLOW_PAGES,
                                        "test_a_tutorial_runs_as_written"), ids=[p.stem for p in PAGES])
def test_a_tutorial_runs_as_written(page, tmp_path):
    if page.stem in CONTINUUM_PAGES and not HAS_FENICSX:
        pytest.skip(f"{page.name} runs the default continuum code, DOLFINx, which is not installed here")
    for name in ("scenes", "examples"):
        (tmp_path / name).symlink_to(ROOT / name)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), str(tmp_path)]),
               OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    t0 = time.perf_counter()
    run = subprocess.run([sys.executable, "-c", DRIVER], input=json.dumps([page.name, steps(page)]),
                         cwd=tmp_path, env=env, capture_output=True, text=True, timeout=2 * PAGE_BUDGET_S)
    took = time.perf_counter() - t0
    assert run.returncode == 0, f"{page.name} failed:\n{run.stdout[-4000:]}\n{run.stderr[-4000:]}"
    assert took < PAGE_BUDGET_S, f"{page.name} took {took:.0f} s (budget {PAGE_BUDGET_S:g} s):\n{run.stdout}"
