"""The cohesive case in the user's units (`solve_cohesive_case`, `case --adhesion dugdale`):
bad input refused before any computation (one line, exit 2); the Maugis-Dugdale pull-off
of a solid hemisphere through the whole chain of units (J/m^2, MPa, lambda, N); the exact
scaling of a shell's answer with R, C10 and gamma, with sigma0 and lambda as two spellings
of one law; the command's JSON and table; a path that cannot answer is refused, exit 1.
"""
import json
import math

import numpy as np
import pytest

from shell_adhesion import cli
from shell_adhesion.solver import arclength
from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.solver.mesh import mesh_spec
from shell_adhesion.study import case as case_api
from shell_adhesion.study import cohesive_case as cc

BASE = ["case", "--R", "20", "--t", "3", "--h", "20", "--C10", "0.3", "--gamma", "30"]
DUGDALE = ["--adhesion", "dugdale"]

BAD = [
    (DUGDALE + ["--sigma0", "0"], "--sigma0: 0 MPa must be > 0"),
    (DUGDALE + ["--sigma0", "-0.2"], "--sigma0: -0.2 MPa must be > 0"),
    (DUGDALE + ["--sigma0", "x"], "--sigma0: 'x' must be a number (MPa)"),
    (DUGDALE + ["--sigma0", "0.1", "--tabor", "1"], "--sigma0/--tabor: give exactly one of "
                                                    "them with --adhesion dugdale (both given)"),
    (DUGDALE, "(neither given)"),
    (["--sigma0", "0.1"], "--sigma0: 0.1 given with --adhesion energy"),
    (["--adhesion", "energy", "--tabor", "1"], "--tabor: 1 given with --adhesion energy"),
    (DUGDALE + ["--tabor", "0"], "--tabor: 0 must be > 0"),
    (DUGDALE + ["--tabor", "inf"], "--tabor"),
    (DUGDALE + ["--tabor", "5"], "--tabor: 5: outside the supported domain 0.05 <= lambda <= 3"),
    (DUGDALE + ["--sigma0", "1e-4"], "--sigma0 = 0.0001 MPa gives lambda = 0.000549"),
    (DUGDALE + ["--tabor", "1", "--gamma", "20"], "--gamma: 2 values given"),
    (DUGDALE[:1] + ["dugdale", "--tabor", "1", "--material", "yeoh", "--C20", "0.01"],
     "--material: yeoh with --adhesion dugdale"),
    (DUGDALE + ["--tabor", "1", "--cavity", "sealed"], "--cavity: sealed with --adhesion dugdale"),
    (DUGDALE + ["--tabor", "1", "--t", "30"], "--t"),      # the shell's own rules still apply
    (DUGDALE + ["--tabor", "1", "--zone-elements", "0.5"],
     "--zone-elements: 0.5 must be between 1 and 32 (elements across the cohesive zone)"),
    (DUGDALE + ["--tabor", "1", "--zone-elements", "64"], "--zone-elements: 64 must be between"),
    (DUGDALE + ["--tabor", "1", "--zone-elements", "nan"], "--zone-elements"),
    (DUGDALE + ["--tabor", "1", "--zone-elements", "x"], "--zone-elements: 'x' must be a number"),
    (["--zone-elements", "8"], "--zone-elements: 8 given with --adhesion energy"),
    # the mixed-mode option (no_slip only)
    (DUGDALE + ["--tabor", "1", "--interface", "no_slip", "--beta", "-1"],
     "--beta: -1 must be >= 0 (delta_c / delta_t of the mixed-mode law)"),
    (DUGDALE + ["--tabor", "1", "--interface", "no_slip", "--beta", "nan"],
     "--beta: nan must be a finite number"),
    (DUGDALE + ["--tabor", "1", "--interface", "no_slip", "--beta", "inf"],
     "--beta: inf must be a finite number"),
    (DUGDALE + ["--tabor", "1", "--beta", "1"], "--beta: 1 given with --interface "
                                                "frictionless: the mixed-mode law is for no_slip only"),
    (["--beta", "1"], "--beta: 1 given with --adhesion energy: a mixed-mode law needs "
                      "--adhesion dugdale"),
    # the contact history (no_slip only)
    (DUGDALE + ["--tabor", "1", "--interface", "no_slip", "--history", "pressed"],
     "--history: 'pressed' must be one of loading, adhesive"),
    (DUGDALE + ["--tabor", "1", "--history", "loading"], "--history: loading given with "
     "--interface frictionless: a frictionless path has the law act from the first touch "
     "(the choice is for no_slip only)"),
    (["--history", "adhesive"], "--history: adhesive given with --adhesion energy: a cohesive "
                                "contact history needs --adhesion dugdale"),
]


@pytest.mark.parametrize("extra, message", BAD, ids=[" ".join(b[0][2:]) or "none" for b in BAD])
def test_bad_input_is_one_line_and_exit_2_before_any_computation(extra, message, capsys,
                                                                  monkeypatch):
    def no_solve(*args, **kwargs):
        raise AssertionError("a computation started")
    monkeypatch.setattr(cc, "_solve", no_solve)
    monkeypatch.setattr(case_api, "solve_case", no_solve)
    assert cli.main(BASE + extra) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and err.startswith("shell-adhesion: error: ")
    assert message in err


def test_the_api_names_its_arguments():
    with pytest.raises(cc.InputError, match="sigma0_MPa: 0 MPa must be > 0"):
        cc.solve_cohesive_case(20, 3, 20, 0.3, 30, sigma0_MPa=0)
    with pytest.raises(cc.InputError, match="gamma_J_m2: 0 values given"):
        cc.solve_cohesive_case(20, 3, 20, 0.3, [], tabor=1)


def test_hemisphere_pull_off_in_units_follows_maugis_dugdale():
    # R 20 mm, C10 0.3 MPa, gamma 1 J/m^2: gamma / (C10 R) = 1.7e-4, small strain; the
    # closed form's P* at lambda 0.3 is -1.8156 pi gamma R (gamma in N/mm here)
    r = cc.solve_cohesive_case(20, 20, 20, 0.3, 1.0, tabor=0.3, mesh="coarse", error_bars=False)
    assert not r.refused
    P = r.to_dict()["pull_off"]["P_star_N"] / (math.pi * 1e-3 * 20)
    print(f"P*/(pi gamma R) {P:.4f} (Maugis-Dugdale {md.pull_off(0.3).P:.4f})")
    assert abs(P / md.pull_off(0.3).P - 1) <= 0.02
    # sigma0 from lambda: lambda = 2 sigma0 (R / (pi gamma K^2))^(1/3), K = 4 E*/3 = 32 C10 / 3
    K = 32 / 3 * 0.3
    assert r.input.sigma0_MPa == pytest.approx(0.5 * 0.3 * (math.pi * 1e-3 * K * K / 20) ** (1 / 3),
                                               rel=1e-12)


def test_the_answer_scales_exactly_with_R_C10_and_gamma():
    # doubling R and C10 and four times gamma keeps gamma / (C10 R); sigma0 twice (it scales
    # with C10) keeps lambda: the same dimensionless problem, P times 8, lengths times 2
    one = cc.solve_cohesive_case(20, 3, 20, 0.3, 30, tabor=1.0, mesh="coarse", error_bars=False)
    two = cc.solve_cohesive_case(40, 6, 40, 0.6, 120, sigma0_MPa=2 * one.input.sigma0_MPa,
                                 mesh="coarse", error_bars=False)
    assert two.input.tabor == pytest.approx(1.0, rel=1e-12)
    p1, p2 = one.to_dict()["pull_off"], two.to_dict()["pull_off"]
    for name, value in p1.items():
        if value is None or name.endswith("_error"):
            continue
        factor = 8.0 if name.endswith("_N") else 2.0
        assert p2[name] == pytest.approx(factor * value, rel=1e-6, abs=1e-12), name
    assert p1["P_star_N"] < 0 and p1["P_star_N"] < p1["P_dagger_N"] < 0
    assert 0 < p1["a_star_mm"] < p1["c_star_mm"]


def test_the_command_prints_json_with_units_and_curves(capsys):
    assert cli.main(BASE + DUGDALE + ["--tabor", "1", "--mesh", "coarse", "--no-error-bars",
                                      "--json", "--curves"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["refused"] is None and out["law"]["tabor"] == pytest.approx(1.0)
    assert out["law"]["delta_c_mm"] == pytest.approx(30e-3 / out["law"]["sigma0_MPa"])
    po, curves = out["pull_off"], out["curves"]
    assert set(po) >= {"P_star_N", "delta_star_mm", "a_star_mm", "c_star_mm", "P_dagger_N"}
    assert len(curves["P_N"]) == len(curves["delta_mm"]) == out["checks"]["states"]
    assert min(curves["P_N"]) <= po["P_star_N"] + 1e-3 * abs(po["P_star_N"])
    assert out["checks"]["path_ended_by"] == "left the cohesive range"
    assert out["checks"]["cohesive_zone_edges"] >= cc.ZONE_EDGES_MIN
    q = out["checks"]["quality"]        # the retraction's elements were checked
    assert 0.75 <= q["J_min"] <= q["J_max"] <= 4 / 3 and q["detF_min"] > 0


def test_a_path_that_does_not_turn_is_refused_with_exit_1(capsys, monkeypatch):
    real = arclength.trace

    def short(*args, **kwargs):
        return real(*args, **{**kwargs, "settings": arclength.ArcSettings(max_steps=25)})
    monkeypatch.setattr(cc, "trace", short)
    assert cli.main(BASE + DUGDALE + ["--tabor", "1", "--mesh", "coarse", "--no-error-bars"]) == 1
    out = capsys.readouterr().out
    assert "no pull-off: the path did not turn round (step limit: 25 states)" in out
    assert "fixed load" not in out


def test_the_mesh_is_fitted_to_the_zone_before_the_solve(monkeypatch):
    # lambda 3 on the coarse mesh: the zone Maugis expects at a sphere's pull-off (0.0085 R
    # = 0.17 mm for the base shell's gamma / (C10 R)) is 1.06 coarse apex elements (0.008
    # R); the solve's mesh has ZONE_ELEMENTS elements across it (the slow test holds the
    # estimate against a traced zone, lambda 2)
    real = arclength.trace
    seen = []

    def short(iface, *a, **k):
        seen.append(iface.d.capmesh)
        return real(iface, *a, **{**k, "settings": arclength.ArcSettings(max_steps=25)})
    monkeypatch.setattr(cc, "trace", short)
    zone_mm = cc.zone_estimate(0.005, 3.0) * 20
    for elements in (cc.ZONE_ELEMENTS, 2.0):        # the default, and one asked for (fewer: cheaper)
        seen.clear()
        r = cc.solve_cohesive_case(20, 3, 20, 0.3, 30, tabor=3.0, mesh="coarse",
                                   zone_elements=elements)
        # the 25-state path is refused: traced once more with twice the elements, then
        # refused; no coarser mesh for a refused path
        assert r.refused and r.coarser is None and len(seen) == 2
        first = r.provenance["first_path"]
        assert first["zone_elements"] == elements and first["states"] == 25
        assert r.provenance["zone_elements"] == cc.RETRY_FACTOR * elements
        assert r.to_dict()["input"]["zone_elements"] == elements     # as asked
        h_mm = r.provenance["apex_element_mm"]
        assert abs(zone_mm / h_mm - cc.RETRY_FACTOR * elements) < 1e-9
        factor = r.provenance["zone_refinement"]
        assert any(f"traced again with {cc.RETRY_FACTOR * elements:g} (the coarse mesh x "
                   f"{factor:.2g} at the contact)" in n for n in r.notes), r.notes
        assert any(f": {elements:g} elements across" in n for n in r.notes), r.notes
        # the apex elements of the meshes actually solved (mesh.graded rescales the sizes
        # to fit the meridian: a few per cent)
        for mesh, n in zip(seen, (elements, cc.RETRY_FACTOR * elements)):
            nodes = mesh.nodes[:, mesh.outer]
            h = np.hypot(*(nodes[:, 2] - nodes[:, 0])) * 20
            assert abs(h - zone_mm / n) < 0.05 * zone_mm / n


def test_a_path_that_snaps_without_turning_is_answered_with_twice_the_elements(monkeypatch):
    """The first path is cut to 25 states (as the base shell's at lambda 3 with no_slip
    and four elements runs out of its 3000 states snapping from node to node); the retry
    with eight runs in full and answers, without error bars (the coarser mesh would have
    the failed path's four) and with the first path named in the notes and provenance."""
    real = arclength.trace
    calls = []

    def first_short(iface, *a, **k):
        calls.append(iface.d.ndof)
        if len(calls) == 1:
            k = {**k, "settings": arclength.ArcSettings(max_steps=25)}
        return real(iface, *a, **k)
    monkeypatch.setattr(cc, "trace", first_short)
    r = cc.solve_cohesive_case(20, 3, 20, 0.3, 30, tabor=1.0, mesh="coarse",
                               interface="no_slip", beta=0, history="adhesive")
    assert not r.refused and r.coarser is None and len(calls) == 2
    assert calls[1] > calls[0]                      # the retried mesh is finer
    assert r.provenance["first_path"]["refused"].startswith("did not turn round")
    assert r.provenance["zone_elements"] == cc.RETRY_FACTOR * cc.ZONE_ELEMENTS
    assert any("no error bars: the next coarser mesh would have 4 elements" in n
               for n in r.notes), r.notes
    po = r.to_dict()["pull_off"]
    assert po["P_star_N_error"] is None
    # the pull-off of the retried path: the base shell's at lambda 1 within its error bar
    # (the normal-only law with the adhesive history; default mesh, four across: -2.1747
    # +- 0.0083 N, docs/adhesion-range.md; measured -2.1768 N)
    assert po["P_star_N"] == pytest.approx(-2.1747, abs=0.0083)


def test_the_fitted_family_keeps_its_ratio():
    fit = dict(uniform=0.15, refine=0.3)
    sizes = {m: cc.fitted_spec(m, fit) for m in ("fine", "default", "coarse")}
    assert sizes["coarse"].h_apex == pytest.approx(2 * sizes["default"].h_apex, rel=1e-12)
    assert sizes["default"].h_apex == pytest.approx(2 * sizes["fine"].h_apex, rel=1e-12)
    assert sizes["default"].layer0 == pytest.approx(0.3 * mesh_spec("default").layer0, rel=1e-12)
    # a zone the named mesh resolves leaves it as it is
    assert cc.zone_refinement(1.0, "default") == 1.0
    assert cc.fitted_spec("default", dict(uniform=0.15, refine=1.0)) == mesh_spec("default", 0.15)


def test_a_long_range_pull_off_is_resolved_where_the_contact_is_lost():
    """At small lambda P(delta) has a corner at its least P (where the compressive contact
    ends, the slope jumps from about +90 to -42 N per unit delta/R on the solid cap at
    lambda 0.1): the retraction's steps, 0.1 delta_max there, sampled it coarsely and
    the two meshes missed it differently (P* -3.4555 +- 0.244 N, a* 0.27 +- 1.15 mm).  A
    step that passes a new least P is halved until P varies across it by at most
    ArcSettings.P_resolve |P|: measured P* -3.5340 +- 0.0050 N, a* 0.584 +- 0.0033 mm."""
    r = cc.solve_cohesive_case(R_mm=20, t_mm=20, h_mm=20, C10_MPa=0.3, gamma_J_m2=30,
                               tabor=0.1, mesh="coarse")
    po = r.to_dict()["pull_off"]
    print({k: po[k] for k in ("P_star_N", "P_star_N_error", "a_star_mm", "a_star_mm_error")})
    assert po["P_star_N_error"] <= 0.005 * abs(po["P_star_N"])
    assert po["a_star_mm_error"] <= 0.02 * po["a_star_mm"]
    # the least P is resolved on the traced path: its neighbours lie within 2 P_resolve
    states = r.solve.path.states[r.solve.path.turn:]
    P = np.array([s.P for s in states])
    i = int(np.argmin(P))
    assert np.all(np.abs(P[[i - 1, i + 1]] / P[i] - 1) <= 2 * arclength.ArcSettings().P_resolve)
