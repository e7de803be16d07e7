"""Validation 7: the paper's numbers for its base shell (R = h = 20 mm, t = 3 mm,
C10 = 0.3 MPa, gamma = 30 J/m^2), default mesh, no-slip interface (the paper's).

The paper's a*, delta*, a_dagger, P_dagger are values at its own mesh nodes on a curve that
is flat at its extrema, so those points are checked against our equilibrium curve at the
same a (DESIGN.md section 4); P* and delta_dagger compare directly.
"""
import numpy as np
import pytest
from scipy.interpolate import CubicHermiteSpline, CubicSpline

from shell_adhesion.solver.case import relaxation_starts, solve_loading
from shell_adhesion.solver.path import relax

from conftest import C10_MPA, GAMMA_HAT, R_MM, base_case

# the base shell on the default mesh takes about 2 minutes: `python -m pytest -m slow` runs it
pytestmark = pytest.mark.slow

F = C10_MPA * R_MM ** 2      # force unit, N


def loading_P(states, delta):
    """P at delta on the loading curve (one-sided slopes at contact events)."""
    d = np.array([s.delta for s in states])
    i = np.searchsorted(d, delta) - 1
    s0, s1 = states[i], states[i + 1]
    return float(CubicHermiteSpline([s0.delta, s1.delta], [s0.P, s1.P],
                                    [s0.dP_ddelta, s1.dP_ddelta_left])(delta))


@pytest.fixture(scope="module")
def base():
    return base_case("default", "no_slip", 0.006, 0.25)


@pytest.fixture(scope="module")
def pull(base):
    ps, _, _ = base
    return ps.pull_off(GAMMA_HAT)


def test_fig2a_load_and_radius(base):
    _, _, loading = base
    P5 = loading_P(loading.states, 0.25) * F
    assert P5 == pytest.approx(14.67, rel=0.05)
    a5 = [s.a for s in loading.states if s.delta <= 0.25][-1] * R_MM
    assert a5 == pytest.approx(10.0, rel=0.05)


def test_fig2a_frictionless_loads_less(base):
    _, _, loading = base
    _, fric = solve_loading(0.15, 1.0, "frictionless", "default", 0.25)
    ratio = fric.states[-1].P / loading_P(loading.states, 0.25)
    assert 0.8 < ratio < 0.95          # DESIGN.md: frictionless loading gives about 10 % less


def test_fig2b_held_contact_pulled_to_delta_zero(base):
    """a = 10 mm held, delta = 0: the paper's P = -35.49 N (steep in a: compare at 10 mm)."""
    ps, d, loading = base
    starts = relaxation_starts(loading, d.capmesh)
    a = np.array([s.a for s in starts])
    k = int(np.searchsorted(a, 10.0 / R_MM))
    P0 = []
    for s in starts[k - 1:k + 1]:
        path = relax(d, "no_slip", s, lambda st: st.delta <= 0, 0.02)
        dd, PP, kk = path.array("delta"), path.array("P"), path.array("dP_ddelta")
        o = np.argsort(dd)
        P0.append(float(CubicHermiteSpline(dd[o], PP[o], kk[o])(0.0)) * F)
    P10 = np.interp(10.0 / R_MM, a[k - 1:k + 1], P0)
    assert P0[1] < P10 < P0[0] < 0
    assert P10 == pytest.approx(-35.49, rel=0.10)


def test_fig5_pull_off_direct(pull):
    _, po = pull
    assert po.P_star * F == pytest.approx(-1.70, rel=0.03)
    assert po.delta_dagger * R_MM == pytest.approx(-0.685, rel=0.03)


@pytest.mark.parametrize("a_mm,delta_mm,P_N", [(2.13, -0.563, -1.70), (1.598, -0.685, -1.640)])
def test_fig5_points_lie_on_our_curve(pull, a_mm, delta_mm, P_N):
    eq, _ = pull
    a = a_mm / R_MM
    assert abs(CubicSpline(eq.a, eq.delta)(a) * R_MM - delta_mm) < 0.02
    assert CubicSpline(eq.a, eq.P)(a) * F == pytest.approx(P_N, rel=0.02)


def test_fig5_order_of_pull_off_points(pull):
    """Fixed grips holds beyond the fixed-load point: smaller a, more negative delta."""
    eq, po = pull
    assert po.a_dagger < po.a_star < po.a0
    assert po.delta_dagger < po.delta_star and po.P_star < po.P_dagger < 0
    i = np.argmin(np.abs(eq.a - po.a_star))
    assert not eq.stable_fixed_load[max(0, i - 3)] and eq.stable_fixed_load[i + 3]
