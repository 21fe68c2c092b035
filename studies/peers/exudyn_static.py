"""The static cases of Exudyn's published numbers, run in Exudyn (the peer side of
:mod:`studies.peers.exudyn_published`; runs in `.venv-peers`).

    .venv-peers/bin/python studies/peers/exudyn_static.py --cases CASES_JSON [--module fast|regular]

Imports only exudyn, numpy, the standard library and the builders beside this file
(``exudyn_model``: :func:`add_cable`, :func:`static_settings`), never ``ancf``:
this file runs in the separate venv that ``tools/setup_peers.sh`` creates. The cases come
as JSON on the command line (:func:`studies.peers.exudyn_published.cases`, as data:
model, static tolerances, whether to solve a second time); each is built by
:func:`solve` and solved by ``SolveStatic``. Output: one JSON object on the LAST line of
stdout: the versions, and each case's run by name.
"""
from __future__ import annotations

import argparse
import json
import platform
import sys

import exudyn_model as model      # beside this file (the script's directory is on sys.path)


def solve(exu, case: dict) -> dict:
    """One case built by the harness's cable builder and solved by SolveStatic: the free end's
    displacement {'ux', 'uy'} (GetNodeOutput Displacement of the last node: the example's
    last node's ODE2 coordinates) and the static solver's counters."""
    m = case["model"]
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    support = {"pin": model.PIN, "clamp": model.CLAMP}[m["support"]]
    nodes = model.add_cable(mbs, m["length"], m["elements"], EA=m["EA"], EI=m["EI"], rhoA=m["rhoA"],
                            gravity=m["gravity"], support=support, tip_force=m["tip_force"])
    mbs.Assemble()
    s = model.static_settings(exu, case["static"]["relative_tolerance"], case["static"]["absolute_tolerance"])
    second = case.get("second_solve", False)   # as the example's author: SolveStatic again from the result
    try:
        mbs.SolveStatic(s, updateInitialValues=second)       # raises exudyn.SolverError when it fails
        solver = mbs.sys["staticSolver"]
        u = mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Displacement)
        again = {}
        if second:
            mbs.SolveStatic(s)
            u2 = mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Displacement)
            again = {"ux2": float(u2[0]), "uy2": float(u2[1]),
                     "newtonSteps2": int(mbs.sys["staticSolver"].it.newtonStepsCount)}
    except Exception as e:                     # the record says so, and its checks fail
        return {"status": "failed", "reason": f"{type(e).__name__}: {e}"[:300]}
    return {"status": "converged", "ux": float(u[0]), "uy": float(u[1]), **again,
            "newtonSteps": int(solver.it.newtonStepsCount), "newtonJacobians": int(solver.it.newtonJacobiCount),
            "residual_N": float(solver.conv.residual), "linearSolver": str(s.linearSolver.solverType),
            "relativeTolerance": s.staticSolver.newton.relativeTolerance,
            "absoluteTolerance": s.staticSolver.newton.absoluteTolerance,
            "numberOfLoadSteps": int(s.staticSolver.numberOfLoadSteps),
            "adaptiveStep": bool(s.staticSolver.adaptiveStep)}


def peer_main(module: str, cases: list[dict]) -> int:
    """Every case solved in Exudyn's ``module`` build, printed as JSON on the last line."""
    sys.exudynFast = module == "fast"
    import exudyn as exu
    import numpy

    runs = {c["name"]: solve(exu, c) for c in cases}
    print(json.dumps({"status": "converged", "exudyn": exu.__version__, "numpy": numpy.__version__,
                      "module": exu.__dict__.get("_compiledModuleName", "?"), "python": platform.python_version(),
                      "runs": runs}))
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="exudyn_static.py", description=__doc__.splitlines()[0])
    ap.add_argument("--cases", required=True, help="the cases as JSON (exudyn_published.cases())")
    ap.add_argument("--module", choices=("fast", "regular"), default="fast",
                    help="Exudyn's compiled module (default fast, as the pendulum comparison)")
    a = ap.parse_args(argv)
    return peer_main(a.module, json.loads(a.cases))


if __name__ == "__main__":
    sys.exit(main())
