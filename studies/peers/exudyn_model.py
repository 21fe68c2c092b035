"""Exudyn's model of a harness scene: the one place where a scene becomes an Exudyn system
(runs in `.venv-peers`). Its users: the adapter (``exudyn_scene.py``, a scene in and a record
out, for :mod:`studies.external`), the peer benchmark's timed runs (``exudyn_pendulum.py``,
for :mod:`studies.peers.compare` and the work-precision grid) and the checks against
Exudyn's published numbers (``exudyn_static.py``, which builds Exudyn's own cantilevers with
:func:`add_cable` and :func:`static_settings`).

Imports exudyn (inside the functions), the standard library and ``mechanics.laws`` (pure
Python over numpy: the law's small-strain shear modulus), never ``ancf``.

The section law is the scene's law at small strain (:func:`section`): E = 3 mu (an
incompressible law's Young's modulus, mu = 2 (dpsi/dI1 + dpsi/dI2) at rest), EA = E h w,
EI = E w h^3 / 12, rho A = density h w; so it stands for the law only where the strains are
small, and for plane stress (free lateral faces).

- ObjectANCFCable2D (:func:`add_cable`; Euler-Bernoulli, 2 nodes with position and slope):
  the clamp holds the first node's position and slope direction (so does the slide: a
  cable's face has no thickness to free), the pin its position.
- ObjectBeamGeometricallyExact2D (:func:`add_beam`; Simo-Reissner, 2 nodes with position
  and rotation, shear deformable): the same section law plus the shear stiffness kappa G A
  with G = mu and kappa = 5/6 (the card's Timoshenko reference uses the same), and the
  rotary inertia rho I. Its clamp and slide hold the first node's position and rotation,
  its pin and hinge the position (a beam's section stays straight: the hinge's face); the
  end moment is a torque on the last node (a constant couple in the plane is conservative).

Gravity acts on every element, the tip force on the last node. Static: ``SolveStatic`` in
the scene's load steps, its Newton to the scene's tolerance. Dynamic: generalized-alpha at
the scene's rho_inf and fixed step dt (Newmark's average acceleration for ``newmark``).
"""
from __future__ import annotations

import sys
from pathlib import Path
from typing import NamedTuple

ROOT = Path(__file__).resolve().parents[2]

# Supports of the cable's first node, as the node coordinates held at their reference
# values (NodePoint2DSlope1: x, y, slope x, slope y); Exudyn's examples write the same as
# ``fixedConstraintsNode0`` of GenerateStraightLineANCFCable2D, a 0/1 list
PIN = (0, 1)                  # x, y held, the slope (the rotation) free: the pendulum
CLAMP = (0, 1, 3)             # x, y and the slope's y held: a cantilever ([1, 1, 0, 1])
CABLE_SUPPORTS = {"clamp": CLAMP, "slide": CLAMP, "pin": PIN}

BEAM = "ObjectBeamGeometricallyExact2D"
BEAM_SUPPORTS = {"clamp": (0, 1, 2), "slide": (0, 1, 2), "pin": (0, 1), "hinge": (0, 1)}   # of x, y, phi


class Model(NamedTuple):
    """An assembled scene: its system, nodes, tip sensor, the settings of its analysis and
    the section values it was built with."""
    SC: object
    mbs: object
    nodes: list
    tip: int
    settings: object
    section: dict
    element: str


def section(scene: dict) -> dict:
    """E, EA, EI, rho A, kappa G A and rho I of the scene's beam and law at small strain
    (see the module doc)."""
    sys.path.insert(0, str(ROOT))
    from mechanics.laws import get_law

    m, b = scene["material"], scene["beam"]
    law = get_law(m["law"])
    mu = law.shear_modulus({k: m[k] for k in law.constants})
    E, h, w = 3.0 * mu, b["height"], b["width"]
    return {"E": E, "EA": E * h * w, "EI": E * w * h ** 3 / 12.0, "rhoA": m["density"] * h * w,
            "kGA": 5.0 / 6.0 * mu * h * w, "rhoI": m["density"] * w * h ** 3 / 12.0}


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


def add_beam(mbs, length: float, elements: int, sec: dict, gravity=None, support=(0, 1, 2), tip_force=None,
             end_moment=None) -> list:
    """A straight ObjectBeamGeometricallyExact2D beam from the origin along x (nodes
    NodeRigidBody2D: x, y, phi), loaded and held as :func:`add_cable` holds the cable
    (``support``: the first node's coordinates held), ``end_moment`` a torque on the last
    node. Returns the node numbers."""
    from exudyn.itemInterface import (LoadMassProportional, MarkerBodyMass, MarkerNodeRigid, NodeRigidBody2D,
                                      ObjectBeamGeometricallyExact2D, Torque, VObjectBeamGeometricallyExact2D)
    le = length / elements
    nodes = [mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[i * le, 0.0, 0.0])) for i in range(elements + 1)]
    for i in range(elements):
        beam = mbs.AddObject(ObjectBeamGeometricallyExact2D(
            nodeNumbers=[nodes[i], nodes[i + 1]], length=le, massPerLength=sec["rhoA"],
            crossSectionInertia=sec["rhoI"], bendingStiffness=sec["EI"], axialStiffness=sec["EA"],
            shearStiffness=sec["kGA"],
            visualization=VObjectBeamGeometricallyExact2D(show=False)))
        if gravity is not None:
            m = mbs.AddMarker(MarkerBodyMass(bodyNumber=beam))
            mbs.AddLoad(LoadMassProportional(markerNumber=m, loadVector=[gravity[0], gravity[1], 0.0]))
    hold_and_push(mbs, nodes, support, tip_force)
    if end_moment is not None:
        mr = mbs.AddMarker(MarkerNodeRigid(nodeNumber=nodes[-1]))
        mbs.AddLoad(Torque(markerNumber=mr, loadVector=[0.0, 0.0, end_moment]))
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


NEWTON = ("modified", "linear")        # dynamic_settings' newton: Exudyn's Newton, or one linear solve per step


def dynamic_settings(exu, dt: float, t_end: float, rho_inf: float, newton: str = "modified",
                     newmark: bool = False):
    """SimulationSettings for ``SolveDynamic``: :func:`common_settings`, generalized-alpha at
    ``rho_inf`` (``newmark``: Exudyn's Newmark form of it), a fixed step ``dt`` to ``t_end``
    (no adaptive or automatic step: a failed step stops the run), the sensors sampled every
    step, verbose off. ``newton`` (:data:`NEWTON`): "modified", modified Newton to Exudyn's
    default tolerances; "linear", one linear solve per step (``newton.active = False``: the
    step's equations linearised at its predictor, no convergence test)."""
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


def build(exu, scene: dict, newton: str = "modified") -> Model:
    """The scene's model in a fresh SystemContainer, assembled, with a sensor of the last
    node's position and the settings of the scene's analysis (``newton`` as in
    :func:`dynamic_settings`, for a dynamic scene). The element is the one the scene's
    ``ancf.element`` names: :data:`BEAM`, else the cable."""
    from exudyn.itemInterface import SensorNode

    a, loads = scene["analysis"], scene.get("loads", {})
    L, n = scene["beam"]["length"], scene["ancf"]["elements"]
    sec = section(scene)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    gravity, force, moment = loads.get("gravity"), loads.get("tip_force"), loads.get("end_moment")
    gravity, force = (tuple(gravity) if gravity else None), (tuple(force) if force else None)
    element = scene["ancf"]["element"]
    if element == BEAM:
        nodes = add_beam(mbs, L, n, sec, gravity, BEAM_SUPPORTS[scene["supports"]["left"]], force, moment)
    else:
        nodes = add_cable(mbs, L, n, EA=sec["EA"], EI=sec["EI"], rhoA=sec["rhoA"], gravity=gravity,
                          support=CABLE_SUPPORTS[scene["supports"]["left"]], tip_force=force)
        sec = {k: sec[k] for k in ("E", "EA", "EI", "rhoA")}
    tip = mbs.AddSensor(SensorNode(nodeNumber=nodes[-1], outputVariableType=exu.OutputVariableType.Position,
                                   storeInternal=True, writeToFile=False))
    mbs.Assemble()
    if a["kind"] == "static":
        # Newton to the scene's relative tolerance, Exudyn's default absolute one (1e-10 N)
        s = static_settings(exu, a.get("newton_rtol", 1e-8), 1e-10)
        s.staticSolver.numberOfLoadSteps = int(a.get("load_steps", 10))
    else:
        s = dynamic_settings(exu, a["dt"], a["t_end"], a.get("rho_inf", 0.5), newton,
                             newmark=a.get("integrator") == "newmark")
    return Model(SC, mbs, nodes, tip, s, sec, element)


def tip_history(exu, model: Model, times) -> list[dict]:
    """The tip sensor's position at each of ``times`` ({'t', 'x', 'y'}), from its sample at
    every step; a time with no sample within a thousandth of a step is an error."""
    import numpy as np

    data = np.asarray(model.mbs.GetSensorStoredData(model.tip))          # rows: t, x, y, z
    dt = model.settings.timeIntegration.endTime / model.settings.timeIntegration.numberOfSteps
    out = []
    for t in times:
        k = int(np.argmin(np.abs(data[:, 0] - t)))
        if abs(data[k, 0] - t) > 1e-3 * dt:
            raise RuntimeError(f"no sensor sample at t = {t} (nearest {data[k, 0]})")
        out.append({"t": float(t), "x": float(data[k, 1]), "y": float(data[k, 2])})
    return out
