"""Element quality (issue 10, item 3): every converged state is checked for inverted or
distorted elements and for the pointwise J range of the incompressible material; the worst
values go into the path set's stats and a state beyond the thresholds is refused."""
import numpy as np
import pytest

from shell_adhesion.solver.case import solve_loading
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.errors import QualityError
from shell_adhesion.solver.quality import J_RANGE, quality


@pytest.fixture(scope="module")
def d():
    return discretise(cap_mesh(Cap(0.15, 1.0), mesh_spec("coarse")))


def test_undeformed_state_is_perfect(d):
    q = quality(d, np.zeros(d.ndof))
    assert q.J_min == pytest.approx(1) and q.J_max == pytest.approx(1)
    assert q.detF_min == pytest.approx(1) and q.problem() == ""


def test_check_fires_on_a_deliberately_distorted_mesh(d):
    """Pull the centre node of one element through its opposite edge: the element folds."""
    e = 40
    nodes = d.capmesh.mesh.t[:, e]                          # 4 corners, edges, centre (Q2)
    r, z = d.capmesh.nodes
    centre = d.edofs[8, e]
    corners = nodes[:4]
    x = np.zeros(d.ndof)
    x[d.ur(centre)] = 2.0 * (r[corners].max() - r[corners].min())
    q = quality(d, x)
    assert q.detF_min < 0 and q.element == e
    assert "inverted" in q.problem()
    # a milder shift of the same node trips the J range, not the fold check
    x[:] = 0.0
    x[d.ur(centre)] = 0.15 * (r[corners].max() - r[corners].min())
    q = quality(d, x)
    assert q.detF_min > 0 and not J_RANGE[0] <= q.J_min <= q.J_max <= J_RANGE[1]
    assert "pointwise J" in q.problem()


def test_shallow_cap_is_refused_with_the_mesh_named():
    """The issue's case: h/R = 0.2 on the coarse mesh to delta = 0.1 R exited 0 with
    pointwise J from 0.15 to 2.53 (and P = 312 N for R = 20 mm, C10 = 0.3 MPa)."""
    with pytest.raises(QualityError, match="pointwise J.*coarse mesh.*t/R = 0.15, h/R = 0.2"):
        solve_loading(0.15, 0.2, "no_slip", "coarse", 0.1)


def test_quality_is_in_the_provenance(base_coarse):
    ps, _, loading = base_coarse
    st = ps.stats
    assert J_RANGE[0] < st["J_min"] < 1 < st["J_max"] < J_RANGE[1]
    assert 0 < st["detF_min"] <= 1 and 0 < st["distortion_min"] <= 1
    assert st["J_min"] == pytest.approx(loading.quality.J_min)
    assert st["relaxation_J_min"] == min(r.J_min for r in ps.relaxations)
    assert st["relaxation_detF_min"] > 0
