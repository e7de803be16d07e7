"""Validation 4: exact scaling.  The FE problem is solved in dimensional units (mesh
lengths times L, material constant C10) and compared at the contact events, which are
located exactly: P scales by C10 L^2, delta and a by L, U by C10 L^3."""
import numpy as np
import pytest

from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec, scaled
from shell_adhesion.solver.path import load
from shell_adhesion.solver.scaling import force_N, gamma_hat, gamma_J_m2


def _events(L, C10, interface="no_slip"):
    cm = scaled(cap_mesh(Cap(0.15, 1.0), mesh_spec("coarse")), L)
    path = load(discretise(cm, C10=C10), interface, 0.06 * L)
    ev = path.events
    return (np.array([s.delta for s in ev]), np.array([s.P for s in ev]),
            np.array([s.a for s in ev]), np.array([s.U for s in ev]))


@pytest.fixture(scope="module")
def reference():
    return _events(1.0, 1.0)


def test_C10_doubled_doubles_P(reference):
    d1, P1, a1, U1 = reference
    d2, P2, a2, U2 = _events(1.0, 2.0)
    assert len(d1) == len(d2) > 10
    np.testing.assert_allclose(d2, d1, rtol=1e-9, atol=1e-14)
    np.testing.assert_allclose(P2[1:], 2 * P1[1:], rtol=1e-9)
    # U = sum of w (I1bar - 3): at the first states (U ~ 1e-12) that is round-off, 1e-16
    np.testing.assert_allclose(U2[1:], 2 * U1[1:], rtol=1e-9, atol=2 * 1e-14)


def test_lengths_doubled_scale_P_by_four(reference):
    d1, P1, a1, U1 = reference
    d2, P2, a2, U2 = _events(2.0, 1.0)
    assert len(d1) == len(d2) > 10
    np.testing.assert_allclose(d2, 2 * d1, rtol=1e-9, atol=1e-14)
    np.testing.assert_allclose(a2, 2 * a1, rtol=1e-9)
    np.testing.assert_allclose(P2[1:], 4 * P1[1:], rtol=1e-9)
    np.testing.assert_allclose(U2[1:], 8 * U1[1:], rtol=1e-9, atol=8 * 1e-14)


def test_dimensional_edge():
    """gamma / (C10 R) and P = P_hat C10 R^2 with the tool's units (J/m^2, MPa, mm, N)."""
    assert gamma_hat(30.0, 0.3, 20.0) == pytest.approx(0.005)
    assert gamma_J_m2(0.005, 0.3, 20.0) == pytest.approx(30.0)
    assert force_N(0.1, 0.3, 20.0) == pytest.approx(12.0)
