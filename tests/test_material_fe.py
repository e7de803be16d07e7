"""The material models inside the FE: consistent assembled tangents, homogeneous
deformations of a block against closed forms, the Gent limit, and exact scaling.

Block: a cylinder of radius 1 and height 1 (axisymmetric), meshed with the solver's own
Q2/Q1 elements; the homogeneous field is in the FE space, so the discrete solution is exact.
"""
import types

import numpy as np
import pytest
from skfem import MeshQuad1, MeshQuad2

from shell_adhesion.solver.contact import Constraints, constraints
from shell_adhesion.solver.forms import deformation, discretise, residual, tangent
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.material import Material, cauchy_stress, limit_exceeded, limit_state
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec, scaled
from shell_adhesion.solver.path import LOCK_UP, Settings, Timer, _Problem, load
from shell_adhesion.errors import ConvergenceError, MaterialLimitError

C10 = 0.7
MATERIALS = {
    "mooney_rivlin": Material("mooney_rivlin", C01_over_C10=0.25),
    "yeoh": Material("yeoh", C20_over_C10=-0.03, C30_over_C10=0.004),
    "gent": Material("gent", Jm=20.0),
    "neo_hooke_D1": Material(D1_times_C10=0.05),
    "mooney_rivlin_D1": Material("mooney_rivlin", C01_over_C10=0.25, D1_times_C10=0.05),
    "yeoh_D1": Material("yeoh", C20_over_C10=-0.03, C30_over_C10=0.004, D1_times_C10=0.05),
    "gent_D1": Material("gent", Jm=20.0, D1_times_C10=0.05),
}
# W1 = dW/dI1 (units of C10) and W2 = C01/C10, independent of the solver
W1 = {"neo_hooke": lambda I1: 1.0, "mooney_rivlin": lambda I1: 1.0,
      "yeoh": lambda I1: 1 - 0.06 * (I1 - 3) + 0.012 * (I1 - 3) ** 2,
      "gent": lambda I1: 20.0 / (20.0 - (I1 - 3))}
W2 = {"neo_hooke": 0.0, "mooney_rivlin": 0.25, "yeoh": 0.0, "gent": 0.0}
INCOMPRESSIBLE = ["mooney_rivlin", "yeoh", "gent"]


@pytest.mark.parametrize("name", list(MATERIALS))
def test_assembled_tangent_matches_finite_differences(name):
    d = discretise(cap_mesh(Cap(0.15, 1.0), mesh_spec("coarse")), material=MATERIALS[name])
    r0, z0 = d.capmesh.nodes
    x = np.zeros(d.ndof)
    x[: d.n2] = 0.05 * r0 * np.sin(3 * z0)
    x[d.n2: 2 * d.n2] = 0.03 * np.cos(2 * r0) * z0
    x[2 * d.n2:] = 0.2 * np.cos(np.arange(d.n1))
    v = np.zeros(d.ndof)
    v[: d.n2], v[d.n2: 2 * d.n2], v[2 * d.n2:] = r0 * np.cos(5 * z0), np.sin(4 * r0), 1.0
    K, r = tangent(d, x)
    assert np.array_equal(r, residual(d, x))
    eps = 1e-6
    fd = (residual(d, x + eps * v) - residual(d, x - eps * v)) / (2 * eps)
    assert np.abs(fd - K @ v).max() <= 1e-7 * np.abs(K @ v).max()
    assert abs(K - K.T).max() <= 1e-12 * abs(K).max()
    # same sparsity as the incompressible neo-Hookean tangent
    K0, _ = tangent(discretise(d.capmesh), x)
    assert np.array_equal(K.indices, K0.indices) and np.array_equal(K.indptr, K0.indptr)


def test_compressible_newton_converges_quadratically():
    d = discretise(cap_mesh(Cap(0.15, 1.0), mesh_spec("coarse")),
                   material=Material("mooney_rivlin", C01_over_C10=0.25, D1_times_C10=0.05))
    pb = _Problem(d, "no_slip", Settings(max_iter=30), Timer())
    c = constraints(d, "no_slip", list(range(7)))
    _, _, _, _, history = pb.newton(c, np.zeros(d.ndof), 0.03)
    e = np.array(history)
    e = e[e > 1e-12]
    assert len(e) >= 4, history
    orders = np.log(e[2:] / e[1:-1]) / np.log(e[1:-1] / e[:-2])
    assert orders[-1] > 1.7, (history, orders)


def _block(material):
    m = MeshQuad2.from_mesh(MeshQuad1.init_tensor(np.linspace(0, 1, 4), np.linspace(0, 1, 3)))
    block = types.SimpleNamespace(mesh=m, nodes=m.doflocs, outer=np.zeros(0, dtype=int))
    return discretise(block, C10=C10, material=material), m.doflocs


def _solve(d, fixed, driven, delta, steps=5):
    fixed = np.unique(np.concatenate([fixed, driven]))
    mask = np.ones(d.ndof, dtype=bool)
    mask[fixed] = False
    free = np.flatnonzero(mask)
    pos = np.full(d.ndof, -1)
    pos[free] = np.arange(len(free))
    c = Constraints(fixed, free, driven, pos)
    pb = _Problem(d, "no_slip", Settings(), Timer())
    x = np.zeros(d.ndof)
    for step in np.linspace(0, delta, steps + 1)[1:]:
        x, _, _, r, _ = pb.newton(c, x, step)
    return x, r


@pytest.mark.parametrize("model", INCOMPRESSIBLE)
@pytest.mark.parametrize("lam", [0.7, 1.6])
def test_block_uniaxial(model, lam):
    d, (r0, z0) = _block(MATERIALS[model])
    n2 = d.n2
    axis, bottom, top = (np.flatnonzero(r0 < 1e-12), np.flatnonzero(z0 < 1e-12),
                         np.flatnonzero(z0 > 1 - 1e-12))
    x, res = _solve(d, np.concatenate([axis, n2 + bottom]), n2 + top, -(lam - 1.0))
    I1 = lam ** 2 + 2 / lam
    expected = 2 * C10 * (lam ** 2 - 1 / lam) * (W1[model](I1) + W2[model] / lam)
    assert res[n2 + top].sum() / (np.pi / lam) == pytest.approx(expected, rel=1e-8, abs=1e-8)
    f, p = deformation(d, x)
    s_rr, s_zz, s_tt, s_rz = cauchy_stress(f, p, d.material) * C10
    assert np.abs(s_zz - expected).max() < 1e-8
    assert np.abs(s_rr).max() < 1e-8 and np.abs(s_tt).max() < 1e-8 and np.abs(s_rz).max() < 1e-8


@pytest.mark.parametrize("model", INCOMPRESSIBLE)
@pytest.mark.parametrize("lam", [0.8, 1.4])
def test_block_equibiaxial(model, lam):
    d, (r0, z0) = _block(MATERIALS[model])
    n2 = d.n2
    axis, bottom, side = (np.flatnonzero(r0 < 1e-12), np.flatnonzero(z0 < 1e-12),
                          np.flatnonzero(r0 > 1 - 1e-12))
    x, res = _solve(d, np.concatenate([axis, n2 + bottom]), side, -(lam - 1.0))
    I1 = 2 * lam ** 2 + lam ** -4
    expected = 2 * C10 * (lam ** 2 - lam ** -4) * (W1[model](I1) + lam ** 2 * W2[model])
    assert res[side].sum() / (2 * np.pi * lam ** -1) == pytest.approx(expected, rel=1e-8, abs=1e-8)
    f, p = deformation(d, x)
    s_rr, s_zz, s_tt, _ = cauchy_stress(f, p, d.material) * C10
    assert np.abs(s_rr - expected).max() < 1e-8 and np.abs(s_tt - expected).max() < 1e-8
    assert np.abs(s_zz).max() < 1e-8


@pytest.mark.parametrize("name", ["neo_hooke_D1", "mooney_rivlin_D1", "yeoh_D1", "gent_D1"])
@pytest.mark.parametrize("lam", [0.96, 1.03])
def test_block_dilation(name, lam):
    """All faces moved out by lam: sigma = p I = 2 (J - 1) / D1, J = lam^3."""
    m = MATERIALS[name]
    d, (r0, z0) = _block(m)
    n2 = d.n2
    axis, bottom = np.flatnonzero(r0 < 1e-12), np.flatnonzero(z0 < 1e-12)
    side, top = np.flatnonzero(r0 > 1 - 1e-12), np.flatnonzero(z0 > 1 - 1e-12)
    x, res = _solve(d, np.concatenate([axis, n2 + bottom]), np.concatenate([side, n2 + top]),
                    -(lam - 1.0), steps=2)
    D1 = m.D1_times_C10 / C10                                  # 1/MPa
    expected = 2 * (lam ** 3 - 1) / D1
    f, p = deformation(d, x)
    sigma = cauchy_stress(f, p, m) * C10
    np.testing.assert_allclose(sigma[:3], expected, rtol=1e-9)
    assert np.abs(sigma[3]).max() < 1e-9 * abs(expected)
    assert res[n2 + top].sum() / (np.pi * lam ** 2) == pytest.approx(expected, rel=1e-9)


def test_gent_limit_fails_the_newton_step():
    """A state beyond I1bar - 3 = Jm is refused with the reason, never a NaN."""
    d, (r0, z0) = _block(Material("gent", Jm=0.5))
    n2 = d.n2
    axis, bottom, top = (np.flatnonzero(r0 < 1e-12), np.flatnonzero(z0 < 1e-12),
                         np.flatnonzero(z0 > 1 - 1e-12))
    # uniaxial lam = 1.25: I1 - 3 = 0.16 < Jm is reached; lam = 1.6: I1 - 3 = 0.81 is not
    x, res = _solve(d, np.concatenate([axis, n2 + bottom]), n2 + top, -0.25, steps=10)
    I1 = 1.25 ** 2 + 2 / 1.25
    expected = 2 * C10 * (1.25 ** 2 - 1 / 1.25) * 0.5 / (0.5 - (I1 - 3))
    assert res[n2 + top].sum() / (np.pi / 1.25) == pytest.approx(expected, rel=1e-8)
    with pytest.raises(ConvergenceError, match=r"gent limit reached: I1bar - 3 = .* >= Jm = 0.5"):
        _solve(d, np.concatenate([axis, n2 + bottom]), n2 + top, -0.6, steps=1)


def test_gent_shell_near_lock_up_loads():
    """Trial iterates beyond the limit only cut the step: a Gent shell with a small Jm loads
    to delta = R/4 with every state inside the limit (and close to it)."""
    m = Material("gent", Jm=0.05)
    d = discretise(cap_mesh(Cap(0.15, 1.0), mesh_spec("coarse")), material=m)
    path = load(d, "no_slip", 0.25)
    assert path.states[-1].delta == pytest.approx(0.25)
    assert np.all(np.isfinite(path.array("P"))) and np.all(np.isfinite(path.array("U")))
    worst = max(limit_exceeded(deformation(d, s.x)[0], m) for s in path.states)
    assert 0.5 < worst < 1.0


def test_gent_lock_up_ends_the_loading_with_the_reason():
    """A Gent shell whose Jm the loading cannot stay under stops with MaterialLimitError
    at a converged state within 1 % of Jm (never NaN, never a generic stall)."""
    m = Material("gent", Jm=0.001)
    d = discretise(cap_mesh(Cap(0.15, 1.0), mesh_spec("coarse")), material=m)
    with pytest.raises(MaterialLimitError) as info:
        load(d, "no_slip", 0.25)
    e = info.value
    assert LOCK_UP <= e.ratio < 1.0
    assert 0.0 < e.delta < 0.25 and np.isfinite(e.I1bar) and 1.0 < e.stretch < 1.1
    assert e.I1bar - 3 == pytest.approx(e.ratio * 0.001, rel=1e-9)
    text = str(e)
    assert "locks up at delta" in text and "Jm = 0.001" in text and "np." not in text


def test_limit_state_of_a_uniaxial_stretch():
    """limit_state finds I1bar and the largest principal stretch of a homogeneous state."""
    lam = 1.2
    f = np.array([1 / np.sqrt(lam), 0.0, 0.0, lam, 1 / np.sqrt(lam)])[:, None]
    ratio, I1bar, stretch = limit_state(f, Material("gent", Jm=2.0))
    assert I1bar == pytest.approx(lam ** 2 + 2 / lam, rel=1e-12)
    assert ratio == pytest.approx((I1bar - 3) / 2.0, rel=1e-12)
    assert stretch == pytest.approx(lam, rel=1e-12)
    assert limit_state(f, Material()) is None


def _events(L, C10_, material):
    cm = scaled(cap_mesh(Cap(0.15, 1.0), mesh_spec("coarse")), L)
    ev = load(discretise(cm, C10=C10_, material=material), "no_slip", 0.06 * L).events
    return (np.array([s.delta for s in ev]), np.array([s.P for s in ev]),
            np.array([s.a for s in ev]), np.array([s.U for s in ev]))


@pytest.mark.parametrize("name", ["mooney_rivlin", "mooney_rivlin_D1"])
def test_scaling_mooney_rivlin_shell(name):
    """At fixed ratios C01/C10 and D1 C10, P scales by C10 L^2 and U by C10 L^3."""
    m = MATERIALS[name]
    d1, P1, a1, U1 = _events(1.0, 1.0, m)
    d2, P2, a2, U2 = _events(2.0, 3.0, m)
    assert len(d1) == len(d2) > 10
    np.testing.assert_allclose(d2, 2 * d1, rtol=1e-9, atol=1e-14)
    np.testing.assert_allclose(a2, 2 * a1, rtol=1e-9)
    np.testing.assert_allclose(P2[1:], 12 * P1[1:], rtol=1e-9)
    np.testing.assert_allclose(U2[1:], 24 * U1[1:], rtol=1e-9, atol=24 * 1e-14)
