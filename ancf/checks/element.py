"""The contract checks of an element, as measurements: each returns the measured number(s),
the bound it is held to and whether it passes. ``tests/test_elements.py`` and
``tests/test_model.py`` assert them over every registered element; the element report
card (``python -m studies card``) prints them.

- :func:`nodality`: interpolating any basis function's nodal coordinates gives the
  function and its gradient back;
- :func:`reference_state`: the reference nodal coordinates give F = I;
- :func:`energy_gradient`, :func:`tangent_gradient`: Taylor tests (force = energy
  gradient, tangent = force gradient; remainder slopes near 2);
- :func:`rigid_motion`: a rigid rotation + translation of a bent state leaves the energy
  and rotates the force;
- :func:`patch`: a homogeneous deformation: the assembled force equals the constant
  stress P(F0) (from the energy, by central differences) times the boundary integrals of
  the shape functions (divergence theorem);
- :func:`mass`: 1^T M 1 = rho A L, the gravity resultant = rho g V, M symmetric positive
  definite;
- :func:`conformity`: the jump of r and r_y across a shared element face under a bent state
  (measured, not required: elements whose trace involves other nodes jump).
"""
from __future__ import annotations

import numpy as np

from contract import paper
from contract.scene import MaterialSpec
from mechanics.laws import get_law

from ..build import build_material
from ..core.spec import KINDS, ElementSpec
from ..elements import get_element
from .rank import default_quadrature
from ..kinematics.section.model import BeamModel
from ..build import model_for
from ..core.formulations import FORMULATIONS
from ..core.mesh import Mesh
from ..core.quadrature import gauss

GEOMETRIES = ((0.160 / 16, 0.005), (0.160 / 640, 0.005), (0.350 / 4, 0.005))   # (l_e, h), m
HS = np.array([4e-6, 2e-6, 1e-6])                                               # Taylor steps
SLOPE = 1.8          # Taylor remainder slope required (2 in exact arithmetic)


def _spec(element) -> ElementSpec:
    return get_element(element) if isinstance(element, str) else element


def law_constants(law: str) -> dict:
    """The paper's constants and density of ``law``; for a law the paper does not have,
    the law's example constants with the density of the paper's neo-Hookean rubber."""
    if law in paper.materials():
        return dict(paper.materials()[law])
    return {**get_law(law).example, "density": paper.materials()["neo-hookean"]["density"]}


def paper_material(law: str, formulation: str, penalty: float = paper.PENALTY):
    """The paper's constants of ``law`` in ``formulation`` (penalty where it has one)."""
    c = law_constants(law)
    rho = c.pop("density")
    return build_material(MaterialSpec(law, formulation, rho, c,
                                       penalty if FORMULATIONS[formulation].penalised else None))


def small_model(element, law: str = "yeoh", formulation: str = "plane-stress", n: int = 3,
                penalty: float = 20e6, length: float = 0.16) -> BeamModel:
    """n elements of the cantilever's section, clamped face, quadrature [3, 2] (an element
    with a pressure field: its default rule, which resolves the pressure)."""
    mesh = Mesh(_spec(element), n, length, 0.005, 0.007)
    material = paper_material(law, formulation, penalty)
    rule = (3, 2) if not mesh.element.pressure else \
        default_quadrature(mesh.element, material.formulation.penalised, mesh.element_length / mesh.height)
    return model_for(mesh, material, gauss(*rule), mesh.element.family.fixed_dofs(mesh, "clamp", "face"))


def runs(element, formulation: str) -> bool:
    """Can the element run the formulation (its kinematics': a cable, plane stress alone)?"""
    return _spec(element).family.runs(formulation)


def bent_state(model: BeamModel, rng, angle: float = 0.2, noise: float = 1e-6) -> np.ndarray:
    """An admissible large-deformation state: the centre line bent to a circular arc
    (tip rotation ``angle``), sections stretched 1 % and squeezed 1 %, plus ``noise``
    (m, normal, from ``rng``)."""
    m = model.mesh
    kinds = m.element.kinds
    q = m.reference.reshape(m.n_nodes, -1, 2).copy()
    th = angle * m.node_x / m.length
    R = m.length / angle
    q[:, kinds.index("r")] = np.c_[R * np.sin(th), R * (1 - np.cos(th))]
    if "r_x" in kinds:
        q[:, kinds.index("r_x")] = 1.01 * np.c_[np.cos(th), np.sin(th)]
    if "r_y" in kinds:                      # (a cable has no section coordinates)
        q[:, kinds.index("r_y")] = 0.99 * np.c_[-np.sin(th), np.cos(th)]
    u = q.reshape(-1) - m.reference
    return u + noise * rng.standard_normal(m.n_dof) if noise else u


def inadmissible_state(model) -> np.ndarray:
    """A state no point may take: the beam mirrored x -> -x (det F = -1 everywhere) for a
    continuum-based element; for a kinematics whose mirrored state is admissible (a cable:
    mirrored or folded, its fibres keep their stretch) the bent arc of :func:`bent_state` (1 rad) shrunk 1000 times,
    |r_x| = 0.001 at the curvature 1 / L, where the outer points of any rule with two or more
    across (|Y| >= h / (2 sqrt 3)) have the stretch 0.001 - |Y| / L < 0 (L / h < 290)."""
    ref = model.mesh.reference
    if model.mesh.element.family.mirror_admissible:
        return 0.001 * (ref + bent_state(model, None, angle=1.0, noise=0.0)) - ref
    return np.where(np.arange(ref.size) % 2 == 0, -2.0 * ref, 0.0)


def rotate(model: BeamModel, u: np.ndarray, t: float, shift=(0.0, 0.0)):
    """The state rotated by t about the origin and translated: positions and gradients
    rotate, positions also shift. Returns (displacement, Q)."""
    m = model.mesh
    Q = np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])
    q = (m.reference + u).reshape(m.n_nodes, -1, 2) @ Q.T
    q[:, m.element.kinds.index("r")] += shift
    return q.reshape(-1) - m.reference, Q


def _nodal_values(spec: ElementSpec, poly, length: float) -> np.ndarray:
    return np.array([poly(xi * length, 0.0, *KINDS[k]) for xi in spec.nodes for k in spec.kinds])


def nodality(element, geometries=GEOMETRIES, seed: int = 0) -> dict:
    """Worst error of reproducing every basis function and its gradient at random
    points, relative to the size of the terms summed (round-off scale)."""
    spec, rng, worst = _spec(element), np.random.default_rng(seed), 0.0
    for length, height in geometries:
        xi, eta = rng.uniform(0, 1, 20), rng.uniform(-0.5, 0.5, 20)
        N, dN = spec.tabulate(xi, eta, length, height)
        x, y = xi * length, eta * height
        for p in spec.polys:
            q = _nodal_values(spec, p, length)
            for M, expected in ((N, p(x, y)), (dN[:, :, 0], p(x, y, 1, 0)), (dN[:, :, 1], p(x, y, 0, 1))):
                terms = (np.abs(M) @ np.abs(q)).max()
                err = np.abs(M @ q - expected).max()
                worst = max(worst, float(err / terms) if terms > 0 else float(err))
    return {"error": worst, "bound": 1e-11, "passes": worst <= 1e-11}


def reference_state(element) -> dict:
    """max |G - G_ref| at points of an element in its reference coordinates, G the point data
    of its kinematics (a continuum's F = I; a cable's (r_x, Y r_xx) = ((1, 0), 0)), and the
    positions against the identity map (a cable's r(x) = (x, 0) has no section field)."""
    spec = _spec(element)
    family = spec.family
    le, h = 0.01, 0.005
    q = np.concatenate([spec.reference_coordinates(x * le) for x in spec.nodes])
    xi = np.linspace(0, 1, 7)
    eta = np.full(7, 0.3)
    N, _ = spec.tabulate(xi, eta, le, h)
    G = np.einsum("ai,paj->pij", q, family.point_data(spec, xi, eta, le, h))
    y = eta * h if family.section_field else np.zeros(7)
    err = max(float(np.abs(G - family.reference_gradient).max()),
              float(np.abs(N @ q - np.c_[xi * le, y]).max() / h))
    return {"error": err, "bound": 1e-12, "passes": err <= 1e-12}


def _slopes(r) -> np.ndarray:
    return np.diff(np.log(r)) / np.diff(np.log(HS))


def energy_gradient(model: BeamModel, rng, directions: int = 3) -> dict:
    """Taylor test |U(u + h d) - U(u) - h f.d| ~ h^2: the smallest remainder slope."""
    u = bent_state(model, rng)
    f, U0 = model.internal_force(u), model.strain_energy(u)
    slopes = [_slopes([abs(model.strain_energy(u + h * d) - U0 - h * f @ d) for h in HS])
              for d in rng.standard_normal((directions, u.size))]
    s = float(np.min(slopes))
    return {"slope": s, "bound": SLOPE, "passes": s > SLOPE}


def tangent_gradient(model: BeamModel, rng) -> dict:
    """Taylor test |f(u + h d) - f(u) - h K d| ~ h^2, and the symmetry of K."""
    u = bent_state(model, rng)
    f, K = model.internal_force_and_tangent(u)
    Kd = K.to_sparse().toarray()
    asym = float(np.abs(Kd - Kd.T).max() / np.abs(Kd).max())
    d = rng.standard_normal(u.size)
    s = float(_slopes([np.abs(model.internal_force(u + h * d) - f - h * (Kd @ d)).max() for h in HS]).min())
    return {"slope": s, "asymmetry": asym, "bound": SLOPE, "passes": s > SLOPE and asym <= 1e-10}


def rigid_motion(model: BeamModel, rng) -> dict:
    """A bent state rotated by 0.7 rad and shifted: relative energy change and force
    rotation error; and the rigidly moved reference (zero energy when stress-free)."""
    u = bent_state(model, rng)
    U, f = model.strain_energy(u), model.internal_force(u)
    v, Q = rotate(model, u, 0.7, shift=(0.03, -0.2))
    energy = abs(model.strain_energy(v) - U) / abs(U)
    force = float(np.abs(model.internal_force(v) - (f.reshape(-1, 2) @ Q.T).reshape(-1)).max() / np.abs(f).max())
    w, Q = rotate(model, np.zeros_like(u), -1.1, shift=(0.5, 0.1))
    f0 = model.internal_force(np.zeros_like(u))
    scale = max(np.abs(f0).max(), np.abs(f).max())
    moved = float(np.abs(model.internal_force(w) - (f0.reshape(-1, 2) @ Q.T).reshape(-1)).max() / scale)
    ok = energy <= 1e-9 and force <= 1e-8 and moved <= 1e-9
    return {"energy": energy, "force": force, "reference_moved": moved, "passes": ok}


def _face_integrals(model: BeamModel) -> np.ndarray:
    """G[a, i, j] = integral over the boundary of N_a n_j (element faces x = 0, l_e of the
    end elements, and the faces y = +-h/2), by Gauss rules exact for the polynomials."""
    m, spec = model.mesh, model.mesh.element
    le, h, w = m.element_length, m.height, m.width
    G = np.zeros((m.n_dof // 2, 2))
    x, wx = np.polynomial.legendre.leggauss(8)
    xi, wxi = (x + 1) / 2, wx / 2
    for e, dofs in enumerate(m.element_dofs):
        shape_ids = dofs[:, 0] // 2
        for eta, sign in ((0.5, 1.0), (-0.5, -1.0)):             # top and bottom faces: n = (0, +-1)
            N, _ = spec.tabulate(xi, np.full(xi.size, eta), le, h)
            G[shape_ids, 1] += sign * (wxi @ N) * le * w
        for xe, sign, end in ((0.0, -1.0, e == 0), (1.0, 1.0, e == m.n_elements - 1)):
            if end:                                               # end faces: n = (-+1, 0)
                N, _ = spec.tabulate(np.full(xi.size, xe), xi - 0.5, le, h)
                G[shape_ids, 0] += sign * (wxi @ N) * h * w
    return G


def patch(element, law: str = "neo-hookean", formulation: str = "plane-stress", n: int = 3,
          length: float = 0.02) -> dict:
    """Constant stress: u from F0 = [[1.1, 0.04], [-0.03, 0.93]] on a free n-element beam.
    The assembled force must equal f_a = P(F0) . integral_boundary N_a n (divergence
    theorem over the beam's outer boundary), with P = dW/dF from the energy U(F) / V by
    central differences (error ~1e-9 of P). Returns the worst nodal error relative to
    max |f|: round-off for a conforming element; for a non-conforming one, the interior
    faces' jump terms, which do not cancel (Irons' patch test fails). A kinematics whose patch
    test is uniaxial (a cable) takes :func:`axial_patch`."""
    spec = _spec(element)
    if spec.family.patch_test == "uniaxial":
        return axial_patch(spec, law, n=n, length=length)
    mesh = Mesh(spec, n, length, 0.005, 0.007)
    model = BeamModel(mesh, paper_material(law, formulation), gauss(*_exact(spec)), np.array([], int))
    F0 = np.array([[1.1, 0.04], [-0.03, 0.93]])

    def state(F):
        q = mesh.reference.reshape(mesh.n_nodes, -1, 2)
        return (q @ F.T).reshape(-1) - mesh.reference       # positions and gradients map by F

    V = mesh.length * mesh.height * mesh.width
    P, d = np.zeros((2, 2)), 1e-6
    for i in range(2):
        for j in range(2):
            E = np.zeros((2, 2)); E[i, j] = d
            P[i, j] = (model.strain_energy(state(F0 + E)) - model.strain_energy(state(F0 - E))) / (2 * d * V)
    expected = (_face_integrals(model) @ P.T).reshape(-1)
    f = model.internal_force(state(F0))
    err = float(np.abs(f - expected).max() / np.abs(f).max())
    return {"error": err, "bound": 1e-6, "passes": err <= 1e-6}


def axial_patch(element, law: str = "neo-hookean", n: int = 3, length: float = 0.02, stretch: float = 1.3) -> dict:
    """A cable's patch test: the uniform stretch r = (lambda x, 0), r_x = (lambda, 0) on a free
    n-element cable; the assembled force must be the uniaxial nominal stress P(lambda) times
    h w at the two ends (-P h w at x = 0, +P h w at x = L, on r's x-components) and zero on
    every other dof (the divergence theorem of a constant stress), P = dW_u/dlambda from the
    model's own energy per volume by central differences (error ~1e-9 of P; the closed form
    of P(lambda) is the benchmarks' and tests/test_cable.py's). Returns the worst nodal
    error relative to P h w."""
    spec = _spec(element)
    mesh = Mesh(spec, n, length, 0.005, 0.007)
    model = model_for(mesh, paper_material(law, "plane-stress"), gauss(*_exact(spec)), np.array([], int))
    q = mesh.reference.reshape(mesh.n_nodes, -1, 2) * np.array([stretch, 1.0])
    u = q.reshape(-1) - mesh.reference
    V, d = mesh.length * mesh.height * mesh.width, 1e-6

    def energy(lam):
        return model.strain_energy((mesh.reference.reshape(mesh.n_nodes, -1, 2) * np.array([lam, 1.0])).reshape(-1)
                                   - mesh.reference)
    P = (energy(stretch + d) - energy(stretch - d)) / (2 * d * V)
    expected = np.zeros(mesh.n_dof)
    expected[mesh.dofs(0, ("r",))[0]] = -P * mesh.height * mesh.width
    expected[mesh.dofs(mesh.n_nodes - 1, ("r",))[0]] = P * mesh.height * mesh.width
    f = model.internal_force(u)
    err = float(np.abs(f - expected).max() / (P * mesh.height * mesh.width))
    return {"error": err, "bound": 1e-6, "passes": err <= 1e-6, "stretch": stretch,
            "nominal_stress": float(P)}


def _exact(spec: ElementSpec) -> tuple[int, int]:
    dx, dy = spec.degree()
    return dx + 1, dy + 1


def mass(element, n: int = 5) -> dict:
    """Relative errors of the translational mass and the gravity resultant; M SPD."""
    mesh = Mesh(_spec(element), n, 0.35, 0.005, 0.007)
    model = model_for(mesh, paper_material("yeoh", "plane-stress"), gauss(1, 1), np.array([], int))
    M = model.mass_matrix()
    ex = np.zeros(mesh.n_dof)
    for node in range(mesh.n_nodes):
        ex[mesh.dofs(node, ["r"])[0]] = 1.0
    ey = np.roll(ex, 1)
    exact = model.material.density * 0.35 * 0.005 * 0.007
    g = model.gravity_force((0.0, -9.81))
    Md = M.to_sparse().toarray()
    errs = {"mass": max(abs(ex @ M.matvec(ex) / exact - 1), abs(ey @ M.matvec(ey) / exact - 1),
                        abs(ex @ M.matvec(ey)) / exact),
            "gravity": max(abs(g @ ey / (-9.81 * exact) - 1), abs(g @ ex) / (9.81 * exact)),
            "asymmetry": float(np.abs(Md - Md.T).max() / np.abs(Md).max())}
    spd = bool(M.is_positive_definite())
    return {**errs, "positive_definite": spd, "bound": 1e-12,
            "passes": spd and max(errs.values()) <= 1e-12}


def conformity(element, angle: float = 0.5, n: int = 2) -> dict:
    """Jumps across the shared face of two elements under the bent state (no noise):
    max |r_left - r_right| / h and max |r_y,left - r_y,right| over the face (a cable:
    r_x, whose normal its section is, in r_y's place)."""
    spec = _spec(element)
    mesh = Mesh(spec, n, 0.02, 0.005, 0.007)
    model = model_for(mesh, paper_material("neo-hookean", "plane-stress"), gauss(2, 2), np.array([], int))
    q = mesh.reference + bent_state(model, None, angle, noise=0.0)
    eta = np.linspace(-0.5, 0.5, 11)
    le, h = mesh.element_length, mesh.height
    jr = jy = 0.0
    section = spec.family.section_slope        # the slope the section is made of (a cable's: r_x)
    for e in range(n - 1):
        left, right = mesh.element_dofs[e], mesh.element_dofs[e + 1]
        NL, dNL = spec.tabulate(np.ones(eta.size), eta, le, h)
        NR, dNR = spec.tabulate(np.zeros(eta.size), eta, le, h)
        qL, qR = q[left], q[right]
        jr = max(jr, float(np.abs(NL @ qL - NR @ qR).max() / h))
        jy = max(jy, float(np.abs(dNL[:, :, section] @ qL - dNR[:, :, section] @ qR).max()))
    return {"jump_r": jr, "jump_r_y": jy, "conforming": jr <= 1e-12 and jy <= 1e-12}


def strain_split(model: BeamModel, u: np.ndarray) -> dict:
    """Where a small-strain state of an incompressible beam keeps its energy, from the
    strains at the elastic rule's points (the linear regime: eps = sym(F) - I, energy
    2 mu eps:eps with eps_zz = -(eps_xx + eps_yy)):

    - ``shear_share``: the transverse shear energy mu gamma_xy^2 over the total (a
      slender beam's is about 1.2 (h/L)^2 by Timoshenko's theory; a share many times
      that is spurious shear: shear locking);
    - ``eyy_exx``: the section's contraction, sum w eps_yy eps_xx / sum w eps_xx^2 (the
      exact bending state of an incompressible plane-stress beam has eps_yy = eps_zz =
      -eps_xx / 2, so -1/2; 0: the height cannot contract, Poisson locking in the plane,
      E / (1 - nu^2); -1: eps_zz is held at 0, the beam is as stiff as in plane strain;
      both are 4/3 too stiff at nu = 1/2, -25 % in deflection)."""
    F = model.gradients(u)
    eps = 0.5 * (F + np.swapaxes(F, -1, -2)) - np.eye(2)
    exx, eyy, gxy = eps[..., 0, 0], eps[..., 1, 1], 2.0 * eps[..., 0, 1]
    w = model._w
    normal = 2.0 * (exx ** 2 + eyy ** 2 + (exx + eyy) ** 2)
    shear = gxy ** 2
    return {"shear_share": float(np.sum(shear * w) / np.sum((normal + shear) * w)),
            "eyy_exx": float(np.sum(eyy * exx * w) / np.sum(exx * exx * w))}
