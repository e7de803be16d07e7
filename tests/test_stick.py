"""The sticking (no_slip) ring contact of the snap's penalty (issue 42, item 3; solver.snap
`interface="no_slip"`, `PenaltyContact.mixed`, cohesive.point_anchors_at): a contact
point is held radially where it touched by a tangential penalty of the normal one's
stiffness, its anchor per quadrature point updated at converged states.

Default tier: the sticking penalty's derivatives against finite differences (well under a
second), bad input, and one sealed unloading sticking from the turn at p_a/C10 0.3378
(about 13 s alone on the shared machine: the one path the energy balance needs).
`slow`: the soft gas (p_a/C10 0.01), n = 1.4, the gas under suction at the turn, the
vented unloading, and the loading sticking from the first touch (about 12 s each).

Measured (t/R 0.02, h/R 1, coarser mesh, pressed frictionless to 5.04 t, then sticking and
sealed): the sticking ring does not pin the pocket.  The dimple springs back towards the
plane as delta falls (its volume goes as the mirror-buckled cap's), so the pocket shrinks
and its gas is compressed; the contact ring moves by rolling (points peel at one edge, new
ones touch and stick at the other), not by sliding; the ring opens under a compressed gas
with P still compressive, where the frictionless ring does (4.69 t, P +2.93e-4): no
tensile force with gamma = 0, sticking or not."""
import math

import numpy as np
import pytest

from shell_adhesion.errors import InputError
from shell_adhesion.solver import pocket as pk
from shell_adhesion.solver.cohesive import Interface, point_anchors_at
from shell_adhesion.solver.forms import discretise, residual, tangent
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.snap import (PenaltyContact, SnapSettings, loading_cap, ring_arc,
                                        trace_loading, trace_shell)

ENERGY = 1e-4        # |work of P - U - Pi - E_gas + anchor jumps| / max U along the path
P_ATM = pk.p_atm_over_C10(101.325, 300.0)
T, DELTA_MAX = 0.02, 0.1


def _d(delta_max=DELTA_MAX, mesh="coarser"):
    return discretise(cap_mesh(loading_cap(T, 1.0), mesh_spec(mesh, ring_arc(delta_max))))


def test_sticking_penalty_derivatives_against_finite_differences():
    law = PenaltyContact(1e4, 1e-4)
    rng = np.random.default_rng(0)
    g = rng.uniform(-3e-4, 1e-4, 200)      # (the slopes' kinks at 0 and -onset missed)
    s = rng.uniform(-1e-3, 1e-3, g.size)
    Phi, Pg, Ps, Pgg, Pgs, Pss = law.mixed(1.0, g, s)
    h = 1e-9

    def f(gg, ss):
        return np.array(law.mixed(1.0, gg, ss)[:3])
    dg = (f(g + h, s) - f(g - h, s)) / (2 * h)
    ds = (f(g, s + h) - f(g, s - h)) / (2 * h)
    for k, (a, b) in enumerate(((Pg, Ps), (Pgg, Pgs), (Pgs, Pss))):
        scale = np.abs(a).max() + np.abs(b).max()
        assert np.abs(dg[k] - a).max() <= 1e-5 * scale
        assert np.abs(ds[k] - b).max() <= 1e-5 * scale
    # off the plane nothing acts; without slip it is the frictionless penalty
    off = g >= 0
    assert np.all(np.array(law.mixed(1.0, g[off], s[off])) == 0.0)
    assert np.array_equal(law.mixed(1.0, g, 0 * s)[0], law(g)[0])
    # beyond the onset the tangential stiffness is the normal one
    deep = g < -1e-4
    assert np.allclose(Pss[deep], 1e4) and np.allclose(Ps[deep], 1e4 * s[deep])


def test_sticking_interface_residual_and_tangent_against_finite_differences():
    d = _d(0.02)
    iface = Interface(d, PenaltyContact(1e4, 1e-4), 1.0)
    cm = d.capmesh
    r0 = cm.nodes[0]
    x = np.zeros(d.ndof)
    x[d.uz(np.arange(cm.nodes.shape[1]))] = -4e-4 + 1e-3 * np.exp(-(r0 / 0.005) ** 2)
    anchors = point_anchors_at(iface, x)           # every point: its radius here
    rng = np.random.default_rng(3)
    x[d.ur(np.setdiff1d(np.arange(cm.nodes.shape[1]), cm.axis))] += 2e-4 * rng.standard_normal(
        cm.nodes.shape[1] - len(cm.axis))
    _, z, _ = iface._points(x)
    assert (z < -1e-4).any() and ((z < 0) & (z > -1e-4)).any() and (z > 0).any()
    K, r = iface.add(x, *tangent(d, x), anchors)
    v = rng.standard_normal(d.ndof) * 1e-4
    h = 1e-6
    fd = (iface.energy(x + h * v, anchors) - iface.energy(x - h * v, anchors)) / (2 * h)
    f = iface.residual(x, anchors)
    assert abs(fd - f @ v) <= 1e-6 * np.abs(f).max() * np.abs(v).sum()
    fd = (residual(d, x + h * v) + iface.residual(x + h * v, anchors)
          - residual(d, x - h * v) - iface.residual(x - h * v, anchors)) / (2 * h)
    assert np.abs(fd - K @ v).max() <= 1e-5 * np.abs(K @ v).max()
    # the tangential part is there: the slip is held
    assert np.abs(iface.residual(x, anchors) - Interface(
        d, PenaltyContact(1e4, 1e-4)).residual(x)).max() > 0
    # anchors move only off the plane (where nothing acts): the energy does not change
    moved = point_anchors_at(iface, x, anchors)
    assert np.array_equal(moved[z < 0], anchors[z < 0]) and not np.array_equal(moved, anchors)
    assert iface.energy(x, moved) == iface.energy(x, anchors)


@pytest.mark.parametrize("call", [
    lambda: trace_shell(T, 1.0, "coarser", 0.02, interface="sticky"),
    lambda: trace_loading(_d(0.02), 0.02, interface="friction")])
def test_sticking_refuses_bad_interface(call):
    with pytest.raises(InputError, match="^interface: ") as err:
        call()
    assert "\n" not in str(err.value) and "must be one of" in str(err.value)


def _unloading(mode, n, unload_to, p_atm=P_ATM, mesh="coarser", **kw):
    """Pressed frictionless to DELTA_MAX, then sticking (and sealed at the turn)."""
    d = pk.bind(_d(mesh=mesh), pk.Pocket(mode, p_atm, n))
    settings = SnapSettings(**{**dict(seal_at_turn=True, stick_at_turn=True),
                               **kw})
    return trace_loading(d, DELTA_MAX, settings, unload_to=unload_to, interface="no_slip")


def _energy_miss(path):
    """Along the sticking part (from the turn; from the start if it sticks from the
    first touch): the work of P against U + Pi (both parts of the penalty) + E_gas, the
    anchor jumps before each state taken off (cohesive design; 0 here by construction),
    relative to max U.  (The frictionless loading before the turn: tests/test_snap.py.)"""
    W, U = path.work(), path.array("U")
    J = np.concatenate([[0.0], np.cumsum(path.array("anchor_jump"))[:-1]])
    miss = W - U - path.array("Pi") - path.array("E_gas") + J
    k = max(path.turn, 0)
    return float(np.abs(miss[k:] - miss[k]).max() / U.max())


def _sticking_checks(path, n, p_atm, energy=True):
    """Pressed through the snap, sticking and sealed at the turn; the energy balances;
    the tangential penalty acts; P stays compressive until the ring opens."""
    assert path.jumps() and path.turn > path.jumps()[0].i_to
    turn = path.states[path.turn]
    assert turn.ring and turn.sealed
    assert np.all(path.array("anchor_jump") == 0.0)
    if energy:
        assert _energy_miss(path) <= ENERGY
    assert path.ended_by.startswith("pocket opened")
    sealed = path.states[path.turn:]
    for s in sealed:
        assert (s.p + p_atm) * s.V ** n == pytest.approx(p_atm * turn.V ** n, rel=1e-8)
    P = np.array([s.P for s in sealed])
    ideal = p_atm * math.pi * max(s.r_seal for s in sealed) ** 2
    assert -P.min() <= ideal
    last = sealed[-1]
    assert P.min() > 0 and last.p > 0 and last.V < turn.V     # compressed, no tension
    return last


def test_sticking_sealed_unloading_conserves_energy_and_gives_no_tension():
    path = _unloading("sealed", 1.0, -T)
    last = _sticking_checks(path, 1.0, P_ATM)
    # the balance sees the gas: its energy reaches 2e-4 of max U (twice the tolerance)
    E = path.array("E_gas")
    assert np.abs(E).max() > 2 * ENERGY * path.array("U").max()
    # the tangential penalty holds slip: Pi exceeds the normal penalty's alone
    d = pk.bind(_d(), pk.Pocket("sealed", P_ATM, 1.0))
    plain = Interface(d, PenaltyContact(1e4, 1e-4))
    extra = [s.Pi - plain.energy(s.x) for s in path.states[path.turn + 1:]]
    assert max(extra) > 0 and min(extra) >= 0
    # docs/thin-shells.md: opens at 4.69 t under +6.42e-4 C10 with P +2.93e-4, as the
    # frictionless ring does (4.69 t, +6.42e-4, +2.93e-4); the gas alone holds the rim
    assert last.delta / T == pytest.approx(4.69, abs=0.005)
    assert last.P == pytest.approx(2.93e-4, abs=0.005e-4)
    assert last.p == pytest.approx(6.42e-4, abs=0.005e-4)
    assert last.P == pytest.approx(last.p * math.pi * last.r_seal ** 2, rel=1e-3)
    # pull-off 0 of the ideal suction force p_a pi r_seal^2 (largest seal radius) 0.156
    r_max = max(s.r_seal for s in path.states[path.turn:])
    assert P_ATM * math.pi * r_max ** 2 == pytest.approx(0.156, abs=5e-4)


@pytest.mark.slow
def test_sticking_sealed_soft_gas():
    # p_a / C10 = 0.01 (the gas's energy well above the tolerance): the same, opens at
    # 4.58 t with P +2.88e-4, as frictionless
    path = _unloading("sealed", 1.0, -T, 0.01)
    last = _sticking_checks(path, 1.0, 0.01)
    assert np.abs(path.array("E_gas")).max() > 10 * ENERGY * path.array("U").max()
    print("RESULT soft", last.delta / T, last.P, last.p, _energy_miss(path))
    assert last.delta / T == pytest.approx(4.58, abs=0.005)
    assert last.P == pytest.approx(2.88e-4, abs=0.01e-4)


@pytest.mark.slow
@pytest.mark.parametrize("n", [1.4])
def test_sticking_sealed_pocket_at_ambient_pressure(n):
    path = _unloading("sealed", n, -T)
    last = _sticking_checks(path, n, P_ATM)
    print("RESULT", n, last.delta / T, last.P, last.p, last.r_seal, _energy_miss(path))
    # docs/thin-shells.md: n = 1.4 opens as n = 1 does, 4.69 t with P +2.93e-4
    assert last.delta / T == pytest.approx(4.69, abs=0.005)
    assert last.P == pytest.approx(2.93e-4, abs=0.005e-4)


@pytest.mark.slow
def test_sticking_vented_unloading_has_no_tensile_force():
    path = _unloading("vented", 1.0, 3 * T)
    assert path.turn > 0 and not any(s.sealed for s in path.states)
    P = path.array("P")
    assert P.min() >= -1e-9 * P.max()
    print("RESULT vented", path.ended_by, path.states[-1].delta / T, _energy_miss(path))
    assert _energy_miss(path) <= ENERGY


@pytest.mark.slow
def test_sticking_from_the_first_touch_does_not_snap():
    # sticking from the first touch, the flattened disc does not invert: no jump, the
    # contact stays a disc with at most a lift of the centre far below a thickness
    d = _d()
    path = trace_loading(d, DELTA_MAX, SnapSettings(), interface="no_slip")
    print("RESULT touch", path.ended_by, len(path.states), max(s.apex_gap for s in path.states) / T, _energy_miss(path))
    assert path.ended_by == "" and not path.jumps()
    assert np.all(path.array("anchor_jump") == 0.0)
    assert max(s.apex_gap for s in path.states) < 0.01 * T
    assert _energy_miss(path) <= ENERGY


@pytest.mark.slow
def test_sticking_with_the_gas_under_suction():
    # sealed at the first ring lifted by a thickness with a soft gas (p_a / C10 = 0.001):
    # the dimple grows under the press and the gas expands (-0.86 p_a at the turn); the
    # ring sticks from the turn.  Unloading, the suction falls as the dimple recovers,
    # the gas is compressed and the ring opens with P compressive, where the
    # frictionless ring does (1.75 t, P +1.87e-4)
    p_atm = 0.001
    path = _unloading("sealed", 1.0, -5 * T, p_atm, seal_at_turn=False, seal_lift=1.0)
    turn = path.states[path.turn]
    assert turn.sealed and turn.p / p_atm == pytest.approx(-0.86, abs=0.005)
    assert np.all(path.array("anchor_jump") == 0.0)
    assert _energy_miss(path) <= ENERGY
    P = path.array("P")[path.turn:]
    last = path.states[-1]
    print("RESULT suction", last.delta / T, last.P, last.p / p_atm, P.min(), _energy_miss(path))
    assert path.ended_by.startswith("pocket opened") and P.min() > 0 and last.p > 0
    assert last.delta / T == pytest.approx(1.75, abs=0.005)
    assert last.P == pytest.approx(1.87e-4, abs=0.005e-4)
