"""The shipped pull-off maps against FE cases off their grid, `design` on a case whose
optimum is known, and the `map` / `design` commands' bad input.

The shipped default map is checked against default-mesh cases (slow), the coarse one
against coarse cases (every run).  Map and case come from different meshes of the same family (each shell
meshed for itself), so their difference is held to the map's whole stated error:
interpolation and FE in quadrature; the interpolation part is held below 2 %.
"""
import json
import math

import numpy as np
import pytest

import shell_adhesion as sa
from shell_adhesion.cli import main
from shell_adhesion.study.pull_off_map import DEFAULT_MAP, SHIPPED, map_path, pull_off_map
from validation import within

R_MM, C10_MPA = 20.0, 1.0
# off the grid (t/R 0.05 ... 0.4 x h/R 0.5, 0.75, 1 x gamma_hat 0.0003 ... 0.03): a thin
# shell, a shallow one, a thick one, and two between; gamma_hat from 0.0015 to 0.02
OFF_GRID = [(0.06, 0.9, 0.004), (0.17, 0.55, 0.007), (0.25, 0.65, 0.0015),
            (0.35, 0.85, 0.02), (0.11, 0.8, 0.012)]
INTERPOLATION_MAX = 0.02    # the map's interpolation error, relative to P*, at these shells
# docs/map.md: each map's misses against cases on its mesh there [%], its stated errors [%]
# (interpolation and FE in quadrature) and their interpolation parts [%]
DOC = {"coarse": dict(misses=(+0.18, -0.49, -0.46, -0.53, -0.22), stated=(1.4, 1.7, 2.5, 1.9, 1.3)),
       "default": dict(misses=(+0.12, -0.21, +0.06, -0.14, -0.29), stated=(1.4, 0.9, 0.8, 1.0, 1.1),
                       interpolation=(1.3, 0.6, 0.3, 0.7, 0.9))}


def _case(t, h, g, mesh, error_bars):
    res = sa.solve_case(R_MM, t * R_MM, h * R_MM, C10_MPA, [g * C10_MPA * R_MM * 1e3],
                        mesh=mesh, progress=False, error_bars=error_bars)
    po = res.to_dict()["pull_off"][0]
    assert po["status"] == "ok", po
    scale = C10_MPA * R_MM ** 2
    return po["fixed_load"]["P_N"] / scale, (po["fixed_load"].get("P_N_error") or 0) / scale


def _check(map_name):
    """The map's P* against a case on its own mesh at each OFF_GRID shell, printed; every
    miss within the stated error, every interpolation error below INTERPOLATION_MAX, and
    docs/map.md's numbers, each to one unit of its last digit."""
    pm = pull_off_map(map_name)
    assert pm.ds.attrs["mesh"] == map_name
    rows = []
    for t, h, g in OFF_GRID:
        P_fe, _ = _case(t, h, g, map_name, False)
        ans = pm.predict(t, h, g)["P_star"]
        rows.append((t, h, g, P_fe, ans.value, ans.interpolation_error, ans.error))
    print("\nt/R   h/R   g_hat   P*_FE/(C10R^2)  map      interp err  stated err  miss")
    for t, h, g, fe, v, ie, e in rows:
        print(f"{t:<5} {h:<5} {g:<7} {fe:<15.6f} {v:<8.6f} {100 * ie / abs(v):6.2f} %  "
              f"{100 * e / abs(v):6.2f} %   {100 * (v - fe) / abs(fe):+.2f} %")
    doc = DOC[map_name]
    for k, (t, h, g, fe, v, ie, e) in enumerate(rows):
        assert abs(v - fe) <= e, f"t/R {t}, h/R {h}, gamma_hat {g}: map {v} vs FE {fe}, stated {e}"
        assert ie <= INTERPOLATION_MAX * abs(v), f"t/R {t}: interpolation {ie / abs(v):.3%}"
        within(f"miss at t/R {t}", 100 * (v - fe) / abs(fe), doc["misses"][k], 0.0, floor=0.01)
        within(f"stated error at t/R {t}", 100 * e / abs(v), doc["stated"][k], 0.0, floor=0.1)
        if map_name == "default":   # issue 22: the shipped map's stated error below 2 %
            assert e < 0.02 * abs(v), f"t/R {t}: stated {e / abs(v):.3%}"
        if "interpolation" in doc:
            within(f"interpolation error at t/R {t}", 100 * ie / abs(v),
                   doc["interpolation"][k], 0.0, floor=0.1)


def test_coarse_map_against_coarse_cases_off_its_grid():
    _check("coarse")


@pytest.mark.slow
def test_default_map_against_default_cases_off_its_grid():
    # five default-mesh cases: about 200 s on 2 cores, too long for every run
    _check("default")


def test_the_maps_errors_as_the_docs_state_them():
    """docs/map.md's interpolation errors of the shipped default map over gamma/(C10 R)
    0.001-0.03: 3000 shells drawn uniformly in (ln t/R, h/R, ln gamma/(C10 R)), seed 0,
    none refused: the map has no holes (`python benchmarks/map_errors.py` prints the
    same)."""
    pm = pull_off_map()
    assert not (pm.ds["reason"] != "").any(), "a grid point of the shipped map failed"
    assert math.isfinite(pm.predict(0.05, 0.5, 0.02)["P_star"].value)     # a hole before
    s = pm.survey()
    t, g, interp, total = s["t_over_R"], s["gamma_hat"], s["interpolation"], s["total"]
    assert s["holes"] == 0
    within("median interpolation error [%]", np.median(interp), 0.8, 0.0, floor=0.1)
    within("p90 interpolation error [%]", np.percentile(interp, 90), 2.3, 0.0, floor=0.1)
    within("largest interpolation error [%]", interp.max(), 7.5, 0.0, floor=0.1)
    within("share below 2 % [%]", 100 * np.mean(interp < 2), 89, 0.0, floor=1)
    band = (t >= 0.1) & (t < 0.2)
    within("share above 2 % at t/R 0.1-0.2 [%]", 100 * np.mean(interp[band] > 2), 18, 0.0, floor=1)
    within("share above 2 % at gamma_hat > 0.01 [%]", 100 * np.mean(interp[g > 0.01] > 2), 18,
           0.0, floor=1)
    within("median total error [%]", np.median(total), 1.2, 0.0, floor=0.1)
    # the FE part: grid points whose error bar is above 2 % of P*, and the largest
    fe = s["fe_grid"]
    within("grid points with an FE error bar above 2 % [%]", np.mean(fe > 2) * 100, 20, 0.0, floor=1)
    within("largest FE error bar [%]", fe.max(), 5.55, 0.0, floor=0.1)


def test_the_coarse_maps_fe_error_bars_as_the_docs_state_them():
    """docs/map.md: on the coarse map (today's error-bar rule) 45 % of the grid points have
    an FE error bar above 2 % of P*, the largest 11.9 %."""
    fe = pull_off_map("coarse").survey(n=0)["fe_grid"]
    within("grid points with an FE error bar above 2 % [%]", 100 * np.mean(fe > 2), 45, 0.0,
           floor=1)
    within("largest FE error bar [%]", fe.max(), 11.9, 0.0, floor=0.1)


def test_shipped_maps_are_in_the_package_with_their_studies():
    assert DEFAULT_MAP in SHIPPED
    for name in SHIPPED:
        assert map_path(name).is_file()
        pm = pull_off_map(name)
        assert pm.bounds["t_over_R"] == (0.05, 0.4) and pm.bounds["h_over_R"] == (0.5, 1.0)
        assert pm.ds.attrs["interface"] == "no_slip"
        assert pm.ds.attrs["mesh"] == name
    assert sa.examples.study_text("map").count("mesh: default") == 1
    assert sa.examples.study_text("map-coarse").count("mesh: coarse") == 1


def test_design_puts_the_thickness_on_its_bound_and_the_case_agrees():
    # at fixed h/R, |P*| grows with t/R on the whole map (checked here), so the best
    # shell within t <= 6 mm is the thickest: t on its upper bound
    pm = pull_off_map("coarse")
    g = 30e-3 / (C10_MPA * R_MM)
    along_t = [abs(pm.predict(t / R_MM, 1.0, g)["P_star"].value) for t in (2, 3, 4, 5, 6)]
    assert along_t == sorted(along_t)
    result = sa.design(C10_MPA, 30, "pull_off", R_mm=R_MM, t_mm=(2, 6), h_mm=(20, 20),
                       map="coarse")
    assert result.design.t_mm == pytest.approx(6, rel=1e-3)
    assert "t at its upper bound 6 mm (your bound)" in result.design.on_bounds
    assert result.agrees, result.to_text()
    fe, _ = result.confirmation["P_star_N"]
    assert fe == pytest.approx(result.design.answers["P_star_N"][0], rel=0.02)


@pytest.mark.parametrize("args, message", [
    (["map", "query", "--R", "20", "--t", "9", "--h", "15", "--C10", "0.3", "--gamma", "30",
      "--map", "coarse"], "--t: 9 mm is t/R = 0.45, outside the map's [0.05, 0.4]"),
    (["map", "query", "--R", "20", "--t", "3", "--h", "15", "--C10", "0.3", "--gamma", "900",
      "--map", "coarse"], "--gamma: 900 J/m^2 is gamma/(C10 R) = 0.15, outside the map's"),
    (["map", "query", "--R", "x", "--t", "3", "--h", "15", "--C10", "0.3", "--gamma", "30"],
     "--R: 'x' is not a number"),
    (["map", "query", "--R", "20", "--t", "3", "--h", "15", "--C10", "0.3", "--gamma", "30",
      "--map", "nowhere.nc"], "--map: 'nowhere.nc' is neither a shipped map"),
    (["design", "--C10", "0.3", "--gamma", "-1", "--R", "20"], "--gamma: -1 must be"),
    (["design", "--C10", "0.3", "--gamma", "30", "--R", "20", "--t", "6", "2"],
     "--t: 6 2: MIN must be <= MAX"),
    (["design", "--C10", "0.3", "--gamma", "30", "--R", "20", "--t", "30", "40", "--map",
      "coarse"],
     "--t: 30 to 40 mm is outside the map: t from 1 to 8 mm for R 20 mm"),
    (["map", "build", "study.yaml", "--out", "map.txt"], "--out: map.txt: the map file must end"),
])
def test_bad_input_is_one_line_and_exit_2(args, message, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(args) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and len(err.splitlines()) == 1, err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("C10, grid, message", [
    (-1, "t_over_R: [0.1], h_over_R: [1.0], gamma_J_m2: [10]", "base.C10_MPa: -1 must be > 0"),
    # a map interpolates: one value on an axis is refused before any FE work
    (0.3, "t_over_R: [0.1, 0.2], h_over_R: [1.0], gamma_J_m2: [10, 20]",
     "grid.h_over_R: 1: a map interpolates along t_over_R, h_over_R and gamma_J_m2: give "
     "each two or more values in the grid"),
])
def test_a_bad_map_study_is_one_line_and_exit_2(C10, grid, message, capsys, tmp_path,
                                                monkeypatch, forbid_fe):
    """`map build` checks its study as `run` does, and that it spans a map: one line
    naming the field, exit 2, nothing created (no catalogue, no map, no study folder)."""
    study = tmp_path / "map.yaml"
    study.write_text(f"name: m\nR_mm: 20\nbase: {{C10_MPa: {C10}}}\nmesh: coarse\n"
                     f"grid: {{{grid}}}\n")
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    assert main(["map", "build", str(study), "--out", "m.nc", "--catalogue", "cat"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == f"shell-adhesion: error: {study}: {message}", err
    assert list(work.iterdir()) == []


def test_query_answers_in_units_with_error_bars(capsys):
    assert main(["map", "query", "--R", "20", "--t", "3", "--h", "15", "--C10", "0.3",
                 "--gamma", "30", "--gamma", "60", "--map", "coarse", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    first = out["pull_off"][0]
    direct = pull_off_map("coarse").shell(20, 3, 15, 0.3, 30)
    assert first["P_star_N"]["value"] == pytest.approx(direct["P_star_N"][0])
    assert 0 < first["P_star_N"]["error"] < 0.1 * abs(first["P_star_N"]["value"])
    assert math.isfinite(out["pull_off"][1]["delta_star_mm"]["value"])
