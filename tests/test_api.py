"""The Python API: `shell_adhesion.solve_case` and what its result renders; the command line
prints exactly `CaseResult.to_json()`; a foreign top-level `catalogue` package is harmless."""
import json
import math
import subprocess
import sys

import numpy as np
import pytest

import shell_adhesion as sa
from shell_adhesion.errors import InputError
from shell_adhesion.solver.scaling import force_N, gamma_hat, length_mm
from shell_adhesion.study import case as case_module
from shell_adhesion.cli import main

from conftest import ENV

BASE = dict(R_mm=20, t_mm=3, h_mm=20, C10_MPa=0.3)
GAMMAS = [30, 20]


@pytest.fixture(scope="module")
def solved():
    return sa.solve_case(**BASE, gamma_J_m2=GAMMAS, delta_max_mm=2, mesh="coarse",
                         progress=False)


def test_exports():
    from shell_adhesion.analysis import open_results
    assert sa.solve_case is case_module.solve_case and sa.CaseResult is case_module.CaseResult
    assert sa.open_results is open_results
    assert {"solve_case", "CaseResult", "open_results", "run_study"} <= set(dir(sa))
    with pytest.raises(AttributeError):
        sa.no_such_thing


@pytest.mark.parametrize("change, message", [
    (dict(R_mm=math.nan), "R_mm: nan must be a finite number (mm)"),
    (dict(R_mm=1e200), "R_mm: 1e+200 must be from 0.001 to 10000 mm"),
    (dict(t_mm=25), "t_mm (t/R = 25/20): 1.25 must satisfy 0 < t <= R"),
    (dict(C10_MPa=-1), "C10_MPa: -1 must be > 0"),
    (dict(gamma_J_m2=[30, 900]), "gamma_J_m2: 900 J/m^2 with C10 = 0.3 MPa and R = 20 mm "
                                 "gives gamma/(C10 R) = 0.15, which must be <= 0.03"),
    (dict(gamma_J_m2="30"), "gamma_J_m2: '30' must be a number"),
    (dict(delta_max_mm=25), "delta_max_mm (delta_max/R = 25/20): 1.25 is outside the supported domain delta/R <= 0.25"),
    (dict(mesh="ultra"), "mesh: 'ultra' must be one of coarse, default, fine"),
])
def test_bad_input_raises_before_any_computation(monkeypatch, change, message):
    def no_fe(*args, **kwargs):
        raise AssertionError("the FE solver ran on bad input")
    monkeypatch.setattr(case_module, "solve_request", no_fe)
    with pytest.raises(InputError) as e:
        sa.solve_case(**dict(BASE, **change))
    assert isinstance(e.value, ValueError)
    assert str(e.value).startswith(message) and "\n" not in str(e.value)


def test_dataset_named_dimensions_units_everywhere(solved):
    ds = solved.to_dataset()
    assert dict(ds.sizes).keys() >= {"gamma", "loading_state", "relaxation", "relaxation_state",
                                     "point"}
    for name, var in ds.variables.items():
        assert var.attrs.get("units") and var.attrs.get("long_name"), name
    assert list(ds.gamma.values) == GAMMAS and ds.gamma.units == "J/m^2"
    # curves are coordinates: select and plot against them
    eq = ds.P_eq.sel(gamma=30)
    assert eq.a_eq_mm.units == "mm" and np.isfinite(eq.values).sum() > 3
    import matplotlib
    matplotlib.use("Agg")
    assert ds.loading_P.plot(x="loading_delta_mm")
    # the dimensional values are the path set's, scaled by C10 R^2 and R
    R, C10 = BASE["R_mm"], BASE["C10_MPa"]
    ps = solved.pathset
    np.testing.assert_allclose(ds.loading_P.values, force_N(ps.loading_P, C10, R), rtol=1e-14)
    np.testing.assert_allclose(ds.loading_delta_mm.values, length_mm(ps.loading_delta, R),
                               rtol=1e-14)
    assert ds.loading_delta_mm.values[-1] == pytest.approx(2.0)
    for g in GAMMAS:
        _, po = ps.pull_off(gamma_hat(g, C10, R))
        assert float(ds.P_star.sel(gamma=g)) == pytest.approx(force_N(po.P_star, C10, R),
                                                               rel=1e-12)
    # adhesion pulls harder the larger gamma, and the pull-off is tensile
    assert ds.P_star.sel(gamma=30) < ds.P_star.sel(gamma=20) < 0


def test_json_matches_dataset(solved):
    data = json.loads(solved.to_json(curves=True))
    ds = solved.to_dataset()
    assert data["input"] == dict(BASE, delta_max_mm=2.0, gamma_J_m2=[30.0, 20.0],
                                 interface="no_slip", mesh="coarse")
    for po in data["pull_off"]:
        g = po["gamma_J_m2"]
        assert po["fixed_load"]["P_N"] == pytest.approx(float(ds.P_star.sel(gamma=g)), rel=1e-9)
        assert po["fixed_grips"]["a_mm"] == pytest.approx(float(ds.a_dagger.sel(gamma=g)),
                                                          rel=1e-9)
    assert len(data["relaxation"]) == ds.sizes["relaxation"]
    assert data["loading"]["P_N"] == pytest.approx(list(ds.loading_P.values), rel=1e-9)


def test_the_default_json_is_the_summary(solved):
    """Issue 24: `case --json` is short (the pull-off numbers with error bars and units, the
    input, the provenance); the curves come with curves=True (`--curves`)."""
    short, full = solved.to_json(), solved.to_json(curves=True)
    assert len(short.splitlines()) < 200 < len(full.splitlines())
    data, everything = json.loads(short), json.loads(full)
    assert list(data) == ["input", "material", "pull_off", "provenance"]
    assert {"loading", "relaxation", "equilibrium"} <= set(everything)
    assert data["pull_off"] == everything["pull_off"] and data["input"] == everything["input"]
    assert "P_N_error" in data["pull_off"][0]["fixed_load"]


def test_cli_prints_exactly_to_json(solved, monkeypatch, capsys):
    calls = []

    def fake(*args, **kwargs):
        calls.append((args, kwargs))
        return solved
    monkeypatch.setattr(case_module, "solve_case", fake)
    code = main(["case", "--R", "20", "--t", "3", "--h", "20", "--C10", "0.3", "--gamma", "30",
                 "--gamma", "20", "--delta-max", "2", "--mesh", "coarse", "--json"])
    assert code == 0 and len(calls) == 1
    assert calls[0][0] == (20.0, 3.0, 20.0, 0.3, (30.0, 20.0))
    assert capsys.readouterr().out == solved.to_json() + "\n"


def test_cli_text_gives_every_pull_off_number_its_error_bar(solved, monkeypatch, capsys):
    """The text output of `case` carries the error bar of every pull-off number, a0 too
    (it printed a0 bare while the JSON had its error)."""
    monkeypatch.setattr(case_module, "solve_case", lambda *a, **k: solved)
    code = main(["case", "--R", "20", "--t", "3", "--h", "20", "--C10", "0.3", "--gamma", "30",
                 "--gamma", "20", "--delta-max", "2", "--mesh", "coarse"])
    lines = [s for s in capsys.readouterr().out.splitlines() if s.startswith("gamma = ")]
    assert code == 0 and len(lines) == len(GAMMAS)
    for line, po in zip(lines, solved.to_dict()["pull_off"]):
        # P*, delta*, a*, P, delta, a, eta, and a0 where it is defined (delta_max = 2 mm
        # ends the 30 J/m^2 curve before P = 0)
        if po["a0_mm"] is None:
            assert "a0 = undefined" in line and line.count(" +- ") == 7
        else:
            assert po["a0_mm_error"] > 0 and line.count(" +- ") == 8
            assert f"a0 = {po['a0_mm']:.4f} +- {po['a0_mm_error']:.2g} mm" in line
    assert any(po["a0_mm"] is not None for po in solved.to_dict()["pull_off"])


FOREIGN = """\
import sys
import catalogue
assert catalogue.__file__.startswith(sys.argv[1]) and not hasattr(catalogue, "Catalogue")
import shell_adhesion
from shell_adhesion.catalogue import Catalogue
import shell_adhesion.study.run
print("ok", shell_adhesion.__version__)
"""


def test_foreign_catalogue_package_first_on_sys_path(tmp_path):
    foreign = tmp_path / "foreign"
    (foreign / "catalogue").mkdir(parents=True)
    (foreign / "catalogue" / "__init__.py").write_text('"""Not the shell-adhesion one."""\n')
    env = dict(ENV, PYTHONPATH=f"{foreign}:{ENV['PYTHONPATH']}")
    env.pop("SHELL_ADHESION_CATALOGUE", None)
    out = subprocess.run([sys.executable, "-c", FOREIGN, str(foreign)], env=env, cwd=foreign,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0 and out.stdout.startswith("ok"), out.stderr
    # -m runs with the working folder first on sys.path: there the foreign package sits
    def run(*argv):
        return subprocess.run([sys.executable, "-m", "shell_adhesion", *argv], env=env,
                              cwd=foreign, capture_output=True, text=True, timeout=300)
    case = run("case", "--R", "20", "--t", "3", "--h", "20", "--C10", "0.3", "--mesh", "coarse",
               "--delta-max", "0.5", "--json", "--curves")
    assert case.returncode == 0, case.stderr
    assert json.loads(case.stdout)["loading"]["delta_mm"][-1] == pytest.approx(0.5)
    listed = run("catalogue", "list")
    assert listed.returncode == 0 and listed.stdout.startswith("fingerprint"), listed.stderr


def test_mooney_rivlin_case_carries_its_material():
    """--material mooney-rivlin reaches the FE (stiffer than neo-Hookean), and the JSON and
    the Dataset carry the model and its coefficients in MPa; eta uses mu0 = 2 (C10 + C01)."""
    from shell_adhesion import theory
    from shell_adhesion.solver.material import Material

    kw = dict(gamma_J_m2=30, delta_max_mm=1, mesh="coarse", progress=False)
    mr = sa.solve_case(**BASE, material="mooney-rivlin", C01_MPa=0.06, **kw)
    nh = sa.solve_case(**BASE, **kw)
    data = json.loads(mr.to_json(curves=True))
    assert data["material"] == dict(model="mooney_rivlin", C10_MPa=0.3, C01_MPa=0.06,
                                    C20_MPa=0.0, C30_MPa=0.0, Jm=None, D1_per_MPa=0.0)
    assert json.loads(nh.to_json())["material"]["model"] == "neo_hooke"
    assert data["provenance"]["material"] == Material("mooney_rivlin", 0.2).as_dict()
    # same delta, stiffer solid: a larger load
    assert data["loading"]["P_N"][-1] > json.loads(nh.to_json(curves=True))["loading"]["P_N"][-1] > 0
    po = data["pull_off"][0]
    m = Material("mooney_rivlin", 0.2)
    assert po["eta"] == pytest.approx(
        abs(po["fixed_load"]["P_N"]) / theory.shell_law_scale_N(20, 3, 0.3, 30, m), rel=1e-8)
    ds = mr.to_dataset()
    assert ds.attrs["material_model"] == "mooney_rivlin"
    assert float(ds.C01_MPa) == pytest.approx(0.06) and ds.C01_MPa.units == "MPa"
    assert "mooney_rivlin" in ds.attrs["title"]


@pytest.mark.parametrize("change, message", [
    (dict(material="yeoh", C20_MPa=-0.1), "material: yeoh (C10 = 0.3 MPa, C20 = -0.1 MPa"),
    (dict(material="yeoh", C01_MPa=0.05), "C01_MPa: 0.05 is not a coefficient of the yeoh"),
    (dict(material="gent"), "Jm: the gent model needs Jm"),
    (dict(D1_per_MPa=-1), "D1_per_MPa: -1 /MPa must be >= 0"),
    (dict(material="ogden"), "material: 'ogden' must be one of neo-hookean, mooney-rivlin"),
])
def test_bad_material_raises_before_any_computation(monkeypatch, change, message):
    def no_fe(*args, **kwargs):
        raise AssertionError("the FE solver ran on bad input")
    monkeypatch.setattr(case_module, "solve_request", no_fe)
    with pytest.raises(InputError) as e:
        sa.solve_case(**dict(BASE, **change))
    assert str(e.value).startswith(message) and "\n" not in str(e.value)


def test_error_bars_beside_every_number(solved):
    """Issue 10 item 7, issue 21 item 7: every headline number and the loading P carry the
    error estimate of solver.error_bars from the same shell on the next two coarser meshes
    (the observed order where the three converge, beside it as "<name>_order")."""
    from shell_adhesion.solver.error_bars import (error_bar, observed_order,
                                                   refines_through_thickness, rule)
    out = solved.to_dict(curves=True)
    observable = refines_through_thickness(solved.input.t_mm / solved.input.R_mm, "coarse")
    assert (solved.coarser.mesh, solved.coarsest.mesh) == ("coarser", "coarsest")
    assert out["provenance"]["error_bars"]["coarser_meshes"] == ["coarser", "coarsest"]
    # the companions relax contact fronts of the answer's kind (solver.error_bars)
    family = solved.pathset.stats["relaxation_family"]
    assert family in ("corner", "midside")
    assert {c.stats["relaxation_family"] for c in (solved.coarser, solved.coarsest)} == {family}
    for po, (_, _, c1), c2, c3 in zip(out["pull_off"], solved.adhesion,
                                      solved.coarser_pull_off, solved.coarsest_pull_off):
        for group, name, key in (("fixed_load", "P_N", "P_star"), ("fixed_grips", "delta_mm",
                                                                     "delta_dagger")):
            err = po[group][f"{name}_error"]
            dim = ((lambda x: force_N(x, 0.3, 20)) if name == "P_N"
                   else (lambda x: length_mm(x, 20)))
            value, coarser, coarsest = (dim(getattr(c, key)) for c in (c1, c2, c3))
            assert err == pytest.approx(float(error_bar(value, coarser, coarsest, observable)),
                                        rel=1e-6)
            order = observed_order(value, coarser, coarsest, observable)
            assert (po[group][f"{name}_order"] is None) == bool(np.isnan(order))
            assert po[group][f"{name}_rule"] == rule(value, coarser, coarsest, observable)
            assert 0 < err < 0.1 * abs(value)      # coarse mesh: a few per cent
        assert po["eta_error"] > 0 and "a0_mm_error" in po
    errors = out["loading"]["P_N_error"]
    assert len(errors) == len(out["loading"]["P_N"]) and errors[-1] > 0
    ds = solved.to_dataset()
    assert {"P_star_error", "a_dagger_error", "eta_error", "loading_P_error"} <= set(ds)


def test_no_error_bars_skips_the_coarser_mesh():
    out = subprocess.run([sys.executable, "-m", "shell_adhesion", "case", "--R", "20", "--t", "3",
                          "--h", "20", "--C10", "0.3", "--mesh", "coarse", "--delta-max", "0.5",
                          "--json", "--curves", "--no-error-bars"], env=ENV, capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    assert "P_N_error" not in d["loading"] and d["provenance"]["error_bars"] is None
