"""Contact-zone inversion (issue 10, item 6): a thin shell's contact centre leaves the plane
(the paper's "buckling").  Found case: t/R = 0.02, h/R = 1, coarse mesh, no-slip: loaded to
delta = 0.05 R, the 7 relaxation paths held at a/R = 0.046 to 0.092 have their centre
pulled off the plane (2 element layers through the thickness since issue 39; with 1, 8
paths held at 0.046 to 0.100 lifted at delta/R = -0.09 to -0.26).
They are reported (where, and on which paths) and serve the energy method up to their
inversion (issue 21); equilibrium points that bridge a path left out entirely are flagged."""
import numpy as np
import pytest

from shell_adhesion.solver import solve_paths
from shell_adhesion.energy import equilibrium


@pytest.fixture(scope="module")
def thin():
    return solve_paths(0.02, 1.0, "no_slip", "coarse", 0.05, 0.006)


def test_thin_shell_inversion_is_located(thin):
    ps, _, _ = thin
    flipped = [r for r in ps.relaxations if r.centre_lifts]
    # README: 7 of its 25 relaxation paths, held at a/R = 0.046 to 0.092
    assert (len(flipped), len(ps.relaxations)) == (7, 25)
    assert (round(flipped[0].a, 3), round(flipped[-1].a, 3)) == (0.046, 0.092)
    assert all(np.isfinite(r.inversion_delta) and r.inversion_delta < r.delta[0] for r in flipped)
    assert all(np.isnan(r.inversion_delta) for r in ps.relaxations if not r.centre_lifts)
    st = ps.stats
    assert st["inversion_stage"] == "relaxation" and st["inverted_paths"] == len(flipped)
    first = min(flipped, key=lambda r: r.a)
    assert (st["inversion_a"], st["inversion_delta"]) == (first.a, first.inversion_delta)
    assert st["inversion_a_loading"] is None


def test_inverted_paths_serve_up_to_their_inversion(thin):
    """Issue 21, item 5: a path whose centre lifts serves the energy method with its states
    before the inversion (a contact disc on the plane); the equilibrium points come from
    those states only."""
    ps, _, _ = thin
    flipped = [r for r in ps.relaxations if r.centre_lifts]
    for r in flipped:
        up = r.upright()
        assert np.all(up.delta > r.inversion_delta) and len(up.delta) < len(r.delta)
        assert r.usable == (len(up.delta) >= 2)
    used = {r.a: r for r in ps.usable()}
    assert any(r.usable for r in flipped)
    for r in flipped:
        if r.usable:
            assert used[r.a].delta.min() > r.inversion_delta


def test_points_bridging_unusable_paths_are_flagged(thin):
    """A path that inverted before two states is left out; the points that bridge it (and
    only those) are flagged."""
    ps, _, _ = thin
    eq = equilibrium(ps.surface(), 0.002)
    gone = [r.a for r in ps.relaxations if r.centre_lifts and not r.usable]
    flags = ps.inverted(eq.a)
    usable = np.array([r.a for r in ps.usable()])
    expect = np.zeros(len(eq.a), dtype=bool)
    for a in gone:
        lo = usable[usable < a].max(initial=-np.inf)
        hi = usable[usable > a].min(initial=np.inf)
        expect |= (eq.a > lo) & (eq.a < hi)
    assert np.array_equal(flags, expect)


def test_base_shell_does_not_invert(base_coarse):
    ps, _, _ = base_coarse
    assert ps.stats["inverted_paths"] == 0 and ps.stats["inversion_stage"] is None
    assert not ps.inverted(np.linspace(0, 0.5, 11)).any()


def test_a_curve_ended_by_inverted_paths_says_so(thin):
    """A curve not bracketed at large a names the inverted paths held beyond its end (the
    energy method of a contact disc ends at an inversion), and only those."""
    ps, _, _ = thin
    beyond = ps._why_the_curve_ends(0.03)
    assert "the 7 relaxation paths held beyond it (a = 0.04608 to 0.09202 R) invert" in beyond
    assert "invert" not in ps._why_the_curve_ends(0.2)
    with pytest.raises(ValueError, match="stopped by its depth bound delta_max") as e:
        ps.pull_off(0.003)
    assert "invert" not in str(e.value)     # its inverted paths lie inside the curve


@pytest.mark.slow      # the domain map (`long`) holds the same refusal on this point
def test_the_flattened_hemisphere_is_refused_for_its_physics():
    """t/R = 0.02, h/R = 1 at gamma/(C10 R) = 0.015 (coarse mesh, as a user calls it): its
    equilibrium curve still falls where the hemisphere snaps flat.  The thin-shell depth
    bound (0.9 h) lets the loading go through the snap (the contact radius jumps past
    0.95 R), so the refusal names the inverted paths beyond the curve's end, not a depth
    we chose (0.5 R before: "stopped by its depth bound" at a = 0.79 R).  With 2 element
    layers on the coarse mesh (issue 39; 1 before, which reached the 0.9 h bound) the
    loading stops on element quality at delta = 0.85 R, a = 1.023 R.  About 20 s."""
    import shell_adhesion as sa
    res = sa.solve_case(20.0, 0.4, 20.0, 0.3, [90.0], mesh="coarse", progress=False,
                        error_bars=False).to_dict()
    (p,) = res["pull_off"]
    assert p["status"] != "ok"
    assert "relaxation paths held beyond it" in p["reason"] and "invert" in p["reason"]
    reached = res["provenance"]["loading_reached"]
    assert reached["delta_reached_mm"] == pytest.approx(16.85, abs=0.01)
    assert "element quality" in reached["stopped_by"]    # not a depth we chose
    assert "with the contact radius a = 1.023 R" in p["reason"]     # through the snap
    assert res["provenance"]["inversion"]["inverted_relaxation_paths"] >= 10
