"""How far the relaxations reach in G (issue 10, item 2, the reporting half): the stats
say the G every pair of neighbouring paths reached, and which pair radii a gamma misses."""
import numpy as np
import pytest

from conftest import GAMMA_HAT


def test_G_max_reached_is_reported(base_coarse):
    ps, _, _ = base_coarse
    a, G = ps.G_reached()
    assert len(a) == len(ps.usable()) - 1 and np.all(np.isfinite(G))
    assert ps.stats["G_max_reached"] == pytest.approx(G.min())
    # the flat-punch stop rule (3 gamma_max) reaches less than gamma_max at the smallest a
    assert G.min() < ps.gamma_max < G.max()


def test_unreached_pairs_have_no_equilibrium_point(base_coarse):
    ps, _, _ = base_coarse
    eq, _ = ps.pull_off(GAMMA_HAT)
    missing = ps.unreached(GAMMA_HAT)
    assert len(missing) > 0 and not np.isin(eq.a, missing).any()
    assert len(ps.unreached(0.5 * ps.stats["G_max_reached"])) == 0
