"""Saint-Venant torsion of a rectangular bar: the torsion constant J (torque = mu J dtheta/dx in
small twist), exact and within a polynomial section.

- :func:`saint_venant_rectangle`: the exact J of an h x w rectangle by its series
  (Timoshenko and Goodier, *Theory of Elasticity*, 3rd ed., 1970, section 109: with a <= b the
  sides, J = a^3 b / 3 (1 - (192 a / (pi^5 b)) sum_{n odd} tanh(n pi b / (2 a)) / n^5));
  :data:`TIMOSHENKO_GOODIER_TABLE` holds the book's table of k1 = J / (a^3 b), which the
  series is checked against;
- :func:`polynomial_warping` (:func:`warping_bound` for any set of monomials,
  :func:`warping_state` its state) and :func:`quadratic_warping`: J of the same bar when
  the warping psi (the axial displacement per twist rate, u_x = dtheta/dx psi(y, z)) is
  restricted to the
  polynomials in (y, z) of a degree, as in a beam element whose section is complete to that
  degree: the Saint-Venant energy mu/2 (dtheta/dx)^2 int (psi_y - z)^2 + (psi_z + y)^2 dA
  minimised over that space (a Ritz bound: never below the exact J, falling to it with the
  degree). Degree 0 or 1 holds no warping (J = I_p, the polar moment); degrees 2 and 3 hold
  psi = c y z only (psi must be odd in y and in z), for which the minimum is closed:
  c = (A - B) / (A + B) and J = 4 A B / (A + B), with A = int z^2 dA and B = int y^2 dA
  (:func:`quadratic_warping`, derived here: the energy (c - 1)^2 A + (c + 1)^2 B, minimised
  in c). A square's c is 0: its quadratic section is as stiff as no warping at all.

Lengths in any unit; J in that unit to the fourth. Nothing here is computed by a solver of
this project.
"""
from __future__ import annotations

import numpy as np

# k1 = J / (a^3 b) against b / a (Timoshenko and Goodier 1970, section 109, table 3 (the
# book's k1, three digits))
TIMOSHENKO_GOODIER_TABLE = {1.0: 0.141, 1.5: 0.196, 2.0: 0.229, 2.5: 0.249, 3.0: 0.263, 4.0: 0.281,
                            5.0: 0.291, 10.0: 0.312}


def saint_venant_rectangle(h: float, w: float, terms: int = 100) -> float:
    """The exact torsion constant of an h x w rectangle (its series, ``terms`` odd terms:
    the remainder is below 1e-10 of the sum at 100)."""
    a, b = sorted((float(h), float(w)))
    n = np.arange(1, 2 * terms, 2)
    return a ** 3 * b / 3.0 * (1.0 - 192.0 * a / (np.pi ** 5 * b) * float(np.sum(np.tanh(n * np.pi * b / (2.0 * a)) / n ** 5)))


def polar_moment(h: float, w: float) -> float:
    """I_p = int y^2 + z^2 dA of the h x w rectangle: J without warping."""
    return h * w * (h * h + w * w) / 12.0


def quadratic_warping(h: float, w: float) -> float:
    """J with the warping psi = c y z, the best c (see the module doc): 4 A B / (A + B)."""
    A, B = h * w ** 3 / 12.0, w * h ** 3 / 12.0
    return 4.0 * A * B / (A + B)


def polynomial_warping(h: float, w: float, degree: int) -> float:
    """J with the warping in the complete polynomials of ``degree`` in (y, z) (see the
    module doc)."""
    if degree < 0:
        raise ValueError(f"degree: a polynomial degree of 0 or more, got {degree!r}")
    return warping_bound(h, w, [(a, c) for a in range(degree + 1) for c in range(degree + 1 - a)])


def warping_bound(h: float, w: float, modes) -> float:
    """J with the warping in the span of the monomials y^a z^c, (a, c) in ``modes`` (see
    the module doc; :func:`warping_state`)."""
    return warping_state(h, w, modes)[0]


def warping_state(h: float, w: float, modes):
    """(J, shear) of the Saint-Venant state with the warping in the span of the monomials
    y^a z^c, (a, c) in ``modes``: the least-squares minimum of int (psi_y - z)^2 +
    (psi_z + y)^2 dA by a Gauss rule exact for it, on Legendre products in the coordinates
    scaled to the unit square (the same span as the monomials when the modes hold (a - 2, c)
    and (a, c - 2) with (a, c), as a complete section does and y^3 z, y z^3 added to one of
    degree two; well conditioned to degree 12). ``shear(y, z)`` gives (psi_y - z, psi_z + y)
    at points: the state's shear stresses (sigma_xy, sigma_xz) per mu dtheta/dx, the
    traction its end faces carry."""
    mons = [(a, c) for a, c in modes if a + c >= 1]
    degree = max([a + c for a, c in mons], default=0)
    # d/dy and d/dz of the Legendre products P_a(s) P_c(t), y = s h / 2, z = t w / 2
    P = lambda k, x, d: np.polynomial.legendre.Legendre.basis(k).deriv(d)(x)

    def derivatives(y, z):
        s, t = 2.0 * np.asarray(y, float) / h, 2.0 * np.asarray(z, float) / w
        Dy = np.array([P(a, s, 1) * (2.0 / h) * P(c, t, 0) for a, c in mons]).reshape(len(mons), -1)
        Dz = np.array([P(a, s, 0) * P(c, t, 1) * (2.0 / w) for a, c in mons]).reshape(len(mons), -1)
        return Dy, Dz

    g, wg = np.polynomial.legendre.leggauss(degree + 2)
    s, t = (a.ravel() for a in np.meshgrid(g, g, indexing="ij"))
    wt = np.outer(wg, wg).ravel() * h * w / 4.0
    y, z = s * h / 2.0, t * w / 2.0
    coef = np.zeros(len(mons))
    if mons:
        Dy, Dz = derivatives(y, z)
        K = (Dy * wt) @ Dy.T + (Dz * wt) @ Dz.T
        coef = np.linalg.lstsq(K, (Dy * wt) @ z - (Dz * wt) @ y, rcond=None)[0]

    def shear(y, z):
        y, z = np.asarray(y, float).ravel(), np.asarray(z, float).ravel()
        if not mons:
            return -z, y
        Dy, Dz = derivatives(y, z)
        return coef @ Dy - z, coef @ Dz + y

    gy, gz = shear(y, z)
    return float(wt @ (gy ** 2 + gz ** 2)), shear
