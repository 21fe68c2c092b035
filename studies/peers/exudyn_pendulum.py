"""The paper's flexible pendulum in Exudyn (peer benchmark; runs in `.venv-peers`).

    .venv-peers/bin/python studies/peers/exudyn_pendulum.py [--dt 1e-3] [--rho-inf 0.8]

Imports only exudyn, numpy and the standard library (not ``ancf``): this file runs in the
separate venv that ``tools/setup_peers.sh`` creates, never in ``.venv``. Its builders are the
peer's one set-up of the cable, shared with the checks against Exudyn's published numbers
(``exudyn_static.py``, for ``exudyn_published.py``): :func:`add_cable` (the elements, gravity, the first node's support,
a tip force), :func:`common_settings`, :func:`static_settings` and :func:`dynamic_settings`.

The model: 32 (``--elements``) ObjectANCFCable2D elements (Euler-Bernoulli, linear elastic, 2 nodes with
position and slope, 8 coordinates each), L = 0.350 m, h = 0.005 m (``--height``), w = 0.007 m, density
2150 kg/m^3, E = 6 C10 with C10 = 0.545235 MPa (the small-strain Young's modulus of the
incompressible plane-stress Yeoh law: E = 3 mu, mu = 2 C10), A = h w, I = w h^3 / 12.
The left node's position is held at the origin by two CoordinateConstraints (its slope,
i.e. the rotation, is free); gravity (0, -9.81) m/s^2 on every element through
MarkerBodyMass + LoadMassProportional; released from horizontal at rest; 0.5 s with a
fixed step.

Settings ("fastest fair"): generalized-alpha with spectral radius = rho_inf, modified
Newton (``--newton linear``: one linear solve per step instead, Exudyn's
``newton.active = False``, which takes a fresh Jacobian at each step's predictor; the
work-precision bench runs both), EigenSparse linear solver, fixed step (adaptiveStep off:
a failed step stops the run instead of being silently cut), no solution / restart /
sensor files, verbose off, one thread. The compiled module is Exudyn's `fast` build (no
range checks, AVX2) when the CPU has AVX2, else the regular one (``--module`` chooses).

Output: one JSON object on the LAST line of stdout (anything Exudyn prints comes before
it): the settings, the build and solve wall times of ``--repeats`` warm repetitions
(one untimed warm-up first; each repetition builds a fresh system outside the timed
region, then times ``SolveDynamic`` alone), their medians, and the tip (last node)
position in m at the output times.
"""
from __future__ import annotations

import argparse
import json
import platform
import statistics
import sys
import time

L, H, W = 0.350, 0.005, 0.007          # m
DENSITY = 2150.0                       # kg/m^3 (Yeoh, the paper's Table 2)
C10 = 0.545235e6                       # Pa
E = 6.0 * C10                          # Pa, small-strain modulus of incompressible plane-stress Yeoh
GRAVITY = (0.0, -9.81)                 # m/s^2
ELEMENTS = 32
T_END = 0.5                            # s
OUTPUT_TIMES = (0.1, 0.2, 0.3, 0.4, 0.5)
NEWTON = ("modified", "linear")        # --newton: Exudyn's Newton, or one linear solve per step


# Supports of the cable's first node, as the node coordinates held at their reference
# values (NodePoint2DSlope1: x, y, slope x, slope y); Exudyn's examples write the same as
# ``fixedConstraintsNode0`` of GenerateStraightLineANCFCable2D, a 0/1 list
PIN = (0, 1)                  # x, y held, the slope (the rotation) free: the pendulum
CLAMP = (0, 1, 3)             # x, y and the slope's y held: a cantilever ([1, 1, 0, 1])


def add_cable(mbs, length: float, elements: int, EA: float, EI: float, rhoA: float,
              gravity: tuple | None = None, support: tuple = PIN, tip_force: tuple | None = None) -> list:
    """A straight cable from the origin along x in ``mbs``: ``elements`` ObjectANCFCable2D of
    equal length (nodes with unit slope (1, 0)); ``gravity`` (gx, gy) on every element through
    MarkerBodyMass + LoadMassProportional (none if None); the first node's coordinates
    ``support`` (:data:`PIN`, :data:`CLAMP`) held at their reference values by one
    CoordinateConstraint each to a ground node; ``tip_force`` (fx, fy) a Force on the last
    node's position (MarkerNodePosition; none if None). Returns the node numbers."""
    from exudyn.itemInterface import (LoadMassProportional, MarkerBodyMass, NodePoint2DSlope1, ObjectANCFCable2D,
                                      VObjectANCFCable2D)
    le = length / elements
    nodes = [mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[i * le, 0.0, 1.0, 0.0]))
             for i in range(elements + 1)]
    for i in range(elements):
        cable = mbs.AddObject(ObjectANCFCable2D(
            length=le, massPerLength=rhoA, bendingStiffness=EI, axialStiffness=EA,
            nodeNumbers=[nodes[i], nodes[i + 1]], visualization=VObjectANCFCable2D(show=False)))
        if gravity is not None:
            m = mbs.AddMarker(MarkerBodyMass(bodyNumber=cable))
            mbs.AddLoad(LoadMassProportional(markerNumber=m, loadVector=[gravity[0], gravity[1], 0.0]))
    hold_and_push(mbs, nodes, support, tip_force)
    return nodes


def hold_and_push(mbs, nodes: list, support: tuple, tip_force: tuple | None) -> None:
    """The first node's coordinates ``support`` held at their reference values (one
    CoordinateConstraint each to a ground node) and ``tip_force`` (fx, fy) a Force on the
    last node's position (none if None): the support and tip load of every beam here."""
    from exudyn.itemInterface import (CoordinateConstraint, Force, MarkerNodeCoordinate, MarkerNodePosition,
                                      NodePointGround, VCoordinateConstraint)
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0]))
    mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
    for c in support:
        mc = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=c))
        mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mc], visualization=VCoordinateConstraint(show=False)))
    if tip_force is not None:
        mt = mbs.AddMarker(MarkerNodePosition(nodeNumber=nodes[-1]))
        mbs.AddLoad(Force(markerNumber=mt, loadVector=[tip_force[0], tip_force[1], 0.0]))


def common_settings(exu, s) -> None:
    """The settings every peer run shares, dynamic or static: EigenSparse linear solver, one
    thread, no solution / restart files, no statistics or timers printed."""
    s.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    s.parallel.numberOfThreads = 1
    s.solution.file.write = False
    s.solution.restart.write = False
    s.show.statistics = False
    s.show.computationTime = False
    s.show.globalTimers = False


def static_settings(exu, relative_tolerance: float, absolute_tolerance: float):
    """SimulationSettings for ``SolveStatic``: :func:`common_settings`, the static solver's
    Newton to the given tolerances (Exudyn's test: |residual| / |initial residual| <= relative
    or |residual| <= absolute, in N), verbose off; everything else at Exudyn's defaults (full
    Newton, one load step, adaptive load stepping)."""
    s = exu.SimulationSettings()
    common_settings(exu, s)
    ss = s.staticSolver
    ss.newton.relativeTolerance = relative_tolerance
    ss.newton.absoluteTolerance = absolute_tolerance
    ss.verboseMode = 0
    ss.verboseModeFile = 0
    return s


def build(exu, dt: float, rho_inf: float, elements: int = ELEMENTS, newton: str = "modified"):
    """A fresh SystemContainer with the assembled pendulum, its settings and the tip sensor.
    ``newton`` (:data:`NEWTON`): "modified", modified Newton to Exudyn's default tolerances;
    "linear", one linear solve per step (``newton.active = False``: the step's equations
    linearised at its predictor, no convergence test)."""
    from exudyn.itemInterface import SensorNode
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    A, I = H * W, W * H ** 3 / 12.0
    # pin: x and y of the first node held at 0 (slope coordinates free)
    nodes = add_cable(mbs, L, elements, EA=E * A, EI=E * I, rhoA=DENSITY * A, gravity=GRAVITY, support=PIN)
    tip = mbs.AddSensor(SensorNode(nodeNumber=nodes[-1], outputVariableType=exu.OutputVariableType.Position,
                                   storeInternal=True, writeToFile=False))
    mbs.Assemble()

    s = dynamic_settings(exu, dt, T_END, rho_inf, newton)
    return SC, mbs, s, tip


def dynamic_settings(exu, dt: float, t_end: float, rho_inf: float, newton: str = "modified",
                     newmark: bool = False):
    """SimulationSettings for ``SolveDynamic``: :func:`common_settings`, generalized-alpha at
    ``rho_inf`` (``newmark``: Exudyn's Newmark form of it), a fixed step ``dt`` to ``t_end``
    (no adaptive or automatic step: a failed step stops the run), the sensors sampled every
    step, verbose off; ``newton`` (:data:`NEWTON`) as in :func:`build`."""
    s = exu.SimulationSettings()
    common_settings(exu, s)
    ti = s.timeIntegration
    ti.solverType = exu.DynamicSolverType.GeneralizedAlpha
    ti.generalizedAlpha.spectralRadius = rho_inf
    ti.generalizedAlpha.useNewmark = newmark
    ti.generalizedAlpha.useIndex2Constraints = False
    ti.generalizedAlpha.computeInitialAccelerations = True
    # linear: one solve per step with the Jacobian at the step's predictor (newton.active =
    # False; with modified Newton on, the first step's Jacobian would serve every step and
    # the run diverges: measured, thick scene, 2 cables, 10 ms)
    ti.newton.useModifiedNewton = newton != "linear"
    ti.newton.active = newton != "linear"
    ti.startTime = 0.0
    ti.endTime = t_end
    ti.numberOfSteps = int(round(t_end / dt))
    ti.adaptiveStep = False
    ti.automaticStepSize = False
    ti.verboseMode = 0
    ti.verboseModeFile = 0
    s.solution.sensors.writePeriod = dt       # sample every step; output times picked by the caller
    return s


def settings_summary(exu, s, steps: int, dt: float, elements: int = ELEMENTS) -> dict:
    ti = s.timeIntegration
    nw = ti.newton
    return {
        "exudyn": exu.__version__, "module": exu.__dict__.get("_compiledModuleName", "?"),
        "python": platform.python_version(),
        "element": "ObjectANCFCable2D", "elements": elements,
        "height_m": H, "E_Pa": E, "EA_N": E * H * W, "EI_Nm2": E * W * H ** 3 / 12.0, "rhoA_kg_m": DENSITY * H * W,
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
        "dt": dt, "steps": steps, "endTime": ti.endTime,
    }


def kernel_times(exu, elements: int, calls: int = 100, repeats: int = 10) -> dict:
    """Chrono's form for the cable: the solver's ODE2 right-hand side (internal forces of
    every cable element, plus the gravity loads) and its Jacobian, each called through
    the Python interface of an initialised MainSolverImplicitSecondOrder (Exudyn does not
    expose one element's force), warm: 10 untimed calls, then ``repeats`` x ``calls``;
    microseconds per call and per element in thread CPU time (median over the repeats;
    the Python call's own cost is included)."""
    SC, mbs, s, _ = build(exu, 1e-3, 0.8, elements)
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
    global H
    p = argparse.ArgumentParser(prog="exudyn_pendulum.py", description=__doc__.splitlines()[0])
    p.add_argument("--dt", type=float, default=1e-3, help="fixed time step, s (default 1e-3)")
    p.add_argument("--rho-inf", type=float, default=0.8, help="generalized-alpha spectral radius (default 0.8)")
    p.add_argument("--repeats", type=int, default=5, help="timed warm repetitions (default 5)")
    p.add_argument("--elements", type=int, default=ELEMENTS, help=f"cable elements (default {ELEMENTS})")
    p.add_argument("--height", type=float, default=H, help=f"cross-section height h, m (default {H}; the "
                   "work-precision's thick scene: 0.02)")
    p.add_argument("--newton", choices=NEWTON, default="modified",
                   help="modified: modified Newton to Exudyn's default tolerances (default); linear: one linear "
                   "solve per step (newton.active = False)")
    p.add_argument("--module", choices=("fast", "regular"), default="fast",
                   help="Exudyn compiled module: fast (no range checks, AVX2, if the CPU has it) or regular")
    p.add_argument("--kernels", action="store_true", help="time the force and Jacobian calls instead "
                   "(kernel_times) and print them as JSON")
    a = p.parse_args(argv)
    if not a.height > 0:
        p.error(f"--height must be > 0 (m), got {a.height}")
    H = a.height                                   # build() and settings_summary() read it
    steps = int(round(T_END / a.dt))
    if abs(steps * a.dt - T_END) > 1e-9 * T_END:
        p.error(f"--dt {a.dt} does not divide t_end = {T_END}")

    sys.exudynFast = a.module == "fast"
    import exudyn as exu
    import numpy as np
    if a.kernels:
        print(json.dumps(kernel_times(exu, a.elements)))
        return 0

    builds, solves, cpus, newton = [], [], [], None
    tips = None
    for rep in range(a.repeats + 1):               # rep 0: untimed warm-up
        t0 = time.perf_counter()
        SC, mbs, s, tip = build(exu, a.dt, a.rho_inf, a.elements, a.newton)
        t1, c1 = time.perf_counter(), time.process_time()
        ok = mbs.SolveDynamic(s)
        t2, c2 = time.perf_counter(), time.process_time()
        if not ok:
            print(json.dumps({"status": "failed", "reason": "SolveDynamic returned False"}))
            return 1
        if rep:
            builds.append(t1 - t0)
            solves.append(t2 - t1)
            cpus.append(c2 - c1)
        data = np.asarray(mbs.GetSensorStoredData(tip))          # rows: t, x, y, z
        tips = []
        for t in OUTPUT_TIMES:
            k = int(np.argmin(np.abs(data[:, 0] - t)))
            if abs(data[k, 0] - t) > 1e-3 * a.dt:
                raise RuntimeError(f"no sensor sample at t = {t} (nearest {data[k, 0]})")
            tips.append({"t": t, "x": float(data[k, 1]), "y": float(data[k, 2])})
        solver = mbs.sys["dynamicSolver"]
        newton = {"newtonSteps": int(solver.it.newtonStepsCount),
                  "newtonJacobians": int(solver.it.newtonJacobiCount),
                  "currentStepIndex": int(solver.it.currentStepIndex),
                  "ODE2_coordinates": int(mbs.systemData.ODE2Size()),
                  "algebraic_coordinates": int(mbs.systemData.AEsize())}
        summary = settings_summary(exu, s, steps, a.dt, a.elements)
        del SC, mbs
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
