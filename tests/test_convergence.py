"""Validation 6: mesh convergence of the headline numbers of the base shell, from the
default mesh to one uniform refinement (every size halved): the README's differences (P(5 mm) 0.03 %,
P* 0.18 %, delta_dagger 0.24 %), each held at twice its size.

The pull-off numbers need only the contact radii around the pull-off points, so their
paths are loaded to delta = 0.05 R (a up to about 4.4 mm, beyond a* = 2 mm); P(5 mm) from
the loading curve alone."""
import pytest

from shell_adhesion.solver.case import solve_loading

from conftest import GAMMA_HAT, base_case
from validation import loading_P, within

# the fine mesh (20k dofs) takes minutes: `python -m pytest -m slow` runs it
pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def meshes():
    out = {}
    for mesh in ("default", "fine"):
        ps, _, _ = base_case(mesh, "no_slip", 0.006, 0.05)
        _, po = ps.pull_off(GAMMA_HAT)
        _, loading = solve_loading(0.15, 1.0, "no_slip", mesh, 0.25)
        out[mesh] = dict(P5=loading_P(loading.states, 0.25), P_star=po.P_star,
                         delta_dagger=po.delta_dagger)
    print("mesh convergence (dimensionless):", out)
    return out


@pytest.mark.parametrize("name,stated", [("P5", 3e-4), ("P_star", 1.8e-3), ("delta_dagger", 2.4e-3)])
def test_default_to_fine_as_the_readme_states(meshes, name, stated):
    within(f"default mesh {name} against the fine mesh", meshes["default"][name],
           meshes["fine"][name], 2 * stated)
