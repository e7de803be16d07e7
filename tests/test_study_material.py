"""A study with a material: one set of FE paths per swept ratio, the ratio a cube dimension,
and C01/C10 = 0 exactly the neo-Hookean study (it shares its FE paths)."""
import numpy as np
import pytest
import xarray as xr

from shell_adhesion.study.run import execute

NH = """\
name: nh
R_mm: 20
base: {C10_MPa: 0.3, t_over_R: 0.15, h_over_R: 1.0, gamma_J_m2: 30}
mesh: coarse
delta_max_over_R: 0.1
error_bars: false
outputs: {deformed_states: false}
"""
MR = NH.replace("name: nh", "name: mr") + """\
material: {model: mooney_rivlin}
sweeps:
  C01_over_C10: [0, 0.5]
"""


MPA = NH.replace("name: nh", "name: mpa").replace("C10_MPa: 0.3, ", "") + """\
material: {model: mooney_rivlin, C10_MPa: 0.3}
grid:
  C01_MPa: [0, 0.15]
"""


def run(tmp_path, name, text, cat):
    path = tmp_path / f"{name}.yaml"
    path.write_text(text)
    outcome = execute(path, tmp_path / "results", catalogue=cat, progress=False, workers=1)
    with xr.open_dataset(outcome.output) as ds:
        return outcome, ds.load()


@pytest.mark.slow      # CI time: see README (python -m pytest -m slow)
def test_c01_sweep_is_a_dimension_and_zero_is_neo_hooke(tmp_path):
    cat = tmp_path / "cat"
    nh_out, nh = run(tmp_path, "nh", NH, cat)
    mr_out, mr = run(tmp_path, "mr", MR, cat)
    assert len(mr_out.plan.shells) == 2
    assert mr_out.reused == [nh_out.plan.shells[0].fingerprint]     # C01/C10 = 0: NH's set
    assert len(mr_out.computed) == 1
    assert list(mr.C01_over_C10.values) == [0.0, 0.5]
    assert set(nh.P_star.dims) == {"C10", "t_over_R", "h_over_R", "gamma"}
    assert mr.attrs["material_model"] == "mooney_rivlin"
    at = dict(C10=0.3, t_over_R=0.15, h_over_R=1.0, gamma=30)
    p0 = mr.P_star.sel(C01_over_C10=0.0, **at).item()
    assert p0 == nh.P_star.sel(**at).item()
    assert mr.eta.sel(C01_over_C10=0.0, **at).item() == nh.eta.sel(**at).item()
    p5 = mr.P_star.sel(C01_over_C10=0.5, **at).item()
    assert np.isfinite(p5) and p5 < p0 < 0          # stiffer: a more tensile pull-off
    assert (mr.status.sel(**at) == "ok").all()

    # the same solids in MPa: C01_MPa = 0.15 at C10 = 0.3 is C01/C10 = 0.5, nothing solved
    mpa_out, mpa = run(tmp_path, "mpa", MPA, cat)
    assert mpa_out.computed == [] and len(mpa_out.reused) == 2
    assert list(mpa.C01_over_C10.values) == [0.0, 0.5]
    assert mpa.C01_MPa.attrs["units"] == "MPa"
    assert mpa.C01_MPa.sel(C10=0.3).values.tolist() == [0.0, 0.15]
    np.testing.assert_array_equal(mpa.P_star.sel(**at).values, mr.P_star.sel(**at).values)
    from shell_adhesion.study.config import validate
    from shell_adhesion.cube import study_of
    back = validate(study_of(mpa))
    assert back.grid == {"C01_MPa": (0.0, 0.15)} and back.base["C10_MPa"] == 0.3
