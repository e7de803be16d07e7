"""Nothing loops (issue 10, item 1): the two hangs found by users end, each run in a
subprocess under a timeout that fails the test, and a solve that cannot go on ends with a
ConvergenceError that says why."""
import subprocess
import sys
import textwrap

import pytest

from shell_adhesion.solver.case import relaxation_starts
from shell_adhesion.solver.path import Settings, load
from shell_adhesion.errors import ConvergenceError

from conftest import ENV, REPO

TIMEOUT_S = 240     # the coarse runs below take 5-20 s on a busy machine


def run_python(code, timeout=TIMEOUT_S):
    """Run `code` in a fresh interpreter; a hang fails the test (TimeoutExpired)."""
    try:
        return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], cwd=REPO, env=ENV,
                              capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        pytest.fail(f"did not end within {timeout} s")


def test_loading_past_the_old_stall_ends():
    """`case --R 20 --t 3 --h 20 --C10 0.3 --mesh coarse --delta-max 10` looped forever at
    delta = 0.480 R: a node found below the plane was re-located from the tangent
    prediction, beyond the step that had just failed, and the failure reset the step cap to
    that same size.  The solver itself (below the domain check) now goes through."""
    out = run_python("""
        from shell_adhesion.solver import quality
        from shell_adhesion.solver.forms import discretise
        from shell_adhesion.solver.geometry import Cap
        from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
        from shell_adhesion.solver.path import load
        quality.J_RANGE = (0.0, float("inf"))   # prove the loop, not the quality check
        d = discretise(cap_mesh(Cap(0.15, 1.0), mesh_spec("coarse")))
        path = load(d, "no_slip", 0.5)
        print(path.states[-1].delta, len(path.states))
    """)
    assert out.returncode == 0, out.stderr
    delta, n = out.stdout.split()
    assert float(delta) == pytest.approx(0.5) and int(n) < 200


def test_loading_past_the_old_stall_is_refused_by_quality():
    """With the quality check on, the same run ends with a reason naming the mesh."""
    out = run_python("""
        from shell_adhesion.solver.forms import discretise
        from shell_adhesion.solver.geometry import Cap
        from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
        from shell_adhesion.solver.path import QualityError, load
        d = discretise(cap_mesh(Cap(0.15, 1.0), mesh_spec("coarse")))
        try:
            load(d, "no_slip", 0.5)
        except QualityError as e:
            print(e)
    """)
    assert out.returncode == 0, out.stderr
    assert "coarse mesh" in out.stdout and "pointwise J" in out.stdout


def test_cli_old_hang_is_refused_before_computing():
    out = subprocess.run([sys.executable, "-m", "shell_adhesion", "case", "--R", "20", "--t", "3",
                          "--h", "20", "--C10", "0.3", "--mesh", "coarse", "--delta-max", "10"],
                         cwd=REPO, env=ENV, capture_output=True, text=True, timeout=60)
    assert out.returncode == 2
    assert out.stdout == "" and len(out.stderr.strip().splitlines()) == 1
    assert "0.25" in out.stderr and "delta" in out.stderr


def test_relaxation_from_a_softening_start_ends():
    """A start with dP/ddelta <= 0 sized its step from the square root of a negative
    number: NaN steps, and the relaxation loop never ended.  It now relaxes with a fixed
    step and ends."""
    out = run_python("""
        from dataclasses import replace
        import numpy as np
        from shell_adhesion.solver.case import relax_from, relaxation_starts, solve_loading
        d, loading = solve_loading(0.15, 1.0, "no_slip", "coarse", 0.05)
        start = relaxation_starts(loading, d.capmesh)[-1]
        for k in (0.0, -abs(start.dP_ddelta), np.nan):
            path = relax_from(d, "no_slip", replace(start, dP_ddelta=k), 0.006)
            delta = np.array([s.delta for s in path.states])
            assert np.all(np.isfinite(delta)) and np.all(np.diff(delta) < 0), delta
            print(len(path.states), path.ended_by)
    """)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.strip().splitlines()
    assert len(lines) == 3 and all(1 < int(l.split()[0]) <= Settings().max_points for l in lines)


def test_relaxation_has_a_point_limit(base_coarse):
    """A stop criterion that never fires ends at the point limit, with the reason."""
    _, d, loading = base_coarse
    start = relaxation_starts(loading, d.capmesh)[3]
    from shell_adhesion.solver.path import relax
    path = relax(d, "no_slip", start, lambda s: False, 0.002, Settings(max_points=6))
    assert len(path.states) == 6 and path.ended_by.startswith("point limit")


def test_non_finite_input_is_a_failure_with_a_reason(base_coarse):
    _, d, _ = base_coarse
    with pytest.raises(ValueError, match="delta_max"):
        load(d, "no_slip", float("nan"))
    with pytest.raises(ValueError, match="step"):
        from shell_adhesion.solver.path import relax
        relax(d, "no_slip", base_coarse[2].states[5], lambda s: True, float("nan"))


def test_loading_has_a_state_limit(base_coarse):
    _, d, _ = base_coarse
    with pytest.raises(ConvergenceError, match="states"):
        load(d, "no_slip", 0.25, Settings(max_states=5))
