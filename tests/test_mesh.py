"""The cap mesh: exact volume, nodes on the spheres, boundary sets, refinement."""
import math

import numpy as np
import pytest

from shell_adhesion.solver.geometry import Cap, check_cap
from shell_adhesion.errors import InputError
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.forms import discretise


@pytest.mark.parametrize("t,h", [(0.15, 1.0), (0.15, 0.5), (0.5, 1.0), (1.0, 1.0), (1.0, 0.6)])
def test_volume_and_boundaries(t, h):
    cap = Cap(t, h)
    cm = cap_mesh(cap, mesh_spec("coarse"))
    d = discretise(cm)
    assert d.w.sum() == pytest.approx(cap.volume, rel=1e-5)
    assert np.all(d.w > 0)
    r, z = cm.nodes
    assert np.allclose(np.hypot(r[cm.outer], z[cm.outer] - 1), 1, atol=1e-12)
    assert cm.outer[0] in cm.axis and np.isclose(z[cm.outer[0]], 0)
    assert np.allclose(z[cm.rim], h) and np.allclose(r[cm.axis], 0)
    assert np.all(np.diff(np.arctan2(r[cm.outer], 1 - z[cm.outer])) > 0)
    assert cm.outer_corner[0] and not cm.outer_corner[1] and cm.outer_corner[2]
    if t < 1:
        assert np.allclose(np.hypot(r[cm.inner], z[cm.inner] - 1), 1 - t, atol=1e-12)


def test_refinement_halves_apex_size():
    c, d, f = (mesh_spec(n) for n in ("coarse", "default", "fine"))
    assert c.h_apex == 2 * d.h_apex == 4 * f.h_apex
    n = [len(cap_mesh(Cap(0.15, 1.0), s).outer) for s in (c, d, f)]
    assert n[0] < n[1] < n[2]


@pytest.mark.parametrize("t,h,rule", [(0, 1, "0 < t"), (1.2, 1, "0 < t"), (0.3, 0.3, "> t"),
                                      (0.3, 1.1, "h <= R"), (float("nan"), 1, "finite")])
def test_bad_geometry(t, h, rule):
    with pytest.raises(InputError, match=rule):
        check_cap(t, h)


def test_solid_cap_allows_any_depth():
    check_cap(1.0, 0.3)
    assert Cap(1.0, 1.0).volume == pytest.approx(2 * math.pi / 3)


def test_thin_shell_layers_halve_with_the_family():
    """A thin shell (t/R below about 0.041: solver.mesh.thin_shell, where the graded rule
    gives the default mesh fewer than 4 layers) has 4 layers on the default mesh, twice as
    many per finer level and half as many per coarser one, each growing by the level's
    layer_growth from the outer surface; a thicker shell (the shipped maps' grids from
    t/R 0.05, the base shell) keeps the graded rule on every level."""
    from shell_adhesion.solver.mesh import (THIN_LAYERS, _graded_layers, thickness_layers,
                                            thin_shell)
    assert thin_shell(0.01) and thin_shell(0.02) and thin_shell(0.04)
    assert not thin_shell(0.041) and not thin_shell(0.05) and not thin_shell(1.0)
    for t in (0.01, 0.02, 0.04):
        depth = {m: thickness_layers(t, mesh_spec(m)) for m in ("coarse", "default", "fine")}
        assert [len(x) - 1 for x in depth.values()] == [THIN_LAYERS // 2, THIN_LAYERS,
                                                        2 * THIN_LAYERS]
        for x in depth.values():
            assert x[0] == 0 and x[-1] == pytest.approx(t, rel=1e-14)
            assert np.all(np.diff(x, 2) > 0)         # growing inward
        # each level about halves the first layer and the largest one
        for coarse, fine in (("coarse", "default"), ("default", "fine")):
            ratio = np.diff(depth[coarse])[[0, -1]] / np.diff(depth[fine])[[0, -1]]
            assert np.all((1.7 < ratio) & (ratio < 2.4))
    for t in (0.041, 0.05, 0.06, 0.15, 0.5):   # the graded rule, on every level
        for m in ("coarsest", "coarser", "coarse", "default", "fine", "finer"):
            assert np.array_equal(thickness_layers(t, mesh_spec(m)),
                                  _graded_layers(t, mesh_spec(m)))
