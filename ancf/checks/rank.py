"""Rank tests of an element's elastic quadrature rule, and the default rule they choose.

Two tests of one free element l_e = aspect x h:

- :func:`rank_test`, the standard eigenvalue test at u = 0: the zero-energy modes of the
  small-strain tangent beyond the 3 rigid ones (the rank deficiency of the stacked
  sqrt(w) B_sym at the rule's points: the null space of K for any law whose small-strain
  tangent is positive definite on symmetric strains), and mu_min, the smallest ratio
  (energy under the rule) / (exact energy) over all deformation modes (a generalized
  eigenproblem on the complement of the rigid modes; 1 when the rule is exact for K).
- :func:`strain_test`, its finite-strain form: at u = 0 the test sees only the linear
  strain, but the Green strain E = sym(grad u) + grad u^T grad u / 2 has twice the
  degree, and an incompressible law has W = 0 only at E = 0. The test searches the
  element's states of a given true rms Green strain (under a rule exact for them) for the
  one whose strain the rule sees least: seen / true. A ratio << 1 is a near-spurious
  finite-strain family. It found the cause of the "loss of convergence" of HB2n-12 and
  HB3n-12 at l_e << h: x^2 + y^2 in u_x with x y in u_y strains, at finite amplitude,
  evenly in y and vanishes at the two thickness points of any [n, 2] rule (seen/true
  0.26 / 0.13 / 0.03 for HB2n-12 at l_e/h = 0.1 / 0.05 / 0.01; every [n, 3] rule >= 0.89).

A cable (``ElementSpec.kinematics = "cable"``) takes both tests on its fibre strain: the
small u_x' - y u_y'' and the finite lambda - 1, at its point data (N', y N'')
(:meth:`ancf.kinematics.cable.Cable.point_data`), a rule exact across being two points.

:func:`default_quadrature` reads the rule an element declares (``ElementSpec.quadrature``,
chosen by these tests: tests/test_rank.py checks that each declared rule passes both
over the aspect ratios it is declared for, and that the next cheaper one fails);
:func:`rule_warnings` is what a record says of a rule a scene asked for.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
import scipy.linalg as sla

from ..kinematics.section.assumed import sampling
from ..elements import ElementSpec, get_element
from ..core.quadrature import Rule, exact_for, gauss

# thresholds of the verdicts (Jacobi-scaled matrices, unit diagonal)
SVD_TOL = 3e-7        # zero singular value of sqrt(w) B_sym, relative to the largest (eigenvalue ~1e-14)
MU_MIN = 0.1          # a deformation mode whose energy the rule sees below 10 % is near-spurious
STRAIN_RATIO = 0.3    # a finite-strain state whose strain the rule sees below 30 % (full-rank rules: >= 0.78)
ASPECTS = (35.0, 17.5, 10.0, 3.0, 1.0, 0.3, 0.1, 0.05, 0.025, 0.01)   # l_e / h of the tests' sweeps
# (35, 17.5: the slender pendulum's 2 and 4 elements)


def exact_rule(element: ElementSpec) -> Rule:
    """A rule exact for the small-strain stiffness (its kinematics' degrees,
    :meth:`ancf.kinematics.family.Kinematics.exact_degree`: the squared basis; a cable's
    small strain u_x' - y u_y'' squared is linear in y: two points across)."""
    return exact_for(*element.family.exact_degree(element))


def _strain_rows(element: ElementSpec, rule: Rule, aspect: float) -> tuple[np.ndarray, np.ndarray]:
    """sqrt(w) [eps_xx; eps_yy; 2 eps_xy] rows at the rule's points (3 nq, 2 ns), for u = N q
    with q (ns, 2) flattened, on l_e = aspect, h = 1 (its kinematics' small strain,
    :meth:`ancf.kinematics.family.Kinematics.small_strain`: a cable's is its fibres' alone);
    and the point data."""
    family = element.family
    dN = family.point_data(element, rule.xi, rule.eta, aspect, 1.0)      # (nq, ns, 2)
    nq, ns = dN.shape[:2]
    B = family.small_strain(dN)
    return (np.sqrt(rule.weight)[:, None, None, None] * B).reshape(3 * nq, 2 * ns), dN


def _rigid(element: ElementSpec, aspect: float) -> np.ndarray:
    """(2 ns, 3): the translations and the infinitesimal rotation (-y, x), as element dofs,
    by fitting u = N q at a rule exact for the basis."""
    rule = exact_rule(element)
    N, _ = element.tabulate(rule.xi, rule.eta, aspect, 1.0)
    x, y = rule.xi * aspect, rule.eta
    fields = [(np.ones_like(x), 0 * x), (0 * x, np.ones_like(x)), (-y, x)]
    out = []
    for ux, uy in fields:
        qx = np.linalg.lstsq(N, ux, rcond=None)[0]
        qy = np.linalg.lstsq(N, uy, rcond=None)[0]
        out.append(np.stack([qx, qy], axis=1).ravel())
    return np.array(out).T


LAME = np.array([[3.0, 1.0, 0.0], [1.0, 3.0, 0.0], [0.0, 0.0, 1.0]])  # plane, lambda = mu = 1:
# the isotropic small-strain tangent of the tests, on [eps_xx, eps_yy, 2 eps_xy]


def _stiffness(G: np.ndarray) -> np.ndarray:
    """sum over the points of G_q^T LAME G_q, G the rows of :func:`_strain_rows`."""
    return sum(G[3 * q:3 * q + 3].T @ LAME @ G[3 * q:3 * q + 3] for q in range(G.shape[0] // 3))


def small_strain_stiffness(element: ElementSpec, rule: Rule, aspect: float) -> np.ndarray:
    """The small-strain stiffness (2 ns, 2 ns) of one element l_e = aspect, h = 1, under
    ``rule``, per unit element area, with the tests' tangent :data:`LAME`."""
    return _stiffness(_strain_rows(element, rule, aspect)[0])


def _eigen(element: ElementSpec, G_r: np.ndarray, G_e: np.ndarray, aspect: float
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(mu ascending, V, s): the generalized eigenproblem of the small-strain energy of a
    rule's strain rows G_r against the exact rule's G_e on the complement of the rigid
    modes, Jacobi-scaled by s = diag(K_exact)^-1/2; V (2 ns, k) the modes as element dofs."""
    K_r, K_e = _stiffness(G_r), _stiffness(G_e)
    s = 1.0 / np.sqrt(np.diag(K_e))
    Z = np.linalg.qr(_rigid(element, aspect) / s[:, None], mode="complete")[0][:, 3:]
    S_r, S_e = s[:, None] * K_r * s, s[:, None] * K_e * s
    mu, V = sla.eigh(Z.T @ S_r @ Z, Z.T @ S_e @ Z)
    return mu, s[:, None] * (Z @ V), s


def _row_pair(element: str | ElementSpec, rule: tuple[int, int] | Rule, aspect: float
              ) -> tuple[ElementSpec, np.ndarray, np.ndarray]:
    """(the element, the rule's strain rows, the exact rule's): what the u = 0 tests compare."""
    el = get_element(element) if isinstance(element, str) else element
    rule = gauss(*rule) if not isinstance(rule, Rule) else rule
    return el, _strain_rows(el, rule, aspect)[0], _strain_rows(el, exact_rule(el), aspect)[0]


def softest_modes(element: str | ElementSpec, rule: tuple[int, int] | Rule, aspect: float,
                  count: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """The ``count`` deformation modes whose energy ``rule`` sees least against the exact
    rule (:func:`rank_test`'s eigenproblem): (mu (count,), modes (2 ns, count) as element
    dofs, q flattened node by node as (ux, uy))."""
    el, G_r, G_e = _row_pair(element, rule, aspect)
    mu, modes, _ = _eigen(el, G_r, G_e, aspect)
    return mu[:count], modes[:, :count]


def rank_test(element: str | ElementSpec, rule: tuple[int, int] | Rule, aspect: float) -> dict:
    """The u = 0 eigenvalue test: {"spurious": zero-energy modes beyond the rigid three,
    "mu_min": smallest rule/exact energy ratio of a deformation mode, "passes": bool}.
    Energies are those of an isotropic small-strain tangent (:data:`LAME`); the null space
    does not depend on the law."""
    el, G_r, G_e = _row_pair(element, rule, aspect)
    mu, _, s = _eigen(el, G_r, G_e, aspect)
    sv = np.linalg.svd(G_r * s, compute_uv=False)
    sv_e = np.linalg.svd(G_e * s, compute_uv=False)
    rank = int(np.sum(sv > SVD_TOL * sv_e[0]))
    spurious = G_r.shape[1] - rank - 3
    mu_min = max(float(mu.min()), 0.0)
    return {"spurious": spurious, "mu_min": mu_min, "passes": spurious == 0 and mu_min >= MU_MIN}


@lru_cache(maxsize=256)
def _strain_test(name: str, rule: tuple[int, int], aspect: float, amplitude: float, starts: int) -> float:
    from scipy.optimize import least_squares

    el = get_element(name)
    r, fine = gauss(*rule), gauss(8, 8)
    seen_at, T = (r, None) if not el.assumed else sampling(el.assumed, el.assumed_points, r)
    family = el.family                        # its strain measure (a cable's: the fibre stretch's, lambda - 1)
    dN_r = family.point_data(el, seen_at.xi, seen_at.eta, aspect, 1.0)
    dN_f = family.point_data(el, fine.xi, fine.eta, aspect, 1.0)
    strain = family.finite_strain
    ns, nk = el.n_shape, len(el.kinds)
    fixed = [0, 1, 2 * (ns - nk) + 1]         # node 0's r, the last node's r_y component: no rigid motion
    free = np.setdiff1d(np.arange(2 * ns), fixed)
    sw_r, sw_f = np.sqrt(r.weight)[:, None], np.sqrt(fine.weight)[:, None]

    def unpack(z):
        q = np.zeros(2 * ns)
        q[free] = z
        return q.reshape(ns, 2)

    def resid(z):
        q = unpack(z)
        seen = (sw_r * strain(q, dN_r, T)).ravel()
        true = np.sqrt(np.sum((sw_f * strain(q, dN_f)) ** 2))
        return np.concatenate([seen, [30.0 * (true - amplitude)]])

    scale = np.repeat(1.0 / np.maximum(np.abs(dN_f).max(axis=(0, 2)), 1e-300), 2)[free]
    method = "lm" if 3 * len(r.weight) + 1 >= len(free) else "trf"
    rng = np.random.default_rng(0)
    best = 1.0
    for _ in range(starts):
        z0 = rng.standard_normal(len(free)) * scale * amplitude
        sol = least_squares(resid, z0, x_scale=scale, method=method, max_nfev=4000, xtol=1e-15, ftol=1e-15, gtol=1e-15)
        q = unpack(sol.x)
        true = np.sqrt(np.sum((sw_f * strain(q, dN_f)) ** 2))
        if abs(true - amplitude) <= 0.05 * amplitude:
            best = min(best, float(np.sqrt(np.sum((sw_r * strain(q, dN_r, T)) ** 2)) / true))
    return best


def strain_test(element: str, rule: tuple[int, int], aspect: float, amplitude: float = 0.2,
                starts: int = 6) -> dict:
    """The finite-strain test: {"ratio": seen / true rms Green strain of the worst state
    found (deterministic starts), "passes": ratio >= STRAIN_RATIO}."""
    ratio = _strain_test(element, tuple(int(v) for v in rule), float(aspect), float(amplitude), int(starts))
    return {"ratio": ratio, "passes": ratio >= STRAIN_RATIO}


def default_quadrature(element: ElementSpec, penalised: bool, aspect: float) -> tuple[int, int]:
    """The element's declared rule for this formulation kind and l_e / h, or the rule
    exact for its basis when it declares none."""
    for pen, smallest, rule in element.quadrature:
        if pen == penalised and aspect >= smallest:
            return tuple(rule)
    dx, dy = element.degree()
    return dx + 1, dy + 1


def rule_warnings(element: ElementSpec, rule: tuple[int, int], penalised: bool, aspect: float) -> list[str]:
    """What a record says of a rule that is not the element's default: the spurious-mode
    count and near-spurious modes of the u = 0 test, and the finite-strain family of the
    strain test, at the scene's l_e / h."""
    if tuple(rule) == default_quadrature(element, penalised, aspect):
        return []
    out = []
    lin = rank_test(element, rule, aspect)
    if lin["spurious"] > 0:
        out.append(f"quadrature {list(rule)}: {lin['spurious']} spurious zero-energy mode(s) per element at "
                   f"l_e/h = {aspect:.3g} (rank test)")
    elif lin["mu_min"] < MU_MIN:
        out.append(f"quadrature {list(rule)}: a near-spurious mode per element at l_e/h = {aspect:.3g} (the rule "
                   f"sees {100 * lin['mu_min']:.2g} % of its energy; rank test)")
    fs = strain_test(element.name, rule, aspect) if lin["spurious"] == 0 else None
    if fs is not None and not fs["passes"]:
        default = default_quadrature(element, penalised, aspect)
        has = not strain_test(element.name, default, aspect)["passes"]     # (a cable's [3, 3], slender: kept)
        out.append(f"quadrature {list(rule)}: a near-spurious finite-strain family at l_e/h = {aspect:.3g} (the "
                   f"rule sees {100 * fs['ratio']:.2g} % of its Green strain); the default {list(default)} "
                   + ("has it too (the element's note says why it is kept)" if has else "does not have it"))
    return out
