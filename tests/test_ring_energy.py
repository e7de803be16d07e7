"""The energy method at a ring contact's two edges (solver.ring_energy), against the
finite-range adhesion switched on at the same ring (solver.ring_adhesion).

t/R 0.02, h/R 1, frictionless, pressed to 5 t (past the snap: a ring around a dimple
whose apex is 4 t up).  Measured (`python benchmarks/ring_energy.py --mesh MESH --lo 1e-5
--hi 1e-4`): G of the inner edge, growing inward element edge by element edge, rises
from 0 to a broad maximum of 4.32e-5 C10 R near 0.28 R and falls as the dimple shrinks;
the outer edge's G rises without a maximum (5.9e-6, 2.1e-5, 4.6e-5, 7.7e-5 over its
first four element edges, coarse).  With both edges free, gamma_c / (C10 R) lies in
[4.051e-5, 4.081e-5] (coarser), [4.081e-5, 4.111e-5] (coarse and default); the smoothed
Dugdale law at lambda 0.3 gives [4.07e-5, 4.27e-5] (coarse) and [4.13e-5, 4.26e-5]
(default).
"""
import math

import numpy as np
import pytest

from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.solver.cohesive import CohesiveLaw
from shell_adhesion.solver.ring_adhesion import ring_holds
from shell_adhesion.solver.ring_energy import (RingLattice, held_ring, release_rates, settle,
                                               zip_limit)
from shell_adhesion.solver.snap import trace_shell

T, DELTA = 0.02, 0.1


@pytest.fixture(scope="module")
def coarser():
    d, path = trace_shell(T, 1.0, "coarser", DELTA)
    assert path.ended_by == ""
    return d, path.states[-1], RingLattice(d, path.states[-1])


def test_the_held_ring_is_the_pressed_ring_on_element_corners(coarser):
    d, pressed, lattice = coarser
    ring = lattice(0, 0)
    assert ring.delta == pressed.delta and not ring.disc
    assert d.capmesh.outer_corner[ring.held[0]] and d.capmesh.outer_corner[ring.held[-1]]
    assert list(ring.held) == list(range(ring.held[0], ring.held[-1] + 1))
    # the held ring covers the penalty contact's ring, within an element edge (0.008 R)
    (r0, r1), = pressed.radii
    assert ring.r_in <= r0 + 1e-3 and ring.r_out >= r1 - 1e-3
    assert r0 - ring.r_in < 0.01 and ring.r_out - r1 < 0.01
    # P moves by less than 2 % from the penalty contact (onset 1e-4 R) to the held one
    assert abs(ring.P / pressed.P - 1) < 0.02
    assert ring.apex_gap > 4 * T
    assert math.isclose(ring.A, math.pi * (ring.r_out ** 2 - ring.r_in ** 2))


def test_without_adhesion_the_pressed_ring_stays(coarser):
    _, _, lattice = coarser
    s = settle(lattice, 0.0)
    assert (s.j, s.k, s.moves, s.closed) == (0, 0, 0, False)


def test_the_inner_edge_has_a_maximum_of_G_and_the_outer_edge_none(coarser):
    _, _, lattice = coarser
    r_in, G_in = release_rates(lattice, "in", 20)
    assert len(G_in) == 20 and np.all(np.diff(r_in) < 0) and np.all(G_in > 0)
    top = int(np.argmax(G_in))
    # a fold: G rises from near 0 at the pressed ring to an interior maximum (measured
    # 4.3e-5 on the coarse mesh) and falls after it
    assert G_in[0] < 0.5 * G_in[top] and 0 < top < len(G_in) - 2
    assert G_in[-1] < G_in[top]
    assert 3.8e-5 < G_in[top] < 4.8e-5
    r_out, G_out = release_rates(lattice, "out", 6)
    assert np.all(np.diff(r_out) > 0) and np.all(np.diff(G_out) > 0)
    assert G_out[-1] > 2 * G_in[top]


def test_the_bisection_brackets_the_zero_range_limit(coarser):
    _, _, lattice = coarser
    lo, hi = zip_limit(lattice, 1e-5, 1e-4, rel=0.01)
    assert not lo.closed and hi.closed and hi.gamma <= 1.01 * lo.gamma
    # measured [4.051e-5, 4.081e-5]; the finite-range law at lambda 0.3 brackets 4.07e-5
    # to 4.27e-5 (coarse) and 4.13e-5 to 4.26e-5 (default): within 5 %
    assert 3.9e-5 < lo.gamma and hi.gamma < 4.3e-5
    # just below the limit the inner edge has run inward (coarser: 0.094 R), the outer
    # edge outward by one element edge (0.019 R)
    ring = lo.ring
    start = lattice(0, 0)
    assert start.r_in - ring.r_in > 3 * (ring.r_out - start.r_out) > 0
    assert ring.apex_gap > 0.1 * T
    with pytest.raises(ValueError, match="closes at gamma_lo"):
        zip_limit(lattice, 1e-4, 2e-4)
    with pytest.raises(ValueError, match="still holds at gamma_hi"):
        zip_limit(lattice, 1e-6, 2e-6)
    with pytest.raises(ValueError, match="gamma"):
        settle(lattice, -1.0)


def test_a_state_that_is_not_one_ring_is_refused():
    d, path = trace_shell(T, 1.0, "coarser", 0.01)
    with pytest.raises(ValueError, match="not one ring"):
        held_ring(d, path.states[-1])


@pytest.mark.slow
def test_two_methods_one_limit_on_the_coarse_mesh():
    """The finite-range law at lambda 0.3 keeps the ring 5 % below the energy method's
    limit and closes the dimple 5 % above it, on the same mesh."""
    d, path = trace_shell(T, 1.0, "coarse", DELTA)
    state = path.states[-1]
    lo, hi = zip_limit(RingLattice(d, state), 1e-5, 1e-4, rel=0.01)
    assert 3.9e-5 < lo.gamma and hi.gamma < 4.3e-5

    def law(gamma):
        return CohesiveLaw(md.sigma0_of(0.3, gamma, 1.0, 32 / 3), gamma)

    assert ring_holds(d, state, law(0.95 * lo.gamma)).holds
    assert not ring_holds(d, state, law(1.05 * hi.gamma)).holds
