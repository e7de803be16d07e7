"""A thin shell follows the thin-shell point-load law at delta << t (issue 10): for an
incompressible shell (nu = 1/2, E = 6 C10) Reissner's stiffness 4 E t^2 / (R sqrt(3 (1 -
nu^2))) is P / delta = 16 C10 t^2 / R;
dimensionless, P/(C10 R^2) = 16 (t/R)^2 delta/R.  README: the ratio is 0.874, 0.895 and
0.903 at delta = 0.02, 0.05 and 0.1 t (coarse mesh), each held to 0.005."""
import numpy as np
import pytest

from shell_adhesion.solver.case import solve_loading

T = 0.025


@pytest.mark.parametrize("fraction,ratio", [(0.02, 0.874), (0.05, 0.895), (0.1, 0.903)])
def test_thin_frictionless_shell_stiffness(fraction, ratio):
    _, loading = solve_loading(T, 1.0, "frictionless", "coarse", 0.1 * T)
    delta = fraction * T
    P = np.interp(delta, loading.array("delta"), loading.array("P"))
    assert P / delta / (16 * T ** 2) == pytest.approx(ratio, abs=0.005)
