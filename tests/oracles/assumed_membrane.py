"""Which strain the three points along the beam relieve (issue 20; experiments/along_rule.py).

A prototype in numpy; the remedy it found is built in as ``ElementSpec.assumed``
(ancf/kinematics/section/assumed.py) and the element HB2n-20xypm, which tests/test_hb2n_20xypm.py holds
equal to this prototype (a test oracle, kept with the tests since: it is the second
route the built-in element is checked against). HB2n-20xyp keeps its default rule ([4, 2]; [5, 2] from l_e / h =
15). Chosen components of C = F^T F are taken from three points along the beam: sampled at
the 3 Gauss points along x at each of the rule's 2 points across, and interpolated
(quadratic Lagrange) to the rule's points along (4, or 5 from l_e / h = 15). Components:
"xx", the membrane stretch; "xy", the shear; "yy", the thickness stretch. The energy is
the harness's law at the modified C, W(a, J) with a = tr C and J = sqrt(det C)
(``Material.energy_jet``, plane stress). The force is its exact gradient. Everything else
is the harness's own: the mesh, the mass matrix, the gravity load and the supports of
``ancf.build``, and the generalized-alpha coefficients, predictor and update of
``mechanics.alpha_family``. The Newton tangent is
the force's central difference (the residual test is the harness's, rtol 1e-8, so the
answer does not depend on it).

In small strain the element's eps_xx is quadratic along x (u_x is cubic), so three
points see it exactly: an assumed C_xx leaves the u = 0 stiffness, and with it the rank
tests, as they are (the shear is not: u_x's y-slope r_y is cubic along x). The rule
[3, 2] instead drops a thickness-stretch mode (experiments/along_rule.py). The script prints
the slender pendulum's error and the paper's cantilever's tip under each choice.

    .venv/bin/python -m tests.oracles.assumed_membrane
"""
from __future__ import annotations

import numpy as np

from ancf.build import build_model, external_loads, plan
from ancf.core.quadrature import gauss
from contract import paper
from contract.scene import scene_from_dict
from mechanics import alpha_family
from studies.peers.work_precision import error, scene_dict

ELEMENT = "HB2n-20xyp"
MODES = ("none", "xx", "xy", "yy", "xx+xy", "xx+xy+yy")
COMPONENT = {"xx": (0, 0), "yy": (1, 1), "xy": (0, 1)}


class AssumedStrain:
    """Strain energy and force of a model's mesh with the components ``mode`` of C taken
    from the three-point rows along the beam ("none": the model's plain rule, [4, 2], or
    [5, 2] from l_e / h = 15), carried to the model's rule [n, 2] along the beam."""

    def __init__(self, model, mode: str):
        m = model.mesh
        self.model, self.material = model, model.material
        self.modes = [] if mode == "none" else [COMPONENT[c] for c in mode.split("+")]
        rule, r3 = model.rule, gauss(3, 2)
        vol = m.element_length * m.height * m.width
        _, self.dN = m.element.tabulate(rule.xi, rule.eta, m.element_length, m.height)
        _, self.dN3 = m.element.tabulate(r3.xi, r3.eta, m.element_length, m.height)
        self.w = rule.weight * vol
        x3, xr = np.unique(r3.xi.round(14)), np.unique(rule.xi.round(14))
        if len(rule.weight) != 2 * len(xr):
            raise ValueError(f"the model's rule has {len(rule.weight) // len(xr)} points across; the prototype wants 2")
        # quadratic Lagrange from the 3 points to the rule's (points are ordered x-major, y fastest)
        self.P = np.array([[np.prod([(x - x3[j]) / (x3[i] - x3[j]) for j in range(3) if j != i]) for i in range(3)]
                           for x in xr])
        self.dofs = model._dofs                                      # (ne, 2 ns), local order (a, i)

    def _C(self, ue, dN):
        """C at the points and dC_ab / du_(k, i), for element displacements ue (ne, ns, 2)."""
        F = np.eye(2) + np.einsum("eki,qkj->eqij", ue, dN)
        C = np.einsum("eqia,eqib->eqab", F, F)
        dC = np.einsum("qka,eqib->eqabki", dN, F) + np.einsum("eqia,qkb->eqabki", F, dN)
        return C, dC

    def energy_and_force(self, u: np.ndarray) -> tuple[float, np.ndarray]:
        ue = u[self.dofs].reshape(len(self.dofs), -1, 2)
        C, dC = self._C(ue, self.dN)
        if self.modes:
            C3, dC3 = self._C(ue, self.dN3)
            for a, b in self.modes:
                rows = C3[:, :, a, b].reshape(len(ue), 3, 2)
                drows = dC3[:, :, a, b].reshape(len(ue), 3, 2, *dC3.shape[-2:])
                npts = len(self.w)
                cbar = np.einsum("pm,emy->epy", self.P, rows).reshape(len(ue), npts)
                dbar = np.einsum("pm,emy...->epy...", self.P, drows).reshape(len(ue), npts, *dC3.shape[-2:])
                for i, j in {(a, b), (b, a)}:
                    C[:, :, i, j], dC[:, :, i, j] = cbar, dbar
        det = C[..., 0, 0] * C[..., 1, 1] - C[..., 0, 1] * C[..., 1, 0]
        if not np.all(np.isfinite(C)) or det.min() <= 0.0:
            raise FloatingPointError("det C <= 0 at a point")
        J = np.sqrt(det)
        W = self.material.energy_jet(C[..., 0, 0] + C[..., 1, 1], J)
        # dW/dC_ab = W_a delta_ab + W_J dJ/dC_ab, dJ/dC = J / 2 C^-T (C_ab and C_ba apart)
        dWdC = W.a[..., None, None] * np.eye(2) + (W.J * J / 2)[..., None, None] * np.linalg.inv(C).swapaxes(-1, -2)
        fe = np.einsum("q,eqab,eqabki->eki", self.w, dWdC, dC)
        f = np.bincount(self.dofs.ravel(), fe.reshape(len(ue), -1).ravel(), minlength=len(u))
        return float(np.sum(self.w * W.v)), f

    def force(self, u: np.ndarray) -> np.ndarray:
        return self.energy_and_force(u)[1]

    def tangent(self, u: np.ndarray, free: np.ndarray, eps: float = 1e-8) -> np.ndarray:
        """K on the free dofs by central differences of the force."""
        K = np.empty((free.size, free.size))
        for j, d in enumerate(free):
            du = np.zeros_like(u)
            du[d] = eps
            K[:, j] = (self.force(u + du) - self.force(u - du))[free] / (2 * eps)
        return 0.5 * (K + K.T)


def pendulum_error(n: int, mode: str, dt: float = 2.5e-3, rtol: float = 1e-8) -> float:
    """The slender pendulum of the work-precision bench (plane-stress Yeoh, rho_inf 0.5,
    pin, gravity) on n elements: error / L against the continuum (max over t = 0.1 ... 0.5 s)."""
    scene = scene_from_dict(scene_dict(ELEMENT, n, dt, 0.5))
    p = plan(scene)
    model = build_model(p)
    f_ext = sum(external_loads(model, p).values())
    M = model.mass_matrix().to_sparse().toarray()
    free = np.setdiff1d(np.arange(model.mesh.n_dof), model.fixed)
    Mf = M[np.ix_(free, free)]
    law = AssumedStrain(model, mode)
    c = alpha_family.generalized_alpha(0.5)
    am, af, beta, gamma = c["alpha_m"], c["alpha_f"], c["beta"], c["gamma"]
    u, v, a = (np.zeros(model.mesh.n_dof) for _ in range(3))
    a[free] = np.linalg.solve(Mf, (f_ext - law.force(u))[free])
    tip = model.mesh.element_dofs[-1][list(model.mesh.element.kinds).index("r") + len(model.mesh.element.kinds)]
    ref = model.mesh.reference
    tips = [{"t": 0.0, "x": ref[tip[0]] + u[tip[0]], "y": ref[tip[1]] + u[tip[1]]}]
    steps = int(round(0.5 / dt))
    for k in range(1, steps + 1):
        up = alpha_family.predict(u, v, a, dt)
        x = up.copy()
        scale = np.linalg.norm(f_ext[free]) + np.linalg.norm((M @ a)[free])
        for it in range(25):
            an, _ = alpha_family.update(x, up, v, a, dt, beta, gamma)
            ue = (1 - af) * x + af * u
            r = (M @ ((1 - am) * an + am * a) + law.force(ue) - f_ext)[free]
            if np.linalg.norm(r) <= rtol * scale:
                break
            if it == 0:                       # the tangent at the predictor, kept for the step
                S = (1 - am) / (beta * dt * dt) * Mf + (1 - af) * law.tangent(ue, free)
            x[free] -= np.linalg.solve(S, r)
        else:
            raise RuntimeError(f"{mode}, {n} elements: Newton did not converge at step {k}")
        a_new, v = alpha_family.update(x, up, v, a, dt, beta, gamma)
        u, a = x, a_new
        if k % int(round(0.1 / dt)) == 0:
            tips.append({"t": round(k * dt, 9), "x": ref[tip[0]] + u[tip[0]], "y": ref[tip[1]] + u[tip[1]]})
    return error(tips, "pendulum")


def cantilever_tip(n: int, mode: str, increments: int = 20, rtol: float = 1e-10) -> float:
    """The paper's cantilever (``contract.paper.cantilever_scene``: plane-stress Yeoh, face
    clamp, gravity) on n elements: the tip's vertical displacement (m), by Newton on equal load
    increments."""
    scene = scene_from_dict(paper.cantilever_scene("yeoh", "plane-stress", ELEMENT, n, quadrature=None))
    p = plan(scene)
    model = build_model(p)
    f_ext = sum(external_loads(model, p).values())
    free = np.setdiff1d(np.arange(model.mesh.n_dof), model.fixed)
    law = AssumedStrain(model, mode)
    u = np.zeros(model.mesh.n_dof)
    for lam in np.linspace(1.0 / increments, 1.0, increments):
        for _ in range(30):
            r = (law.force(u) - lam * f_ext)[free]
            if np.linalg.norm(r) <= rtol * np.linalg.norm(f_ext[free]):
                break
            u[free] -= np.linalg.solve(law.tangent(u, free), r)
        else:
            raise RuntimeError(f"{mode}, {n} elements: Newton did not converge at load {lam:g}")
    return float(model.tip_displacement(u)[1])


def main() -> None:
    print(f"{ELEMENT} on the slender pendulum, dt = 2.5 ms: error / L against the continuum, with the")
    print("components of C taken from the three points along the beam ('none': the element's default rule)")
    print("| elements | " + " | ".join(MODES) + " |")
    print("|---|" + "---|" * len(MODES))
    for n in (2, 4):
        print(f"| {n} | " + " | ".join(f"{100 * pendulum_error(n, m):.3f} %" for m in MODES) + " |", flush=True)
    print("\nThe paper's cantilever (plane-stress Yeoh, face clamp, gravity): tip deflection (mm)")
    print("| elements | " + " | ".join(MODES) + " |")
    print("|---|" + "---|" * len(MODES))
    for n in (2, 4):
        print(f"| {n} | " + " | ".join(f"{-1e3 * cantilever_tip(n, m):.3f}" for m in MODES) + " |", flush=True)


if __name__ == "__main__":
    main()
