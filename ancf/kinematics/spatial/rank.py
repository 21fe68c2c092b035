"""The rank test of a spatial element's quadrature rule, the planar one's
(:func:`ancf.checks.rank.rank_test`) in 3D.

One free element l_e = aspect x h, h = 1, w = ``width`` x h, at q = reference: the
zero-energy modes of the small-strain tangent beyond the six rigid ones (the rank deficiency
of the stacked sqrt(w) B_sym, six strains at each of the rule's points) and mu_min, the
smallest ratio (energy under the rule) / (exact energy) over the deformation modes (a
generalized eigenproblem on the complement of the rigid modes, Jacobi-scaled; 1 when the
rule is exact). The tangent is the isotropic one with lambda = mu = 1, the planar test's;
the thresholds are the planar test's (:data:`ancf.checks.rank.SVD_TOL`, ``MU_MIN``).
"""
from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from ...checks.rank import MU_MIN, SVD_TOL
from .beam import gauss_box
from .spec import SpatialSpec

# lambda = mu = 1 on [e_xx, e_yy, e_zz, 2 e_yz, 2 e_xz, 2 e_xy]
LAME = np.diag([3.0, 3.0, 3.0, 1.0, 1.0, 1.0])
LAME[:3, :3] += np.ones((3, 3)) - np.eye(3)
_VOIGT = ((0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1))


def exact_rule(spec: SpatialSpec) -> tuple[int, int, int]:
    """A product rule exact for the squared basis (degree d per direction: d + 1 points)."""
    return tuple(d + 1 for d in spec.degree())


ASPECTS = (32.0, 4.0, 1.0, 0.25)      # l_e / h of the tests (the paper's cantilever at 1 to 128 elements)


def passes(spec: SpatialSpec, rule, width: float = 1.4, aspects=ASPECTS) -> bool:
    """The rule passes :func:`rank_test` at every aspect."""
    return all(rank_test(spec, rule, a, width)["passes"] for a in aspects)


def _rows(spec: SpatialSpec, rule, aspect: float, width: float) -> np.ndarray:
    """sqrt(w) strain rows (6 nq, 3 ns), dofs q (ns, 3) flattened."""
    X, wq = gauss_box(tuple(rule))
    _, dN = spec.tabulate(X[:, 0], X[:, 1], X[:, 2], aspect, 1.0, width)     # (nq, ns, 3)
    nq, ns = dN.shape[:2]
    B = np.zeros((nq, 6, ns, 3))
    for c, (I, J) in enumerate(_VOIGT):
        B[:, c, :, I] += dN[:, :, J]
        if I != J:
            B[:, c, :, J] += dN[:, :, I]
    return (np.sqrt(wq)[:, None, None, None] * B).reshape(6 * nq, 3 * ns)


def _rigid(spec: SpatialSpec, aspect: float, width: float) -> np.ndarray:
    """(3 ns, 6): the translations and the infinitesimal rotations, as element dofs, fitted
    at the exact rule."""
    X, _ = gauss_box(exact_rule(spec))
    N, _ = spec.tabulate(X[:, 0], X[:, 1], X[:, 2], aspect, 1.0, width)
    x = np.stack([X[:, 0] * aspect, X[:, 1], X[:, 2] * width], axis=1)
    fields = [np.tile(e, (len(x), 1)) for e in np.eye(3)] + [np.cross(e, x) for e in np.eye(3)]
    return np.array([np.linalg.lstsq(N, u, rcond=None)[0].ravel() for u in fields]).T


def _stiffness(G: np.ndarray) -> np.ndarray:
    G = G.reshape(-1, 6, G.shape[1])
    return np.einsum("qci,cd,qdj->ij", G, LAME, G)


def rank_test(spec: SpatialSpec, rule, aspect: float, width: float = 1.4) -> dict:
    """{"spurious": zero-energy modes beyond the rigid six, "mu_min", "passes"}."""
    G_r, G_e = _rows(spec, rule, aspect, width), _rows(spec, exact_rule(spec), aspect, width)
    K_r, K_e = _stiffness(G_r), _stiffness(G_e)
    s = 1.0 / np.sqrt(np.diag(K_e))
    Z = np.linalg.qr(_rigid(spec, aspect, width) / s[:, None], mode="complete")[0][:, 6:]
    mu = sla.eigh(Z.T @ (s[:, None] * K_r * s) @ Z, Z.T @ (s[:, None] * K_e * s) @ Z, eigvals_only=True)
    sv = np.linalg.svd(G_r * s, compute_uv=False)
    sv_e = np.linalg.svd(G_e * s, compute_uv=False)
    spurious = G_r.shape[1] - int(np.sum(sv > SVD_TOL * sv_e[0])) - 6
    mu_min = max(float(mu.min()), 0.0)
    return {"spurious": spurious, "mu_min": mu_min, "passes": spurious == 0 and mu_min >= MU_MIN}
