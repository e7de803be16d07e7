"""The examples run, and the base-case example lands near the paper's P* = -1.70 N."""
import importlib.util
import pathlib

import numpy as np
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


def test_ex03_writes_where_it_is_told(tmp_path):
    """The figure goes to --out (default: the working folder), never over the tracked
    docs/figures/mooney_rivlin.png."""
    spec = importlib.util.spec_from_file_location("ex03", EXAMPLES / "ex03_mooney_rivlin.py")
    ex = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ex)
    assert ex.arguments([]).out == pathlib.Path(".")
    assert ex.arguments(["--out", str(tmp_path)]).out == tmp_path
    tracked = EXAMPLES.parent / "docs" / "figures" / ex.FIGURE
    before = tracked.read_bytes() if tracked.exists() else None
    rows = np.array([[0.0, -1.7, -0.56, -0.68, -1.64, 8.0], [0.5, -2.0, -0.5, -0.6, -1.9, 8.5]])
    ex.figure(rows, tmp_path / "sub" / ex.FIGURE)
    assert (tmp_path / "sub" / ex.FIGURE).stat().st_size > 0
    assert (tracked.read_bytes() if tracked.exists() else None) == before
