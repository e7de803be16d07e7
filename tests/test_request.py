"""The paths fitted to the request (issue 21): the even zone, the loading depth and the
relaxation's reach follow from the gammas asked; the rim corner; paths that invert.

Coarse meshes, the real solver.  The "forced" tests make the first guess wrong on purpose
(monkeypatching the estimate or the margins) to prove that the fallback fires and answers.
"""
from dataclasses import replace

import numpy as np
import pytest

from shell_adhesion.solver import request as rq
from shell_adhesion.solver.case import UNIFORM_SHARE, solve_paths
from shell_adhesion.solver.geometry import Cap, delta_bound, domain_delta_max
from shell_adhesion.solver.mesh import mesh_spec, uniform_radius
from shell_adhesion.solver.quality import J_RANGE, rim_corner_elements

from conftest import _pool


def solve(t, h, gammas, mesh="coarse", delta_max=None):
    return rq.solve_request(t, h, rq.Request(tuple(gammas), delta_max), 1.25 * max(gammas),
                            mesh=mesh, map=_pool().map)


@pytest.fixture(scope="module")
def paper_c10():
    """The base shell at the paper study's C10 = 0.1 MPa, gamma = 30 J/m^2 (0.015), which the
    default even zone (0.15 of arc) refused: a* = 0.22 R."""
    return solve(0.15, 1.0, [0.005, 0.015])


def test_even_zone_holds_the_pull_off(paper_c10):
    ps, d, _ = paper_c10
    got = rq.answers(ps, [0.005, 0.015])
    for g, r in got.items():
        assert not isinstance(r, Exception), r
        eq, po = r
        assert max(po.a_star, po.a_dagger) <= UNIFORM_SHARE * ps.uniform_radius
    _, po = got[0.015]
    assert po.a_star > UNIFORM_SHARE * uniform_radius(Cap(0.15, 1.0), mesh_spec("coarse"))
    assert ps.uniform == pytest.approx(rq.even_arc(Cap(0.15, 1.0),
                                                   rq.a_star_estimate(Cap(0.15, 1.0), 0.015)))
    assert ps.stats["fit"]["remeshed"] == 0


def test_loading_depth_from_the_request(paper_c10):
    """No delta_max: the loading ends at the contact radius the pull-offs need (a_stop),
    well short of the domain's bound, and the curve has turned with its margin."""
    ps, _, loading = paper_c10
    fit = ps.stats["fit"]
    assert loading.reached_a and fit["a_stop"] is not None
    assert loading.states[-1].a >= fit["a_stop"] > loading.states[-2].a
    assert ps.stats["delta_reached"] < delta_bound(Cap(0.15, 1.0))
    _, po = rq.answers(ps, [0.015])[0.015]
    assert loading.states[-1].a >= rq.TURN * po.a_star * 0.999


def test_no_default_exceeds_the_cap_depth():
    for t, h in ((0.15, 0.2), (0.02, 0.2), (1.0, 0.2), (0.05, 1.0), (0.15, 1.0)):
        cap = Cap(t, h)
        assert delta_bound(cap) < cap.h
        assert delta_bound(cap) <= domain_delta_max(t)
    assert domain_delta_max(0.05) == 0.9 and domain_delta_max(0.15) == 0.25
    assert delta_bound(Cap(0.05, 1.0)) == pytest.approx(0.9) and delta_bound(Cap(0.05, 0.5)) \
        == pytest.approx(0.45)


def test_a_wrong_estimate_remeshes(monkeypatch):
    """An estimate of a* far too small (a third): the first solve's loading and even zone
    fall short of the pull-off; the zone grows with the loading (a new mesh, at most
    MAX_REMESH times) until the pull-off is given inside it."""
    monkeypatch.setattr(rq, "A_STAR_MARGIN", 0.3)
    ps, _, _ = solve(0.15, 1.0, [0.015])
    assert 1 <= ps.stats["fit"]["remeshed"] <= rq.MAX_REMESH
    eq, po = ps.pull_off(0.015)
    assert po.a_star <= UNIFORM_SHARE * ps.uniform_radius


def test_a_short_loading_goes_deeper(monkeypatch):
    """A loading target short of a* (0.1 R against 0.22 R) in an even zone that holds it:
    the curve has not turned at its end, so the loading goes on (DEEPER x its end) on the
    same mesh; its first states are those of the shorter loading, state for state."""
    first = rq.initial_fit(Cap(0.15, 1.0), rq.Request((0.015,)))
    short_fit = replace(first, a_stop=0.1)
    monkeypatch.setattr(rq, "initial_fit", lambda cap, request: short_fit)
    short, _, _ = solve_paths(0.15, 1.0, "no_slip", "coarse", first.delta_max, 0.02,
                              uniform=first.uniform, a_stop=0.1, relax_paths=False)
    ps, _, _ = solve(0.15, 1.0, [0.015])
    fit = ps.stats["fit"]
    assert fit["solves"] >= 2 and fit["remeshed"] == 0 and fit["a_stop"] > 0.1
    n = len(short.loading_delta)
    for k in ("delta", "P", "a", "U"):
        np.testing.assert_array_equal(getattr(ps, f"loading_{k}")[:n],
                                      getattr(short, f"loading_{k}"))
    eq, po = ps.pull_off(0.015)
    assert eq.a[-1] >= rq.TURN * po.a_star * 0.999 or not ps.stats["loading_reached_a"]


def test_short_pairs_are_relaxed_further(monkeypatch):
    """Relaxations stopped early (G_SAFETY 1 instead of 3): the small pairs, where the
    flat-punch estimate of G runs ahead of G, fall short of gamma near the pull-off, so
    their paths are relaxed further (reach) and the pull-off is given."""
    import shell_adhesion.solver.case as case
    monkeypatch.setattr(case, "G_SAFETY", 1.0)      # in this process: no pool
    ps, _, _ = rq.solve_request(0.15, 1.0, rq.Request((0.005,)), 0.00625, mesh="coarse")
    assert ps.stats["fit"]["paths_taken_further"] > 0
    further = [r for r in ps.relaxations if r.reach > 1]
    assert further and all(r.reach in (rq.REACH_FACTOR, rq.REACH_FACTOR ** 2) for r in further)
    ps.pull_off(0.005)


def test_rim_corner_neighbourhood():
    """The inner rim corner's neighbourhood (RIM_CORNER t) is left out of the J check: the
    shallow cap that stopped at delta = 0.047 R now loads further, every J outside that
    neighbourhood inside J_RANGE; the neighbourhood is a few elements at the corner."""
    ps, d, loading = solve_paths(0.15, 0.2, "no_slip", "coarse", 0.07, 0.01, relax_paths=False)
    mask = rim_corner_elements(d.capmesh)
    assert 1 <= mask.sum() <= 4
    assert loading.delta_reached > 0.06
    lo, hi = J_RANGE
    assert lo <= ps.stats["J_min"] and ps.stats["J_max"] <= hi
    from shell_adhesion.solver.forms import deformation
    f, _ = deformation(d, loading.states[-1].x)
    J = (f[0] * f[3] - f[1] * f[2]) * f[4]
    assert J[mask].min() < ps.stats["J_min"]        # the corner is where J is worst
    assert not rim_corner_elements(solve_paths(1.0, 0.2, "no_slip", "coarse", 0.01, 0.01,
                                               relax_paths=False)[1].capmesh).any()


def test_a_distorted_corner_element_warns_nothing():
    """The thin, shallow cap whose stress maps evaluated J ** (-2/3) of a negative J at the
    rim corner's element nodes (a RuntimeWarning on every run): such a node has no value,
    the run warns nothing; its P* is given with the fixed grips' reason."""
    import warnings
    import shell_adhesion as sa
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        case = sa.solve_case(20, 0.4, 4, 0.3, [30], mesh="coarse", progress=False)
    (g, eq, po), = case.adhesion
    assert np.isfinite(po.P_star) and (np.isfinite(po.P_dagger) or po.note)
