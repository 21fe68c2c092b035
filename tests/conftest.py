import numpy as np
import pytest

from ancf.checks import paper_material
from ancf.elements import ELEMENTS
from ancf.formulations import FORMULATIONS
from ancf.laws import LAWS


material = paper_material   # the paper's constants of a law in a formulation


@pytest.fixture
def rng():
    return np.random.default_rng(20211206)


ALL_ELEMENTS = sorted(ELEMENTS)
ALL_LAWS = sorted(LAWS)
ALL_FORMULATIONS = sorted(FORMULATIONS)
