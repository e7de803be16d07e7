"""A loading refused by the element-quality check or stalled keeps the states converged so
far (issue 10): it says how far it got and why, and the pull-offs come from what it has."""
import numpy as np
import pytest

from shell_adhesion.solver import quality as quality_module
from shell_adhesion.solver.case import solve_loading, solve_paths
from shell_adhesion.solver.path import load
from shell_adhesion.errors import QualityError


def _all_pass(loading):
    return all(s.quality.problem() == "" for s in loading.states)


def test_quality_limit_stops_the_loading_and_keeps_its_states(base_coarse):
    """The base shell to delta = 0.5 R leaves the J bound near 0.3 R: without
    stop_at_limit that is an error, with it the path ends at the last good state."""
    _, d, _ = base_coarse
    path = load(d, "no_slip", 0.5, stop_at_limit=True)
    assert "pointwise J" in path.stopped_by and "coarse mesh" in path.stopped_by
    assert 0.25 < path.delta_reached < 0.5
    assert np.all(np.diff(path.array("delta")) > 0) and _all_pass(path)
    with pytest.raises(QualityError):
        load(d, "no_slip", 0.5)


def test_thin_frictionless_stall_keeps_its_states():
    """t/R = 0.02, frictionless: the contact front's event moves behind the last state
    near delta = 0.044 R (coarse mesh, 2 element layers through the thickness, 93 states;
    0.084 R with the 1 layer it had before issue 39)."""
    _, path = solve_loading(0.02, 1.0, "frictionless", "coarse", 0.25, stop_at_limit=True)
    assert "stalled" in path.stopped_by
    assert 0.04 < path.delta_reached < 0.25
    assert np.all(np.isfinite(path.array("P"))) and len(path.states) > 20


def test_the_set_says_how_far_the_loading_got(monkeypatch):
    """A tight J bound stops the base shell's loading early: the path set's stats (and so
    the provenance and the cube) say where and why."""
    monkeypatch.setattr(quality_module, "J_RANGE", (0.97, 1.03))
    ps, _, loading = solve_paths(0.15, 1.0, "no_slip", "coarse", 0.1, 0.006, relax_paths=False)
    assert "pointwise J" in loading.stopped_by
    assert ps.stats["loading_stopped_by"] == loading.stopped_by
    assert ps.stats["delta_reached"] == pytest.approx(ps.loading_delta[-1])
    assert ps.stats["delta_reached"] < 0.1


@pytest.mark.slow
def test_pull_off_from_a_loading_stopped_short(monkeypatch):
    """... and the pull-off still comes from the relaxation paths it has (80 s)."""
    monkeypatch.setattr(quality_module, "J_RANGE", (0.97, 1.03))
    ps, _, loading = solve_paths(0.15, 1.0, "no_slip", "coarse", 0.1, 0.006)
    assert ps.stats["delta_reached"] < 0.1
    _, po = ps.pull_off(0.005)
    assert po.P_star < 0 and np.isfinite(po.a_star)


@pytest.mark.slow
def test_shallow_cap_keeps_what_it_loaded():
    """h/R = 0.2 (coarse) is refused near delta = 0.05 R; the pull-off at gamma/(C10 R) =
    0.005 needs less."""
    ps, _, loading = solve_paths(0.15, 0.2, "no_slip", "coarse", 0.1, 0.006)
    assert 0.03 < ps.stats["delta_reached"] < 0.1 and "pointwise J" in loading.stopped_by
    _, po = ps.pull_off(0.005)
    assert po.P_star < 0 and np.isfinite(po.delta_dagger)
