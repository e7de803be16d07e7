"""Validation 3: the JKR limit.  Solid hemisphere t = h = R = 20 mm, C10 = 0.3 MPa,
gamma = 1 J/m^2 (gamma / (C10 R) = 1.7e-4, so a*/R = 0.04: small strain)."""
import pytest

from shell_adhesion.solver import solve_paths, theory
from shell_adhesion.solver.scaling import force_N, gamma_hat, length_mm

from conftest import _pool

# the solid hemisphere on the default mesh takes about 2 minutes: `python -m pytest -m slow` runs it
pytestmark = pytest.mark.slow

R_MM, C10, GAMMA = 20.0, 0.3, 1.0


@pytest.fixture(scope="module")
def jkr():
    g = gamma_hat(GAMMA, C10, R_MM)
    ps, _, _ = solve_paths(1.0, 1.0, "no_slip", "default", delta_max=0.011, gamma_max=1.25 * g,
                           map=_pool().map)
    _, po = ps.pull_off(g)
    return po


def test_fixed_load_pull_off(jkr):
    assert force_N(jkr.P_star, C10, R_MM) == pytest.approx(theory.jkr_P_star_N(R_MM, GAMMA), rel=0.03)
    assert length_mm(jkr.a_star, R_MM) == pytest.approx(theory.jkr_a_star_mm(R_MM, C10, GAMMA), rel=0.05)


def test_fixed_grips_pull_off(jkr):
    assert force_N(jkr.P_dagger, C10, R_MM) == pytest.approx(theory.jkr_P_dagger_N(R_MM, GAMMA), rel=0.05)
    assert jkr.a_dagger < jkr.a_star and jkr.delta_dagger < jkr.delta_star


def test_zero_load_radius(jkr):
    assert length_mm(jkr.a0, R_MM) == pytest.approx(theory.jkr_a0_mm(R_MM, C10, GAMMA), rel=0.05)
