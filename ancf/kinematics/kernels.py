"""The element interface of the compiled loops: the one place where a model's data choose
the kernel that assembles it.

The static Newton (:mod:`ancf.solvers.compiled_statics`) and the step loop (:mod:`ancf.solvers.compiled_steps`)
call only these, with the model's data (:attr:`ancf.kinematics.model.ElementModel.fused`: dN, w, dofs,
the law's tape ops and consts, the element's fields pr) and the work arrays of
:func:`element_work`; they keep no element knowledge. The data say which kernel: a
cable's tape is the law's uniaxial energy in the fibre stretch
(:func:`ancf.core.tape.trace_uniaxial`, first instruction VAR_STRETCH), and goes to
:mod:`ancf.kinematics.cable.kernels` (its dN: N', N'' at the points along; its pr[0]: the section
rule); every other tape is W(a, J) of a continuum-based element's F and goes to
:mod:`ancf.kinematics.section.kernels` (which itself chooses the assumed strain's and the pressure field's
terms from pr). Both kinds have the same types, so one compiled
specialisation of each loop runs every element (numba does not cache a function that takes
another compiled function as an argument, so the choice is a branch here, not a kernel
passed in).
"""
from __future__ import annotations

from numba import njit

from .cable.kernels import cable_assemble, cable_energy, cable_force_magnitude, cable_points, cable_scratch
from .section.dg_kernels import assemble_dg
from .section.assumed_kernels import assumed_invariants
from .section.kernels import INADMISSIBLE, OK, assemble_fused, force_magnitude_fused, point_gradients, step_scratch, strain_energy_fused
from ..core.tape import VAR_STRETCH


@njit(cache=True, inline="always")
def is_cable(ops):
    """Is this the tape of a cable (the law's uniaxial energy in the fibre stretch)?"""
    return ops.shape[0] > 0 and ops[0, 0] == VAR_STRETCH


@njit(cache=True)
def element_work(ops, dN, pr):
    """The work arrays (chunk, R, Fb, ab, Jb, ew) of :func:`element_assemble` and
    :func:`element_energy` for these data: :func:`ancf.kinematics.cable.kernels.cable_scratch` for a
    cable (its fibres per element are its points along times its section's),
    :func:`ancf.kinematics.section.kernels.step_scratch` otherwise; the same types."""
    if is_cable(ops):
        return cable_scratch(ops.shape[0], dN, pr)
    return step_scratch(ops.shape[0], dN, pr)


@njit(cache=True, inline="always")
def element_assemble(u, u_n, alpha_f, dN, w, dofs, ops, consts, pr, f, Kc, with_tangent, chunk, R, Fb, ab, Jb, ew):
    """Internal force at (1 - alpha_f) u + alpha_f u_n into f and, if with_tangent, the upper
    half of the tangent into Kc (column band): :func:`ancf.kinematics.cable.kernels.cable_assemble` for
    a cable, :func:`ancf.kinematics.section.kernels.assemble_fused` otherwise. Returns OK or INADMISSIBLE."""
    if is_cable(ops):
        return cable_assemble(u, u_n, alpha_f, dN, w, dofs, ops, consts, pr, f, Kc, with_tangent, chunk, R, Fb, ab,
                              Jb, ew)
    return assemble_fused(u, u_n, alpha_f, dN, w, dofs, ops, consts, pr, f, Kc, with_tangent, chunk, R, Fb, ab, Jb,
                          ew)


@njit(cache=True, inline="always")
def element_energy(u, dN, w, dofs, ops, consts, pr, chunk, R, Fb, ab, Jb, ew):
    """The strain energy (J) at u; nan at an inadmissible state."""
    if is_cable(ops):
        return cable_energy(u, dN, w, dofs, ops, consts, pr, chunk, R, Fb, ab, Jb)
    return strain_energy_fused(u, dN, w, dofs, ops, consts, pr, chunk, R, Fb, ab, Jb, ew)


@njit(cache=True, inline="always")
def element_admissible(u, dN, dofs, ops, pr, chunk, Fb, ab, Jb):
    """OK if the state u is admissible where the element's energy is evaluated (a
    continuum-based element: det F > 0, det C_bar with an assumed strain, at every point;
    a cable: every fibre's stretch > 0), else INADMISSIBLE: the kinematics of
    :func:`element_assemble` alone, no law, no force."""
    ne = dofs.shape[0]
    for e0 in range(0, ne, chunk):
        e1 = min(ne, e0 + chunk)
        if is_cable(ops):
            m = cable_points(u, u, 0.0, dN, dofs, pr[0], e0, e1, Fb, ab)
        else:
            m = point_gradients(u, u, 0.0, dN, dofs, e0, e1, Fb, ab, Jb)
            if m >= 0 and pr[3].shape[1] > 0:
                m = assumed_invariants(Fb, ab, Jb, m, pr[3])
        if m < 0:
            return INADMISSIBLE
    return OK


@njit(cache=True)
def element_force_magnitude(u, dN, w, dofs, ops, consts, pr, out):
    """out (n,) <- the internal force assembled from the magnitudes of its terms (what its
    round-off is relative to); returns OK or INADMISSIBLE."""
    if is_cable(ops):
        chunk, R, Fb, ab, Jb, _ = cable_scratch(ops.shape[0], dN, pr)
        return cable_force_magnitude(u, dN, w, dofs, ops, consts, pr, out, chunk, R, Fb, ab, Jb)
    return force_magnitude_fused(u, dN, w, dofs, ops, consts, pr, out)


@njit(cache=True)
def element_assemble_dg(u0, u1, dN, w, dofs, ops, consts, pr, f, Kc, chunk, R, Fb, ab, Jb, ew, F0, F1, aL, JL, RL,
                        W):
    """The discrete gradient's force and tangent (:func:`ancf.kinematics.section.dg_kernels.assemble_dg`). A cable
    has none (its fibre stretch is not quadratic in u; the loop refuses it when it is built,
    :func:`ancf.kinematics.model.refuse_discrete_gradient`): INADMISSIBLE."""
    if is_cable(ops):
        return INADMISSIBLE
    return assemble_dg(u0, u1, dN, w, dofs, ops, consts, pr, f, Kc, chunk, R, Fb, ab, Jb, ew, F0, F1, aL, JL, RL, W)

