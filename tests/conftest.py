import numpy as np
import pytest

from ancf.build import build_material
from ancf.elements import ELEMENTS
from ancf.formulations import FORMULATIONS
from ancf.laws import LAWS
from contract.scene import MaterialSpec
from contract import paper


def material(law: str, formulation: str, penalty: float = paper.PENALTY):
    c = dict(paper.materials()[law])
    rho = c.pop("density")
    return build_material(MaterialSpec(law, formulation, rho, c,
                                       penalty if FORMULATIONS[formulation].penalised else None))


@pytest.fixture
def rng():
    return np.random.default_rng(20211206)


ALL_ELEMENTS = sorted(ELEMENTS)
ALL_LAWS = sorted(LAWS)
ALL_FORMULATIONS = sorted(FORMULATIONS)
