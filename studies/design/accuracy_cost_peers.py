"""The pendulum's cheapest runs of the accuracy-cost study beside the peer report's
(``reports/accuracy_cost_pendulum_peers.md``): each grid under each refinement rule, and why
they differ, from the two sets of records (the peer report's: ``data/peers/``,
:mod:`studies.peers.records`)."""
from __future__ import annotations

from .accuracy_cost_points import with_settled
from ..common.pendulum_cases import LENGTH
from ..engine.report import Section, Table
from ..peers.precision_grid import SCENE, our_element
from ..peers.records import read


# the peer report's records (studies.peers.work_precision), read where they are beside this study's
PEER_RECORDS = ("peers", "peers-work-precision.jsonl")


def two_way_finer(sel: list[dict]):
    """The peer report's refinement (:func:`studies.peers.precision_rules.finer`): the same
    element, its mesh at every step no larger, or its step on every mesh at least as fine."""
    return lambda p: [q for q in sel if q["element"] == p["element"]
                      and ((q["n"] == p["n"] and q["dt"] <= p["dt"]) or (q["dt"] == p["dt"] and q["n"] >= p["n"]))]


def quadrant_finer(sel: list[dict]):
    """This study's refinement (:func:`studies.design.accuracy_cost_points.settled_steps`): the same element, at least as many
    elements and at most the step."""
    return lambda p: [q for q in sel if q["element"] == p["element"] and q["n"] >= p["n"] and q["dt"] <= p["dt"]]


def cheapest_under(sel: list[dict], finer, a: float) -> dict | None:
    """The fastest point of ``sel`` whose every refinement (``finer``, its own among them) is
    good and within ``a``."""
    ok = [p for p in with_settled(sel, finer) if p["settled"] is not None and p["settled"] <= a]
    return min(ok, key=lambda p: p["time"]) if ok else None


def peer_points(ctx) -> list[dict]:
    """The peer report's runs of ours on its `pendulum` scene (the paper's pendulum) as
    points (element label with its setting, n, dt, solve time, error); [] without its records."""
    recs = read(ctx.out / "data" / PEER_RECORDS[0] / PEER_RECORDS[1])
    return [{"element": r["element"], "n": r["elements"], "dt": r["dt"], "time": r["time_s"], "error": r["error"],
             "verdict": "converged" if r["error"] is not None else "failed", "law": r.get("law"),
             "rho_inf": r.get("rho_inf"), "height": r.get("height"), "guard": r.get("energy_guard")}
            for r in recs if r["solver"] == "ancf" and r.get("scene", SCENE) == SCENE]


def peer_comparison(ctx, sec: Section, pts: list[dict]) -> None:
    """The pendulum's cheapest runs beside the peer report's on the same scene, each grid under
    each rule, and why they differ, from the two sets of records."""
    peer = peer_points(ctx)
    ours = [p for p in pts if p["formulation"] == "plane-stress"]
    if not (peer and ours):
        return
    g = ctx.study.grid
    defaults = [p for p in peer if our_element(p["element"])[0] == p["element"]]

    def cell(p):
        return f"{p['element']} x {p['n']}, dt {1e3 * p['dt']:g} ms ({p['time']:.3g} s, {100 * p['error']:.3f} %)" \
            if p else "none"

    picks = {a: [cheapest_under(ours, quadrant_finer(ours), a), cheapest_under(ours, two_way_finer(ours), a),
                 cheapest_under(defaults, quadrant_finer(defaults), a), cheapest_under(defaults, two_way_finer(defaults), a),
                 cheapest_under(peer, two_way_finer(peer), a)] for a in g["accuracies"]}
    rows = [[f"{100 * a:g} %", *map(cell, ps)] for a, ps in picks.items()]
    # element (without its setting) and mesh of each cell: where the five agree on them
    agree = [a for a, ps in picks.items()
             if all(ps) and len({(our_element(p["element"])[0], p["n"]) for p in ps}) == 1]
    verdict = ("At every accuracy the five cells name the same element and mesh"
               if len(agree) == len(picks) else
               "The five cells name the same element and mesh at " + (", ".join(f"{100 * a:g} %" for a in agree)
                                                                       or "no accuracy"))

    def ladder(sel):
        return ", ".join(f"{1e3 * d:g}" for d in sorted({p["dt"] for p in sel}, reverse=True)) + " ms"

    def counts(sel):
        ns = sorted({p["n"] for p in sel})
        return f"{ns[0]} to {ns[-1]}"

    shared = sorted({p["dt"] for p in ours} & {p["dt"] for p in peer}, reverse=True)
    same = ({(p["law"], p["rho_inf"]) for p in peer} == {(p["law"], p["rho_inf"]) for p in ours}
            and {p["height"] for p in peer} == {round(LENGTH / p["slenderness"], 9) for p in ours})
    settings = sorted({p["element"][len(our_element(p["element"])[0]):].strip() for p in peer} - {""})
    sec.table(ctx, Table("accuracy_cost_pendulum_peers",
                         ["accuracy", "this study: its grid, its rule", "its grid, the peer report's rule",
                          "peer report's grid at our defaults, this study's rule", "the same, the peer report's rule",
                          "peer report: every setting, its rule (its table)"], rows, {}),
              "The plane-stress pendulum's cheapest run here beside the peer report's (peers_work_precision.md, scene "
              "`pendulum`), each grid under each refinement rule (time in parentheses: each grid's own measure, "
              "error: the run's own). " + verdict + ". The scenes are " + ("the same (the paper's pendulum, Yeoh, plane stress, "
              "rho_inf 0.5, h = 5 mm, against the same continuum gold)" if same else "NOT the same in these records")
              + "; what differs, from the two sets of records: the step ladder (this study's, Table 4's: "
              + ladder(ours) + "; the peer report's: " + ladder(peer) + "; "
              + ("no step in common" if not shared else "in common: " + ", ".join(f"{1e3 * d:g}" for d in shared) + " ms")
              + ") and the meshes (" + counts(ours) + " against " + counts(peer) + " elements), so that where the two "
              "agree on element and mesh they can still name different steps; the time (here the median serial warm wall "
              "time of a whole run, build and solve; there the solve's, the median of its timed runs); the Newton "
              "settings (here each element's defaults; the peer report also takes " + ", ".join(settings)
              + ", last column against the one before); the refinement rule (here every run with at least as many "
              "elements and at most the step must stay within the accuracy; there every finer step of the same mesh "
              "and every finer mesh at the same step: second column against the first, fourth against the third); "
              "and the energy guard (here each scene's; there none on either side, "
              + ", ".join(sorted({str(p["guard"]) for p in peer})) + " in its records).")
