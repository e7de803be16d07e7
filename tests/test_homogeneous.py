"""Validation 1: homogeneous deformations of an incompressible neo-Hookean cylinder.

A cylinder of radius 1 and height 1 (axisymmetric block), meshed with the solver's own
Q2/Q1 elements.  Uniaxial: axial stretch lam, lateral surface free, sigma_zz =
2 C10 (lam^2 - 1/lam).  Equibiaxial: radial stretch lam, top free, sigma_rr =
2 C10 (lam^2 - lam^-4).  The FE field is linear, so the discrete solution is exact.
"""
import types

import numpy as np
import pytest
from skfem import MeshQuad1, MeshQuad2

from shell_adhesion.solver.contact import Constraints
from shell_adhesion.solver.forms import discretise, deformation
from shell_adhesion.solver.material import cauchy_stress
from shell_adhesion.solver.path import Settings, Timer, _Problem

C10 = 0.7


def _block():
    m = MeshQuad2.from_mesh(MeshQuad1.init_tensor(np.linspace(0, 1, 4), np.linspace(0, 1, 3)))
    block = types.SimpleNamespace(mesh=m, nodes=m.doflocs, outer=np.zeros(0, dtype=int))
    return discretise(block, C10=C10), m.doflocs


def _solve(d, fixed, driven, delta):
    fixed = np.unique(np.concatenate([fixed, driven]))
    mask = np.ones(d.ndof, dtype=bool)
    mask[fixed] = False
    free = np.flatnonzero(mask)
    pos = np.full(d.ndof, -1)
    pos[free] = np.arange(len(free))
    c = Constraints(fixed, free, driven, pos)
    pb = _Problem(d, "no_slip", Settings(), Timer())
    x = np.zeros(d.ndof)
    for step in np.linspace(0, delta, 6)[1:]:     # a few load increments
        x, _, _, r, _ = pb.newton(c, x, step)
    return x, r


@pytest.mark.parametrize("lam", [0.7, 1.3, 2.0])
def test_uniaxial(lam):
    d, (r0, z0) = _block()
    n2 = d.n2
    axis, bottom, top = np.flatnonzero(r0 < 1e-12), np.flatnonzero(z0 < 1e-12), np.flatnonzero(z0 > 1 - 1e-12)
    x, res = _solve(d, np.concatenate([axis, n2 + bottom]), n2 + top, -(lam - 1.0))
    force = res[n2 + top].sum()
    area = np.pi * lam ** -1                      # deformed cross-section
    expected = 2 * C10 * (lam ** 2 - 1 / lam)
    assert force / area == pytest.approx(expected, rel=1e-8, abs=1e-8)
    f, p = deformation(d, x)
    s_rr, s_zz, s_tt, s_rz = cauchy_stress(f, p) * C10
    assert np.abs(s_zz - expected).max() < 1e-8
    assert np.abs(s_rr).max() < 1e-8 and np.abs(s_tt).max() < 1e-8 and np.abs(s_rz).max() < 1e-8


@pytest.mark.parametrize("lam", [0.8, 1.25, 1.6])
def test_equibiaxial(lam):
    d, (r0, z0) = _block()
    n2 = d.n2
    axis, bottom, side = np.flatnonzero(r0 < 1e-12), np.flatnonzero(z0 < 1e-12), np.flatnonzero(r0 > 1 - 1e-12)
    x, res = _solve(d, np.concatenate([axis, n2 + bottom]), side, -(lam - 1.0))
    force = res[side].sum()                       # total radial force over 360 degrees
    area = 2 * np.pi * lam * lam ** -2            # deformed lateral area
    expected = 2 * C10 * (lam ** 2 - lam ** -4)
    assert force / area == pytest.approx(expected, rel=1e-8, abs=1e-8)
    f, p = deformation(d, x)
    s_rr, s_zz, s_tt, s_rz = cauchy_stress(f, p) * C10
    assert np.abs(s_rr - expected).max() < 1e-8 and np.abs(s_tt - expected).max() < 1e-8
    assert np.abs(s_zz).max() < 1e-8
