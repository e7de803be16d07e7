"""The rigid lid at the rim of a shell's cavity (solver.lid): its contact is the derivative
of its energy, it adds nothing where nothing reaches it, and the pattern it needs keeps
every element entry.  (The collapse of a depressurised shell onto its lid:
tests/test_depressurised_pocket.py.)"""
import numpy as np
import pytest
import scipy.sparse as sp

from shell_adhesion.solver import cavity as cv
from shell_adhesion.solver.forms import (discretise, lagrangian, residual, tangent,
                                         with_couplings)
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.lid import LID_THROUGH, lid_of
from shell_adhesion.solver.penalty import CONTACT_ONSET, CONTACT_STIFFNESS
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.quality import quality, worst

P_ATM = 0.3378


def _shell(mode="pressure"):
    d = discretise(cap_mesh(Cap(0.1, 0.5), mesh_spec("coarser")))
    cavity = (cv.Cavity("pressure", p=-1e-3, p_atm=P_ATM) if mode == "pressure"
              else cv.Cavity("sealed", p0=0.0, p_atm=P_ATM))
    return d, cv.bind(d, cavity)


def _through(d, lid, depth):
    """A smooth bump of the cap near the axis whose inner apex is `depth` / R above the
    lid (the shell moved rigidly there: no element inverts)."""
    x = cv.start_vector(d)
    R = d.capmesh.nodes[0]
    near = np.flatnonzero(R < 0.15)
    rise = lid.Z_rim - lid.Z0[0, 0] + depth
    x[d.n2 + near] = rise * (1 - (R[near] / 0.15) ** 2)
    return x


def _slope(f, x, v, h):
    """d f(x + s v) / ds at s = 0: central differences at h and h / 2, extrapolated
    (Richardson: error O(h^4))."""
    c = lambda h: (f(x + h * v) - f(x - h * v)) / (2 * h)
    return (4 * c(h / 2) - c(h)) / 3


@pytest.mark.parametrize("mode", ["pressure", "sealed"])
def test_the_lids_forces_and_stiffness_are_the_derivatives_of_its_energy(mode):
    _, d = _shell(mode)
    lid = d.cavity.lid
    x = _through(d, lid, 2e-4)
    x += 1e-6 * np.random.default_rng(0).standard_normal(d.ndof)
    assert lid.penetration(x) > lid.onset / 10 and lid.energy(x) > 0
    K, r = tangent(d, x)
    v = np.random.default_rng(1).standard_normal(d.ndof)
    if mode == "pressure":      # (sealed, the Lagrangian's gas term is the gas law's)
        dL = _slope(lambda y: lagrangian(d, y), x, v, 1e-6)
        assert dL == pytest.approx(r @ v, rel=1e-9)
    dr = _slope(lambda y: residual(d, y), x, v, 1e-6)
    assert np.abs(dr - K @ v).max() <= 1e-9 * np.abs(K @ v).max()
    # and the lid's own part alone, at the same state
    n_fe = len(d.csr_indptr) - 1        # its slots are the FE pattern's (before a border)
    zero = sp.csr_matrix((np.zeros(len(d.csr_indices)), d.csr_indices, d.csr_indptr),
                         shape=(n_fe, n_fe))
    x, v = x[:n_fe], v[:n_fe]
    K_lid, r_lid = lid.add_tangent(zero, np.zeros(n_fe), x)
    dE_lid = _slope(lid.energy, x, v, 1e-7)
    assert dE_lid == pytest.approx(r_lid @ v, rel=1e-7)
    dr_lid = _slope(lambda y: lid.add_residual(y, np.zeros(n_fe)), x, v, 1e-7)
    assert np.abs(dr_lid - K_lid @ v).max() <= 1e-7 * np.abs(K_lid @ v).max()


def test_the_lid_pushes_down_on_the_shell_and_up_on_the_rim():
    _, d = _shell()
    lid = d.cavity.lid
    x = _through(d, lid, 30 * CONTACT_ONSET)
    f = lid.add_residual(x, np.zeros(d.ndof))
    rim = lid.dofs[0, 3]
    # internal forces dE/dx: the penetrating u_z are pushed back (dE/du_z > 0), the rim
    # carries the reaction, and the lid's forces balance (it is part of the rig)
    shell = np.setdiff1d(lid.dofs[:, :3], [rim])
    assert f[rim] < 0 and f[shell].sum() > 0   # (Q2 edges: a node may pull a little)
    assert f[shell].sum() == pytest.approx(-f[rim], rel=1e-12)
    # the push is the penalty's traction over the penetrating surface: for a penetration
    # s, k s^2 / (2 e) within the onset e, k (s - e / 2) beyond it
    depth = np.maximum(-lid.gaps(x), 0.0)
    assert (depth > CONTACT_ONSET).sum() >= 3
    k, e = CONTACT_STIFFNESS, CONTACT_ONSET
    traction = np.where(depth < e, k * depth ** 2 / (2 * e), k * (depth - e / 2))
    assert f[shell].sum() == pytest.approx(np.sum(lid.w * traction), rel=1e-12)
    # over the reference inner surface, a spherical zone of radius 1 - t from its apex
    # (z = t) to the rim (z = h): area 2 pi (1 - t) (h - t)
    assert lid.w.sum() == pytest.approx(2 * np.pi * 0.9 * (0.5 - 0.1), rel=1e-4)


def test_where_nothing_reaches_the_lid_it_adds_nothing():
    _, d = _shell()
    lid = d.cavity.lid
    x = cv.start_vector(d)
    assert lid.penetration(x) == 0 and lid.energy(x) == 0
    r = np.arange(d.ndof, dtype=float)
    assert lid.add_residual(x, r) is r
    K, _ = tangent(d, x)
    assert lid.add_tangent(K, r, x) == (K, r)
    # the undeformed inner surface lies below the lid, up to its rim (gap 0 there)
    assert lid.gaps(x).min() >= -1e-12


def test_the_lids_pattern_keeps_every_element_entry():
    d = discretise(cap_mesh(Cap(0.1, 0.5), mesh_spec("coarser")))
    r, z = d.capmesh.nodes[:, d.capmesh.inner]
    inner = d.capmesh.inner[np.argsort(np.arctan2(r, 1.0 - z))]
    nodes = np.stack([inner[0:-1:2], inner[1::2], inner[2::2]], axis=1)
    wide, _ = lid_of(d, nodes)
    assert len(wide.csr_indices) > len(d.csr_indices)
    x = 1e-3 * np.random.default_rng(2).standard_normal(d.ndof)
    K, r = tangent(d, x)
    K_wide, r_wide = tangent(wide, x)
    assert np.array_equal(r, r_wide)
    assert (K - K_wide).count_nonzero() == 0 and K_wide.nnz == len(wide.csr_indices)
    # couplings already in the pattern change nothing
    assert with_couplings(d, d.edofs[9, :1], d.edofs[10, :1]) is d


def test_a_state_through_the_lid_is_refused_as_element_quality_is():
    # the energy method's paths check each state (solver.quality); a surface the lid's
    # penalty has let through by more than LID_THROUGH is not an equilibrium it vouches for
    _, d = _shell()
    lid = d.cavity.lid
    held = _through(d, lid, 2 * CONTACT_ONSET)
    assert 0 < quality(d, held).lid_penetration <= LID_THROUGH
    assert "lid" not in quality(d, held).problem()
    through = _through(d, lid, 2 * LID_THROUGH)
    q = quality(d, through)
    assert q.lid_penetration > LID_THROUGH
    assert q.problem().startswith("the inner surface passed the cavity's lid by")
    assert worst(quality(d, held), q).lid_penetration == q.lid_penetration
