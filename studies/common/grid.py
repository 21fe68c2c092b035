"""Grid helpers shared by the ANCF studies: element counts and one cantilever case."""
from __future__ import annotations

from contract.paper import cantilever_scene, element_count

from ..engine.case import Case, make_case


def fem_table(backend: str, **keys) -> dict:
    """A scene's [fem] table for ``backend``: ``keys`` and the backend's name, left out for
    the default backend (:data:`reference_fem.backends.DEFAULT`), as the scenes have it."""
    from reference_fem.backends import DEFAULT as DEFAULT_BACKEND

    return dict(keys) | ({} if backend == DEFAULT_BACKEND else {"backend": backend})


def count_for(grid: dict, element: str) -> int:
    """The element count of ``element`` for grids with ``counts = "paper"`` (the paper's
    Table 3 counts, :func:`contract.paper.element_count`) or a table {element: count}."""
    counts = grid["counts"]
    if counts == "paper":
        return element_count(element)
    if isinstance(counts, dict):
        return int(counts[element])
    raise ValueError(f"counts: expected \"paper\" or a table {{element = count}}, got {counts!r}")


# A grid's quadrature entry: [n_x, n_y], or this word for the element's own rule at the
# mesh's l_e / h (ElementSpec.quadrature; the scene then leaves `quadrature` out).
DEFAULT = "default"


def rule(quadrature) -> tuple[int, int] | str:
    """A grid's quadrature entry as a hashable value: (n_x, n_y) or :data:`DEFAULT`."""
    return DEFAULT if quadrature == DEFAULT else tuple(int(v) for v in quadrature)


def qlabel(quadrature) -> str:
    """"q32" for (3, 2), "qdef" for the element default: names, figure and gold keys."""
    q = rule(quadrature)
    return "qdef" if q == DEFAULT else f"q{q[0]}{q[1]}"


def takes(grid: dict, element: str, quadrature) -> bool:
    """Whether ``element`` runs with ``quadrature`` in this grid: the rules the grid's
    ``per_element.<element>.quadratures`` lists, else every rule, except that an element
    with a pressure field takes its own rule only (a fixed rule of the paper's, [2, 2],
    cannot resolve the field: :mod:`ancf.kinematics.section.pressure`)."""
    from ancf.elements import get_element

    allowed = grid.get("per_element", {}).get(element, {}).get("quadratures")
    if allowed is None:
        return rule(quadrature) == DEFAULT or not get_element(element).pressure
    return rule(quadrature) in {rule(a) for a in allowed}


def counts_of(grid: dict, element: str) -> list[int]:
    """The mesh counts of ``element``: ``per_element.<element>.counts``, else the grid's."""
    return grid.get("per_element", {}).get(element, {}).get("counts", grid["counts"])


def cantilever_case(study: str, law: str, formulation: str, element: str, elements: int,
                    quadrature, clamp: str, options: dict | None = None) -> Case:
    q = rule(quadrature)
    name = f"cantilever-{law}-{formulation}-{element}-{elements}-{qlabel(q)}-{clamp}"
    return make_case(study, "ancf", cantilever_scene(law, formulation, element, int(elements),
                                                     quadrature=None if q == DEFAULT else q,
                                                     clamp=clamp, name=name), options)
