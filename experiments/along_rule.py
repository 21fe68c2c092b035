"""An experiment, not a remedy (issue 20): HB2n-20xyp with three Gauss points along the beam.

On the slender pendulum, a coarse mesh of HB2n-20xyp is much further from the continuum
with its default rule ([4, 2]; [5, 2] from l_e / h = 15) than with [3, 2]. This script measures that effect and asks
where it comes from:

1. the pendulums of the work-precision bench (``studies.peers.work_precision``: plane-stress
   Yeoh, rho_inf = 0.5, against the scene's converged continuum) at dt = 1.25 ms, the
   error of each mesh under both rules;
2. a small-strain check: a linear, plane-strain cantilever (lambda = mu = 1) with a tip
   load, L / h = 70, assembled from the element's shape functions. Its tip deflection
   divided by Timoshenko's is the same under both rules, so the effect is not a
   small-strain shear or membrane locking;
3. the rank test's softest modes under [3, 2] (``ancf.checks.rank``): for each mode, mu (the
   energy [3, 2] sees against the exact rule's) and the shares of its exact energy that
   come from eps_xx, eps_yy (with the eps_xx eps_yy coupling) and shear.

[3, 2] is not adopted: the rank tests reject it at l_e / h = 10, where mu_min is 0.04 and
the finite-strain ratio 0.23 (``reports/cards/HB2n-20xyp.md``). Which strain the three
points relieve, the membrane stretch C_xx, is the finding of the assumed-strain
prototype (``tests/oracles/assumed_membrane.py``, the tests' oracle).

    .venv/bin/python experiments/along_rule.py
"""
from __future__ import annotations

import numpy as np

from ancf.checks import rank
from ancf.elements import get_element
from ancf.core.quadrature import gauss
from ancf.simulation import run_scene
from contract.scene import scene_from_dict
from studies.peers.work_precision import SCENES, error, scene_dict
from studies.common.pendulum_cases import LENGTH

ELEMENT = "HB2n-20xyp"
RULES = (None, (3, 2))            # None: the element's default rule


def pendulum_error(scene: str, n: int, rule, dt: float = 1.25e-3) -> tuple[float, list[int]]:
    """(error / L, the rule used) of the work-precision scene on n elements."""
    d = scene_dict(ELEMENT, n, dt, 0.5, scene)
    if rule:
        d["ancf"]["quadrature"] = list(rule)
    rec = run_scene(scene_from_dict(d))[0]
    if rec["status"] != "converged":
        raise RuntimeError(f"{scene}, {n} elements, rule {rule}: {rec['status']} ({rec.get('reason')})")
    return error(rec["tip_history"], scene), rec["quadrature"]


def linear_tip_ratio(n: int, rule, slenderness: float = 70.0) -> float:
    """Small-strain cantilever, face clamp, tip load on the centre line: tip deflection
    over Timoshenko's P L^3 / (3 E' I) + P L / (k G A) (E' = E / (1 - nu^2), k = 5/6)."""
    el = get_element(ELEMENT)
    h, L = 1.0, slenderness
    Ke = (L / n) * h * rank.small_strain_stiffness(el, gauss(*rule) if rule else rank.exact_rule(el), L / n)
    per_node = 2 * len(el.kinds)
    K = np.zeros(((n + 1) * per_node,) * 2)
    for e in range(n):
        i = slice(e * per_node, e * per_node + Ke.shape[0])
        K[i, i] += Ke
    fixed = [2 * k + c for k, kind in enumerate(el.kinds) if "x" not in kind for c in (0, 1)]
    free = np.setdiff1d(np.arange(K.shape[0]), fixed)
    tip = n * per_node + 2 * el.kinds.index("r") + 1
    f = np.zeros(K.shape[0])
    f[tip] = 1.0
    u = np.zeros_like(f)
    u[free] = np.linalg.solve(K[np.ix_(free, free)], f[free])
    nu, E, G, I = 0.25, 2.5, 1.0, h ** 3 / 12
    return u[tip] / (L ** 3 / (3 * E / (1 - nu ** 2) * I) + L / (5 / 6 * G * h))


def softest_modes(aspect: float, rule=(3, 2), count: int = 2) -> list[tuple[float, float, float, float]]:
    """The ``count`` deformation modes whose energy ``rule`` sees least against the exact
    rule (``rank.softest_modes``): (mu, exact-energy share of eps_xx, of eps_yy with the
    coupling, of shear)."""
    el = get_element(ELEMENT)
    G_e, _ = rank._strain_rows(el, rank.exact_rule(el), aspect)
    mus, modes = rank.softest_modes(el, rule, aspect, count)
    out = []
    for mu, mode in zip(mus, modes.T):
        e = G_e @ mode
        exx, eyy, gxy = e[0::3], e[1::3], e[2::3]
        parts = np.array([3 * exx @ exx, 3 * eyy @ eyy + 2 * exx @ eyy, gxy @ gxy])
        out.append((float(mu), *(parts / parts.sum())))
    return out


def main() -> None:
    print(f"1. {ELEMENT} on the work-precision pendulums, dt = 1.25 ms: error / L against the continuum")
    print("| scene | elements | l_e / h | default rule | error | [3, 2] | error |")
    print("|---|---|---|---|---|---|---|")
    for scene, counts in (("pendulum", (2, 4, 8, 16)), ("thick", (2, 4, 8))):
        for n in counts:
            (e0, q0), (e1, q1) = (pendulum_error(scene, n, r) for r in RULES)
            aspect = LENGTH / n / SCENES[scene]["height"]
            print(f"| {scene} | {n} | {aspect:g} | {q0} | {100 * e0:.3f} % | {q1} | {100 * e1:.3f} % |")
    print("\n2. Small strain: linear cantilever, L / h = 70, tip deflection / Timoshenko's")
    print("| elements | exact rule | [4, 2] | [3, 2] |")
    print("|---|---|---|---|")
    for n in (2, 4, 8, 16):
        print(f"| {n} | " + " | ".join(f"{linear_tip_ratio(n, r):.5f}" for r in (None, (4, 2), (3, 2))) + " |")
    print("\n3. The softest modes under [3, 2]: mu; shares of the exact energy (eps_xx / eps_yy / shear)")
    for aspect in (35.0, 17.5, 10.0, 3.0):
        print(f"l_e / h = {aspect:g}: " + "; ".join(f"mu {m:.4f} ({a:.2f} / {b:.2f} / {c:.2f})"
                                                for m, a, b, c in softest_modes(aspect)))


if __name__ == "__main__":
    main()
