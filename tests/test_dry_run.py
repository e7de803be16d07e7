"""`run --dry-run`: the plan and an estimate, computing and creating nothing, also for a
study whose loading depth is fitted to its request (no delta_max_over_R) and on a new
catalogue (the cost model, study.cost)."""
import pytest

from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.request import Request
from shell_adhesion.study.cost import shell_size
from shell_adhesion.study.run import dry_run

STUDY = dict(name="auto", description="depth fitted to the request", R_mm=20,
             base=dict(C10_MPa=0.3, t_over_R=0.15, h_over_R=1.0, gamma_J_m2=30),
             sweeps=dict(gamma_J_m2=[10, 30]), mesh="coarse")


def test_dry_run_of_a_fitted_depth_on_a_new_catalogue(tmp_path):
    text = dry_run(STUDY, catalogue=tmp_path / "cat", workers=2)
    assert "loading as deep as the pull-offs need" in text
    assert "estimate: about" in text and "from the cost model" in text
    assert not (tmp_path / "cat").exists()


def test_cost_model_counts_dofs_and_paths_before_solving():
    """The dofs equal the discretisation's of the mesh the request gives; the paths are
    within 15 % of the relaxation paths the coarse base shell then solves (to 0.25 R)."""
    from shell_adhesion.solver import solve_paths
    from shell_adhesion.solver.request import initial_fit
    request = Request.serving(0.006, 0.25)
    fit = initial_fit(Cap(0.15, 1.0), request)
    dofs, paths = shell_size(Cap(0.15, 1.0), fit, "coarse")
    ps, d, _ = solve_paths(0.15, 1.0, "no_slip", "coarse", 0.25, 0.006, uniform=fit.uniform)
    assert dofs == d.ndof
    assert paths == pytest.approx(len(ps.relaxations), rel=0.15), (paths, len(ps.relaxations))
