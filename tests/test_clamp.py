"""A thin shell pressed deep is squeezed between the plane and its clamped rim: the loading
stops on element quality there whatever the mesh, and the refusal says so instead of
asking for a finer mesh (solver.quality.clamp_squeeze; `python benchmarks/clamp.py`)."""
import math
from dataclasses import replace

import numpy as np
import pytest

import shell_adhesion.solver.geometry as geometry
import shell_adhesion.solver.path as path
from shell_adhesion.errors import QualityError
from shell_adhesion.solver.case import solve_loading
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import DEPTH_SHARE, Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.quality import clamp_squeeze
from shell_adhesion.solver.request import Request, answers, solve_request

CLAMP = "squeezed between the plane and its clamped rim"


def _pressed(t, h, mesh, monkeypatch):
    """(d, loading, refused x, its Quality): loaded toward 0.9 h until a state is refused."""
    seen, check = {}, path.quality

    def recording(d, x):
        seen["q"], seen["x"] = check(d, x), x.copy()
        return seen["q"]

    d = discretise(cap_mesh(Cap(t, h), mesh_spec(mesh)))
    with monkeypatch.context() as m:
        m.setattr(path, "quality", recording)
        loading = path.load(d, "no_slip", DEPTH_SHARE * h, stop_at_limit=True)
    return d, loading, seen["x"], seen["q"]


def _stop_delta(loading) -> float:
    return float(loading.stopped_by.split("at delta = ")[1].split(" R")[0])


@pytest.fixture(scope="module")
def thinnest_shallow():
    with pytest.MonkeyPatch.context() as m:
        return _pressed(0.02, 0.2, "coarse", m)


def test_a_thin_shell_pressed_deep_stops_at_its_clamp_and_says_so(thinnest_shallow):
    d, loading, x, q = thinnest_shallow
    cap = d.capmesh.cap
    assert "element quality: pointwise J" in loading.stopped_by
    assert CLAMP in loading.stopped_by and "finer mesh or" not in loading.stopped_by
    # the last kept state's contact edge is within the bending length of the rim
    assert cap.rim_outer - loading.states[-1].a <= math.sqrt(cap.t)
    assert 0.13 < _stop_delta(loading) < 0.9 * cap.h


def test_the_rule_needs_the_edge_and_the_worst_element_by_the_rim(thinnest_shallow):
    d, loading, x, q = thinnest_shallow
    cap, ell = d.capmesh.cap, math.sqrt(d.capmesh.cap.t)
    a = loading.states[-1].a
    assert clamp_squeeze(d, x, q, a).startswith("the shell is " + CLAMP)
    # the contact edge farther than the bending length from the rim: not the clamp
    assert clamp_squeeze(d, x, q, cap.rim_outer - 1.01 * ell) == ""
    # the worst element far inside the contact (at the apex): not the clamp
    apex = int(np.argmin(d.r_q.mean(axis=1)))
    assert clamp_squeeze(d, x, replace(q, element=apex), a) == ""
    # a non-finite state is not the clamp's either
    assert clamp_squeeze(d, x, replace(q, J_min=math.nan), a) == ""


def test_a_thicker_shell_keeps_the_mesh_hint():
    """t/R >= THIN_T is not covered by the rule (measured on thin shells only)."""
    with pytest.raises(QualityError, match="try a finer mesh or a smaller delta_max"):
        solve_loading(0.15, 0.2, "no_slip", "coarse", 0.1)


def test_the_clamp_stop_is_not_the_mesh(monkeypatch):
    """Coarse and default meshes of t/R 0.02, h/R 0.5 stop 0.8 % apart (0.3705, 0.3674 R)."""
    stops = [_stop_delta(_pressed(0.02, 0.5, m, monkeypatch)[1]) for m in ("coarse", "default")]
    assert abs(stops[0] - stops[1]) <= 0.02 * stops[1]


@pytest.mark.slow
def test_a_finer_mesh_stops_near_the_same_delta(monkeypatch):
    """Default and fine meshes of t/R 0.02, h/R 0.2 stop 1.2 % apart (0.1388, 0.1371 R),
    both with the clamp named."""
    runs = [_pressed(0.02, 0.2, m, monkeypatch)[1] for m in ("default", "fine")]
    assert all(CLAMP in r.stopped_by for r in runs)
    stops = [_stop_delta(r) for r in runs]
    assert abs(stops[0] - stops[1]) <= 0.03 * stops[1]


@pytest.mark.slow
def test_a_pull_off_beyond_the_clamp_is_refused_naming_it(monkeypatch):
    """Below the domain (t/R 0.01, h/R 0.2, coarse mesh): at gamma/(C10 R) 0.03 the curve
    still falls where the loading stopped at the clamp, and the refusal says so; 0.001 is
    answered from the same paths."""
    monkeypatch.setattr(geometry, "T_MIN", 0.01)
    ps, _, _ = solve_request(0.01, 0.2, Request.serving(0.03), 0.03, mesh="coarse")
    got = answers(ps, [0.001, 0.03])
    assert not isinstance(got[0.001], Exception) and got[0.001][1].P_star < 0
    refusal = str(got[0.03])
    assert "still falling" in refusal and CLAMP in refusal
