"""The closed cavity (solver.cavity): follower pressure, enclosed volume, sealed gas.

Closed form: an incompressible neo-Hookean thick-walled sphere (radii A < B, shear modulus
mu = 2 C10) inflated to inner stretch la = a / A has outer stretch lb = b / B with
b^3 - a^3 = B^3 - A^3 and internal pressure

    p = mu (2 / lb + 1 / (2 lb^4) - 2 / la - 1 / (2 la^4)),

the integral of 2 (sigma_tt - sigma_rr) / r = 2 mu (l^2 - l^-4) / r over the wall.  A
hemisphere (h = R) with a roller rim (u_z = 0, u_r free) is half of that sphere.
"""
import numpy as np
import pytest
from scipy.integrate import quad

from shell_adhesion.solver.cavity import Cavity, bind, pressurise
from shell_adhesion.solver.contact import Constraints
from shell_adhesion.solver.forms import discretise, residual, tangent
from shell_adhesion.solver.geometry import Cap, InputError
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec

P_ATM = 101.325e-3 / 0.3          # the atmosphere over the base shell's C10


def sphere_pressure(la, A, B, mu=2.0):
    """Internal pressure / C10 of the thick sphere at inner stretch la (closed form)."""
    c = (la * A) ** 3 - A ** 3
    lb = (B ** 3 + c) ** (1 / 3) / B
    return mu * (2 / lb + 1 / (2 * lb ** 4) - 2 / la - 1 / (2 * la ** 4))


def test_sphere_closed_form_is_the_wall_integral():
    A, B, la = 0.7, 1.0, 1.3
    c = (la * A) ** 3 - A ** 3
    lam = lambda r: r / (r ** 3 - c) ** (1 / 3)
    integral = quad(lambda r: 4 * (lam(r) ** 2 - lam(r) ** -4) / r, la * A,
                    (B ** 3 + c) ** (1 / 3), epsabs=1e-13)[0]
    assert sphere_pressure(la, A, B) == pytest.approx(integral, rel=1e-10)


def roller(d):
    """Axis u_r = 0 and the rim face on rollers (u_z = 0, u_r free): half a sphere."""
    cm = d.capmesh
    fixed = np.unique(np.concatenate([cm.axis, d.n2 + cm.rim]))
    mask = np.ones(d.ndof, dtype=bool)
    mask[fixed] = False
    free = np.flatnonzero(mask)
    pos = np.full(d.ndof, -1)
    pos[free] = np.arange(len(free))
    return Constraints(fixed, free, d.n2 + cm.rim, pos)


def test_thick_sphere_inflation():
    t = 0.3
    A = 1 - t
    p_end = sphere_pressure(1.3, A, 1.0)
    d = bind(discretise(cap_mesh(Cap(t, 1.0), mesh_spec("coarse"))),
             Cavity("pressure", p=p_end, p_atm=P_ATM))
    cm = d.capmesh
    apex = cm.inner[np.argmin(np.hypot(*(cm.nodes[:, cm.inner] - [[0.0], [t]])))]
    rim = cm.inner[np.argmax(cm.nodes[0, cm.inner])]
    pr = pressurise(d, c=roller(d), steps=6)
    assert len(pr.ramp) >= 6
    worst = 0.0
    for p, V, x in pr.ramp:
        la = (1.0 - cm.nodes[1, apex] - x[d.n2 + apex]) / A
        la_rim = (cm.nodes[0, rim] + x[rim]) / A
        assert la_rim == pytest.approx(la, rel=1e-3)
        assert V == pytest.approx(2 / 3 * np.pi * (la * A) ** 3, rel=5e-3)
        worst = max(worst, abs(p / sphere_pressure(la, A, 1.0) - 1))
    assert la == pytest.approx(1.3, rel=2e-3)
    assert worst <= 5e-3, worst


def _state(d):
    r0, z0 = d.capmesh.nodes
    n2, n1 = d.n2, d.n1
    x = np.zeros(d.ndof)
    x[:n2] = 0.05 * r0 * np.sin(3 * z0)
    x[n2: 2 * n2] = 0.03 * np.cos(2 * r0) * z0
    x[2 * n2: 2 * n2 + n1] = 0.2 * np.cos(np.arange(n1))
    v = np.zeros(d.ndof)
    v[:n2], v[n2: 2 * n2], v[2 * n2: 2 * n2 + n1] = r0 * np.cos(5 * z0), np.sin(4 * r0), 1.0
    return x, v


@pytest.mark.parametrize("cavity", [Cavity("pressure", p=0.3, p_atm=P_ATM),
                                    Cavity("pressure", p=-0.2, p_atm=P_ATM),
                                    Cavity("sealed", p0=0.05, p_atm=P_ATM, n=1.4)])
def test_tangent_matches_finite_differences(cavity):
    d = bind(discretise(cap_mesh(Cap(0.15, 1.0), mesh_spec("coarse"))), cavity)
    x, v = _state(d)
    if cavity.sealed:
        x[-1], v[-1] = 0.1, 0.7
    K, r = tangent(d, x)
    assert K.shape == (d.ndof, d.ndof)
    assert np.array_equal(r, residual(d, x))
    assert abs(K - K.T).max() <= 1e-12 * abs(K).max()
    eps = 1e-6
    fd = (residual(d, x + eps * v) - residual(d, x - eps * v)) / (2 * eps)
    assert np.abs(fd - K @ v).max() <= 1e-7 * np.abs(K @ v).max()
    if cavity.sealed:   # the gas row alone: V_gas(p) - V(x)
        assert abs(fd[-1] - (K @ v)[-1]) <= 1e-7 * abs((K @ v)[-1])


def test_volume_gradient_is_the_pressure_load():
    """The nodal load of a unit pressure is dV/dx: V is homogeneous of degree 2 in r and 1
    in z (from the centre), and invariant under a z translation (the lid moves with it)."""
    d0 = discretise(cap_mesh(Cap(0.15, 0.8), mesh_spec("coarse")))
    d = bind(d0, Cavity("pressure", p=1.0, p_atm=P_ATM))
    cap = d.capmesh.cap
    hi = cap.h - cap.t
    V_exact = np.pi * hi ** 2 * (3 * (1 - cap.t) - hi) / 3
    assert d.cavity.V0 == pytest.approx(V_exact, rel=1e-5)   # Q2 arcs of the sphere
    f = -residual(d, np.zeros(d.ndof))   # the pressure's nodal forces (x = 0: no stress)
    r0, z0 = d.capmesh.nodes
    assert f[: d.n2] @ r0 == pytest.approx(2 * d.cavity.V0, rel=1e-12)
    assert f[d.n2: 2 * d.n2] @ (z0 - 1.0) == pytest.approx(d.cavity.V0, rel=1e-12)
    assert f[d.n2: 2 * d.n2].sum() == pytest.approx(0.0, abs=1e-12)


def test_cavity_input_rules():
    with pytest.raises(InputError, match="negative absolute pressure"):
        Cavity("pressure", p=-0.5, p_atm=0.3)
    with pytest.raises(InputError, match="needs cavity pressure"):
        Cavity("sealed", p=0.1, p_atm=0.3)
    with pytest.raises(InputError, match=">= 1"):
        Cavity("sealed", p_atm=0.3, n=0.9)
    with pytest.raises(InputError, match="solid cap"):
        bind(discretise(cap_mesh(Cap(1.0, 1.0), mesh_spec("coarse"))),
             Cavity("pressure", p=0.1, p_atm=0.3))


def test_zero_pressure_equals_open():
    from shell_adhesion.solver.case import relax_from, relaxation_starts, solve_loading
    d0, open_ = solve_loading(0.15, 1.0, "no_slip", "coarse", 0.03)
    d1, zero = solve_loading(0.15, 1.0, "no_slip", "coarse", 0.03,
                             cavity=Cavity("pressure", p=0.0, p_atm=P_ATM))
    assert d1.cavity is not None and len(open_.states) == len(zero.states)
    for a, b in zip(open_.states, zero.states):
        assert abs(a.delta - b.delta) <= 1e-9 * 0.03
        assert abs(a.P - b.P) <= 1e-9 * abs(open_.states[-1].P)
        assert abs(a.U - b.U) <= 1e-9 * open_.states[-1].U
        assert b.p == 0.0 and b.V > 0
    ra = relax_from(d0, "no_slip", relaxation_starts(open_, d0.capmesh)[-1], 0.006)
    rb = relax_from(d1, "no_slip", relaxation_starts(zero, d1.capmesh)[-1], 0.006)
    Pa, Pb = ra.array("P"), rb.array("P")
    assert Pa.shape == Pb.shape and np.abs(Pa - Pb).max() <= 1e-9 * np.abs(Pa).max()
