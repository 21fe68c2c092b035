"""The sweeps behind the benchmark report's causes (``studies/verification/benchmarks.py``,
``CAUSES``): each missed bending or arc case of an ANCF element re-run around its scene, the
mesh doubled, the rule raised, the penalty x 10, to see which one moves the error.

- ``bending``: the signed error of kappa (kappa / exact - 1, the benchmark's two lengths 8 h
  and 16 h) of every law, formulation and kappa h of the benchmark, per element, at 2 and 4
  elements per h with the element's default rule and with [5, 5] (and [3, 3]), and in plane
  strain at alpha = 1e3, 1e4 (the benchmark's) and 1e5 C10;
- ``arc``: the arc's distance and the end rotation over phi at 32, 64 and 128 elements, and
  with [5, 5].

    PYTHONPATH=. .venv/bin/python experiments/benchmark_causes.py bending HB2n-16 LB2n-12
    PYTHONPATH=. .venv/bin/python experiments/benchmark_causes.py arc HB2n-12

ANCF runs only (a few seconds each element once the compiled code is cached); nothing is
recorded: the numbers go to the comments beside ``CAUSES``.
"""
from __future__ import annotations

import math
import os
import sys

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


def _run(scene: dict) -> dict:
    from ancf.simulation import run_scene
    from contract.scene import scene_from_dict

    return run_scene(scene_from_dict(scene))[0]


def bending_error(law: str, form: str, x: float, element: str, per_h: int = 2, rule=None,
                  penalty_factor: float | None = None) -> float | None:
    """kappa / exact - 1 of the benchmark's bending case with these changes (None: a run failed)."""
    from studies.verification import benchmarks as B

    g = dict(B.STUDY["grid"], bending_elements_per_h=per_h)
    if penalty_factor:
        g["penalty_factor"] = penalty_factor
    n1, n2 = g["bending_lengths"]
    theta = []
    for n in (n1, n2):
        s = B.bending_scene(g, law, form, x, n, element)
        if rule:
            s["ancf"]["quadrature"] = list(rule)
        r = _run(s)
        if r["status"] != "converged":
            return None
        theta.append(r["tip"]["rotation"])
    return (theta[1] - theta[0]) / ((n2 - n1) * B.STRIP["height"]) / (x / B.STRIP["height"]) - 1.0


def arc_error(phi: float, ratio: float, element: str, n: int = 32, rule=None) -> tuple[float, float] | None:
    """(|r_tip - r_arc| / L, end rotation / phi) of the benchmark's arc case with these changes."""
    from studies.verification import benchmarks as B
    from studies.verification.closed_forms import elastica_end_moment

    s = B.arc_scene(dict(B.STUDY["grid"], arc_elements=n), phi, ratio, element)
    if rule:
        s["ancf"]["quadrature"] = list(rule)
    r = _run(s)
    if r["status"] != "converged":
        return None
    L = s["beam"]["length"]
    x, y = elastica_end_moment(phi)
    return math.hypot(1.0 + r["tip"]["ux"] / L - x, r["tip"]["uy"] / L - y), r["tip"]["rotation"] / phi


def _pct(e) -> str:
    return "  failed" if e is None else f"{100 * e:+8.3f}"


def bending(elements: list[str]) -> None:
    from studies.verification import benchmarks as B

    g = B.STUDY["grid"]
    print("kappa / exact - 1 (%): 2/h default | 2/h [3,3] | 2/h [5,5] | 4/h default | 4/h [5,5]"
          " | plane strain, default rule: alpha 1e3 / 1e5 C10")
    for form in g["formulations"]:
        for law, xs in g["bending_curvatures"][form].items():
            for x in xs:
                for el in elements:
                    cols = [bending_error(law, form, x, el, per_h, rule)
                            for per_h, rule in ((2, None), (2, (3, 3)), (2, (5, 5)), (4, None), (4, (5, 5)))]
                    if form == "plane-strain":
                        cols += [bending_error(law, form, x, el, penalty_factor=pf) for pf in (1e3, 1e5)]
                    print(f"{law:13s} {form:12s} kh {x:<4g} {el:11s}", " ".join(_pct(e) for e in cols), flush=True)


def arc(elements: list[str]) -> None:
    from studies.verification import benchmarks as B

    g = B.STUDY["grid"]
    print("distance / rotation over phi: 32 | 64 | 128 elements | 32 with [5,5]")
    for el in elements:
        for phi in g["arc_angles"]:
            for ratio in g["arc_slenderness"]:
                cols = [arc_error(phi, ratio, el, n, rule) for n, rule in ((32, None), (64, None), (128, None),
                                                                            (32, (5, 5)))]
                tol = 2.0 * B.arc_departure(phi, ratio) + B.NEWTON_TOL
                print(f"{el:11s} phi {phi:<6.4g} L/h {ratio:<5g} tol {tol:.1e}:",
                      " | ".join("failed" if c is None else f"{c[0]:.2e} / {c[1]:.4f}" for c in cols), flush=True)


if __name__ == "__main__":
    if len(sys.argv) < 3 or sys.argv[1] not in ("bending", "arc"):
        sys.exit(__doc__)
    {"bending": bending, "arc": arc}[sys.argv[1]](sys.argv[2:])
