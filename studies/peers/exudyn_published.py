"""Our Exudyn set-up against Exudyn's own published numbers for its ANCF cable.

    .venv/bin/python -m studies peers published [--report]        (the checks; Exudyn runs in .venv-peers)

Before the pendulum comparison (:mod:`studies.peers.compare`) says anything about Exudyn's
cable, the cable as we set it up must give the numbers Exudyn's author published for it.
Each case (:data:`CASES`) is built by the harness's cable builder (``exudyn_model.add_cable``:
the same ObjectANCFCable2D, gravity through LoadMassProportional, supports as
CoordinateConstraints of the first node's coordinates, here also a tip Force; and
``static_settings``: the pendulum's linear solver and output settings, the static solver's
Newton to the tolerances the published run used), solved by ``SolveStatic`` in
``.venv-peers``, and compared with the published value of each quantity:

- ``mini-cable2d``: the ObjectANCFCable2D "MINI EXAMPLE" (a cable of 32 elements, L = 2 m,
  EA = 1e6 N, EI = 833.33 N m^2, rhoA = 78 kg/m, clamped at x = 0, under gravity, static
  with Exudyn's default Newton tolerances): ux of the free end, -0.5013058140308901 m,
  Exudyn's own regression reference for it.
- ``cantilever-N``: the static table of the example ``ANCFcantileverTest.py`` (L = 2 m, E =
  2.07e11 Pa, b = h = 0.1 m, clamped, a tip force f = 3 EI / L^2 downwards, relTol 1e-8,
  absTol 1e-3, EigenSparse, one load step), N = 1, 2, ..., 256 elements: the tip's
  displacement (x, y) of each row; the 256-element run also against the table's
  "converged" value and, solved a second time from its result as the example's author did,
  against the table's "with second SolveStatic" line.
- ``cantilever-1-tight``: a diagnostic, the 1-element row with the static Newton to relTol
  1e-13 (the published 1-element row is Newton-converged further than relTol 1e-8 asks).

Sources: :data:`SOURCE` (Exudyn's repository at a named commit; the installed wheel ships
neither Examples, TestModels nor docs: see :data:`INSTALLED`). Tolerances are derived from
the published material before any run (:data:`MINI_TOL`, :data:`ROW_TOL`, the converged
check's in :func:`cases`), each with its reason in the case.

The peer side, which runs in ``.venv-peers``, is the script :data:`PEER_SCRIPT`
(``exudyn_static.py``): it is given :func:`cases` as JSON and prints its runs as JSON.
"""
from __future__ import annotations

import json
from pathlib import Path

from .venv import PEER_PYTHON, run_peer_script

ROOT = Path(__file__).resolve().parents[2]
RECORD = ROOT / "reports" / "data" / "peers" / "peers-published.json"
PEER_SCRIPT = Path(__file__).with_name("exudyn_static.py")      # the peer side, run in .venv-peers

# -- the published material ---------------------------------------------------------------
REPO = "jgerstmayr/EXUDYN"
# the repository's commit cited: 2026-08-05, "final commit for Exudyn1.11.0" (docs/theDoc/version.txt: 1.11.0)
TREE = "e44aca1b4fe3e5f4d820ff407fb3fd30b6581c1c"
INSTALLED = ("not in the installed wheel: exudyn 1.13.6 from PyPI (.venv-peers/lib/python3.11/site-packages/exudyn) "
             "ships no Examples, TestModels or docs, and a search of the package, its compiled modules included, "
             "finds neither number; PyPI has no source distribution of 1.13.6. Cited from Exudyn's repository "
             f"{REPO} at {TREE[:10]} (its tree of version 1.11.0, the newest stored)")
SOURCE = {
    "mini-cable2d": {
        "files": ["main/pythonDev/TestModels/runTestSuiteRefSol.py:176 (MiniExamplesReferenceSolution, "
                  "'ObjectANCFCable2D.py')",
                  "main/pythonDev/TestModels/MiniExamples/ObjectANCFCable2D.py:51 (#ux=-0.5013058140308901)",
                  "docs/RST/items/ObjectANCFCable2D.rst:587-617 (MINI EXAMPLE for ObjectANCFCable2D)"],
        "since": "commit 1d942e01 (2022-03-18); Exudyn's test-suite logs V1.2.0 to V1.10.0 "
                 "(main/pythonDev/TestSuiteLogs/, Linux, Windows, macOS) all print RESULT = -0.5013058140308901",
    },
    "cantilever": {
        "files": ["main/pythonDev/Examples/ANCFcantileverTest.py:135-148 (the static branch, doDynamicSimulation = "
                  "False; table dated 2022-03-16, nEL = 1 ... 256, and 'converged')"],
        "since": "commit 1d942e01 (2022-03-18); the file's header: 'Update: 2022-03-16: get to run static example "
                 "again, compared to paper!'",
    },
}

# ObjectANCFCable2D mini example (TestModels/MiniExamples/ObjectANCFCable2D.py)
MINI = {"length": 2.0, "elements": 32, "EA": 1.0e6, "EI": 833.3333333333333, "rhoA": 78.0,
        "gravity": [0.0, -9.81], "support": "clamp", "tip_force": None}
MINI_STATIC = {"relative_tolerance": 1e-8, "absolute_tolerance": 1e-10}     # mbs.SolveStatic(): Exudyn's defaults
MINI_UX = -0.5013058140308901
# Exudyn's test suite accepts this very value on Linux at |result - reference| < 3e-11
# (runTestSuite.py:81, TSScope.testTolerance); our run differs from the mini example only in
# the linear solver (EigenSparse, the example's default is EXUdense): round-off, not the model
MINI_TOL = 3e-11
MINI_TOL_WHY = ("Exudyn's own test suite accepts this value on Linux within 3e-11 (runTestSuite.py:81, "
                "TSScope.testTolerance); the same model and Newton tolerances, only the linear solver differs "
                "(ours EigenSparse, the example's default EXUdense): round-off")

# ANCFcantileverTest.py, static branch
CANTI_L, CANTI_E, CANTI_B, CANTI_H, CANTI_RHO = 2.0, 2.07e11, 0.1, 0.1, 7800.0
CANTI_STATIC = {"relative_tolerance": 1e-8, "absolute_tolerance": 1e-3}
# its table "2022-03-16": elements -> tip displacement (x, y), m
CANTI_TABLE = {
    1: (-0.36224472989050654, -0.9941447587249747),
    2: (-0.4889263085609102, -1.1752228652637502),
    4: (-0.5074287154557922, -1.2055337025602493),
    8: (-0.5085092365729895, -1.207197756093103),
    16: (-0.5085365799149556, -1.207238895003594),
    32: (-0.508537277761696, -1.2072398264650905),
    64: (-0.5085373030408489, -1.207239853404364),
    128: (-0.5085373043168473, -1.2072398545511795),
    256: (-0.5085373043916903, -1.207239854614031),
}
CANTI_CONVERGED = (-0.508537304326, -1.207239854550)        # "converged:", 12 decimals
# the same file's older table ("here (OLD)", same settings): the spread of a rerun of one mesh
CANTI_OLD = {1: (-0.36224472989050543, -0.994144758724973), 2: (-0.4889263083414858, -1.1752228650551666),
             4: (-0.5074287151188892, -1.2055337022335404), 8: (-0.5085092364970802, -1.2071977560198281),
             64: (-0.5085373029700947, -1.2072398533360738), 256: (-0.5085373043209689, -1.2072398545457785)}
# and its second SolveStatic of the 256-element run
CANTI_SECOND_256 = (-0.5085373043209366, -1.2072398545457574)


def rerun_spread() -> float:
    """The largest distance, in one coordinate, between two published runs of one mesh (the
    2022-03-16 table against the older one, and the 256-element run against its second
    SolveStatic): how far the static Newton's stop (relTol 1e-8 of a 1.29e7 N load) moves
    a published row. 3.4e-10 m (4 elements, x)."""
    d = [abs(a - b) for n, old in CANTI_OLD.items() for a, b in zip(CANTI_TABLE[n], old)]
    d += [abs(a - b) for a, b in zip(CANTI_TABLE[256], CANTI_SECOND_256)]
    return max(d)


# a row of the table: three times the largest rerun spread, rounded up to a decade's unit
ROW_TOL = 1e-9
ROW_TOL_WHY = ("the published rows are printed to 16 digits, but two published runs of one mesh (the file's 2022-03-16 "
               "table against its older one, and the 256-element run against its second SolveStatic) differ by up to "
               "3.4e-10 m: the static Newton's stop at relTol 1e-8; 1e-9 m is three times that")


# Checks added after the first run say so in the record and the report: the second
# SolveStatic's (a published line the first run did not read), and the diagnostic's, whose
# tolerance was set after a probe run of it had given 1.7e-16 and 3.3e-16 m
AFTER_FIRST_RUN = "added after the first run"
# the diagnostic run of the 1-element row with a tight Newton
TIGHT_STATIC = {"relative_tolerance": 1e-13, "absolute_tolerance": 1e-9}
TIGHT_TOL = 1e-14
TIGHT_TOL_WHY = ("the three published 1-element values (the 2022-03-16 table, the older one, the MATLAB value quoted "
                 "beside them: x = -0.3622447298905063) agree within 1.1e-15 m, a Newton-converged value; ten times "
                 "that for a run whose Newton is converged too")


def converged_tolerance() -> float:
    """The 256-element run against the table's "converged" value: a row's tolerance, plus
    the 256 mesh's distance from the limit (the table's last step 128 -> 256 over 15: the
    steps 32 -> 64 -> 128 -> 256 shrink 16-fold, fourth order), plus half a unit of its
    12th decimal."""
    step = max(abs(a - b) for a, b in zip(CANTI_TABLE[256], CANTI_TABLE[128]))
    return ROW_TOL + step / 15.0 + 0.5e-12


def cantilever_model(elements: int) -> dict:
    A, I = CANTI_B * CANTI_H, CANTI_B * CANTI_H ** 3 / 12.0
    EI = CANTI_E * I
    return {"length": CANTI_L, "elements": elements, "EA": CANTI_E * A, "EI": EI, "rhoA": CANTI_RHO * A,
            "gravity": None, "support": "clamp", "tip_force": [0.0, -3.0 * EI / CANTI_L ** 2]}


def cases() -> list[dict]:
    """Every run and its checks, as data: model (the inputs of ``add_cable``), static
    (Newton tolerances), source, and checks [{check, quantity, published, tolerance, why}]."""
    out = [{"name": "mini-cable2d", "title": "ObjectANCFCable2D mini example: clamped cable under its own weight",
            "model": MINI, "static": MINI_STATIC, "source": SOURCE["mini-cable2d"],
            "checks": [{"check": "mini example", "quantity": "ux", "published": MINI_UX, "tolerance": MINI_TOL,
                        "why": MINI_TOL_WHY}]}]
    conv_tol = converged_tolerance()
    for n, (x, y) in CANTI_TABLE.items():
        checks = [{"check": f"table, {n} element{'s' if n > 1 else ''}", "quantity": q, "published": v,
                   "tolerance": ROW_TOL, "why": ROW_TOL_WHY} for q, v in (("ux", x), ("uy", y))]
        if n == max(CANTI_TABLE):
            why = (f"a row's {ROW_TOL:g} m, plus the 256 mesh's distance from the limit (the table's last step "
                   f"128 -> 256 over 15: fourth-order convergence), plus half a unit of the 12th decimal")
            checks += [{"check": "converged", "quantity": q, "published": v, "tolerance": conv_tol, "why": why}
                       for q, v in zip(("ux", "uy"), CANTI_CONVERGED)]
            # added after the first run (its tolerance is a row's, fixed before it)
            checks += [{"check": f"{n} elements, second SolveStatic", "quantity": q, "published": v,
                        "tolerance": ROW_TOL, "why": ROW_TOL_WHY, "added": AFTER_FIRST_RUN}
                       for q, v in zip(("ux2", "uy2"), CANTI_SECOND_256)]
        out.append({"name": f"cantilever-{n}", "title": f"ANCFcantileverTest.py, static, {n} elements",
                    "model": cantilever_model(n), "static": CANTI_STATIC, "source": SOURCE["cantilever"],
                    "second_solve": n == max(CANTI_TABLE), "checks": checks})
    # A diagnostic, added after the first run, whose 1-element row was the farthest (8.2e-10 m
    # in y): the same run with the static Newton to relTol 1e-13. Three published 1-element
    # values (the 2022-03-16 table, the older one, the MATLAB value quoted beside them) agree
    # within 1.1e-15 m: that row is Newton-converged; a tight run must meet it to round-off.
    out.append({"name": "cantilever-1-tight", "title": "ANCFcantileverTest.py, static, 1 element, Newton to "
                "relTol 1e-13 (diagnostic)", "model": cantilever_model(1), "static": TIGHT_STATIC,
                "source": SOURCE["cantilever"],
                "checks": [{"check": "table, 1 element, Newton to 1e-13", "quantity": q, "published": v,
                            "tolerance": TIGHT_TOL, "why": TIGHT_TOL_WHY, "added": AFTER_FIRST_RUN}
                           for q, v in zip(("ux", "uy"), CANTI_TABLE[1])]})
    return out


# -- our side (.venv): run, compare, report -----------------------------------------------
def run_peer(python: Path | None = None, module: str = "fast") -> dict:
    """The peer side in .venv-peers (:data:`PEER_SCRIPT`, given :func:`cases`), its JSON."""
    return run_peer_script(PEER_SCRIPT, ["--module", module, "--cases", json.dumps(cases())], python or PEER_PYTHON)


def evaluate(peer: dict) -> list[dict]:
    """Each check of :func:`cases` with the peer's value: {run, check, quantity, published,
    peer, difference (peer - published), tolerance, why, agrees}; a run that failed gives
    peer None and agrees False."""
    rows = []
    for c in cases():
        r = peer["runs"].get(c["name"], {"status": "missing"})
        for k in c["checks"]:
            v = r.get(k["quantity"]) if r.get("status") == "converged" else None
            d = None if v is None else v - k["published"]
            rows.append({"run": c["name"], **k, "peer": v, "difference": d,
                         "agrees": d is not None and abs(d) <= k["tolerance"]})
    return rows


def record(peer: dict) -> dict:
    """What --report writes (:data:`RECORD`): the cases as data, the peer's output and the
    evaluated checks; the report section is drawn from it alone."""
    return {"cases": cases(), "peer": peer, "checks": evaluate(peer), "installed": INSTALLED,
            "repository": REPO, "tree": TREE}


def farthest(rec: dict) -> str:
    """The sentence on the check farthest from its published value, relative to its
    tolerance, and on the tight-Newton diagnostic of the 1-element row where it ran."""
    done = [k for k in rec["checks"] if k["difference"] is not None]
    if not done:
        return "No run gave a value."
    k = max(done, key=lambda k: abs(k["difference"]) / k["tolerance"])
    out = (f"The farthest, relative to its tolerance: {k['check']}, {k['quantity'].rstrip('2')}, "
           f"{k['difference']:.2e} m ({abs(k['difference']) / k['tolerance']:.2f} of {k['tolerance']:.2g} m).")
    runs = rec["peer"]["runs"]
    tight, plain = runs.get("cantilever-1-tight", {}), runs.get("cantilever-1", {})
    if tight.get("status") == "converged" and plain.get("status") == "converged":
        d = max(abs(x["difference"]) for x in done if x["run"] == "cantilever-1-tight")
        rest = [abs(x["difference"]) for x in done if x["run"].startswith("cantilever-") and x["check"].startswith(
            "table, ") and x["run"] not in ("cantilever-1", "cantilever-1-tight")]
        out += (f" The 1-element run stops after {plain['newtonSteps']} Newton iterations at a residual of "
                f"{plain['residual_N']:.2g} N (relTol {plain['relativeTolerance']:g}); with the Newton to relTol "
                f"{tight['relativeTolerance']:g} ({tight['newtonSteps']} iterations) it meets the published row "
                f"within {d:.1e} m: that published row is Newton-converged further than the example's relTol asks. "
                + (f"The other table rows agree within {max(rest):.1e} m, round-off: the same Newton iterate as the "
                   f"published runs." if rest else ""))
    return out


def published_markdown(rec: dict) -> str:
    """The peers report's section on Exudyn's published numbers, from :func:`record`'s
    output alone."""
    p = rec["peer"]
    checks = rec["checks"]
    n_ok = sum(k["agrees"] for k in checks)
    lines = ["## Exudyn against its own published numbers", "",
             f"Generated by `python -m studies peers published --report` from "
             f"`data/peers/{RECORD.name}`. Each case is built with the harness's cable set-up "
             "(`exudyn_model.add_cable`, the pendulum's and the adapter's: ObjectANCFCable2D, gravity by `LoadMassProportional`, the first node "
             "held by `CoordinateConstraint`s, a tip `Force`; `static_settings`: EigenSparse, one thread, the "
             "static Newton to the published run's tolerances) and solved by `SolveStatic` in `.venv-peers`: "
             f"Exudyn {p['exudyn']} ({p['module']}), numpy {p['numpy']}, Python {p['python']}.", "",
             f"Sources: {rec['installed']}.", ""]
    for c in rec["cases"]:
        if c["name"] == "mini-cable2d" or c["name"] == "cantilever-1":
            lines.append(f"- {c['title'] if c['name'] == 'mini-cable2d' else 'ANCFcantileverTest.py, static'}: "
                         + "; ".join(c["source"]["files"]) + f"; {c['source']['since']}.")
    lines += ["", f"{n_ok} of {len(checks)} checks agree within their tolerance. " + farthest(rec), "",
              "| check | quantity | published (m) | Exudyn here (m) | difference (m) | tolerance (m) | verdict |",
              "|---|---|---|---|---|---|---|"]
    for k in checks:
        peer = "failed" if k["peer"] is None else repr(k["peer"])
        diff = "-" if k["difference"] is None else f"{k['difference']:.2e}"
        lines.append(f"| {k['check']} | {k['quantity'].rstrip('2')} | {k['published']!r} | {peer} | {diff} | "
                     f"{k['tolerance']:.2g} | {'agrees' if k['agrees'] else 'DIFFERS'} |")
    lines += ["", "Tolerances, each derived from the published material (before the first run, unless the check "
              "says it was added after it):", ""]
    seen = []
    for k in checks:
        if (k["why"], k.get("added")) not in seen:
            seen.append((k["why"], k.get("added")))
            added = f" ({k['added']})" if k.get("added") else ""
            lines.append(f"- {k['check']}{added}: {k['tolerance']:.3g} m: {k['why']}.")
    lines += ["", "Exudyn's static runs (Newton iterations, final residual):", "",
              "| run | elements | Newton | residual (N) | linear solver | relTol | absTol |",
              "|---|---|---|---|---|---|---|"]
    for c in rec["cases"]:
        r = p["runs"][c["name"]]
        if r.get("status") != "converged":
            lines.append(f"| {c['name']} | {c['model']['elements']} | {r.get('status')}: {r.get('reason')} | | | | |")
            continue
        again = f" (then {r['newtonSteps2']})" if "newtonSteps2" in r else ""
        lines.append(f"| {c['name']} | {c['model']['elements']} | {r['newtonSteps']}{again} | {r['residual_N']:.2e} | "
                     f"{r['linearSolver']} | {r['relativeTolerance']:g} | {r['absoluteTolerance']:g} |")
    lines.append("")
    return "\n".join(lines)


def read_record(path: Path = RECORD) -> dict | None:
    return json.loads(path.read_text()) if path.exists() else None
