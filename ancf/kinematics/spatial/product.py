"""The tangent of an element whose shape functions are products, by sum factorisation.

Every built-in spatial element's shape functions are products of a function along the beam
and one over the section, N_k(xi, eta, zeta) = c_k h_a(k)(xi) s_b(k)(eta, zeta): a Hermite or
Lagrange function of xi times a section mode (1, y, z, y z, ...), with few distinct factors
(HS2n-180p: 60 shape functions from 4 along and 15 section factors). On a product rule
(n_x points along, n_s = n_y n_z over the section) the tangent

    K_(k i)(l m) = sum_p w_p dN_kJ A_iJmL dN_lL

then splits into two small contractions per pair of gradient directions (J, L): over the
section's points with the section factors (s, s_eta, s_zeta), then over the points along
with the along factors (h, h'), instead of one over every point with every shape function.
For HS2n-180p on the (4, 6, 6) rule that is about a fifth of the products, all in large
matrix products.

:func:`factors` finds the factors from the tabulated shape functions (a rank-one split of
each N_k over the rule's grid, checked to round-off on the gradients of every element), or
returns None when an element's functions do not split; :func:`element_tangents` is the
tangent from them. The pointwise contraction (:meth:`.beam.SpatialBeam.element_tangents`)
is the definition this one is tested against.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# a split whose reconstruction misses a gradient by more than this (relative to its largest
# entry) is not a product: round-off of the tabulation is about 1e-15
SPLIT_TOL = 1e-10


@dataclass(frozen=True)
class Factors:
    along: np.ndarray      # (3, n_x, n_a): h' (for d/dxi), h, h, dimensionless, at the points along
    section: np.ndarray    # (3, n_s, n_b): s, s_eta, s_zeta at the section's points
    a: np.ndarray          # (n,) each shape function's along factor
    b: np.ndarray          # (n,) its section factor
    c: np.ndarray          # (E, n) its coefficient in each element
    scale: np.ndarray      # (E, 3) 1 / (l_e, h, w): d/dx = scale_0 d/dxi, ...


def _unit(v: np.ndarray) -> np.ndarray:
    """v over its norm, signed so that its largest entry is positive."""
    v = v / np.linalg.norm(v)
    return v if v[np.argmax(np.abs(v))] > 0 else -v


def _group(vectors: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """The distinct unit vectors among ``vectors`` (stacked as columns) and each one's index."""
    unique, index = [], []
    for v in vectors:
        for i, u in enumerate(unique):
            if np.max(np.abs(u - v)) < SPLIT_TOL:
                index.append(i)
                break
        else:
            index.append(len(unique))
            unique.append(v)
    return np.stack(unique, axis=1), np.array(index)


def factors(N: np.ndarray, dN: np.ndarray, points: tuple[int, int, int], lengths: np.ndarray,
            height: float, width: float) -> Factors | None:
    """The product split of every element's shape functions, or None if they do not split.

    N (E, npts, n) and dN (E, npts, n, 3) at a product rule of ``points`` (along slowest),
    ``lengths`` (E,) the elements' lengths."""
    E, npts, n = N.shape
    nx = points[0]
    ns = npts // nx
    h_list, s_list = [], []
    for k in range(n):
        u, sig, vt = np.linalg.svd(N[0, :, k].reshape(nx, ns))
        if sig[1:].max(initial=0.0) > SPLIT_TOL * sig[0]:
            return None
        h_list.append(_unit(u[:, 0]))
        s_list.append(_unit(vt[0]))
    H, a = _group(h_list)
    S, b = _group(s_list)
    c = np.empty((E, n))
    for e in range(E):
        for k in range(n):
            c[e, k] = H[:, a[k]] @ N[e, :, k].reshape(nx, ns) @ S[:, b[k]]
    scale = np.column_stack([1.0 / np.asarray(lengths, float), np.full(E, 1.0 / height), np.full(E, 1.0 / width)])
    # the derivatives' factors, projected from element 0's gradients: h' from d/dx, s_eta, s_zeta
    G = dN[0].reshape(nx, ns, n, 3) / (c[0][None, None, :, None] * scale[0][None, None, None, :])
    dH = np.stack([G[:, :, k, 0] @ S[:, b[k]] for k in range(n)], axis=1)     # (nx, n)
    dS = [np.stack([H[:, a[k]] @ G[:, :, k, J] for k in range(n)], axis=1) for J in (1, 2)]
    along = np.stack([_by_factor(dH, a, H.shape[1]), H, H])
    section = np.stack([S, _by_factor(dS[0], b, S.shape[1]), _by_factor(dS[1], b, S.shape[1])])
    f = Factors(along, section, a, b, c, scale)
    # the split must give every element's gradients back
    for e in range(E):
        R = _gradients(f, e)
        if np.max(np.abs(R - dN[e])) > SPLIT_TOL * np.max(np.abs(dN[e])):
            return None
    return f


def _by_factor(columns: np.ndarray, index: np.ndarray, count: int) -> np.ndarray:
    """One column per factor (the first shape function's that has it)."""
    return np.stack([columns[:, list(index).index(i)] for i in range(count)], axis=1)


def _gradients(f: Factors, e: int) -> np.ndarray:
    """dN (npts, n, 3) of element ``e`` rebuilt from the factors."""
    out = [f.along[J][:, f.a][:, None, :] * f.section[J][:, f.b][None, :, :] for J in range(3)]
    dN = np.stack(out, axis=-1) * f.c[e][None, None, :, None] * f.scale[e][None, None, None, :]
    return dN.reshape(-1, len(f.a), 3)


def element_tangents(f: Factors, wA: np.ndarray) -> np.ndarray:
    """Every element's sum_p dN_kJ wA_iJmL dN_lL, (E, 3 n, 3 n) (dof 3 k + i), from the split
    ``f`` and the weighted tangent moduli wA (E, n_x, n_s, 3, 3, 3, 3) (index i J m L)."""
    E, nx, ns = wA.shape[:3]
    n_a, n_b = f.along.shape[2], f.section.shape[2]
    # the directions' scales go into the moduli: dN_kJ = c_k scale_J along_J section_J
    wA = wA * (f.scale[:, None, None, None, :, None, None] * f.scale[:, None, None, None, None, None, :])
    # A's major symmetry makes the pair (L, J)'s block the transpose of (J, L)'s: the pairs
    # J = L, then J < L (added with their transposes)
    wA = wA.reshape(E * nx, ns, 3, 3, 3, 3)
    a, b = f.a, f.b
    blocks = []
    for pairs in (((0, 0), (1, 1), (2, 2)), ((0, 1), (0, 2), (1, 2))):
        # over the section, every pair at once: Q[JL, (m, n), (e, x, i, k)] = sum_j S^J_jm S^L_jn wA_iJkL(e, x, j)
        SS = np.stack([(f.section[J][:, :, None] * f.section[L][:, None, :]).reshape(ns, -1).T for J, L in pairs])
        Z = np.stack([wA[:, :, :, J, :, L].transpose(1, 0, 2, 3).reshape(ns, -1) for J, L in pairs])
        Q = np.matmul(SS, Z).reshape(len(pairs), n_b * n_b, E, nx, 9)
        # along, all pairs in one product: R[(a, a'), (m, n), e, (i, k)] = sum_JL,x H^J_xa H^L_xa' Q
        HH = np.concatenate([(f.along[J][:, :, None] * f.along[L][:, None, :]).reshape(nx, -1) for J, L in pairs])
        R = (HH.T @ Q.transpose(0, 3, 1, 2, 4).reshape(len(pairs) * nx, -1)).reshape(n_a, n_a, n_b, n_b, E, 3, 3)
        K = R[a[:, None], a[None, :], b[:, None], b[None, :]]                   # (k, l, e, i, m)
        blocks.append(K.transpose(2, 0, 3, 1, 4).reshape(E, 3 * len(a), 3 * len(a)))
    K = blocks[0] + blocks[1] + np.swapaxes(blocks[1], 1, 2)
    c3 = np.repeat(f.c, 3, axis=1)
    return K * c3[:, :, None] * c3[:, None, :]
