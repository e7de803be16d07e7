"""The mixed-mode cohesive law (solver.cohesive.mixed, an option for no_slip): its
derivatives, its toughness gamma in any mode mix, the edge forces and tangent with slips
against finite differences, beta = 0 as the normal-only law, and the option's bad input
through the API (the command's: test_cohesive_case.py).
The energy balance along a mixed-mode path is in test_cohesive_mixed_path.py."""
import numpy as np
import pytest

from shell_adhesion.solver.arclength import trace
from shell_adhesion.solver.cohesive import MIXED_EPS, CohesiveLaw, Interface, anchors_at, mixed
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.study import cohesive_case as cc

SIGMA0, GAMMA = 0.2, 2e-4        # / C10 and / (C10 R): delta_c = 1e-3 R
LAW = CohesiveLaw(SIGMA0, GAMMA)


@pytest.fixture(scope="module")
def disc():
    return discretise(cap_mesh(Cap(1.0, 1.0), mesh_spec("coarse")))


def _state(d, seed=0):
    """Outer gaps across the whole law (penetration to beyond its reach): the shell
    pushed down by 2e-4 R, plus noise; anchors a delta_c-sized slip away from the nodes."""
    rng = np.random.default_rng(seed)
    x = 1e-5 * rng.standard_normal(d.ndof)
    x[d.n2:2 * d.n2] -= 2e-4
    iface = Interface(d, LAW, 1.0)
    anchors = iface.radii(x) + LAW.delta_c * rng.uniform(-1.5, 1.5, len(d.capmesh.outer))
    return x, anchors


@pytest.mark.parametrize("beta", [1.0, 0.5])
def test_law_derivatives(beta):
    rng = np.random.default_rng(3)
    dc = LAW.delta_c
    g = np.concatenate([rng.uniform(-0.01, 0.0, 500), rng.uniform(0.0, 1.6, 1500)]) * dc
    s = rng.uniform(-2.0, 2.0, g.size) * dc
    P = mixed(LAW, beta, g, s)
    h = 1e-7 * dc
    dg = [(a - b) / (2 * h) for a, b in zip(mixed(LAW, beta, g + h, s), mixed(LAW, beta, g - h, s))]
    ds = [(a - b) / (2 * h) for a, b in zip(mixed(LAW, beta, g, s + h), mixed(LAW, beta, g, s - h))]
    # (analytic, central difference): Phi_g, Phi_s, Phi_gg, Phi_gs (both ways), Phi_ss
    for exact, fd in ((P[1], dg[0]), (P[2], ds[0]), (P[3], dg[1]), (P[4], ds[1]),
                      (P[4], dg[2]), (P[5], ds[2])):
        assert np.abs(exact - fd).max() <= 1e-7 * np.abs(exact).max()
    # DESIGN.md's shear traction where the gap is open: beta^2 sigma_D(l) s / rho
    rho = np.sqrt(np.maximum(g, 0) ** 2 + (beta * s) ** 2 + (MIXED_EPS * dc) ** 2)
    l = g + rho - np.sqrt(np.maximum(g, 0) ** 2 + (MIXED_EPS * dc) ** 2)
    assert np.allclose(P[2], beta ** 2 * LAW.dugdale(l)[1] * s / rho, rtol=1e-12,
                       atol=1e-12 * SIGMA0)


@pytest.mark.parametrize("beta", [1.0, 0.5])
@pytest.mark.parametrize("angle", [0.0, 0.7, np.pi / 2])
def test_toughness_is_gamma_in_any_mode_mix(beta, angle):
    """The work of the tractions along a straight separation from (0, 0) at `angle` from
    the normal is gamma; in pure shear the traction peaks at beta sigma0."""
    t = np.linspace(0.0, 3.0 * LAW.delta_c * max(1.0, 1.0 / beta), 400001)
    g, s = t * np.cos(angle), t * np.sin(angle)
    _, Tn, Tt, *_ = mixed(LAW, beta, g, s)
    assert np.trapezoid(Tn * np.cos(angle) + Tt * np.sin(angle), t) == pytest.approx(GAMMA, rel=1e-6)
    if angle == np.pi / 2:
        assert Tt.max() == pytest.approx(beta * SIGMA0, rel=1e-3)


@pytest.mark.parametrize("beta", [1.0, 0.5])
def test_edge_forces_and_tangent_with_slips(disc, beta):
    d = disc
    iface = Interface(d, LAW, beta)
    x, anchors = _state(d)
    r, z, _ = iface._points(x)
    s = iface._slips(x, anchors)
    near = z < LAW.reach
    # the state has slipping points both open within the law's range and pressed
    assert ((z > 0) & near & (np.abs(s) > 0.1 * LAW.delta_c)).sum() > 10
    assert ((z < 0) & (np.abs(s) > 0.1 * LAW.delta_c)).sum() > 10
    e = np.random.default_rng(1).standard_normal(d.ndof)
    h = 1e-8
    fd = (iface.energy(x + h * e, anchors) - iface.energy(x - h * e, anchors)) / (2 * h)
    assert fd == pytest.approx(iface.residual(x, anchors) @ e, rel=1e-6)
    K0 = discretise.__globals__["tangent"](d, x)[0] * 0       # the FE pattern, no FE part
    Kc, rc = iface.add(x, K0, np.zeros(d.ndof), anchors)
    assert np.abs(rc - iface.residual(x, anchors)).max() == 0.0
    assert abs(Kc - Kc.T).max() <= 1e-12 * abs(Kc).max()
    h = 1e-9
    fdc = (iface.residual(x + h * e, anchors) - iface.residual(x - h * e, anchors)) / (2 * h)
    assert np.abs(fdc - Kc @ e).max() <= 1e-5 * np.abs(Kc @ e).max()
    # the slip terms matter: without slips (anchors at the nodes) the forces differ
    assert np.abs(iface.residual(x, iface.radii(x)) - rc).max() > 1e-2 * np.abs(rc).max()


def test_beta_zero_is_the_normal_only_law(disc):
    d = disc
    x, anchors = _state(d, 4)
    normal, zero = Interface(d, LAW), Interface(d, LAW, 0.0)
    K0 = discretise.__globals__["tangent"](d, x)[0] * 0
    e0, e1 = normal.energy(x), zero.energy(x, anchors)
    assert abs(e1 - e0) <= 1e-12 * abs(e0)
    (K, r), (K1, r1) = normal.add(x, K0, np.zeros(d.ndof)), zero.add(x, K0, np.zeros(d.ndof), anchors)
    assert np.abs(r1 - r).max() <= 1e-12 * np.abs(r).max()
    assert abs(K1 - K).max() <= 1e-12 * abs(K).max()
    # while a beta > 0 law with the same slips is another law
    assert abs(Interface(d, LAW, 1.0).energy(x, anchors) - e0) > 1e-3 * abs(e0)


def test_anchors_follow_held_and_out_of_reach_nodes_only(disc):
    d = disc
    iface = Interface(d, LAW, 1.0)
    x, anchors = _state(d)
    held = np.array([0, 1, 2])
    out = anchors_at(iface, x, anchors, held)
    gap = d.capmesh.nodes[1, d.capmesh.outer] + x[d.uz(d.capmesh.outer)]
    follow = gap >= LAW.reach
    follow[held] = True
    assert np.array_equal(out[follow], iface.radii(x)[follow])
    assert np.array_equal(out[~follow], anchors[~follow]) and (~follow).sum() > 10


def test_history_goes_with_the_law_only(disc):
    d = disc
    x, anchors = _state(d)
    with pytest.raises(ValueError, match="anchors: needed by the mixed-mode law"):
        Interface(d, LAW, 1.0).energy(x)
    with pytest.raises(ValueError, match="anchors: given to the normal-only law"):
        Interface(d, LAW).energy(x, anchors)
    for bad in (-1.0, np.inf, np.nan):
        with pytest.raises(ValueError, match="beta"):
            Interface(d, LAW, bad)
    with pytest.raises(ValueError, match="mixed-mode law .* no_slip only"):
        trace(Interface(d, LAW, 1.0), 1e-3, interface="frictionless")


def test_the_api_names_beta(monkeypatch):
    monkeypatch.setattr(cc, "_solve", lambda *a, **k: (_ for _ in ()).throw(AssertionError))
    with pytest.raises(cc.InputError, match=r"^beta: -0.5 must be >= 0"):
        cc.solve_cohesive_case(20, 3, 20, 0.3, 30, tabor=1.0, interface="no_slip", beta=-0.5)
    with pytest.raises(cc.InputError, match=r"^beta: 1 given with interface frictionless"):
        cc.solve_cohesive_case(20, 3, 20, 0.3, 30, tabor=1.0, beta=1)
    inp = cc.cohesive_input(20, 3, 20, 0.3, 30, tabor=1.0, interface="no_slip", beta=0)
    assert inp.beta == 0.0 and inp.as_dict()["beta"] == 0.0
    assert "beta" not in cc.cohesive_input(20, 3, 20, 0.3, 30, tabor=1.0).as_dict()


def test_no_slip_defaults_to_the_mixed_mode_law_and_the_loading_history():
    """One question, one answer: the cohesive no_slip case forms its contact as the energy
    method's loading does and charges gamma for any mode mix (cohesive_case.NO_SLIP_DEFAULTS);
    the normal-only law and the adhesive history are options."""
    inp = cc.cohesive_input(20, 3, 20, 0.3, 30, tabor=1.0, interface="no_slip")
    assert (inp.beta, inp.history) == (1.0, "loading")
    assert inp.as_dict()["history"] == "loading"
    other = cc.cohesive_input(20, 3, 20, 0.3, 30, tabor=1.0, interface="no_slip", beta=0,
                              history="adhesive")
    assert (other.beta, other.history) == (0.0, "adhesive")
    frictionless = cc.cohesive_input(20, 3, 20, 0.3, 30, tabor=1.0)
    assert frictionless.beta is None and frictionless.history == "adhesive"
