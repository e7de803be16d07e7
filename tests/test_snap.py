"""The loading of a thin deep shell through its snap (issue 42, items 1 and 2; DESIGN.md
section 10, "Thin shells past buckling"): frictionless, no adhesion, h = R, traced by arc
length (solver.snap).  Pressed by a plane the shell first flattens (Reissner: P = 16 C10
t^2 delta / R for an incompressible neo-Hookean), then the flat region inverts into a
dimple (Pogorelov's mirror buckling): the contact is a ring and P grows about as
delta^(1/2).  Under displacement control the inversion is a jump; the path passes it.

Default tier: t/R = 0.02 on the 'coarser' mesh to delta = 5 t (7 to 15 s): the snap,
the ring after it, the energy balance, the Reissner regime.  `slow`: t/R = 0.01 and 0.02
on the coarse mesh to 10 t (about 30 s and 60 s): the Pogorelov slope over 5 t to 10 t.
Measured (coarse): slope 0.5735 (drift -0.026) for t/R 0.01, 0.5747 (-0.026) for 0.02;
coarser, t/R 0.02 to 5 t: jump at delta = 4.37 t, P from 9.01e-4 to 4.99e-4 C10 R^2,
energy 3.6e-5 (benchmarks/snap.py).
Where the snap falls depends on the contact's regularisation (solver.snap.SnapSettings.
onset): the traced jump comes early; with a sharp contact the loading stops at its loss
of stability, 6.33 t (two `slow` tests, docs/thin-shells.md)."""
import dataclasses

import numpy as np
import pytest

from shell_adhesion.errors import InputError
from shell_adhesion.solver.snap import SnapSettings, log_slope, trace_shell

REISSNER = 0.15     # the brief's band around 16 C10 t^2 delta / R, delta <= t / 2
ENERGY = 1e-4       # |work of P - U - Pi| / max U along the path


def _reissner_ratios(path, T):
    """P / (16 T^2 delta) for 0.05 t <= delta <= t / 2 on the first branch (below 0.05 t
    the penalty's onset, 1e-5 R, is more than 1 % of delta)."""
    D, P = path.array("delta"), path.array("P")
    first = np.flatnonzero(np.diff(D) < 0)
    end = first[0] if len(first) else len(D)
    m = (D[:end] >= 0.05 * T) & (D[:end] <= 0.5 * T)
    return P[:end][m] / (16 * T * T * D[:end][m])


def _energy_miss(path):
    W, U, Pi = path.work(), path.array("U"), path.array("Pi")
    return float(np.abs(W - U - Pi).max() / U.max())


@pytest.fixture(scope="module")
def snap():
    return trace_shell(0.02, 1.0, "coarser", 0.1)


def test_thin_shell_loading_passes_the_snap_to_a_ring(snap):
    T = 0.02
    _, path = snap
    assert path.ended_by == ""
    jumps = path.jumps()
    assert jumps, "no fold of delta: the flattened shell did not snap"
    j = jumps[0]
    # the load drops at the jump (measured: to 0.55 of it, at delta = 4.37 t), and after
    # it the contact is a ring only, with the apex inverted by more than a thickness
    assert j.P_to < 0.7 * j.P_from
    after = path.states[j.i_to]
    assert after.ring and len(after.radii) == 1 and after.apex_gap > T
    assert 3 * T < j.delta < 8 * T
    ring = path.first_ring(0.1 * T)
    assert ring is not None and ring < j.i_to
    # every state's contact set is ordered radii: r_in < r_out, runs apart
    for s in path.states:
        r = np.array(s.radii).ravel()
        assert np.all(np.diff(r) >= 0)


def test_thin_shell_loading_conserves_energy_through_the_snap(snap):
    _, path = snap
    assert _energy_miss(path) <= ENERGY


def test_thin_shell_loading_starts_as_reissner(snap):
    ratios = _reissner_ratios(snap[1], 0.02)
    assert len(ratios) >= 3
    assert np.all(np.abs(ratios - 1) <= REISSNER)


def test_thin_shell_loading_refuses_bad_input():
    with pytest.raises(InputError, match="t/R"):
        trace_shell(0.001, 1.0, "coarser", 0.01)
    with pytest.raises(InputError, match="h/R"):
        trace_shell(0.01, 0.01, "coarser", 0.005)
    with pytest.raises(InputError, match="delta_max"):
        trace_shell(0.02, 1.0, "coarser", 1.5)


@pytest.mark.slow
@pytest.mark.parametrize("T", [0.01, 0.02])
def test_reissner_then_pogorelov(T):
    _, path = trace_shell(T, 1.0, "coarse", 10 * T)
    assert path.ended_by == ""
    ratios = _reissner_ratios(path, T)
    assert len(ratios) >= 3 and np.all(np.abs(ratios - 1) <= REISSNER)
    slope, drift = log_slope(path, 5 * T, 10 * T)
    print(f"t/R {T}: slope {slope:.4f}, drift {drift:+.4f}, first ring (apex > 0.1 t) at "
          f"delta = {path.states[path.first_ring(0.1 * T)].delta / T:.3f} t")
    assert 0.35 <= slope <= 0.65
    assert path.jumps() and path.first_ring(0.1 * T) is not None
    assert _energy_miss(path) <= ENERGY
    # the penalty's share is small: against the strain energy alone the work misses by
    # 1.0e-4 of max U (t/R 0.01; 7.0e-5 at 0.02), held at twice that
    W, U = path.work(), path.array("U")
    assert np.abs(W - U).max() <= 2 * ENERGY * U.max()


def _synthetic(u, delta, P, ddelta, dP):
    """A SnapPath through the points (delta(u), P(u)) with tangents (ddelta, dP)."""
    from shell_adhesion.solver.linear import Timer
    from shell_adhesion.solver.snap import SnapPath, SnapState
    states = tuple(SnapState(float(d), float(p), 0.0, 0.0, (), (), 0.0, 0, (float(a), float(b)))
                   for d, p, a, b in zip(delta(u), P(u), ddelta(u), dP(u)))
    return SnapPath(states, "", Timer())


def test_work_and_jump_through_a_fold_against_the_closed_form():
    # delta = u^3 - 1.5 u^2 + 0.6 u, P = u: delta folds at u1 = (3 - sqrt(1.8)) / 6 and
    # again at (3 + sqrt(1.8)) / 6, and comes back to delta(u1) at u3 = 1.5 - 2 u1
    u = np.linspace(0.0, 1.5, 121)
    path = _synthetic(u, lambda u: u ** 3 - 1.5 * u ** 2 + 0.6 * u, lambda u: u,
                      lambda u: 3 * u ** 2 - 3 * u + 0.6, lambda u: np.ones_like(u))
    exact = 0.75 * u ** 4 - u ** 3 + 0.3 * u ** 2          # integral of u d delta
    # measured 3.3e-9: the Hermite steps are exact to fourth order
    assert np.abs(path.work() - exact).max() <= 1e-8 * np.abs(exact).max()
    (jump,) = path.jumps()
    u1 = (3 - np.sqrt(1.8)) / 6
    # the fold is the sampled state nearest it (u steps of 0.0125): measured -1.3e-6 in
    # delta, -1.4e-3 in P; P after the jump linear between two states: -8.5e-5
    assert jump.delta == pytest.approx(u1 ** 3 - 1.5 * u1 ** 2 + 0.6 * u1, abs=1e-5)
    assert jump.P_from == pytest.approx(u1, abs=0.005)
    assert jump.P_to == pytest.approx(1.5 - 2 * u1, abs=5e-4)


def test_contact_set_of_a_ring_against_the_closed_form():
    from scipy.optimize import brentq
    from shell_adhesion.solver.cohesive import Interface
    from shell_adhesion.solver.forms import discretise
    from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
    from shell_adhesion.solver.snap import PenaltyContact, contact_set, loading_cap
    d = discretise(cap_mesh(loading_cap(0.02, 1.0), mesh_spec("coarse", 0.6)))
    cm = d.capmesh
    c, A, w = 0.02, 0.03, 0.1          # shifted down by c, the apex lifted by A - c
    x = np.zeros(d.ndof)
    x[d.uz(np.arange(d.n2))] = -c + A * np.exp(-(cm.nodes[0] / w) ** 2)
    (edges,), ((r_in, r_out),) = contact_set(Interface(d, PenaltyContact()), x)

    def z(r):                            # the outer sphere, moved as the nodes are
        return 1 - np.sqrt(1 - r * r) - c + A * np.exp(-(r / w) ** 2)
    # measured -6e-8 and 2e-7 (the Q2 edges interpolate the sphere and the lift)
    assert r_in == pytest.approx(brentq(z, 0.0, 0.15), abs=1e-6)
    assert r_out == pytest.approx(brentq(z, 0.15, 0.5), abs=1e-6)
    assert edges[0] > 0


def _onset(onset, stiffness=1e4, jump_push=SnapSettings().jump_push):
    return dataclasses.replace(SnapSettings(), onset=onset, stiffness=stiffness,
                               jump_push=jump_push)


def _sharp_jump(mesh, depth, push=SnapSettings().jump_push):
    """The loading of t/R 0.02 with a sharp contact (onset 3e-6 R) to depth t, its one
    jump and the energy the jump dissipated (C10 R^3)."""
    T = 0.02
    _, path = trace_shell(T, 1.0, mesh, depth * T, settings=_onset(3e-6, jump_push=push))
    jump, = path.jumps()
    return path, jump, -path.states[jump.i_from].anchor_jump


def test_a_sharp_contact_jumps_where_it_loses_stability():
    """With a sharp contact the continuation cannot pass the loss of stability at 6.33 t
    (the centre lifts while delta and P stand still; next test).  There the loading jumps
    as a displacement-controlled test does (`snap._jump`): the rim pushed on by 0.01 t, the
    shell settles by damped descent and is brought back to the same delta on the branch it
    landed on.  t/R 0.02, coarser mesh, onset 3e-6 R, to 6.4 t (4 s).  Measured: at
    6.3258 t P falls from 1.5768e-3 to 6.216e-4 C10 R^2 (0.394 of it), the contact from
    two rings (0.124-0.238 and 0.399-0.448 R) to one at 0.440-0.444 R around a dimple;
    the jump dissipates 3.337e-5 C10 R^3 (0.41 of the largest strain energy) and the work
    of P balances the strain and penalty energies less that within 8.2e-6 of max U.
    Without the jump (jump_push 0) the path ends there, as before."""
    T = 0.02
    path, jump, lost = _sharp_jump("coarser", 6.4)
    assert path.ended_by == "" and path.states[-1].delta >= 6.4 * T
    landed, before = path.states[jump.i_to], path.states[jump.i_from]
    assert landed.landed and jump.i_to == jump.i_from + 1 and landed.delta == before.delta
    assert jump.delta / T == pytest.approx(6.325, abs=0.01)
    assert 0.35 < jump.P_to / jump.P_from < 0.45
    # from two rings around a hovering centre to one ring around a dimple
    assert len(before.radii) == 2 and abs(before.apex_gap) < 1e-3 * T
    assert len(landed.radii) == 1 and landed.radii[0][0] > 0.4 and landed.apex_gap > 5 * T
    U = path.array("U")
    assert lost == pytest.approx(before.U + before.Pi - landed.U - landed.Pi, rel=1e-12)
    assert 0.3 * U.max() < lost < 0.5 * U.max()
    assert path.energy_miss() < 2e-5
    _, stopped = trace_shell(T, 1.0, "coarser", 6.4 * T, settings=_onset(3e-6, jump_push=0.0))
    assert stopped.ended_by.startswith("step below") and not stopped.jumps()
    assert stopped.states[-1].delta == pytest.approx(before.delta, abs=1e-4 * T)


@pytest.mark.slow
def test_the_sharp_jump_lands_on_the_same_state_whatever_the_push_and_the_mesh():
    """The state the jump lands on does not depend on how far the rim is pushed on before
    the shell settles (0.01 t or 0.001 t: the same P and contact to 1e-6), and holds on
    the coarse mesh (two layers through the shell against one): measured, coarser 6.3258 t,
    P 1.5768e-3 -> 6.216e-4, ring 0.440-0.444 R; coarse 6.3368 t, 1.5772e-3 -> 6.270e-4,
    ring 0.4395-0.4457 R (to 8 t with ds_max 0.001: energy balance 3.4e-8).  About a
    minute."""
    T = 0.02
    _, far, _ = _sharp_jump("coarser", 6.4, push=0.01)
    _, near, _ = _sharp_jump("coarser", 6.4, push=0.001)
    assert near.P_to == pytest.approx(far.P_to, rel=1e-6) and near.contact_to == far.contact_to
    path, fine, lost = _sharp_jump("coarse", 6.4)
    print(far, fine, lost)
    assert fine.delta / T == pytest.approx(far.delta / T, abs=0.015)
    assert fine.P_to == pytest.approx(far.P_to, rel=0.015)
    assert fine.P_from == pytest.approx(far.P_from, rel=0.005)


@pytest.mark.slow
def test_the_traced_snap_moves_with_the_contact_penalty():
    """The jump the continuation passes is early, by the contact's softness: t/R 0.02,
    coarser mesh, onset 1e-4, 7e-5, 5e-5 R: jump at 4.368, 4.607, 4.894 t (the central
    contact disc at the fold 0.019, 0.056, 0.080 R); the slope after it 0.5826, 0.5826,
    0.5835.  It moves with the element layers through the shell: at 1e-4 R, 4.827 t on
    the coarse mesh (two layers), 4.905 t on the default (four).  About four minutes."""
    T = 0.02
    for mesh, onset, at, slope in (("coarser", 1e-4, 4.368, 0.5826),
                                   ("coarser", 7e-5, 4.607, 0.5826),
                                   ("coarser", 5e-5, 4.894, 0.5835),
                                   ("coarse", 1e-4, 4.827, None),
                                   ("default", 1e-4, 4.905, None)):
        depth = 8 if slope is not None else 6 if mesh == "coarse" else 5
        _, path = trace_shell(T, 1.0, mesh, depth * T,
                              settings=_onset(onset))
        assert path.ended_by == ""
        (jump,) = path.jumps()
        # the slope over 5 t to the path's end (just past 8 t), as benchmarks/snap.py
        end = path.states[-1].delta
        print(mesh, onset, jump.delta / T, slope and log_slope(path, 5 * T, end))
        assert jump.delta / T == pytest.approx(at, abs=0.01), (mesh, onset)
        if slope is not None:
            assert log_slope(path, 5 * T, end)[0] == pytest.approx(slope, abs=0.005), onset


@pytest.mark.slow
def test_a_sharp_contact_loses_stability_at_the_same_delta_on_refinement():
    """With a sharp contact (onset 1e-5 R and below) the loading stops at a bifurcation:
    delta and P stand still while the flattened centre lifts off (the inner edge of the
    contact moving from the axis outward), and the continuation cannot follow the branch
    beyond (its steps fall below ds_min; `SnapSettings.jump_push` 0: no jump from there).
    Where it stops holds across refinements of the
    contact and of the mesh: the converged snap.  Measured (delta / t), stiffness 1e4
    C10/R unless stated: coarser 6.2702 (onset 1e-5 R; and 1e5 C10/R from 1e-4 R: the
    penetration stays within the onset, so only their ratio counts), 6.3253 (3e-6 R),
    6.3312 (1e-6 R), 6.3341 (1e-6 R, 1e5 C10/R); coarse 6.3368, default 6.3393 (3e-6 R).
    About eight minutes."""
    T = 0.02
    stop = {}
    for mesh, onset, k in (("coarser", 1e-5, 1e4), ("coarser", 1e-4, 1e5),
                           ("coarser", 3e-6, 1e4), ("coarser", 1e-6, 1e4),
                           ("coarser", 1e-6, 1e5), ("coarse", 3e-6, 1e4),
                           ("default", 3e-6, 1e4)):
        depth = 6.6 if mesh == "default" else 8
        _, path = trace_shell(T, 1.0, mesh, depth * T, settings=_onset(onset, k, 0.0))
        assert path.ended_by.startswith("step below"), path.ended_by
        last = path.states[-1]
        # the centre has lifted: the contact is rings, the axis off the plane by less
        # than the penetration's scale (the lifted centre hovers)
        assert last.ring and abs(last.apex_gap) < 1e-3 * T
        stop[mesh, onset, k] = last.delta / T
    print(stop)
    assert stop["coarser", 1e-4, 1e5] == pytest.approx(stop["coarser", 1e-5, 1e4], abs=1e-3)
    # each tenfold sharpening moves it less: 0.055 t, 0.006 t, 0.003 t
    assert abs(stop["coarser", 3e-6, 1e4] - stop["coarser", 1e-5, 1e4]) <= 0.1
    assert abs(stop["coarser", 1e-6, 1e4] - stop["coarser", 3e-6, 1e4]) <= 0.01
    assert abs(stop["coarser", 1e-6, 1e5] - stop["coarser", 1e-6, 1e4]) <= 0.005
    # two refinements of the mesh at 3e-6 R: 0.012 t, then 0.003 t
    assert abs(stop["coarse", 3e-6, 1e4] - stop["coarser", 3e-6, 1e4]) <= 0.015
    assert abs(stop["default", 3e-6, 1e4] - stop["coarse", 3e-6, 1e4]) <= 0.015
    for key, at in {("coarser", 1e-5, 1e4): 6.270, ("coarser", 3e-6, 1e4): 6.325,
                    ("coarser", 1e-6, 1e4): 6.331, ("coarser", 1e-6, 1e5): 6.334,
                    ("coarse", 3e-6, 1e4): 6.337, ("default", 3e-6, 1e4): 6.339}.items():
        assert stop[key] == pytest.approx(at, abs=0.01), key


def test_a_push_from_a_state_whose_branch_goes_on_steps_along_it(snap):
    """`snap._jump` from a state that is not at a fold (2 t, on the coarser loading's
    first branch): the shell settles back on its own branch, so the jump is refused,
    and with `onward` (where the continuation turned round on its own branch) the
    settled state at delta + push is returned instead, on that branch: its P is the
    branch's P there (the state's P plus its tangent's dP/ddelta times the push: measured
    1.5e-5 relative; linear between the loading's next two states: 8.1e-5)."""
    from shell_adhesion.errors import ConvergenceError
    from shell_adhesion.solver.arclength import ArcSettings, _Continuation
    from shell_adhesion.solver.cohesive import Interface
    from shell_adhesion.solver.contact import constraints, rim_load
    from shell_adhesion.solver.snap import PenaltyContact, _fold, _jump
    T = 0.02
    d, path = snap
    s = SnapSettings()
    D = path.array("delta")
    k = int(np.flatnonzero(D >= 2 * T)[0])
    cn = _Continuation(Interface(d, PenaltyContact(s.stiffness, s.onset), None),
                       "frictionless", ArcSettings(tol=s.tol, max_iter=s.max_iter))
    c = constraints(d, "frictionless", [])
    start = path.states[k]
    push = s.jump_push * T
    with pytest.raises(ConvergenceError, match="settled back"):
        _jump(cn, c, start.x, start.delta, push, s.jump_descent)
    x, delta, _, r, _, landed = _jump(cn, c, start.x, start.delta, push, s.jump_descent,
                                      onward=True)
    assert not landed and delta == start.delta + push
    nxt = path.states[k + 1]
    assert start.delta < delta < nxt.delta
    w = (delta - start.delta) / (nxt.delta - start.delta)
    assert rim_load(d, r) == pytest.approx((1 - w) * start.P + w * nxt.P, rel=5e-4)
    dP_ddelta = start.slope[1] / start.slope[0]
    assert rim_load(d, r) == pytest.approx(start.P + dP_ddelta * push, rel=1e-4)
    assert _fold(path.states[:k + 2]) == k + 1


@pytest.mark.slow
def test_the_fine_mesh_loading_does_not_run_back_down_its_own_branch():
    """t/R 0.02, h/R 1 on the fine mesh (29,457 dofs) to 5 t, about 4.5 minutes.  At 4.91 t
    (where the coarser meshes' soft contact folds) the continuation used to turn round
    onto the branch it came along and retrace the loading to delta < 0 (830 states).
    A loading that comes back off the plane now returns to where it turned and pushes the
    rim on (`snap._jump`, onward): the branch goes on past 4.91 t and the path reaches 5 t,
    still a disc and a ring (measured: 5.02 t, P 1.107e-3 C10 R^2; the snap comes later on
    this mesh)."""
    T = 0.02
    _, path = trace_shell(T, 1.0, "fine", 5 * T)
    assert path.ended_by == "" and path.states[-1].delta >= 5 * T
    D = path.array("delta")
    assert D.min() >= 0.0 and not path.jumps()
    assert path.states[-1].P == pytest.approx(1.107e-3, rel=0.01)
    assert _energy_miss(path) < ENERGY
