"""The damped descent's merit: `forms.lagrangian` is the potential whose gradient in the FE
unknowns is `forms.residual` (incompressible and compressible), so a step of
`arclength._descend` that raises it is an overshoot, not round-off."""
import numpy as np
import pytest

from shell_adhesion.solver.forms import discretise, lagrangian, residual
from shell_adhesion.solver.material import Material
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.snap import loading_cap


@pytest.mark.parametrize("material", [Material(), Material(D1_times_C10=0.05)],
                         ids=["incompressible", "compressible"])
def test_the_residual_is_the_gradient_of_the_lagrangian(material):
    d = discretise(cap_mesh(loading_cap(0.1, 0.5), mesh_spec("coarse")), material=material)
    rng = np.random.default_rng(3)
    r_n, z_n = d.capmesh.nodes
    nodes = np.arange(r_n.size)
    x = np.zeros(d.ndof)                             # a smooth deformed state, J != 1
    x[d.ur(nodes)] = 0.05 * r_n * np.sin(3 * z_n)
    x[d.uz(nodes)] = 0.05 * r_n ** 2
    x[2 * d.n2:] = rng.standard_normal(d.ndof - 2 * d.n2)        # the multiplier p != 0
    r = residual(d, x)
    for _ in range(3):
        v = rng.standard_normal(d.ndof)
        h = 1e-6
        slope = (lagrangian(d, x + h * v) - lagrangian(d, x - h * v)) / (2 * h)
        exact = float(r @ v)
        assert slope == pytest.approx(exact, rel=1e-6, abs=1e-9 * np.abs(r).sum())
