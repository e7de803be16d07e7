"""Studies of closed cavities (issue 13, item 5): the `cavity:` block, p_kPa as a sweep or
grid dimension, the plan and the catalogue key (p/C10, p_atm/C10 are FE parameters, so
every C10 of a closed shell is its own path set), and cube values equal to `solve_case`."""
import numpy as np
import pytest

import shell_adhesion as sa
from shell_adhesion.catalogue import Catalogue, fingerprint
from shell_adhesion.solver.cavity import OPEN, Cavity
from shell_adhesion.solver.pathset_dataset import from_dataset
from shell_adhesion.solver.scaling import force_N, length_mm
from shell_adhesion import cube
from shell_adhesion.study import dataset
from shell_adhesion.cli import main
from shell_adhesion.study.config import validate
from shell_adhesion.study.keys import pathset_key
from shell_adhesion.study.plan import make_plan, shell_key
from shell_adhesion.study.run import dry_run

R, C10, GAMMA = 20.0, 0.3, 24.0     # gamma / (C10 R) = 0.004: the paths serve 0.005 in
                                    # both the study (ladder) and solve_case (x 1.25)
STUDY = dict(name="sealed", R_mm=R, base=dict(C10_MPa=C10, t_over_R=0.15, h_over_R=1.0,
                                              gamma_J_m2=GAMMA),
             mesh="coarse", delta_max_over_R=0.05, outputs=dict(deformed_states=False),
             cavity=dict(mode="sealed"))
PRESSURE = dict(STUDY, name="pressure", cavity=dict(mode="pressure", p_kPa=5.0),
                sweeps=dict(p_kPa=[2.0, 5.0]))
AT = dict(C10=C10, t_over_R=0.15, h_over_R=1.0, gamma=GAMMA)
PULL_OFF = dict(P_star="force", a_star="length", delta_star="length", P_dagger="force",
                a_dagger="length", delta_dagger="length")


def study(**change):
    return validate(dict(STUDY, **change))


# -- the study file --------------------------------------------------------------------

GOOD = """\
name: cav
R_mm: 20
base: {C10_MPa: 0.3, t_over_R: 0.15, h_over_R: 1.0, gamma_J_m2: 30}
mesh: coarse
delta_max_over_R: 0.05
"""

BAD = [
    ("unknown key", "cavity: {mode: sealed, p_gauge_kPa: 3}\n",
     "cavity.p_gauge_kPa: unknown key"),
    ("no mode", "cavity: {p_kPa: 3}\n", "cavity.mode: missing"),
    ("unknown mode", "cavity: {mode: vacuum}\n",
     "cavity.mode: 'vacuum' must be one of open, pressure, sealed"),
    ("pressure without p", "cavity: {mode: pressure}\n",
     "cavity.mode: pressure needs cavity.p_kPa"),
    ("p for sealed", "cavity: {mode: sealed, p_kPa: 3}\n",
     "cavity.p_kPa: given without cavity.mode pressure"),
    ("swept p for sealed", "cavity: {mode: sealed}\nsweeps: {p_kPa: [1, 2]}\n",
     "sweeps.p_kPa: given without cavity.mode pressure (cavity.mode is sealed)"),
    ("negative absolute pressure", "cavity: {mode: pressure, p_kPa: 1}\n"
     "sweeps: {p_kPa: [1, -150]}\n",
     "sweeps.p_kPa[1]: -150 gives a negative absolute pressure"),
    ("gas exponent below 1", "cavity: {mode: sealed, gas_exponent: 0.9}\n",
     "cavity.gas_exponent: 0.9 must be >= 1"),
    ("negative absolute sealing pressure", "cavity: {mode: sealed, p0_kPa: -102}\n",
     "cavity.p0_kPa: -102 gives a negative absolute pressure"),
    ("not a number", "cavity: {mode: sealed, p_atm_kPa: high}\n",
     "cavity.p_atm_kPa: 'high' must be a number"),
    ("swept p without base", "cavity: {mode: pressure}\nsweeps: {p_kPa: [1, 2]}\n",
     "cavity.p_kPa: missing"),
    ("solid cap", "cavity: {mode: sealed}\nsweeps: {t_over_R: [0.15, 1.0], h_over_R: [1.0]}\n",
     "cavity.mode: sealed needs a shell (t/R < 1); a solid cap (sweeps.t_over_R[1] = 1)"),
    ("swept ratio", "cavity: {mode: sealed}\nmaterial: {model: mooney_rivlin}\n"
     "sweeps: {C01_over_C10: [0, 0.1]}\n",
     "cavity.mode: sealed with a swept material ratio (sweeps.C01_over_C10) is not supported"),
]


@pytest.mark.parametrize("text, expected", [b[1:] for b in BAD], ids=[b[0] for b in BAD])
def test_bad_cavity_block_exit_2_one_line(tmp_path, capsys, text, expected):
    path = tmp_path / "study.yaml"
    path.write_text(GOOD + text)
    out, cat = tmp_path / "results", tmp_path / "catalogue"
    code = main(["run", str(path), "--out", str(out), "--catalogue", str(cat), "--quiet"])
    err = capsys.readouterr().err
    assert code == 2
    assert expected in err, err
    assert err.strip().count("\n") == 0, err
    assert not out.exists() and not cat.exists()


def test_cavity_block_values():
    s = validate(dict(STUDY, cavity=dict(mode="sealed", p0_kPa=1, p_atm_kPa=90,
                                         gas_exponent=1.4)))
    (shell,) = make_plan(s).shells
    assert shell.cavity == Cavity("sealed", 0.0, 1 * (1e-3 / C10), 90 * (1e-3 / C10), 1.4)
    assert s.as_dict()["cavity"] == dict(mode="sealed", p0_kPa=1.0, p_atm_kPa=90.0,
                                         gas_exponent=1.4)
    grid = dict(STUDY, base=dict(t_over_R=0.15, h_over_R=1.0, gamma_J_m2=GAMMA),
                grid=dict(C10_MPa=[C10], p_kPa=[-10.0, 10.0]), cavity=dict(mode="pressure"))
    plan = make_plan(validate(grid))
    assert plan.cavity_axes == {"p_kPa": (-10.0, 10.0)}
    assert [s.cavity.p for s in plan.shells] == [-10 * (1e-3 / C10), 10 * (1e-3 / C10)]


# -- the plan and the catalogue key ----------------------------------------------------

def test_fingerprint_carries_a_closed_cavity_and_its_C10():
    key = lambda cavity: pathset_key(0.15, 1.0, "no_slip", "coarse", 0.05, 0.005,
                                     cavity=cavity)
    assert key(OPEN) == pathset_key(0.15, 1.0, "no_slip", "coarse", 0.05, 0.005)
    assert "cavity" not in key(OPEN)
    cavities = [OPEN, Cavity("sealed", p_atm=0.3), Cavity("sealed", p_atm=0.6),
                Cavity("pressure", p=0.01, p_atm=0.3), Cavity("pressure", p=0.02, p_atm=0.3),
                Cavity("sealed", p_atm=0.3, n=1.4), Cavity("sealed", p0=0.01, p_atm=0.3)]
    fps = {fingerprint(key(c)) for c in cavities}
    assert len(fps) == len(cavities)

    sweep = dict(sweeps=dict(C10_MPa=[0.3, 0.6]))
    open_plan = make_plan(study(cavity=dict(mode="open"), **sweep))
    assert len(open_plan.shells) == 1 and open_plan.cavities is None   # C10 rescales
    closed = make_plan(study(**sweep))
    assert len(closed.shells) == 2                                      # p_atm / C10 differs
    assert len({s.fingerprint for s in closed.shells}) == 2
    assert {s.cavity.p_atm for s in closed.shells} == {101.325 * (1e-3 / 0.3), 101.325 * (1e-3 / 0.6)}
    pressure = make_plan(validate(dict(PRESSURE, sweeps=dict(p_kPa=[2.0, 5.0],
                                                             C10_MPa=[0.6]))))
    assert len(pressure.shells) == 3        # (0.3, 2), (0.3, 5), (0.6, 5)
    assert pressure.cavity_groups() == [(0.3, (2.0,)), (0.3, (5.0,)), (0.6, (5.0,))]


def test_dry_run_says_each_C10_is_a_path_set(tmp_path):
    text = dry_run(dict(STUDY, sweeps=dict(C10_MPa=[0.3, 0.6]), error_bars=False),
                   catalogue=tmp_path / "c")
    assert "closed cavity (sealed)" in text
    assert "one path set per C10 (2 sets for 1 t/R, h/R)" in text
    assert "2 distinct FE problems" in text
    assert "closed cavity" not in dry_run(dict(STUDY, cavity=dict(mode="open")),
                                          catalogue=tmp_path / "c")


def test_run_dry_run_command_says_so(tmp_path, capsys):
    path = tmp_path / "study.yaml"
    path.write_text(GOOD + "cavity: {mode: pressure, p_kPa: 5}\n"
                           "sweeps: {p_kPa: [2, 5], C10_MPa: [0.6]}\n")
    code = main(["run", str(path), "--dry-run", "--catalogue", str(tmp_path / "c")])
    out = capsys.readouterr().out
    assert code == 0
    assert "closed cavity (pressure)" in out
    assert "one path set per C10 and p_kPa (3 sets for 1 t/R, h/R)" in out
    assert not (tmp_path / "c").exists()


# -- end to end ------------------------------------------------------------------------

def reference(**cavity):
    """solve_case of the study's shell (same mesh, delta_max, gamma)."""
    return sa.solve_case(R, 0.15 * R, R, C10, [GAMMA], delta_max_mm=0.05 * R, mesh="coarse",
                         progress=False, **cavity)


def assert_point_equals_case(ds, result, **sel):
    """The cube's pull-off, loading curves and V, p at `sel` equal the CaseResult's."""
    _, _, po = result.adhesion[0]
    ps = result.pathset
    for k, kind in PULL_OFF.items():
        want = (force_N(getattr(po, k), C10, R) if kind == "force"
                else length_mm(getattr(po, k), R))
        assert ds[k].sel(**AT, **sel).item() == pytest.approx(want, rel=1e-12, abs=1e-15), k
    shell = dict(C10=C10, t_over_R=0.15, h_over_R=1.0, **sel)
    n = len(ps.loading_delta)
    np.testing.assert_allclose(ds.loading_delta_mm.sel(shell).values[:n],
                               length_mm(ps.loading_delta, R), rtol=1e-12)
    np.testing.assert_allclose(ds.loading_P.sel(shell).values[:n],
                               force_N(ps.loading_P, C10, R), rtol=1e-12)
    np.testing.assert_allclose(ds.loading_V_mm3.sel(shell).values[:n], ps.loading_V * R ** 3,
                               rtol=1e-12)
    np.testing.assert_allclose(ds.loading_p_kPa.sel(shell).values[:n],
                               ps.loading_p * C10 * 1e3, rtol=1e-12, atol=1e-12)
    assert ds.cavity_apex_uz_mm.sel(shell).item() == pytest.approx(
        result.provenance["cavity_touch"]["apex_uz_mm"], abs=1e-12)
    rel = ds.relaxation_p_kPa.sel(shell).values
    for i, r in enumerate(ps.relaxations):
        np.testing.assert_allclose(rel[i, :len(r.p)], r.p * C10 * 1e3, rtol=1e-12,
                                   atol=1e-12)


@pytest.fixture(scope="module")
def sealed_run(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("sealed")
    ds = sa.run_study(STUDY, out=tmp / "results", catalogue=tmp / "cat", progress=False,
                      workers=1)
    return ds, tmp


def test_sealed_study_equals_solve_case(sealed_run):
    ds, tmp = sealed_run
    assert ds.attrs["cavity_mode"] == "sealed"
    assert ds.attrs["cavity_p_atm_kPa"] == 101.325 and ds.attrs["cavity_p0_kPa"] == 0.0
    assert ds.attrs["cavity_gas_exponent"] == 1.0
    assert (ds.status == "ok").all()
    result = reference(cavity="sealed")
    assert_point_equals_case(ds, result)
    p = ds.loading_p_kPa.sel(C10=C10, t_over_R=0.15, h_over_R=1.0).values
    assert np.nanmax(p) > 0                 # the gas is compressed on loading
    again = make_plan(validate(cube.study_of(ds)))   # the cube rebuilds the study
    assert [s.key for s in again.shells] == [s.key for s in make_plan(validate(STUDY)).shells]
    assert ds.loading_V_mm3.attrs["units"] == ds.relaxation_V_mm3.attrs["units"] == "mm^3"
    assert ds.relaxation_p_kPa.attrs["units"] == "kPa"
    assert (tmp / "results" / "sealed_tables" / "cases.md").exists()
    assert not (tmp / "results" / "sealed_tables" / "paper.md").exists()   # an open shell's


def test_pressure_sweep_cube_layout(sealed_run):
    """A p_kPa sweep with a C10 value is a p_kPa dimension over the union of C10s, each
    (C10, p_kPa) from its own path set (here the sealed run's set served for each, which
    checks the layout, not the physics); combinations not requested are "not requested"."""
    ds_sealed, tmp = sealed_run
    plan = make_plan(validate(dict(PRESSURE, sweeps=dict(p_kPa=[2.0, 5.0], C10_MPa=[0.6]))))
    with Catalogue(tmp / "cat") as cat:
        (_, stored), = [cat.fetch(s.key) for s in make_plan(validate(STUDY)).shells]
    ps = from_dataset(stored)
    served = {shell_key(s): (s.fingerprint, ps) for s in plan.shells}
    ds = dataset.build(plan, served, {})
    assert ds.P_star.dims[0] == "p_kPa" and list(ds.p_kPa.values) == [2.0, 5.0]
    assert list(ds.C10.values) == [0.3, 0.6]
    status = ds.status.sel(t_over_R=0.15, h_over_R=1.0, gamma=GAMMA)
    assert status.sel(p_kPa=2.0, C10=0.6).item() == "not requested"
    assert (status.sel(p_kPa=5.0) == "ok").all() and status.sel(p_kPa=2.0, C10=0.3).item() == "ok"
    for p in (2.0, 5.0):
        assert ds.P_star.sel(**AT, p_kPa=p).item() == ds_sealed.P_star.sel(**AT).item()
    fps = ds.pathset_fingerprint.sel(t_over_R=0.15, h_over_R=1.0)
    assert fps.sel(p_kPa=2.0, C10=0.3).item() != fps.sel(p_kPa=5.0, C10=0.3).item()
    assert ds.attrs["cavity_mode"] == "pressure" and ds.attrs["cavity_p_kPa"] == 5.0
    assert set(ds.loading_V_mm3.dims) == {"p_kPa", "C10", "t_over_R", "h_over_R",
                                          "loading_state"}
    assert validate(cube.study_of(ds)).sweeps == plan.study.sweeps


@pytest.mark.slow
def test_pressure_sweep_equals_solve_case(tmp_path):
    """Two p_kPa values (and C10 = 0.6 at the base p) end to end, each equal to solve_case."""
    change = dict(sweeps=dict(p_kPa=[2.0, 5.0], C10_MPa=[0.6]))
    ds = sa.run_study(dict(PRESSURE, **change), out=tmp_path / "results",
                      catalogue=tmp_path / "cat", progress=False, workers=1)
    assert list(ds.p_kPa.values) == [2.0, 5.0]
    for p in (2.0, 5.0):
        assert_point_equals_case(ds, reference(cavity="pressure", p_kPa=p), p_kPa=p)
    assert ds.status.sel(p_kPa=2.0, C10=0.6).isin(["not requested"]).all()
    assert ds.status.sel(p_kPa=5.0, C10=0.6, t_over_R=0.15, h_over_R=1.0,
                         gamma=GAMMA).item() == "ok"
    # the inflated shell's apex bulged toward the plane before the first touch
    apex = ds.cavity_apex_uz_mm.sel(C10=C10, t_over_R=0.15, h_over_R=1.0)
    assert apex.sel(p_kPa=5.0).item() < apex.sel(p_kPa=2.0).item() < 0


@pytest.mark.slow      # CI time: see README (python -m pytest -m slow)
def test_sealed_cube_is_cf_and_its_units_read(sealed_run, tmp_path):
    from test_cube import cf_high_priority_failures
    ds, tmp = sealed_run
    failures, result = cf_high_priority_failures(tmp / "results" / "sealed.nc", tmp_path)
    assert result["high_priorities"]        # it did check
    assert not failures, "\n".join(f"{name}: {m}" for name, msgs in failures for m in msgs)
    pint = pytest.importorskip("pint")
    ureg = pint.UnitRegistry()
    for name in ("loading_V_mm3", "loading_p_kPa", "relaxation_V_mm3", "relaxation_p_kPa",
                 "cavity_apex_uz_mm"):
        ureg(ds[name].attrs["units"])       # raises on a unit pint cannot read
