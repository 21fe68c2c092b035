"""What a scene may ask of ANCF: the scene check (:func:`check`) and the one rule of which
integrators an element refuses (:func:`refused_integrators`).

A check decides whether a run happens, never what it computes: it raises a SceneError
naming the field and the allowed values, or returns the scene it was given, untouched
(``tests/test_admission.py``). So no record depends on this module
(:data:`studies.engine.fingerprint.NOT_RESULTS`): a case is checked again whenever it is
made, and a case that a changed check refuses fails there, by name, before any record of
it could be reused.
"""
from __future__ import annotations

from functools import lru_cache

from contract.errors import SceneError
from contract.scene import Scene, check_names
from mechanics.laws import LAWS

from .core.spec import ElementSpec
from .core.formulations import FORMULATIONS
from .elements import ELEMENTS
from .solvers.integrators import INTEGRATORS


def refused_integrators(element: ElementSpec) -> dict[str, str]:
    """{integrator: why the element cannot run it}: its kinematics' rule
    (:meth:`ancf.kinematics.family.Kinematics.refused_integrators`), the one place it is
    written (the scene check, the models, the warm-up, ``ancf elements`` and the studies
    ask it here)."""
    return element.family.refused_integrators(element)


def allowed_integrators(element: ElementSpec) -> list[str]:
    """The registered integrators the element takes, sorted."""
    refused = refused_integrators(element)
    return sorted(i for i in INTEGRATORS if i not in refused)


def check(scene: Scene) -> Scene:
    """The scene's names against ancf's registries (one message naming the field and
    the allowed values); an ANCF run needs the [ancf] table."""
    if scene.ancf is None:
        raise SceneError("ancf: the scene has no [ancf] table (element, elements)")
    check_names(scene, laws=LAWS, formulations=FORMULATIONS, integrators=INTEGRATORS, elements=ELEMENTS)
    el = ELEMENTS[scene.ancf.element]                  # the names are known now
    _check_kinematics(scene, el)
    _check_pressure_rule(scene, el, FORMULATIONS[scene.material.formulation].penalised)
    _check_aspect(scene, el)
    return scene


def _check_aspect(scene: Scene, el: ElementSpec) -> None:
    """The element's basis must be determined by its nodal coordinates at this mesh's l_e and
    h (and at l_e / h, the rank tests' scaling): an element absurdly stout (l_e / h = 1e-7
    for HB2n-12 and HB3n-12) makes the nodal matrix singular in floating point."""
    le, h = scene.beam.length / scene.ancf.elements, scene.beam.height
    if _singular(el, le, h):
        raise SceneError(f"beam.height: an element of l_e / h = {le / h:.3g} (beam.length / ancf.elements / "
                         f"beam.height) is singular for {el.name}: its nodal coordinates do not determine its "
                         "basis in floating point (fewer elements or a more slender beam)") from None


@lru_cache(maxsize=4096)
def _singular(el: ElementSpec, le: float, h: float) -> bool:
    """Whether the element's nodal matrix is singular at l_e x h or at l_e / h x 1 (a study
    checks thousands of scenes of a few meshes: each answered once)."""
    try:
        el.dimensionless(le, h)
        el.dimensionless(le / h, 1.0)
    except ValueError:
        return True
    return False


def _check_kinematics(scene: Scene, el: ElementSpec) -> None:
    """What an element's kinematics cannot run: the formulations it refuses
    (:attr:`ancf.kinematics.family.Kinematics.formulations`: a cable integrates the law's
    uniaxial energy, with free lateral faces, so plane stress alone); the integrators it
    refuses (:func:`refused_integrators`)."""
    family = el.family
    if not family.runs(scene.material.formulation):
        raise SceneError(f"material.formulation: {scene.material.formulation!r} cannot run element {el.name} "
                         f"({el.kinematics}: {family.formulations_why}); "
                         f"allowed for it: {', '.join(repr(f) for f in family.formulations)}")
    a = scene.analysis
    if a.kind == "dynamic" and a.newton == "linear" and INTEGRATORS[a.integrator].compiled != "alpha-family":
        family = sorted(i for i, c in INTEGRATORS.items() if c.compiled == "alpha-family")
        raise SceneError(f"analysis.newton: 'linear' (one solve per step) is a step of the generalized-alpha "
                         f"family; integrator {a.integrator!r} runs full Newton: choose analysis.integrator from "
                         f"{', '.join(repr(i) for i in family)}, or another analysis.newton")
    refused = refused_integrators(el)
    if a.kind == "dynamic" and a.integrator in refused:
        raise SceneError(f"analysis.integrator: {a.integrator!r} cannot run element {el.name} "
                         f"({refused[a.integrator]}); allowed for it: "
                         f"{', '.join(repr(i) for i in allowed_integrators(el))}")


def _check_pressure_rule(scene: Scene, el: ElementSpec, penalised: bool) -> None:
    """A rule the scene chose must resolve the element's pressure field where it carries
    the penalty (a tensor rule with more points than the field's degree in x and in y)."""
    s = scene.ancf
    if not (el.pressure and s.quadrature is not None and penalised):
        return
    dx = max(p.degree()[0] for p in el.pressure_polys)
    dy = max(p.degree()[1] for p in el.pressure_polys)
    if s.quadrature[0] <= dx or s.quadrature[1] <= dy:
        raise SceneError(f"ancf.quadrature: {list(s.quadrature)} does not resolve the pressure field of "
                         f"{el.name} (degree {dx} in x, {dy} in y): at least [{dx + 1}, {dy + 1}] points; "
                         "or leave quadrature out for the element's default")


