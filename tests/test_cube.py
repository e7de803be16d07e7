"""The results cube as the ecosystem reads it: the CF-1.8 compliance checker finds no
high-priority failure, pint (default registry) and UDUNITS read every unit, the curves are
coordinates along named dimensions, and the study is stored as plain attributes from which
the study file's dictionary is rebuilt."""
import json
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr
from matplotlib.figure import Figure

from shell_adhesion import cube
from shell_adhesion.study import config
from shell_adhesion.analysis import open_results

BASE = dict(C10=0.3, t_over_R=0.15, h_over_R=1.0, gamma=30.0)
# the checker's Python API in a subprocess (a timeout fails it instead of hanging)
CHECKER = """import sys
from compliance_checker.runner import CheckSuite, ComplianceChecker
CheckSuite.load_all_available_checkers()
ComplianceChecker.run_checker(sys.argv[1], ["cf:1.8"], 0, "normal",
                              output_filename=sys.argv[2], output_format="json")
"""


@pytest.fixture(scope="module")
def ds(small_study):
    return open_results(small_study)


def cf_high_priority_failures(path, tmp_path):
    """(failures [(check, messages)], report) of the IOOS checker's cf:1.8 suite."""
    pytest.importorskip("compliance_checker", reason="compliance-checker (test extra) is "
                        "not installed")
    report = tmp_path / f"{path.stem}.json"
    done = subprocess.run([sys.executable, "-c", CHECKER, str(path), str(report)],
                          capture_output=True, text=True, timeout=300)
    assert report.is_file(), done.stdout + done.stderr
    result = json.loads(report.read_text())["cf:1.8"]
    failures = [(r["name"], r["msgs"]) for r in result["high_priorities"]
                if r["value"][0] < r["value"][1]]
    return failures, result


def test_cf_compliance_checker_finds_no_high_priority_failure(small_study, tmp_path):
    failures, result = cf_high_priority_failures(small_study, tmp_path)
    assert result["possible_points"] > 1000 and result["high_priorities"]   # it did check
    assert not failures, "\n".join(f"{name}: {m}" for name, msgs in failures for m in msgs)


@pytest.mark.slow      # CI time: see README (python -m pytest -m slow)
def test_cf_checker_catches_a_careless_write(ds, tmp_path):
    """The same cube written with xarray's defaults (64-bit indices, _FillValue on the
    coordinates) fails: the test above can fail."""
    careless = ds.drop_encoding().assign_coords(point=ds["point"].astype(np.int64))
    careless.to_netcdf(tmp_path / "careless.nc")
    failures, _ = cf_high_priority_failures(tmp_path / "careless.nc", tmp_path)
    text = str(failures)
    assert "int64" in text and "_FillValue" in text


def test_index_coordinates_are_32_bit_without_fill_values(small_study):
    import netCDF4
    with netCDF4.Dataset(small_study) as nc:
        for name in nc.dimensions:
            if name in nc.variables:
                var = nc.variables[name]
                assert "_FillValue" not in var.ncattrs(), name
                assert var.dtype != np.int64, name


def test_units_are_read_by_pint_and_udunits(ds):
    pint = pytest.importorskip("pint")
    pytest.importorskip("pint_xarray", reason="pint-xarray (test extra) is not installed")
    cf_units = pytest.importorskip("cf_units", reason="cf_units comes with compliance-checker")
    ureg = pint.get_application_registry()
    q = ds.pint.quantify()
    for name, v in ds.variables.items():
        units = v.attrs["units"]
        assert cf_units.Unit(units).is_unknown() is False, (name, units)
        assert isinstance(q[name].data, pint.Quantity), name
        assert q[name].data.units == ureg.Unit(units), (name, units)
    assert cube.GAMMA_UNITS == ds["gamma"].attrs["units"] == ds["gamma_J_m2"].attrs["units"]
    # 1 J/m^2 = 1 mN/mm; MPa mm^2 = N; N mm = mJ
    np.testing.assert_allclose(q["gamma_J_m2"].pint.to("mN/mm").pint.magnitude,
                               ds["gamma"].values, rtol=1e-14)
    scaled = (q["P_star"] / (q["C10_MPa"] * q["R"] ** 2)).pint.to("dimensionless")
    np.testing.assert_allclose(scaled.pint.magnitude,
                               ds["P_star"] / (ds["C10"] * ds["R"] ** 2), rtol=1e-13)
    work = (q["loading_U"] / (q["loading_P"] * q["loading_delta_mm"])).pint.to("dimensionless")
    np.testing.assert_allclose(work.pint.magnitude,
                               ds["loading_U"] / (ds["loading_P"] * ds["loading_delta_mm"]),
                               rtol=1e-13)
    ghat = (q["gamma_J_m2"] / (q["C10_MPa"] * q["R"])).pint.to("dimensionless")
    np.testing.assert_allclose(ghat.transpose(*ds["gamma_hat"].dims).pint.magnitude,
                               ds["gamma_hat"], rtol=1e-13)
    back = q.pint.dequantify()
    for name in ds.data_vars:
        xr.testing.assert_equal(back[name].drop_attrs(), ds[name].drop_attrs())


def test_every_variable_has_units_and_long_name(ds):
    for name, v in ds.variables.items():
        assert v.attrs.get("units") and v.attrs.get("long_name"), name


def test_curves_are_coordinates_along_named_dimensions(ds):
    ax = Figure().subplots()
    curve = ds["P_eq"].sel(BASE)
    assert curve.dims == ("point",) and "a_eq_mm" in curve.coords
    (line,) = curve.plot(x="a_eq_mm", ax=ax)
    np.testing.assert_array_equal(line.get_xdata(), ds["a_eq_mm"].sel(BASE))
    np.testing.assert_array_equal(line.get_ydata(), curve)
    assert "[mm]" in ax.get_xlabel() and "[N]" in ax.get_ylabel()
    # a point of the curve by its contact radius, once the padding is dropped
    by_a = curve.dropna("point").swap_dims(point="a_eq_mm")
    a_star = float(ds["a_star"].sel(BASE))
    assert float(by_a.sel(a_eq_mm=a_star, method="nearest")) == pytest.approx(
        float(ds["P_star"].sel(BASE)), rel=1e-3)

    # the example: P* against gamma, with its unit on the axis
    ax = Figure().subplots()
    (line,) = ds.P_star.sel(t_over_R=0.15, C10=0.3, h_over_R=1.0).plot(x="gamma_J_m2", ax=ax)
    np.testing.assert_array_equal(line.get_xdata(), [20.0, 30.0, 40.0])
    assert "J/m^2" in ax.get_xlabel()
    lines = ds.P_star.sel(t_over_R=0.15, h_over_R=1.0).plot.line(
        x="gamma_J_m2", hue="C10_MPa", ax=Figure().subplots())
    assert len(lines) == ds.sizes["C10"]
    np.testing.assert_array_equal(ds["C10_MPa"], ds["C10"])
    np.testing.assert_array_equal(ds["gamma_J_m2"], ds["gamma"])

    shell = dict(t_over_R=0.15, h_over_R=1.0)
    loading = ds["loading_P"].sel(C10=0.3, **shell)
    (line,) = loading.plot(x="loading_delta_mm", ax=Figure().subplots())
    np.testing.assert_array_equal(line.get_xdata(), ds["loading_delta_mm"].sel(shell))
    relax = ds["relaxation_P"].sel(C10=0.3, **shell)
    assert relax.dims == ("relaxation", "relaxation_state")
    assert {"relaxation_a_mm", "relaxation_delta_mm"} <= set(relax.coords)
    first = relax.isel(relaxation=0)
    (line,) = first.plot(x="relaxation_delta_mm", ax=Figure().subplots())
    np.testing.assert_array_equal(line.get_xdata(), first["relaxation_delta_mm"])
    assert float(first["relaxation_a_mm"]) == float(ds["relaxation_a_mm"].sel(shell)[0])
    # labels, not results: pull-off values carry no curve coordinate
    assert set(ds["P_star"].coords) == {"C10", "t_over_R", "h_over_R", "gamma", "C10_MPa",
                                        "gamma_J_m2", "t_mm", "h_mm", "gamma_hat", "R"}


def test_study_is_stored_as_numbers_and_rebuilt(ds, small_study):
    a = ds.attrs
    assert (a["base_C10_MPa"], a["base_t_over_R"], a["base_h_over_R"],
            a["base_gamma_J_m2"]) == (0.3, 0.15, 1.0, 30.0)
    np.testing.assert_array_equal(a["sweep_gamma_J_m2"], [20.0, 30.0, 40.0])
    assert a["R_mm"] == 20.0 and a["mesh"] == "coarse" and a["output_loading_curves"] == 1
    for k, v in a.items():
        assert isinstance(v, (str, int, float, np.number, np.ndarray)), k
        assert not (isinstance(v, str) and v.lstrip()[:1] in "{["), f"{k} holds JSON"
    source = config.load_study(small_study.parent.parent / "small.yaml")
    assert config.validate(cube.study_of(ds)).as_dict() == source.as_dict()


@pytest.mark.parametrize("study", [
    dict(name="g", description="", R_mm=10.0, base={"t_over_R": 0.2},
         sweeps={}, grid={"C10_MPa": [0.5], "gamma_J_m2": [10.0, 20.0]}, interface="frictionless",
         mesh="coarse", delta_max_over_R=0.1,
         outputs=dict(equilibrium_curves=True, loading_curves=False, relaxation_curves=True,
                      deformed_states=False)),
    dict(name="s", description="one sweep", R_mm=20.0,
         base={"C10_MPa": 0.3, "t_over_R": 0.15, "h_over_R": 1.0, "gamma_J_m2": 30.0},
         sweeps={"h_over_R": [0.9]}, grid={}, interface="no_slip", mesh="default",
         delta_max_over_R=0.25, outputs=dict(equilibrium_curves=True, loading_curves=True,
                                             relaxation_curves=True, deformed_states=True)),
])
def test_study_attributes_survive_netcdf(study, tmp_path):
    """A partial base, a one-value list and empty groups come back as written."""
    attrs = cube.study_attrs(study)
    xr.Dataset(attrs=attrs).to_netcdf(tmp_path / "s.nc")
    with xr.open_dataset(tmp_path / "s.nc") as back:
        assert cube.study_of(back) == {k: v for k, v in study.items() if v != {}}


def test_the_cube_names_the_mesh_zone_each_shell_used(ds):
    """The base shell's paths also serve C10 = 0.2 MPa (larger gamma / (C10 R)): its mesh
    zone, in the cube with its units, is the one fitted to them, not a single case's."""
    from shell_adhesion import solve_case
    zone = ds["mesh_even_arc_mm"]
    assert zone.attrs["units"] == "mm" and zone.dims == ("t_over_R", "h_over_R")
    served = (ds["pathset_fingerprint"] != "").values
    assert np.isfinite(zone.values[served]).all() and served.any()
    base = dict(t_over_R=0.15, h_over_R=1.0)
    case = solve_case(20, 3, 20, 0.3, [30], mesh="coarse", progress=False, error_bars=False)
    own = case.provenance["fit"]["even_arc_mm"]
    assert float(zone.sel(base)) > own
