"""The examples run, and the base-case example lands near the paper's P* = -1.70 N."""
import importlib.util
import pathlib

import pytest

from shell_adhesion.solver.scaling import force_N

EXAMPLES = pathlib.Path(__file__).parent.parent / "examples"


def test_ex01_base_case():
    spec = importlib.util.spec_from_file_location("ex01", EXAMPLES / "ex01_base_case.py")
    ex = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ex)
    po = ex.pull_off("coarse")
    assert -1.9 < force_N(po.P_star, 0.3, 20.0) < -1.5


def test_ex02_hertz_table():
    spec = importlib.util.spec_from_file_location("ex02", EXAMPLES / "ex02_hertz_table.py")
    ex = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ex)
    rows = ex.table("coarse")
    resolved = rows[rows[:, 0] > 0.03]
    assert len(resolved) >= 2 and abs(resolved[:, 2] - 1).max() < 0.05


@pytest.mark.slow      # CI time: see README (python -m pytest -m slow)
def test_ex03_mooney_rivlin():
    """C01/C10 = 0.5 stiffens the shell (mu0 x 1.5): a more tensile P* and a smaller
    |delta_dagger| than neo-Hookean (C01 = 0), on the coarse mesh."""
    spec = importlib.util.spec_from_file_location("ex03", EXAMPLES / "ex03_mooney_rivlin.py")
    ex = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ex)
    rows = ex.sweep((0.0, 0.5), mesh="coarse", delta_max_over_R=0.15)
    (q0, P0, _, dd0, _, eta0), (q1, P1, _, dd1, _, eta1) = rows
    assert -1.9 < P0 < -1.5 and P1 < P0 < 0
    assert dd0 < dd1 < 0
    assert eta1 > eta0
