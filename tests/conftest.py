import numpy as np
import pytest

from ancf.checks import law_constants, paper_material
from contract import paper
from ancf.elements import ELEMENTS
from ancf.formulations import FORMULATIONS
from mechanics.laws import LAWS


material = paper_material   # the paper's constants of a law in a formulation
PAPER_LAWS = sorted(paper.materials())   # the laws the paper's tables have


def law_scene(law: str, formulation: str, *args, penalty: float = paper.PENALTY, **kw) -> dict:
    """The paper's cantilever scene in any registered law: the paper's constants for its
    three laws, the law's example constants (and the neo-Hookean density) otherwise."""
    s = paper.cantilever_scene("neo-hookean", formulation, *args, penalty=penalty, **kw)
    s["material"] = {"law": law, "formulation": formulation, **law_constants(law),
                     **({"penalty": penalty} if "penalty" in s["material"] else {})}
    s["name"] = s["name"].replace("neo-hookean", law)
    return s


@pytest.fixture
def rng():
    return np.random.default_rng(20211206)


ALL_ELEMENTS = sorted(ELEMENTS)


def contract_rule(element: str):
    """The rule contract tests run an element with: [3, 2] (cheap, the paper's), or the
    element's default where [3, 2] cannot resolve its pressure field or misses modes
    (HB2n-40p)."""
    return None if ELEMENTS[element].pressure else (3, 2)
ALL_LAWS = sorted(LAWS)
ALL_FORMULATIONS = sorted(FORMULATIONS)
