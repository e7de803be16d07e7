"""A pull-off the paths cannot vouch for is refused with its reason, never returned
(issue 10, items 2 and 4): a curve still falling at its end, a pull-off radius in the
graded part of the mesh, a curve bridged near the pull-off because G fell short."""
import numpy as np
import pytest

from conftest import GAMMA_HAT
from shell_adhesion.solver.case import PathSet, solve_paths
from shell_adhesion.energy import Equilibrium, OutOfRange, pull_off
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import mesh_spec, uniform_arc, uniform_radius


def _curve(a, P, delta):
    a, P, delta = map(np.asarray, (a, P, delta))
    return Equilibrium(GAMMA_HAT, a, delta, P, np.gradient(P, a) > 0, np.gradient(delta, a) > 0)


def test_a_dip_inside_a_curve_still_falling_at_its_end_is_not_the_pull_off():
    """P falls toward the largest a reached, with a shallow dip inside: the dip is an
    interior minimum, but the curve's end lies lower, so the pull-off is beyond reach."""
    a = np.linspace(0.02, 0.2, 19)
    delta = (a - 0.08) ** 2 - 0.01                       # fixed grips: a clean minimum
    P = -a + 0.04 * np.exp(-((a - 0.12) / 0.02) ** 2)     # falling; a bump makes a dip
    with pytest.raises(OutOfRange, match="still falling at its end a = 0.2 R"):
        pull_off(_curve(a, P, delta))
    # the same curve turning up before its end has a pull-off
    P_ok = (a - 0.15) ** 2 - 0.1
    po = pull_off(_curve(a, P_ok, delta))
    assert po.a_star == pytest.approx(0.15, abs=1e-6) and po.a_dagger == pytest.approx(0.08, abs=1e-6)


def test_pull_off_in_the_graded_zone_is_refused():
    """The base shell at gamma/(C10 R) = 0.015 (C10 = 0.1 MPa, 30 J/m^2, R = 20 mm) pulls
    off at a* ~ 0.22 R, beyond the evenly meshed 0.134 R: refused with the reason."""
    gamma = 0.015
    ps, _, _ = solve_paths(0.15, 1.0, "no_slip", "coarse", 0.1, 1.25 * gamma)
    with pytest.raises(OutOfRange, match=r"pull-off radius a\* = 0\.2\d* R lies beyond 0\.134 R"):
        ps.pull_off(gamma)
    assert 0.9 * uniform_radius(Cap(0.15, 1.0), mesh_spec("coarse")) == pytest.approx(
        0.9 * np.sin(0.15))


def test_thin_shells_get_a_wider_even_zone():
    """t/R = 0.1 at gamma/(C10 R) = 0.005 pulls off at a* ~ 0.23 R: the request's even zone
    (solver.request.even_arc from the estimate of a*) holds it, so the pull-off is given;
    a base shell asked only small gammas keeps the family's 0.15 R of arc."""
    from shell_adhesion.solver.request import Request, initial_fit, solve_request
    ps, _, _ = solve_request(0.1, 1.0, Request.serving(GAMMA_HAT), GAMMA_HAT, mesh="coarse")
    _, po = ps.pull_off(GAMMA_HAT)
    assert 0.2 < po.a_star < 0.9 * ps.uniform_radius
    assert ps.uniform == initial_fit(Cap(0.1, 1.0), Request.serving(GAMMA_HAT)).uniform > 0.3
    assert initial_fit(Cap(0.15, 1.0), Request.serving(0.001)).uniform == 0.15
    assert uniform_arc(Cap(0.15, 1.0), mesh_spec("fine")) == 0.15


def test_base_shell_pull_off_is_within_the_even_mesh(base_coarse):
    ps, _, _ = base_coarse
    _, po = ps.pull_off(GAMMA_HAT)
    assert max(po.a_star, po.a_dagger) < 0.9 * uniform_radius(Cap(0.15, 1.0), mesh_spec("coarse"))


def test_a_curve_bridged_near_the_pull_off_is_refused(base_coarse, monkeypatch):
    """Where a pair of paths near a* stopped before G reached gamma, the equilibrium curve
    has no point there: the pull-off is refused, with the G the pair reached."""
    ps, _, _ = base_coarse
    eq, po = ps.pull_off(GAMMA_HAT)
    k = int(np.argmin(np.abs(eq.a - po.a_star)))
    a_pair, G = ps.G_reached()
    short = eq.a[k]                                  # the pair nearest a*
    assert short in a_pair
    G_short = np.where(a_pair == short, 0.5 * GAMMA_HAT, G)
    monkeypatch.setattr(PathSet, "G_reached", lambda self: (a_pair, G_short))
    with pytest.raises(OutOfRange, match="reached only G/\\(C10 R\\) = 0.0025"):
        ps.pull_off(GAMMA_HAT)
