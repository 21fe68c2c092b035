"""Continuum models as strategies: how the beam is a continuum, and how it is incompressible.

A :class:`ContinuumModel` says which invariants the law sees, whether a pressure field
is solved for and how incompressibility enters the energy, what the state's stored
energy is (for the energy balance), where a dynamic step evaluates the constraint, and
on which geometry it lives (:mod:`reference_fem.geometry`). The static and dynamic
problems (:mod:`reference_fem.dolfinx_backend.problem`) ask the model, never a flag. The pressure unknown
is scaled by a modulus ``mu`` (p = mu * phat) so that its rows and unknowns have the
size of the displacement ones. Energies per unit reference volume (Pa).

- :class:`PlaneStress`: F33 = 1/det F, psi(I1, I2); displacement only;
- :class:`MixedPlaneStrain`: psi(I1bar, I2bar) + mu phat (J - 1), exactly incompressible;
- :class:`PenaltyPlaneStrain`: ... - (mu phat)^2 / (2 alpha): eliminating phat gives the
  ANCF ``plane-strain`` energy psi + alpha/2 (J - 1)^2 without locking (perturbed
  Lagrangian);
- :class:`Solid` (``model = "3d"``): the real beam (length x height x width) on
  :data:`reference_fem.geometry.BOX`, the full 3D invariants, mixed or penalty as in
  plane strain (:class:`MixedSolid`, :class:`PenaltySolid`).

To add a model: subclass, set its names and ``has_pressure``, write ``invariants`` and
``energy``, and register it in :data:`MODELS` under (model, incompressibility).
"""
from __future__ import annotations

from typing import Mapping

import ufl

from contract.errors import UnknownName

from ..geometry import BOX, Geometry, PLANE
from mechanics.laws import Law

from .laws import energy, plane_strain_invariants, plane_stress_invariants, solid_invariants


class ContinuumModel:
    name = "base"                 # the record's continuum_model
    incompressibility = "base"    # the record's incompressibility
    has_pressure = False
    effects: tuple[str, ...] = ()
    geometry: Geometry = PLANE

    def invariants(self, F):
        """(I1, I2, J) the law sees at the gradient F."""
        raise NotImplementedError

    def energy(self, law: Law, c: Mapping, F, phat=None, mu=None, alpha=None):
        """The energy density (Pa) whose stationary point is the solution."""
        I1, I2, _ = self.invariants(F)
        return energy(law, I1, I2, c)

    def stored_energy(self, law: Law, c: Mapping, F, alpha=None):
        """The strain energy density of a state (Pa), pressure eliminated: what the
        energy balance counts."""
        I1, I2, _ = self.invariants(F)
        return energy(law, I1, I2, c)

    def constraint_displacement(self, u_new, u_alpha):
        """The displacement at which a dynamic step evaluates the constraint row (mixed:
        the new state, so every stored state is incompressible; penalty: where the
        elastic force acts)."""
        return u_new

    def constraint_row(self, s, F, phat, q):
        """The pressure equation dW/dphat q dx (None without a pressure field)."""
        if not self.has_pressure:
            return None
        p = ufl.variable(phat)
        return ufl.diff(s.energy(F, p), p) * q * s.disc.dx

    def start_terms(self, s, u0, a0, lam0, v, q, rho, cell_size: float):
        """The stress and constraint terms of the equations of the initial acceleration
        at rest at u0 (inertia and loads are added by the caller), and the factor that
        turns the solved lam0 into the model's phat."""
        terms = ufl.inner(s.stress(u0, lam0), ufl.grad(v)) * s.disc.dx
        row = self.constraint_row(s, s.gradient(u0), lam0, q)
        return (terms if row is None else terms + row), 1.0


class PlaneStress(ContinuumModel):
    name, incompressibility = "plane-stress", "exact"

    def invariants(self, F):
        return plane_stress_invariants(F)


class PlaneStrain(ContinuumModel):
    """F33 = 1, isochoric invariants, and a scaled pressure field (Taylor-Hood)."""
    name = "plane-strain"
    has_pressure = True

    def invariants(self, F):
        return plane_strain_invariants(F)

    def energy(self, law, c, F, phat=None, mu=None, alpha=None):
        I1, I2, J = self.invariants(F)
        return energy(law, I1, I2, c) + mu * phat * (J - 1)


class MixedPlaneStrain(PlaneStrain):
    incompressibility = "mixed"

    def start_terms(self, s, u0, a0, lam0, v, q, rho, cell_size: float):
        """Exactly incompressible: J(u0) = 1 holds already, so the start enforces the
        constraint's second time derivative at rest, cof F0 : grad a0 = 0, with the
        multiplier scaled by k = rho hc^2 (hc the cell size) instead of mu: the mass block
        (~ rho hc^2) and the constraint block then have the same size (with mu, 1e6 times
        larger, MUMPS reports a failed factorisation); lam0 is converted back."""
        dx, F0 = s.disc.dx, s.gradient(u0)
        k = rho * s.disc.constant(cell_size ** 2)
        terms = (ufl.inner(s.stress(u0, 0.0), ufl.grad(v)) * dx
                 + k * lam0 * ufl.inner(ufl.cofac(F0), ufl.grad(v)) * dx
                 + k * ufl.inner(ufl.cofac(F0), ufl.grad(a0)) * q * dx)
        return terms, float(rho.value) * cell_size ** 2 / s.mu


class PenaltyPlaneStrain(PlaneStrain):
    incompressibility = "penalty"
    effects = ("penalty",)

    def energy(self, law, c, F, phat=None, mu=None, alpha=None):
        return super().energy(law, c, F, phat, mu) - (mu * phat) ** 2 / (2 * alpha)

    def stored_energy(self, law, c, F, alpha=None):
        return super().stored_energy(law, c, F) + alpha / 2 * (ufl.det(F) - 1) ** 2

    def constraint_displacement(self, u_new, u_alpha):
        return u_alpha


class Solid(PlaneStrain):
    """The beam as a 3D continuum: psi(I1bar, I2bar) of the full C, a scaled pressure
    (Taylor-Hood Q2/Q1 or P2/P1) for J = 1; the box geometry."""
    name = "3d"
    geometry = BOX

    def invariants(self, F):
        return solid_invariants(F)


class MixedSolid(Solid, MixedPlaneStrain):
    incompressibility = "mixed"


class PenaltySolid(Solid, PenaltyPlaneStrain):
    incompressibility = "penalty"


MODELS: dict[tuple[str, str], ContinuumModel] = {
    (m.name, m.incompressibility): m for m in (MixedPlaneStrain(), PenaltyPlaneStrain(), PlaneStress(),
                                               MixedSolid(), PenaltySolid())
}


def get_model(name: str, incompressibility: str) -> ContinuumModel:
    try:
        return MODELS[(name, incompressibility)]
    except KeyError:
        raise UnknownName("fem.model/incompressibility", f"{name}/{incompressibility}",
                          [f"{a}/{b}" for a, b in MODELS]) from None
