"""The peer benchmark's timed runs of a dynamic harness scene in Exudyn (runs in `.venv-peers`).

    .venv-peers/bin/python studies/peers/exudyn_pendulum.py SCENE.toml [--repeats 5]
                                                            [--newton modified|linear] [--module fast|regular]
    .venv-peers/bin/python studies/peers/exudyn_pendulum.py SCENE.toml --kernels

The scene is the one our solver runs (written by :func:`studies.peers.compare.peer`, with the
cable's element, ``studies/peers/exudyn.toml``): the paper's pendulum, or the work-precision
grid's points. Its model is the adapter's, :func:`exudyn_model.build` (beside this file), so
there is one way to run Exudyn: for the pendulum, ObjectANCFCable2D elements (Euler-Bernoulli,
linear elastic, E = 3 mu = 6 C10 of the plane-stress Yeoh law), the first node's position held
by two CoordinateConstraints (its slope, i.e. the rotation, free), gravity on every element,
released from horizontal at rest, generalized-alpha at the scene's rho_inf with its fixed step.
Imports only exudyn, numpy, the standard library and :mod:`exudyn_model`, never ``ancf``.

Settings ("fastest fair"): those of :func:`exudyn_model.dynamic_settings`, with ``--newton``:
modified Newton to Exudyn's default tolerances, or one linear solve per step (Exudyn's
``newton.active = False``, which takes a fresh Jacobian at each step's predictor; the
work-precision bench runs both). The compiled module is Exudyn's `fast` build (no range
checks, AVX2) when the CPU has AVX2, else the regular one (``--module`` chooses).

Output: one JSON object on the LAST line of stdout (anything Exudyn prints comes before
it): the settings, the build and solve wall times of ``--repeats`` warm repetitions
(one untimed warm-up first; each repetition builds a fresh system outside the timed
region, then times ``SolveDynamic`` alone), their medians, and the tip (last node)
position in m at the scene's output times. ``--kernels``: the force and Jacobian calls'
times instead (:func:`kernel_times`).
"""
from __future__ import annotations

import argparse
import json
import platform
import statistics
import sys
import time
import tomllib
from pathlib import Path

from exudyn_model import NEWTON, build, tip_history      # beside this file (the script's directory is on sys.path)


def settings_summary(exu, model, scene: dict) -> dict:
    """What the run was: Exudyn's version and module, the model's element and section, and
    every setting of its time integration that bears on the time."""
    s, sec = model.settings, model.section
    ti = s.timeIntegration
    nw = ti.newton
    return {
        "exudyn": exu.__version__, "module": exu.__dict__.get("_compiledModuleName", "?"),
        "python": platform.python_version(),
        "scene": scene["name"], "element": model.element, "elements": len(model.nodes) - 1,
        "height_m": scene["beam"]["height"], "E_Pa": sec["E"], "EA_N": sec["EA"], "EI_Nm2": sec["EI"],
        "rhoA_kg_m": sec["rhoA"], "support": scene["supports"]["left"],
        "pin": "CoordinateConstraint x, y of node 0 to ground (slope free)",
        "gravity": "MarkerBodyMass + LoadMassProportional (0, -9.81, 0) per element",
        "solverType": str(ti.solverType), "spectralRadius": ti.generalizedAlpha.spectralRadius,
        "useNewmark": bool(ti.generalizedAlpha.useNewmark),
        "useIndex2Constraints": bool(ti.generalizedAlpha.useIndex2Constraints),
        "computeInitialAccelerations": bool(ti.generalizedAlpha.computeInitialAccelerations),
        "linearSolver": str(s.linearSolver.solverType),
        "reuseAnalyzedPattern": bool(s.linearSolver.reuseAnalyzedPattern),
        "newton": {"active": bool(nw.active), "useModifiedNewton": bool(nw.useModifiedNewton),
                   "relativeTolerance": nw.relativeTolerance, "absoluteTolerance": nw.absoluteTolerance,
                   "maxIterations": nw.maxIterations,
                   "maxModifiedNewtonIterations": nw.maxModifiedNewtonIterations,
                   "modifiedNewtonContractivity": nw.modifiedNewtonContractivity,
                   "modifiedNewtonJacUpdatePerStep": bool(nw.modifiedNewtonJacUpdatePerStep),
                   "numericalDifferentiation_forODE2": bool(nw.numericalDifferentiation.forODE2)},
        "adaptiveStep": bool(ti.adaptiveStep), "reuseConstantMassMatrix": bool(ti.reuseConstantMassMatrix),
        "threads": s.parallel.numberOfThreads,
        "dt": ti.endTime / ti.numberOfSteps, "steps": int(ti.numberOfSteps), "endTime": ti.endTime,
    }


def kernel_times(exu, scene: dict, calls: int = 100, repeats: int = 10) -> dict:
    """Chrono's form for the cable: the solver's ODE2 right-hand side (internal forces of
    every cable element, plus the gravity loads) and its Jacobian, each called through
    the Python interface of an initialised MainSolverImplicitSecondOrder (Exudyn does not
    expose one element's force), warm: 10 untimed calls, then ``repeats`` x ``calls``;
    microseconds per call and per element in thread CPU time (median over the repeats;
    the Python call's own cost is included)."""
    model = build(exu, scene)
    mbs, s, elements = model.mbs, model.settings, len(model.nodes) - 1
    solver = exu.MainSolverImplicitSecondOrder()
    solver.InitializeSolver(mbs, s)
    out = {}
    calls_of = {"force": lambda: solver.ComputeODE2RHS(mbs),
                "tangent": lambda: solver.ComputeJacobianODE2RHS(mbs, 1.0, 0.0, 0.0)}
    for name, f in calls_of.items():
        for _ in range(10):
            f()
        per = []
        for _ in range(repeats):
            t0 = time.thread_time()
            for _ in range(calls):
                f()
            per.append((time.thread_time() - t0) / calls)
        out[name] = {"us_per_call": [x * 1e6 for x in per], "us_per_element": statistics.median(per) * 1e6 / elements}
    solver.FinalizeSolver(mbs, s)
    return {"status": "converged", "exudyn": exu.__version__, "elements": elements, "calls": calls,
            "repeats": repeats, **out}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="exudyn_pendulum.py", description=__doc__.splitlines()[0])
    p.add_argument("scene", type=Path, help="a dynamic harness scene (TOML) with the cable's element")
    p.add_argument("--repeats", type=int, default=5, help="timed warm repetitions (default 5)")
    p.add_argument("--newton", choices=NEWTON, default="modified",
                   help="modified: modified Newton to Exudyn's default tolerances (default); linear: one linear "
                   "solve per step (newton.active = False)")
    p.add_argument("--module", choices=("fast", "regular"), default="fast",
                   help="Exudyn compiled module: fast (no range checks, AVX2, if the CPU has it) or regular")
    p.add_argument("--kernels", action="store_true", help="time the force and Jacobian calls instead "
                   "(kernel_times) and print them as JSON")
    a = p.parse_args(argv)
    scene = tomllib.loads(a.scene.read_text())
    if scene["analysis"]["kind"] != "dynamic":
        p.error(f"analysis.kind: the timed runs take a dynamic scene, got {scene['analysis']['kind']!r}")

    sys.exudynFast = a.module == "fast"
    import exudyn as exu
    if a.kernels:
        print(json.dumps(kernel_times(exu, scene)))
        return 0

    builds, solves, cpus, newton = [], [], [], None
    tips = summary = None
    times = [t for t in scene["analysis"].get("output_times") or [scene["analysis"]["t_end"]] if t > 0]
    for rep in range(a.repeats + 1):               # rep 0: untimed warm-up
        t0 = time.perf_counter()
        model = build(exu, scene, a.newton)
        mbs = model.mbs
        t1, c1 = time.perf_counter(), time.process_time()
        ok = mbs.SolveDynamic(model.settings)
        t2, c2 = time.perf_counter(), time.process_time()
        if not ok:
            print(json.dumps({"status": "failed", "reason": "SolveDynamic returned False"}))
            return 1
        if rep:
            builds.append(t1 - t0)
            solves.append(t2 - t1)
            cpus.append(c2 - c1)
        tips = tip_history(exu, model, times)
        solver = mbs.sys["dynamicSolver"]
        newton = {"newtonSteps": int(solver.it.newtonStepsCount),
                  "newtonJacobians": int(solver.it.newtonJacobiCount),
                  "currentStepIndex": int(solver.it.currentStepIndex),
                  "ODE2_coordinates": int(mbs.systemData.ODE2Size()),
                  "algebraic_coordinates": int(mbs.systemData.AEsize())}
        summary = settings_summary(exu, model, scene)
        del model, mbs
    print(json.dumps({
        "status": "converged", "settings": summary, "counters": newton,
        "repeats": a.repeats, "build_s": builds, "solve_s": solves,
        "build_median_s": statistics.median(builds), "solve_median_s": statistics.median(solves),
        "solve_cpu_s": cpus, "solve_cpu_median_s": statistics.median(cpus),
        "tip_history": tips,
    }))
    return 0


if __name__ == "__main__":
    sys.exit(main())
