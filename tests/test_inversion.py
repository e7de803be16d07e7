"""Contact-zone inversion (issue 10, item 6): a thin shell's contact centre leaves the plane
(the paper's "buckling").  Found case: t/R = 0.02, h/R = 1, coarse mesh, no-slip: loaded to
delta = 0.05 R, the relaxation paths held at a/R = 0.046 to 0.092 have their centre pulled
off the plane at delta/R = -0.09 to -0.22.  They are reported (where, and on which paths)
and the equilibrium points that bridge them are flagged."""
import numpy as np
import pytest

from shell_adhesion.solver import solve_paths
from shell_adhesion.solver.energy import equilibrium


@pytest.fixture(scope="module")
def thin():
    return solve_paths(0.02, 1.0, "no_slip", "coarse", 0.05, 0.006)


def test_thin_shell_inversion_is_located(thin):
    ps, _, _ = thin
    flipped = [r for r in ps.relaxations if r.centre_lifts]
    assert len(flipped) >= 3
    assert all(np.isfinite(r.inversion_delta) and r.inversion_delta < r.delta[0] for r in flipped)
    assert all(np.isnan(r.inversion_delta) for r in ps.relaxations if not r.centre_lifts)
    st = ps.stats
    assert st["inversion_stage"] == "relaxation" and st["inverted_paths"] == len(flipped)
    first = min(flipped, key=lambda r: r.a)
    assert (st["inversion_a"], st["inversion_delta"]) == (first.a, first.inversion_delta)
    assert st["inversion_a_loading"] is None


def test_bridged_equilibrium_points_are_flagged(thin):
    ps, _, _ = thin
    eq = equilibrium(ps.surface(), 0.002)
    flags = ps.inverted(eq.a)
    a_flip = [r.a for r in ps.relaxations if r.centre_lifts]
    usable = np.array([r.a for r in ps.usable()])
    lo, hi = usable[usable < min(a_flip)].max(), usable[usable > max(a_flip)].min()
    assert flags.any() and not flags.all()
    assert np.array_equal(flags, (eq.a > lo) & (eq.a < hi))


def test_base_shell_does_not_invert(base_coarse):
    ps, _, _ = base_coarse
    assert ps.stats["inverted_paths"] == 0 and ps.stats["inversion_stage"] is None
    assert not ps.inverted(np.linspace(0, 0.5, 11)).any()
