"""Exudyn as an external solver of the harness (:mod:`studies.external`): a harness scene in,
a record out, with Exudyn's ObjectANCFCable2D or ObjectBeamGeometricallyExact2D, the one the
scene's ``ancf.element`` names (runs in `.venv-peers`).

    .venv-peers/bin/python studies/peers/exudyn_scene.py SCENE.toml OUT.json

Declared by ``studies/peers/exudyn.toml`` (the cable) and ``exudyn-beam2d.toml`` (the
geometrically exact beam). Imports exudyn, numpy, the standard library,
the peer's builders (:mod:`exudyn_pendulum` beside this file: :func:`add_cable`, the
settings) and ``mechanics.laws`` (pure Python over numpy: the law's small-strain shear
modulus), never ``ancf``.

The model: ``ancf.elements`` ObjectANCFCable2D elements (Euler-Bernoulli, 2 nodes with
position and slope), with the section law taken from the scene's law at small strain:
E = 3 mu (an incompressible law's Young's modulus, mu = 2 (dpsi/dI1 + dpsi/dI2) at rest),
EA = E h w, EI = E w h^3 / 12, rho A = density h w; so it stands for the law only where
the strains are small, and for plane stress (free lateral faces). The clamp holds the
first node's position and slope direction (so does the slide: a cable's face has no
thickness to free), the pin its position; gravity on every element,
the tip force on the last node. Static: ``SolveStatic`` in the scene's load steps (Exudyn's
load-stepping; its Newton to the scene's tolerance). Dynamic: generalized-alpha at the
scene's rho_inf and fixed step dt (Newmark's average acceleration for ``newmark``), the
tip sampled at the output times. Anything else (another support, an end moment, the
discrete gradient) is outside the model: the declaration leaves it out, so the harness
skips it with the reason before calling this.

The geometrically exact beam (Simo-Reissner, 2 nodes with position and rotation, shear
deformable) takes the same section law at small strain and adds the shear stiffness
kappa G A with G = mu and kappa = 5/6 (the card's Timoshenko reference uses the same), and
the rotary inertia rho I. Its clamp and slide hold the first node's position and rotation,
its pin and hinge the position (a beam's section stays straight: the hinge's face); the
end moment is a torque on the last node (a constant couple in the plane is conservative).
"""
from __future__ import annotations

import json
import sys
import time
import tomllib
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]


def section(scene: dict) -> dict:
    """E, EA, EI and rho A of the scene's beam and law at small strain (see the module doc)."""
    sys.path.insert(0, str(ROOT))
    from mechanics.laws import get_law

    m, b = scene["material"], scene["beam"]
    law = get_law(m["law"])
    mu = law.shear_modulus({k: m[k] for k in law.constants})
    E, h, w = 3.0 * mu, b["height"], b["width"]
    return {"E": E, "EA": E * h * w, "EI": E * w * h ** 3 / 12.0, "rhoA": m["density"] * h * w,
            "kGA": 5.0 / 6.0 * mu * h * w, "rhoI": m["density"] * w * h ** 3 / 12.0}


BEAM = "ObjectBeamGeometricallyExact2D"
BEAM_SUPPORTS = {"clamp": (0, 1, 2), "slide": (0, 1, 2), "pin": (0, 1), "hinge": (0, 1)}   # of x, y, phi


def add_beam(mbs, length: float, elements: int, sec: dict, gravity=None, support=(0, 1, 2), tip_force=None,
             end_moment=None) -> list:
    """A straight ObjectBeamGeometricallyExact2D beam from the origin along x (nodes
    NodeRigidBody2D: x, y, phi), loaded and held as :func:`exudyn_pendulum.add_cable` holds the
    cable (``support``: the first node's coordinates held), ``end_moment`` a torque on the
    last node. Returns the node numbers."""
    from exudyn.itemInterface import (LoadMassProportional, MarkerBodyMass, MarkerNodeRigid, NodeRigidBody2D,
                                      ObjectBeamGeometricallyExact2D, Torque, VObjectBeamGeometricallyExact2D)
    from exudyn_pendulum import hold_and_push
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


def run(scene: dict) -> dict:
    sys.path.insert(0, str(HERE))
    sys.exudynFast = True
    import exudyn as exu
    import numpy as np
    from exudyn.itemInterface import SensorNode
    from exudyn_pendulum import CLAMP, PIN, add_cable, dynamic_settings, static_settings

    a, loads = scene["analysis"], scene.get("loads", {})
    L, n = scene["beam"]["length"], scene["ancf"]["elements"]
    sec = section(scene)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    gravity, force, moment = loads.get("gravity"), loads.get("tip_force"), loads.get("end_moment")
    element = scene["ancf"]["element"]
    if element == BEAM:
        nodes = add_beam(mbs, L, n, sec, tuple(gravity) if gravity else None, BEAM_SUPPORTS[scene["supports"]["left"]],
                         tuple(force) if force else None, moment)
    else:
        # the clamp and the slide both hold the first node's position and its slope's direction
        # (a cable's end face cannot turn, and has no thickness to hold)
        support = {"clamp": CLAMP, "slide": CLAMP, "pin": PIN}[scene["supports"]["left"]]
        nodes = add_cable(mbs, L, n, EA=sec["EA"], EI=sec["EI"], rhoA=sec["rhoA"],
                          gravity=tuple(gravity) if gravity else None, support=support,
                          tip_force=tuple(force) if force else None)
        sec = {k: sec[k] for k in ("E", "EA", "EI", "rhoA")}
    tip = mbs.AddSensor(SensorNode(nodeNumber=nodes[-1], outputVariableType=exu.OutputVariableType.Position,
                                   storeInternal=True, writeToFile=False))
    mbs.Assemble()
    rec = {"schema": "ancf-harness/record/1", "solver": "exudyn", "status": "failed", "reason": None,
           "tip": None, "ndof": int(mbs.systemData.ODE2Size()), "newton_iterations": None, "load_steps": None,
           "rejected_steps": None, "stable": None, "cpu_s": None, "wall_s": None, "setup_s": None,
           "effects": ["elastic", *(["gravity"] if gravity else []), *(["tip_force"] if force else []),
                       *(["end_moment"] if moment is not None else [])],
           "scene": scene, "exudyn": {"version": exu.__version__, "element": element, **sec}}
    t0, c0 = time.perf_counter(), time.process_time()
    if a["kind"] == "static":
        # Newton to the scene's relative tolerance, Exudyn's default absolute one (1e-10 N)
        s = static_settings(exu, a.get("newton_rtol", 1e-8), 1e-10)
        s.staticSolver.numberOfLoadSteps = int(a.get("load_steps", 10))
        what = "SolveStatic"
        ok = _solve(mbs.SolveStatic, s, rec, what)
    else:
        s = dynamic_settings(exu, a["dt"], a["t_end"], a.get("rho_inf", 0.5),
                             newmark=a.get("integrator") == "newmark")
        what = "SolveDynamic"
        ok = _solve(mbs.SolveDynamic, s, rec, what)
    rec["wall_s"], rec["cpu_s"] = time.perf_counter() - t0, time.process_time() - c0
    if not ok:
        rec["reason"] = rec["reason"] or f"Exudyn's {what} returned False"
        return rec
    data = np.asarray(mbs.GetSensorStoredData(tip))          # rows: t, x, y, z
    x, y = (float(v) for v in mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Position)[:2])
    q = mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Coordinates)     # displacements from the reference
    # the end face's rotation: the beam's node angle (not wrapped), the cable's slope angle
    rotation = float(q[2]) if element == BEAM else float(np.arctan2(q[3], 1.0 + q[2]))
    rec.update(status="converged", reason=None, tip={"ux": x - L, "uy": y, "rotation": rotation})
    if a["kind"] == "dynamic":
        times = a.get("output_times") or [a["t_end"]]
        history = []
        for t in times:
            k = int(np.argmin(np.abs(data[:, 0] - t)))
            history.append({"t": float(t), "x": float(data[k, 1]), "y": float(data[k, 2])})
        rec["tip_history"], rec["steps"] = history, int(s.timeIntegration.numberOfSteps)
    return rec


def _solve(solve, settings, rec: dict, what: str) -> bool:
    """Exudyn's solver run; its own error (it raises SolverError when Newton gives up) is
    the record's reason, not a traceback."""
    try:
        return bool(solve(settings))
    except Exception as e:                    # exudyn.SolverError is built in its C++ module
        rec["reason"] = f"Exudyn's {what}: {type(e).__name__}: {e}"
        return False


def main(argv: list[str]) -> int:
    scene_path, out = argv
    scene = tomllib.loads(Path(scene_path).read_text())
    Path(out).write_text(json.dumps(run(scene)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
