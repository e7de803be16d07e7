"""Studies with finite-range adhesion (`adhesion: {model: dugdale, tabor: L}`,
study.cohesive_study): lambda a factor and a cube dimension, the traced paths in the cube,
one solve per dimensionless problem shared by every point that asks for it (exact scaling),
each answer kept in the catalogue (Ctrl-C loses none that finished), bad files refused
before any computation.
"""
import numpy as np
import pytest

from shell_adhesion.analysis.results import NotACube, open_results
from shell_adhesion.cli import main
from shell_adhesion.study.cohesive_case import solve_cohesive_case
from shell_adhesion.study.config import StudyError, validate
from shell_adhesion.study.run import dry_run, execute

STUDY = """\
name: cohesive
R_mm: 20
base: {t_over_R: 0.15, h_over_R: 1.0}
grid:
  C10_MPa: [0.3, 0.6]
  gamma_J_m2: [30, 60]
  tabor: [0.3, 1]
adhesion: {model: dugdale, tabor: 1}
interface: frictionless
mesh: coarse
error_bars: false
"""


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("cohesive")
    (tmp / "cohesive.yaml").write_text(STUDY)
    first = execute(tmp / "cohesive.yaml", tmp / "results", catalogue=tmp / "cat",
                    progress=False, workers=1)
    return first, tmp


def test_lambda_is_a_cube_dimension_and_every_point_is_answered(run):
    outcome, _ = run
    ds = outcome.dataset
    assert outcome.exit_code == 0 and not outcome.failed
    assert ds.P_star.dims == ("C10", "t_over_R", "h_over_R", "gamma", "tabor")
    assert list(ds.tabor.values) == [0.3, 1.0] and (ds.status == "ok").all()
    assert ds.P_star.attrs["units"] == "N" and ds.sigma0.attrs["units"] == "MPa"
    # 8 points, 6 problems: gamma / (C10 R) 0.005 twice (0.3 MPa with 30, 0.6 with 60)
    assert len(outcome.points) == 8 and outcome.computed == 6 and outcome.reused == 0


def test_points_of_one_problem_scale_exactly(run):
    ds = run[0].dataset
    a = ds.sel(C10=0.3, gamma=30.0).squeeze()
    b = ds.sel(C10=0.6, gamma=60.0).squeeze()
    # gamma / (C10 R) and lambda the same: forces x C10 R^2 (x 2), lengths and lambda equal
    np.testing.assert_allclose(b.P_star, 2 * a.P_star, rtol=1e-12)
    np.testing.assert_allclose(b.a_star, a.a_star, rtol=1e-12)
    np.testing.assert_allclose(b.sigma0, 2 * a.sigma0, rtol=1e-12)
    # and the finite range matters: lambda 0.3 pulls harder than lambda 1
    assert (a.P_star.sel(tabor=0.3) < a.P_star.sel(tabor=1.0)).all()


def test_a_point_is_the_case_commands_answer(run):
    ds = run[0].dataset
    r = solve_cohesive_case(20, 3, 20, 0.6, 30, tabor=0.3, interface="frictionless",
                            mesh="coarse", error_bars=False)
    po = r.to_dict()["pull_off"]
    at = ds.sel(C10=0.6, gamma=30.0, tabor=0.3).squeeze()
    for name in ("P_star", "delta_star", "a_star", "c_star"):
        unit = "N" if name.startswith("P") else "mm"
        assert float(at[name]) == pytest.approx(po[f"{name}_{unit}"], rel=1e-12)


def test_the_traced_paths_are_in_the_cube(run):
    ds = run[0].dataset
    for i in range(ds.sizes["point"]):
        n, turn = int(ds.states[i]), int(ds.turn[i])
        P = ds.curve_P.values[i, :n]
        assert np.all(np.isfinite(P)) and np.all(np.isnan(ds.curve_P.values[i, n:]))
        sel = {d: float(ds[f"point_{d}"][i]) for d in ("C10", "t_over_R", "h_over_R",
                                                       "gamma", "tabor")}
        P_star = float(ds.P_star.sel(sel))
        # the pull-off is the vertex through the least sampled P of the retraction
        assert P_star <= P[turn:].min() + 1e-12 and P[turn:].min() - P_star <= 0.01 * abs(P_star)
        assert P[turn] > P_star and abs(P[0]) <= 1e-9


def test_a_rerun_takes_every_answer_from_the_catalogue(run):
    first, tmp = run
    again = execute(tmp / "cohesive.yaml", tmp / "results", catalogue=tmp / "cat",
                    progress=False, workers=1)
    assert again.computed == 0 and again.reused == 6
    np.testing.assert_array_equal(again.dataset.P_star.values, first.dataset.P_star.values)
    assert "6 of them, 0 to compute" in dry_run(tmp / "cohesive.yaml", catalogue=tmp / "cat")


def test_the_energy_methods_tables_refuse_the_cube_by_name(run):
    with pytest.raises(NotACube, match="cohesive .adhesion: dugdale. study's cube"):
        open_results(run[0].output)


BAD = [
    ({"grid": {"tabor": [5]}}, "grid.tabor[0]: 5: outside the supported domain 0.05 <= "
                               "lambda <= 3"),
    ({"adhesion": None, "grid": {"tabor": [1]}}, "grid.tabor: given without adhesion.model "
                                                 "dugdale"),
    ({"adhesion": {"model": "energy", "tabor": 1}}, "adhesion.tabor: given with "
                                                    "adhesion.model energy"),
    ({"adhesion": {"model": "dugdale"}}, "adhesion.tabor: missing"),
    ({"adhesion": {"model": "jkr", "tabor": 1}}, "adhesion.model: 'jkr' must be one of "
                                                 "energy, dugdale"),
    ({"adhesion": {"model": "dugdale", "tabor": 1, "sigma": 2}}, "adhesion.sigma: unknown key"),
    ({"material": {"model": "mooney_rivlin", "C01_over_C10": 0.2}},
     "adhesion.model: dugdale with material mooney_rivlin"),
    ({"cavity": {"mode": "pressure", "p_kPa": 1}}, "adhesion.model: dugdale with cavity.mode "
                                                   "pressure"),
    ({"adhesion": {"model": "dugdale", "tabor": "x"}}, "adhesion.tabor: 'x' must be a number"),
    ({"adhesion": {"model": "dugdale", "tabor": 1, "zone_elements": 64}},
     "adhesion.zone_elements: 64 must be between 1 and 32 (elements across the cohesive zone)"),
    ({"adhesion": {"model": "dugdale", "tabor": 1, "zone_elements": "x"}},
     "adhesion.zone_elements: 'x' must be a number"),
    ({"adhesion": {"model": "energy", "zone_elements": 8}},
     "adhesion.zone_elements: given with adhesion.model energy"),
    ({"adhesion": {"model": "energy", "history": "loading"}},
     "adhesion.history: given with adhesion.model energy"),
    ({"adhesion": {"model": "dugdale", "tabor": 1, "beta": 1}},
     "adhesion.beta: 1 given with interface frictionless: the mixed-mode law is for no_slip"),
    ({"interface": "no_slip", "adhesion": {"model": "dugdale", "tabor": 1, "history": "x"}},
     "adhesion.history: 'x' must be one of loading, adhesive"),
    ({"interface": "no_slip", "adhesion": {"model": "dugdale", "tabor": 1, "beta": -1}},
     "adhesion.beta: -1 must be >= 0"),
]


def _doc(change):
    import yaml
    doc = yaml.safe_load(STUDY)
    for k, v in change.items():
        if v is None:
            doc.pop(k, None)
        elif k == "grid":
            doc["grid"] = dict(doc["grid"], **v)
        else:
            doc[k] = v
    return doc


@pytest.mark.parametrize("change, message", BAD, ids=[m.split(":")[0] for _, m in BAD])
def test_a_bad_file_is_refused_by_name(change, message):
    with pytest.raises(StudyError) as e:
        validate(_doc(change))
    assert message in str(e.value)


def test_the_elements_across_the_zone_reach_every_point_and_its_key():
    from shell_adhesion.study.cohesive_study import point_key, points
    default = points(validate(_doc({})))
    eight = points(validate(_doc({"adhesion": {"model": "dugdale", "tabor": 1,
                                               "zone_elements": 8}})))
    assert {p.input.zone_elements for p in default} == {4.0}
    assert {p.input.zone_elements for p in eight} == {8.0}
    # the two answers are different problems: the catalogue keeps them apart
    assert point_key(default[0].input, False) != point_key(eight[0].input, False)


def test_the_command_refuses_a_bad_file_in_one_line_with_exit_2(tmp_path, capsys):
    import yaml
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(_doc({"grid": {"tabor": [0.01]}})))
    assert main(["run", str(path), "--out", str(tmp_path / "out"),
                 "--catalogue", str(tmp_path / "cat")]) == 2
    out, err = capsys.readouterr()
    assert err.count("\n") == 1 and "grid.tabor[0]: 0.01: outside the supported domain" in err
    assert not (tmp_path / "out").exists() and not (tmp_path / "cat").exists()


def test_a_task_past_its_time_limit_is_refused_and_the_run_exits_1(tmp_path):
    study = STUDY.replace("grid:\n  C10_MPa: [0.3, 0.6]\n  gamma_J_m2: [30, 60]\n  tabor: [0.3, 1]\n",
                          "grid:\n  C10_MPa: [0.3]\n  gamma_J_m2: [30]\n  tabor: [1]\n")
    study += "task_timeout_s: 1e-6\n"
    (tmp_path / "slow.yaml").write_text(study)
    outcome = execute(tmp_path / "slow.yaml", tmp_path / "results", catalogue=tmp_path / "cat",
                      progress=False, workers=1)
    assert outcome.exit_code == 1 and len(outcome.failed) == 1
    ds = outcome.dataset
    assert (ds.status == "refused").all() and "TimeoutError" in str(ds.reason.values[0])
    assert outcome.output.is_file()


def test_the_run_writes_a_table_and_figures(run):
    import csv
    outcome, _ = run
    ds = outcome.dataset
    pr = outcome.products
    assert not pr.skipped and [p.name for p in pr.figures] == ["pull_off_lambda.png",
                                                               "paths.png"]
    assert all(p.stat().st_size > 1000 for p in pr.figures)
    table = next(p for p in pr.tables if p.suffix == ".csv")
    rows = list(csv.DictReader(table.open()))
    assert len(rows) == ds.sizes["point"] == 8
    for r in rows:
        at = dict(C10=float(r["C10 [MPa]"]), t_over_R=float(r["t/R"]),
                  h_over_R=float(r["h/R"]), gamma=float(r["gamma [J/m^2]"]),
                  tabor=float(r["lambda"]))
        assert float(r["P* [N]"]) == float(ds.P_star.sel(at)) and r["status"] == "ok"


def test_the_catalogue_lists_the_cohesive_answers(run):
    from shell_adhesion.catalogue.store import format_entries, list_entries
    text = format_entries(list_entries(run[1] / "cat"))
    assert text.count("dugdale lambda=0.3 gamma/(C10 R)=0.005") == 1
    assert text.count("dugdale") == 6


def test_ctrl_c_keeps_the_finished_answers_and_a_rerun_solves_the_rest(tmp_path):
    import os
    import signal
    import sqlite3
    import subprocess
    import sys
    import time

    from shell_adhesion.catalogue import list_entries

    from conftest import ENV, REPO
    # one worker runs the tasks in submission order: lambda 0.3 (2 s) before lambda 1
    study = STUDY.replace("grid:\n  C10_MPa: [0.3, 0.6]\n  gamma_J_m2: [30, 60]\n  tabor: [0.3, 1]\n",
                          "grid:\n  C10_MPa: [0.3]\n  gamma_J_m2: [30]\n  tabor: [0.3, 1]\n")
    (tmp_path / "ctrl_c.yaml").write_text(study)
    cat, out = tmp_path / "cat", tmp_path / "results"

    def stored():
        try:
            return [r for r in list_entries(cat) if r["status"] == "ok"]
        except (sqlite3.Error, FileNotFoundError):  # the index is being created
            return []

    proc = subprocess.Popen([sys.executable, "-m", "shell_adhesion", "run",
                             str(tmp_path / "ctrl_c.yaml"), "--out", str(out), "--catalogue",
                             str(cat), "--workers", "1"], cwd=REPO, env=ENV,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    try:
        deadline = time.time() + 120
        while not stored():
            assert proc.poll() is None, "the run ended before Ctrl-C: " + proc.stderr.read()
            assert time.time() < deadline, "no answer was stored in time"
            time.sleep(0.05)
        os.killpg(proc.pid, signal.SIGINT)          # Ctrl-C reaches the whole group
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    assert proc.returncode == 130, err
    assert "the finished cohesive points are kept in the catalogue" in err
    assert len(stored()) == 1 and not (out / "cohesive.nc").exists()
    again = execute(tmp_path / "ctrl_c.yaml", out, catalogue=cat, progress=False, workers=1)
    assert again.exit_code == 0 and again.reused == 1 and again.computed == 1


def test_an_unreachable_scheduler_is_refused_before_anything_is_created(tmp_path, capsys):
    (tmp_path / "cohesive.yaml").write_text(STUDY)
    before = sorted(tmp_path.iterdir())
    assert main(["run", str(tmp_path / "cohesive.yaml"), "--out", str(tmp_path / "out"),
                 "--catalogue", str(tmp_path / "cat"), "--scheduler", "tcp://127.0.0.1:9"]) == 2
    _, err = capsys.readouterr()
    assert err.count("\n") == 1 and err.startswith("shell-adhesion: error: --scheduler: ")
    assert sorted(tmp_path.iterdir()) == before
