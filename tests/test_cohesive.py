"""The cohesive interface (solver.cohesive): the smoothed Dugdale law keeps Dugdale's
peak stress and work of separation, its forces are the derivative of its energy and its
tangent the derivative of its forces (finite differences), with the FE solid's."""
import numpy as np
import pytest

from shell_adhesion.solver.cohesive import PENALTY_ONSET, CohesiveLaw, Interface
from shell_adhesion.solver.forms import discretise, residual, tangent
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec

SIGMA0, GAMMA = 0.2, 2e-4        # / C10 and / (C10 R): delta_c = 1e-3 R


@pytest.fixture(scope="module")
def iface():
    d = discretise(cap_mesh(Cap(1.0, 1.0), mesh_spec("coarse")))
    return Interface(d, CohesiveLaw(SIGMA0, GAMMA))


@pytest.mark.parametrize("ramp", [0.1, 0.5, 1.0])
def test_law_has_dugdales_peak_and_work(ramp):
    law = CohesiveLaw(SIGMA0, GAMMA, ramp)
    assert law.delta_c == pytest.approx(1e-3)
    g = np.linspace(0.0, law.reach * 1.1, 200001)
    phi, sigma, dsigma = law(g)
    assert sigma.max() == pytest.approx(SIGMA0) and sigma[0] == SIGMA0
    assert np.trapezoid(sigma, g) == pytest.approx(GAMMA, rel=1e-8)
    assert phi[0] == pytest.approx(-GAMMA) and phi[-1] == 0.0 and sigma[-1] == 0.0
    # sigma = phi' and dsigma = sigma' (central differences away from g = 0)
    assert np.allclose(np.gradient(phi, g)[1:-1], sigma[1:-1], atol=1e-6 * SIGMA0)
    assert np.allclose(np.gradient(sigma, g)[2:-1], dsigma[2:-1],
                       atol=1e-4 * SIGMA0 / (ramp * law.delta_c))


def test_penalty_below_the_plane():
    law = CohesiveLaw(SIGMA0, GAMMA)
    k, e = law.stiffness, PENALTY_ONSET * law.delta_c
    assert k == pytest.approx(1e3 * SIGMA0 / 1e-3)     # the default slope: 1e3 sigma0 / delta_c
    g = -10 * e                     # beyond the onset: slope k
    phi, sigma, dsigma = law(np.array([g]))
    assert sigma[0] == pytest.approx(SIGMA0 + k * (g + e / 2))       # pushes back
    assert dsigma[0] == k
    assert phi[0] == pytest.approx(-GAMMA + SIGMA0 * g + k * (g + e / 2) ** 2 / 2
                                   + k * e ** 2 / 24)
    phi, sigma, dsigma = law(np.array([-e / 2, 0.0]))       # the onset: slope from 0
    assert dsigma == pytest.approx([k / 2, 0.0])
    assert sigma == pytest.approx([SIGMA0 - k * e / 8, SIGMA0])


def test_bad_law():
    for kw in (dict(sigma0=0.0, gamma=GAMMA), dict(sigma0=SIGMA0, gamma=-1.0),
               dict(sigma0=SIGMA0, gamma=GAMMA, ramp=1.5), dict(sigma0=np.nan, gamma=GAMMA)):
        with pytest.raises(ValueError, match="cohesive law"):
            CohesiveLaw(**kw)


def _state(d, seed=0):
    """A state with outer gaps across the whole law (penetration to beyond its reach):
    the shell pushed down by 2e-4 R, plus noise."""
    rng = np.random.default_rng(seed)
    x = 1e-5 * rng.standard_normal(d.ndof)
    x[d.n2:2 * d.n2] -= 2e-4
    return x


def test_forces_are_the_energy_derivative(iface):
    x = _state(iface.d)
    gaps = iface._points(x)[1]
    assert gaps.min() < 0 and (gaps > 0).any() and (gaps < iface.law.reach).sum() > 50
    e = np.random.default_rng(1).standard_normal(iface.d.ndof)
    h = 1e-8
    fd = (iface.energy(x + h * e) - iface.energy(x - h * e)) / (2 * h)
    assert fd == pytest.approx(iface.residual(x) @ e, rel=1e-6)


def test_tangent_against_finite_differences(iface):
    d = iface.d
    x = _state(d)
    K, r = iface.add(x, *tangent(d, x))
    assert np.allclose(r, residual(d, x) + iface.residual(x), rtol=0, atol=1e-14)
    assert abs(K - K.T).max() <= 1e-12 * abs(K).max()
    e = np.random.default_rng(2).standard_normal(d.ndof)
    h = 1e-9
    fd = ((residual(d, x + h * e) + iface.residual(x + h * e))
          - (residual(d, x - h * e) + iface.residual(x - h * e))) / (2 * h)
    Ke = K @ e
    assert np.abs(fd - Ke).max() <= 1e-5 * np.abs(Ke).max()
    # the cohesive part alone, which the FE part would hide
    Kc = iface.add(x, 0 * K, 0 * r)[0]
    fdc = (iface.residual(x + h * e) - iface.residual(x - h * e)) / (2 * h)
    assert np.abs(fdc - Kc @ e).max() <= 1e-5 * np.abs(Kc @ e).max()


def test_a_path_that_passes_no_new_extreme_is_counted_as_stalled():
    from shell_adhesion.solver.arclength import Stall
    # approach (a, c, delta): delta grows, then the jump-in (delta falls while the zone
    # grows, no contact yet), then a grows; then the contact edge zigzags between two
    # nodes while c and delta wobble below their largest values
    st = Stall()
    counts = [st.after(a, c, d, retracting=False) for a, c, d in
              [(0.0, 0.0, -0.01), (0.0, 0.0, 0.0), (0.0, 0.05, -0.01), (0.1, 0.2, -0.02),
               (0.2, 0.25, -0.03)]]
    assert counts == [0, 0, 0, 0, 0]
    zigzag = [st.after(0.19 + 0.01 * (k % 2), 0.24, -0.03, retracting=False)
              for k in range(6)]
    assert zigzag == [1, 2, 3, 4, 5, 6]
    # the retraction is a new leg: its extremes are the least a, c and delta
    assert st.after(0.2, 0.25, 0.01, retracting=True, new_leg=True) == 0
    assert [st.after(a, c, d, retracting=True) for a, c, d in
            [(0.19, 0.25, 0.01), (0.19, 0.25, 0.0), (0.195, 0.25, 0.002), (0.0, 0.1, 0.0),
             (0.0, 0.0, -0.01)]] == [0, 0, 1, 0, 0]


class _Meridian:
    """An interface stub whose outer surface has the given points along the meridian."""

    def __init__(self, r, z, delta_c):
        self.r, self.z = np.asarray(r, float)[None, :], np.asarray(z, float)[None, :]
        self.law = CohesiveLaw(1.0, delta_c)

    def _points(self, x):
        return self.r, self.z, None


def test_contact_and_zone_radii_follow_the_meridian_of_a_shell_pulled_flat():
    """A shell pulled flat beyond 0.9 R curls back inward above its contact: points high
    above the plane there have radii beyond the contact edge.  The zone edge c is where
    the gap first reaches delta_c along the meridian (it was 0, sorting by radius: a
    zone of -320 edges reported for t/R 0.02, h/R 1, gamma 180 J/m^2)."""
    from shell_adhesion.solver.arclength import cohesive_radius, contact_radius
    # flat to r = 0.9, then rising steeply and curling back to r 0.85 high up
    r = [0.0, 0.3, 0.6, 0.9, 0.93, 0.95, 0.94, 0.9, 0.85]
    z = [-1e-4, -1e-4, -1e-4, -1e-5, 0.02, 0.2, 0.5, 0.8, 1.0]
    iface = _Meridian(r, z, delta_c=0.01)
    a = contact_radius(iface, None)
    assert 0.9 < a < 0.93
    c = cohesive_radius(iface, None, a)
    assert a < c < 0.93
    assert c == pytest.approx(0.9 + 0.03 * (0.01 + 1e-5) / (0.02 + 1e-5))
    # a lifted apex: no contact disc
    assert contact_radius(_Meridian([0.0, 0.1, 0.2], [0.01, -1e-4, 0.01], 0.01), None) == 0.0
