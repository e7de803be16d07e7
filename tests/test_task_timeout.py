"""A study task has a wall-time limit (YAML task_timeout_s): a task past it is recorded in
the cube with its reason and the study goes on to write its cube (issue 10, item 1)."""
import numpy as np
import pytest
import xarray as xr

from shell_adhesion.cli import main
from shell_adhesion.study.config import TASK_TIMEOUT_S, load_study
from shell_adhesion.study.run import TaskTimeout, _deadline, execute

STUDY = """\
name: tiny
R_mm: 20
base: {C10_MPa: 0.3, t_over_R: 0.15, h_over_R: 1.0, gamma_J_m2: 30}
mesh: coarse
delta_max_over_R: 0.1
"""


def test_default_and_given_limit(tmp_path):
    (tmp_path / "a.yaml").write_text(STUDY)
    (tmp_path / "b.yaml").write_text(STUDY + "task_timeout_s: 120\nerror_bars: false\n")
    a, b = load_study(tmp_path / "a.yaml"), load_study(tmp_path / "b.yaml")
    assert a.task_timeout_s == TASK_TIMEOUT_S and a.error_bars is True
    assert b.task_timeout_s == 120.0 and b.error_bars is False


@pytest.mark.parametrize("line, words", [("task_timeout_s: 0", "task_timeout_s: 0 must be > 0"),
                                         ("task_timeout_s: soon", "task_timeout_s: 'soon'"),
                                         ("error_bars: 1", "error_bars: 1 must be true or false")])
def test_bad_limit_exit_2_one_line(tmp_path, capsys, line, words):
    (tmp_path / "s.yaml").write_text(STUDY + line + "\n")
    assert main(["run", str(tmp_path / "s.yaml"), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and words in err
    assert not (tmp_path / "out").exists()


def test_deadline_raises_after_the_limit():
    assert _deadline(None, "x") is None
    _deadline(3600, "the loading")(0.01)            # well within the limit: nothing
    with pytest.raises(TaskTimeout, match="task_timeout_s = 0 s"):
        _deadline(0, "the loading")(0.01)


def test_timed_out_task_is_recorded_and_the_run_ends(tmp_path):
    (tmp_path / "s.yaml").write_text(STUDY + "task_timeout_s: 1e-9\nerror_bars: false\n")
    out = execute(tmp_path / "s.yaml", tmp_path / "results", catalogue=tmp_path / "cat",
                  progress=False, workers=1)
    assert out.exit_code == 1 and len(out.failed) == 1
    assert "TaskTimeout" in next(iter(out.failed.values()))
    with xr.open_dataset(out.output) as ds:
        assert (ds["status"] == "solver failed").all() and np.isnan(ds["P_star"]).all()
        assert "task_timeout_s" in str(ds["reason"].values.ravel()[0])
