"""Grid helpers shared by the ANCF studies: element counts and one cantilever case."""
from __future__ import annotations

from .case import Case, make_case
from contract.paper import cantilever_scene, element_count


def count_for(grid: dict, element: str) -> int:
    """The element count of ``element`` for grids with ``counts = "paper"`` (the paper's
    Table 3 counts, :func:`contract.paper.element_count`) or a table {element: count}."""
    counts = grid["counts"]
    if counts == "paper":
        return element_count(element)
    if isinstance(counts, dict):
        return int(counts[element])
    raise ValueError(f"counts: expected \"paper\" or a table {{element = count}}, got {counts!r}")


def cantilever_case(study: str, law: str, formulation: str, element: str, elements: int,
                    quadrature, clamp: str, options: dict | None = None) -> Case:
    q = tuple(int(v) for v in quadrature)
    name = f"cantilever-{law}-{formulation}-{element}-{elements}-q{q[0]}{q[1]}-{clamp}"
    return make_case(study, "ancf", cantilever_scene(law, formulation, element, int(elements),
                                                     quadrature=q, clamp=clamp, name=name), options)
