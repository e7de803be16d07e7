"""The meshes fit the edges of the supported domain (issue 10, item 4): on the shallowest
cap (h/R = 0.2) and the thinnest shell (t/R = 0.02) the coarse and default meshes give
the same loading curve within 5 %, up to where the loading goes."""
import numpy as np
import pytest

from shell_adhesion.solver.case import solve_loading

DELTAS = (0.01, 0.02, 0.03)


def _P(t, h, mesh, delta_max):
    _, path = solve_loading(t, h, "no_slip", mesh, delta_max, stop_at_limit=True)
    assert path.delta_reached >= DELTAS[-1] - 1e-12, path.stopped_by
    return np.interp(DELTAS, path.array("delta"), path.array("P"))


@pytest.mark.parametrize("t, h", [(0.15, 0.2), (0.02, 1.0), (0.02, 0.2)],
                         ids=["shallow", "thin", "thin-shallow"])
def test_coarse_and_default_agree_within_5_percent(t, h):
    """Measured (coarse / default - 1 at delta = 0.01, 0.02, 0.03 R): shallow 1.7, 2.3,
    2.9 %; thin 0.27, 0.19, 0.21 %; thin and shallow 0.21, 0.14, 0.17 %.  (The shallow
    cap's default mesh differs from the fine one by 1.7, 2.6, 3.7 %: the error bar, three
    times the coarse-default difference, holds it; its loading stops near delta = 0.047 R
    at the pointwise J bound, at the rim's inner corner, on every mesh.)"""
    coarse, default = _P(t, h, "coarse", 0.03), _P(t, h, "default", 0.03)
    assert np.all(np.abs(coarse / default - 1) < 0.05)
