"""Profiles, von Mises stress and the total-energy families (fields behind the figures)."""
import numpy as np
import pytest

from shell_adhesion.energy import total_energy_fixed_grips, total_energy_fixed_load
from shell_adhesion.solver.postprocess import profiles, von_mises_field


def test_profiles_and_von_mises(base_coarse):
    ps, d, loading = base_coarse
    outer, inner = profiles(d, np.zeros(d.ndof))
    assert np.allclose(np.hypot(outer[0], outer[1] - 1), 1) and np.allclose(np.hypot(inner[0], inner[1] - 1), 0.85)
    s = loading.states[-1]
    outer, _ = profiles(d, s.x)
    held = outer[:, : max(s.held) + 1]
    assert np.allclose(held[1], 0, atol=1e-12) and held[0, -1] == pytest.approx(s.a)
    assert outer[1].min() >= -1e-12                         # nothing below the plane
    _, _, vm0 = von_mises_field(d, np.zeros(d.ndof))
    assert np.abs(vm0).max() < 1e-12
    r, z, vm = von_mises_field(d, s.x)
    assert vm.min() >= 0 and vm.max() > 0.1 and z.min() > 0


def test_total_energy_minimum_is_the_equilibrium(base_coarse):
    """U_T(A; P) at fixed load has its minimum near the stable equilibrium radius for P,
    and U_T(A; delta) at fixed grips near the equilibrium radius for delta."""
    ps, _, _ = base_coarse
    gamma = 0.005
    surface = ps.surface()
    eq, po = ps.pull_off(gamma, surface)
    stable = np.flatnonzero(eq.stable_fixed_load & (eq.a > 1.5 * po.a_star))
    i = stable[len(stable) // 2]
    A, UT = total_energy_fixed_load(surface, gamma, eq.P[i])
    a_min = np.sqrt(A[np.argmin(UT)] / np.pi)
    spacing = np.diff(surface.a).max()
    assert abs(a_min - eq.a[i]) <= 1.5 * spacing
    A, UT = total_energy_fixed_grips(surface, gamma, eq.delta[i])
    assert abs(np.sqrt(A[np.argmin(UT)] / np.pi) - eq.a[i]) <= 1.5 * spacing


def test_nodal_von_mises_is_exact_for_a_homogeneous_stretch(base_coarse):
    """Uniaxial stretch lam along z of the whole cap (incompressible, any pressure):
    sigma_vm = 2 C10 (lam^2 - 1/lam) at every node, the axis included."""
    from shell_adhesion.solver.postprocess import nodal_von_mises, triangles
    _, d, _ = base_coarse
    lam = 1.3
    r, z = d.capmesh.nodes
    x = np.zeros(d.ndof)
    x[: d.n2] = (lam ** -0.5 - 1) * r
    x[d.n2: 2 * d.n2] = (lam - 1) * z
    x[2 * d.n2:] = 0.37                         # the multiplier does not enter von Mises
    vm = nodal_von_mises(d, x)
    np.testing.assert_allclose(vm, 2 * (lam ** 2 - 1 / lam), rtol=1e-12)
    tri = triangles(d)
    assert tri.shape == (8 * d.capmesh.mesh.nelements, 3)
    # the triangles tile the cross-section: their areas add up to the meridian area
    p = d.capmesh.nodes[:, tri]                 # (2, T, 3)
    area = 0.5 * np.abs((p[0, :, 1] - p[0, :, 0]) * (p[1, :, 2] - p[1, :, 0])
                        - (p[0, :, 2] - p[0, :, 0]) * (p[1, :, 1] - p[1, :, 0]))
    meridian = float(np.sum(d.w / (2 * np.pi * d.r_q)))
    assert area.sum() == pytest.approx(meridian, rel=2e-3)
