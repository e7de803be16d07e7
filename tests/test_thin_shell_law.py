"""A thin shell follows the thin-shell point-load law at delta << t (issue 10): for an
incompressible shell (nu = 1/2, E = 6 C10) Reissner's stiffness 4 E t^2 / (R sqrt(3 (1 -
nu^2))) is P / delta = 16 C10 t^2 / R;
dimensionless, P/(C10 R^2) = 16 (t/R)^2 delta/R.  Measured ratio 0.87 to 0.90 from delta = 0.02 t to 0.1 t (coarse and default
meshes alike)."""
import numpy as np
import pytest

from shell_adhesion.solver.case import solve_loading

T = 0.025


@pytest.mark.parametrize("fraction", [0.02, 0.05, 0.1])
def test_thin_frictionless_shell_stiffness(fraction):
    _, loading = solve_loading(T, 1.0, "frictionless", "coarse", 0.1 * T)
    delta = fraction * T
    P = np.interp(delta, loading.array("delta"), loading.array("P"))
    assert P / delta == pytest.approx(16 * T ** 2, rel=0.15)
