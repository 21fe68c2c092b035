"""Side by side with a peer: our HB2n-12 plane-stress Yeoh pendulum against Exudyn's
ANCF cable pendulum, timed in the same run (``make bench-peers``).

    .venv/bin/python -m studies peers compare [--dt 1e-3] [--rho-inf 0.8] [--repeats 5]
                                              [--rounds 7] [--element HB2n-12 --element HB2n-16]

Ours: ``scenes/pendulum-yeoh-plane-stress.toml`` (32 x HB2n-12, plane-stress Yeoh,
generalized-alpha; HB2n-16 by ``--element``) with the given dt and rho_inf; the wall
and CPU times are the medians of the records' ``wall_s`` and ``cpu_s`` over ``--repeats`` warm runs of :func:`ancf.simulation.run_scene` in this
process (one untimed run first: numba compilation, caches). Exudyn: the same scene with the
cable's element (:func:`peer_scene`, the element and features its declaration
``studies/peers/exudyn.toml`` gives), timed by the script ``exudyn_pendulum.py`` beside this
file with ``.venv-peers/bin/python`` (made by ``tools/setup_peers.sh``) and the same repeats;
the script builds the scene's model as the adapter does (``exudyn_model.build``) and prints
its settings and the median wall and CPU times of its ``SolveDynamic`` calls as JSON on its
last line.
The ratio is taken on both; on a shared machine the CPU ratio is the steadier one.

The two models differ in physics: Exudyn's ObjectANCFCable2D is an Euler-Bernoulli,
linear elastic cable (E = 6 C10, no thickness deformation); ours is a 2D continuum
beam with the incompressible plane-stress Yeoh law. The tip-position differences are
reported, not asserted. Times are printed, never asserted.
"""
from __future__ import annotations

import json
import math
import statistics
import time
from pathlib import Path

from ancf.simulation import run_scene
from contract.errors import SceneError
from contract.scene import load_scene, scene_from_dict
from reference_fem.launch import scene_toml
from studies.external.declaration import load_declaration, unsupported

from .exudyn_published import RECORD as PUBLISHED, published_markdown, read_record
from .venv import PEER_PYTHON, parse_peer_output, run_peer_script  # noqa: F401  (the peer's venv, shared)

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "scenes" / "pendulum-yeoh-plane-stress.toml"
PEER_SCRIPT = Path(__file__).with_name("exudyn_pendulum.py")
DECLARATION = Path(__file__).with_name("exudyn.toml")         # the cable as an external solver
TARGET_RATIO = 1.0          # at least as fast as Exudyn
# at equal steps, HB2n-12 within half of Exudyn's time and HB2n-16 within 0.8 of it
TARGETS = {"HB2n-12": 0.5, "HB2n-16": 0.8}


def pendulum_scene(dt: float, rho_inf: float, scene_path: Path = SCENE) -> dict:
    """The compared scene (:data:`SCENE`) at this step and spectral radius, as a dict."""
    d = load_scene(scene_path).to_dict()
    d["analysis"].update(dt=dt, rho_inf=rho_inf)
    return d


def ours(dt: float, rho_inf: float, repeats: int = 5, scene_path: Path = SCENE, element: str | None = None) -> dict:
    """Time our pendulum: {'wall_s': [...], 'wall_median_s', 'first_run_s', 'setup_s',
    'steps', 'newton_iterations', 'ndof', 'elements', 'element', 'tip_history'}."""
    d = pendulum_scene(dt, rho_inf, scene_path)
    if element:
        d["ancf"]["element"] = element
    scene = scene_from_dict(d)
    t0 = time.perf_counter()
    first, _ = run_scene(scene)                    # warm-up: numba compile, caches
    first_s = time.perf_counter() - t0
    recs = [run_scene(scene)[0] for _ in range(repeats)]
    for r in [first, *recs]:
        if r["status"] != "converged":
            raise RuntimeError(f"our pendulum failed: {r['reason']}")
    last = recs[-1]
    return {
        "element": scene.ancf.element, "elements": scene.ancf.elements,
        "formulation": scene.material.formulation, "law": scene.material.law,
        "integrator": last["integrator"], "dt": dt, "rho_inf": rho_inf,
        "wall_s": [r["wall_s"] for r in recs], "wall_median_s": statistics.median(r["wall_s"] for r in recs),
        "cpu_s": [r["cpu_s"] for r in recs], "cpu_median_s": statistics.median(r["cpu_s"] for r in recs),
        "setup_median_s": statistics.median(r["setup_s"] for r in recs), "first_run_s": first_s,
        "steps": last["steps"], "rejected_steps": last["rejected_steps"],
        "newton_iterations": last["newton_iterations"], "ndof": last["ndof"],
        "tip_history": last["tip_history"],
    }


def peer_scene(scene: dict) -> dict:
    """Our scene as Exudyn's cable runs it: the element of its declaration
    (:data:`DECLARATION`) in ``ancf.element``; a scene with a feature the declaration does
    not take is refused (SceneError, the declaration's reason), as the engine skips it."""
    decl = load_declaration(DECLARATION)
    why = unsupported(decl, scene)
    if why:
        raise SceneError(f"{decl.name}: {why}")
    return {**scene, "ancf": {**scene["ancf"], "element": decl.element}}


def peer(scene: dict, repeats: int = 5, python: Path = PEER_PYTHON, module: str = "fast",
         newton: str = "modified") -> dict:
    """Time Exudyn's run of ``scene`` (:func:`peer_scene`) in .venv-peers (the script in a
    scratch directory, so that nothing it might write lands in the repository) and return
    its JSON output; ``newton``: the script's ``--newton``."""
    args = ["--repeats", str(repeats), "--module", module, "--newton", newton]
    return run_peer_script(PEER_SCRIPT, args, python, scene_toml(peer_scene(scene)))


def tip_differences(ours_tips: list[dict], peer_tips: list[dict]) -> list[dict]:
    """Ours minus peer at the peer's output times, in mm: {'t', 'dx', 'dy', 'dist'}."""
    by_t = {round(r["t"], 9): r for r in ours_tips}
    out = []
    for q in peer_tips:
        r = by_t.get(round(q["t"], 9))
        if r is None:
            raise RuntimeError(f"our run has no tip position at t = {q['t']}")
        dx, dy = (r["x"] - q["x"]) * 1e3, (r["y"] - q["y"]) * 1e3
        out.append({"t": q["t"], "x": r["x"], "y": r["y"], "peer_x": q["x"], "peer_y": q["y"],
                    "dx": dx, "dy": dy, "dist": math.hypot(dx, dy)})
    return out


def format_table(o: dict, p: dict, load: tuple | None = None, rounds: int = 1) -> str:
    """The report: times, ratio, steps, tip differences, the peer's settings."""
    s = p["settings"]
    ratio = o["wall_median_s"] / p["solve_median_s"]
    cpu_ratio = o["cpu_median_s"] / p["solve_cpu_median_s"]
    rr, med, target, met = round_verdict(o, p, rounds)
    lines = [
        f"Flexible pendulum, 0.5 s, dt = {o['dt']:g} s, rho_inf = {o['rho_inf']:g}; "
        f"wall time = median of {len(o['wall_s'])} warm runs (rounds interleaved with Exudyn's), one thread",
        "",
        f"{'solver':34s} {'dofs':>5s} {'steps':>5s} {'newton':>6s} {'median s':>9s} {'runs s':s}",
        f"{'ours: ' + o['element'] + ' x' + str(o['elements']) + ' ' + o['law'] + ' ' + o['formulation']:34s} "
        f"{o['ndof']:5d} {o['steps']:5d} {o['newton_iterations']:6d} {o['wall_median_s']:9.4f} "
        + " ".join(f"{t:.4f}" for t in o["wall_s"]),
        f"{'Exudyn ' + s['exudyn'] + ': ANCFCable2D x' + str(s['elements']):34s} "
        f"{p['counters'].get('ODE2_coordinates', 0):5d} {s['steps']:5d} {p['counters']['newtonSteps']:6d} {p['solve_median_s']:9.4f} "
        + " ".join(f"{t:.4f}" for t in p["solve_s"]),
        f"(dofs: ours after supports; Exudyn: ODE2 coordinates, plus "
        f"{p['counters'].get('algebraic_coordinates', '?')} Lagrange multipliers of the pin. newton: ours "
        f"Newton iterations (chord: one factorisation per step); Exudyn modified Newton iterations, "
        f"{p['counters']['newtonJacobians']} Jacobian updates)",
        "",
        f"ratio ours / Exudyn: {ratio:.2f} wall, {cpu_ratio:.2f} CPU (ours {o['cpu_median_s']:.4f} s, "
        f"Exudyn {p['solve_cpu_median_s']:.4f} s CPU); by round (CPU) "
        + ", ".join(f"{x:.2f}" for x in rr) + f", median {med:.2f}; target: within {target:g}x -> "
        + ("within target" if met else "NOT within target"),
        f"spread (min-max): ours {min(o['wall_s']):.4f}-{max(o['wall_s']):.4f} s wall, "
        f"{min(o['cpu_s']):.4f}-{max(o['cpu_s']):.4f} s CPU; Exudyn {min(p['solve_s']):.4f}-{max(p['solve_s']):.4f} s "
        f"wall, {min(p['solve_cpu_s']):.4f}-{max(p['solve_cpu_s']):.4f} s CPU",
        f"ours: first run (numba compile, caches) {o['first_run_s']:.2f} s, set-up per run "
        f"{o['setup_median_s']:.3f} s (not in the wall time); rejected steps {o['rejected_steps']}",
        f"Exudyn: system build + Assemble {p['build_median_s']:.4f} s (not in the wall time)",
        "",
        "Tip position (free-end centre line), ours minus Exudyn, mm "
        "(2D hyperelastic continuum beam vs Euler-Bernoulli linear elastic cable: reported, not asserted)",
        f"{'t s':>5s} {'ours x':>9s} {'ours y':>9s} {'Exu x':>9s} {'Exu y':>9s} {'dx':>8s} {'dy':>8s} {'|d|':>8s}",
    ]
    for d in tip_differences(o["tip_history"], p["tip_history"]):
        lines.append(f"{d['t']:5.2f} {d['x'] * 1e3:9.2f} {d['y'] * 1e3:9.2f} {d['peer_x'] * 1e3:9.2f} "
                     f"{d['peer_y'] * 1e3:9.2f} {d['dx']:8.2f} {d['dy']:8.2f} {d['dist']:8.2f}")
    lines += ["", "Exudyn settings:"]
    for k, v in s.items():
        if isinstance(v, dict):
            lines += [f"  {k}:"] + [f"    {k2} = {v2}" for k2, v2 in v.items()]
        else:
            lines.append(f"  {k} = {v}")
    if load is not None:
        lines += ["", "load average (1, 5, 15 min): before " + " ".join(f"{x:.2f}" for x in load[0])
                  + ", after " + " ".join(f"{x:.2f}" for x in load[1])]
    return "\n".join(lines)


def round_ratios(ours: list[float], peer: list[float], rounds: int) -> list[float]:
    """ours / peer of each round's medians (the samples of ``rounds`` rounds in run order,
    equally many per round). The machine's speed can change within a run (measured
    2026-11-25: both sides 1.6 to 1.9 times faster after a switch); the pooled medians can
    then fall in different phases, a round's two medians in the same one."""
    if rounds < 1 or len(ours) % rounds or len(peer) % rounds:
        raise ValueError(f"rounds: {len(ours)} and {len(peer)} samples do not split into {rounds} rounds")
    a, b = len(ours) // rounds, len(peer) // rounds
    return [statistics.median(ours[i * a:(i + 1) * a]) / statistics.median(peer[i * b:(i + 1) * b])
            for i in range(rounds)]


def round_verdict(o: dict, p: dict, rounds: int) -> tuple[list[float], float, float, bool]:
    """The comparison's verdict for our run ``o`` against the peer's ``p``: (the rounds'
    CPU ratios, their median, the element's target, whether the median is within it)."""
    rr = round_ratios(o["cpu_s"], p["solve_cpu_s"], rounds)
    target = TARGETS.get(o["element"], TARGET_RATIO)
    med = statistics.median(rr)
    return rr, med, target, med <= target


def pool(old: dict | None, new: dict, lists: dict[str, str]) -> dict:
    """new with the samples of ``lists`` (list key -> median key) appended to old's, and
    the medians over all of them."""
    if old is None:
        return new
    for k, med in lists.items():
        new[k] = old[k] + new[k]
        new[med] = statistics.median(new[k])
    return new


RECORD = ROOT / "reports" / "data" / "peers" / "peers-compare.json"

METHOD = """\
`make bench-peers` runs the paper's flexible pendulum in our solver and in
[Exudyn](https://github.com/jgerstmayr/EXUDYN) (PyPI `exudyn`, a C++ multibody code), side by
side in one run (`python -m studies peers compare`), and then both on one work-precision
diagram (`peers_work_precision.md`).

- `tools/setup_peers.sh` (idempotent) makes a separate venv `.venv-peers` (no system site
  packages) with `exudyn` and `numpy`; it never touches `.venv`.
- `studies/peers/exudyn_pendulum.py` runs inside `.venv-peers` and imports only exudyn, numpy
  and the standard library. It takes our scene with the cable's element and builds its model
  as the adapter of `studies/peers/exudyn.toml` does (`exudyn_model.build`, one way to run
  Exudyn): `ObjectANCFCable2D` elements (Euler-Bernoulli, linear elastic), E = 6 C10 (the
  small-strain modulus of incompressible plane-stress Yeoh), pinned by two
  `CoordinateConstraint`s (slope free), gravity by `LoadMassProportional`, from horizontal at
  rest, 0.5 s at a fixed step. Each timed repetition builds a fresh system outside the timed
  region and times `SolveDynamic` alone.
- Ours: `scenes/pendulum-yeoh-plane-stress.toml` (plane-stress Yeoh, generalized-alpha) at the
  same dt and rho_inf, the records' `wall_s` and `cpu_s` (the solve alone) of warm runs of
  `ancf.simulation.run_scene`.
- Rounds: Exudyn's runs and ours in turn, the medians over all rounds (the machine's speed
  drifts on a shared host). CPU time (`time.process_time`) beside wall time on both sides.
  The verdict takes the median over the rounds of each round's ratio of medians: when the
  machine changes speed within the run, the pooled medians can come from different phases.
- The two models differ in physics (a 2D hyperelastic continuum beam against a linear elastic
  Euler-Bernoulli cable): the tip differences are reported, not asserted. Times are printed,
  never asserted in tests."""


def peers_markdown(result: dict, published: dict | None = None) -> str:
    """reports/peers.md from the comparison's record (``--json`` / :data:`RECORD`: {'ours':
    [...], 'exudyn': {...}, 'load': [...]}) alone: a plain function, records in, markdown out;
    with the record of the checks against Exudyn's published numbers
    (:data:`studies.peers.exudyn_published.RECORD`), their section at the end."""
    p, os_ = result["exudyn"], result["ours"]
    load0, load1 = result["load"]
    rounds = result["rounds"]
    lines = ["# Side by side with a peer: Exudyn's ANCF cable pendulum", "",
             "Generated by `python -m studies peers compare --report` (`make bench-peers`) from "
             "`data/peers/peers-compare.json`; do not edit.", "", METHOD, "",
             "## Equal element count and step", "",
             f"dt = {os_[0]['dt']:g} s, rho_inf = {os_[0]['rho_inf']:g}; Exudyn {p['settings']['exudyn']} "
             f"({p['settings'].get('module', '?')}); load average (1 min) {load0[0]:.2f} before, {load1[0]:.2f} after.",
             "",
             "| solver | elements | dofs | steps | Newton | runs | median wall s | wall min-max | median CPU s | "
             "CPU min-max | ours / Exudyn (wall, CPU) | rounds' ratios (CPU) | target |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    s = p["settings"]
    lines.append(f"| Exudyn ANCFCable2D | {s['elements']} | {p['counters'].get('ODE2_coordinates', '?')} | {s['steps']} | "
                 f"{p['counters']['newtonSteps']} | {len(p['solve_s'])} | {p['solve_median_s']:.4f} | "
                 f"{min(p['solve_s']):.4f}-{max(p['solve_s']):.4f} | {p['solve_cpu_median_s']:.4f} | "
                 f"{min(p['solve_cpu_s']):.4f}-{max(p['solve_cpu_s']):.4f} | 1 | - | - |")
    for o in os_:
        rw, rc = o["wall_median_s"] / p["solve_median_s"], o["cpu_median_s"] / p["solve_cpu_median_s"]
        rr, med, target, met = round_verdict(o, p, rounds)
        verdict = "met" if met else "NOT met"
        lines.append(f"| ours {o['element']} {o['law']} {o['formulation']} | {o['elements']} | {o['ndof']} | "
                     f"{o['steps']} | {o['newton_iterations']} | {len(o['wall_s'])} | {o['wall_median_s']:.4f} | "
                     f"{min(o['wall_s']):.4f}-{max(o['wall_s']):.4f} | {o['cpu_median_s']:.4f} | "
                     f"{min(o['cpu_s']):.4f}-{max(o['cpu_s']):.4f} | {rw:.2f}, {rc:.2f} | "
                     f"{med:.2f} ({', '.join(f'{x:.2f}' for x in rr)}) | {target:g}: {verdict} |")
    lines += ["", "Targets: HB2n-12 within 0.5 and HB2n-16 within 0.8 of Exudyn's time; a target "
              "counts as met when the median over the rounds of each round's CPU ratio is within it (the CPU "
              "ratio is the steadier one on a shared machine, and a round's two medians are taken in the same "
              "phase of the machine's speed).", "",
              "Tip position, ours minus Exudyn (mm; the models' physics differ, reported, not asserted):", "",
              "| element | t (s) | dx | dy | distance |", "|---|---|---|---|---|"]
    for o in os_:
        for d in tip_differences(o["tip_history"], p["tip_history"]):
            lines.append(f"| {o['element']} | {d['t']:.2f} | {d['dx']:.2f} | {d['dy']:.2f} | {d['dist']:.2f} |")
    lines += ["", "Exudyn's settings (all printed by its script):", ""]
    for k, v in s.items():
        if isinstance(v, dict):
            lines += [f"- {k}:"] + [f"  - {k2} = {v2}" for k2, v2 in v.items()]
        else:
            lines.append(f"- {k} = {v}")
    lines.append("")
    if published is not None:
        lines.append(published_markdown(published))
    return "\n".join(lines)


def write_report(reports: Path = ROOT / "reports") -> None:
    """reports/peers.md from the comparison's record and, where it exists, the published
    checks' record (both under ``reports/data/peers/``)."""
    data = reports / "data" / "peers"
    (reports / "peers.md").write_text(peers_markdown(json.loads((data / RECORD.name).read_text()),
                                                     read_record(data / PUBLISHED.name)))
