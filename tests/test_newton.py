"""Newton with the consistent tangent converges quadratically."""
import numpy as np
import pytest

from shell_adhesion.solver.contact import constraints
from shell_adhesion.solver.forms import discretise, residual, tangent
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.path import Settings, Timer, _Problem


def test_tangent_matches_finite_differences():
    d = discretise(cap_mesh(Cap(0.15, 1.0), mesh_spec("coarse")))
    r0, z0 = d.capmesh.nodes
    x = np.zeros(d.ndof)
    x[: d.n2] = 0.05 * r0 * np.sin(3 * z0)
    x[d.n2: 2 * d.n2] = 0.03 * np.cos(2 * r0) * z0
    x[2 * d.n2:] = 0.2 * np.cos(np.arange(d.n1))
    v = np.zeros(d.ndof)
    v[: d.n2], v[d.n2: 2 * d.n2], v[2 * d.n2:] = r0 * np.cos(5 * z0), np.sin(4 * r0), 1.0
    K, _ = tangent(d, x)
    Kv = K @ v

    def miss(eps):
        fd = (residual(d, x + eps * v) - residual(d, x - eps * v)) / (2 * eps)
        return np.abs(fd - Kv).max() / np.abs(Kv).max()

    # central differences miss a consistent tangent by O(eps^2): 1.5e-7 at eps = 1e-4,
    # 1.5e-9 at 1e-5 (README), each step of 10 dividing the miss by 100; steps this large
    # keep round-off (about 1e-16 / eps relative) out of the check
    coarse_step, fine_step = miss(1e-4), miss(1e-5)
    assert fine_step <= 3e-9, fine_step
    assert coarse_step / fine_step == pytest.approx(100, rel=0.1), (coarse_step, fine_step)


def test_residuals_fall_quadratically():
    d = discretise(cap_mesh(Cap(0.15, 1.0), mesh_spec("coarse")))
    pb = _Problem(d, "no_slip", Settings(max_iter=30), Timer())
    held = list(range(7))                     # the apex zone glued, rim pushed in one step
    c = constraints(d, "no_slip", held)
    x = np.zeros(d.ndof)
    _, _, _, _, history = pb.newton(c, x, 0.03)
    e = np.array(history)
    above = e > 1e-12
    e = e[above]
    assert len(e) >= 4, history
    orders = np.log(e[2:] / e[1:-1]) / np.log(e[1:-1] / e[:-2])
    # the asymptotic order is 2; the last ratio before the round-off floor shows it
    assert orders[-1] > 1.7, (history, orders)
