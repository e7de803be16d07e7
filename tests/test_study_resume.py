"""A run killed with SIGKILL after its first path set is stored loses nothing finished: the
rerun reuses that set, computes the rest and writes the same dataset as an uninterrupted run."""
import os
import signal
import sqlite3
import subprocess
import sys
import time

import pytest

import xarray as xr

from shell_adhesion.catalogue import Catalogue, list_entries
from shell_adhesion.study.run import execute, summary

from conftest import ENV, REPO, load_cube

# a two-shell study killed between its shells (about 1.5 minutes; test_study_faults kills
# one in the middle of a shell in CI): `python -m pytest -m slow` runs it
pytestmark = pytest.mark.slow

# two shells (a thin shell, then a costlier solid cap) on one worker: dask runs the tasks
# in submission order, so the thin shell is stored seconds before the solid one
STUDY = """\
name: resume
R_mm: 20
grid:
  C10_MPa: [0.2]
  t_over_R: [0.15, 1.0]
  h_over_R: [0.5]
  gamma_J_m2: [10, 15]     # a* of t/R = 1 inside the coarse mesh's even zone (25, 30: refused)
mesh: coarse
delta_max_over_R: 0.1
error_bars: false
"""


def ok_rows(cat):
    try:
        return [r for r in list_entries(cat) if r["status"] == "ok"]
    except (sqlite3.Error, FileNotFoundError):  # the index is still being created
        return []


def group_alive(pgid) -> bool:
    try:
        os.killpg(pgid, 0)
        return True
    except ProcessLookupError:
        return False


def test_killed_run_resumes(tmp_path):
    study = tmp_path / "resume.yaml"
    study.write_text(STUDY)
    cat, out = tmp_path / "cat", tmp_path / "results"
    log = open(tmp_path / "run.log", "w")
    proc = subprocess.Popen(
        [sys.executable, "-m", "shell_adhesion", "run", str(study), "--out", str(out),
         "--catalogue", str(cat), "--workers", "1"],
        cwd=REPO, env=ENV, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
    try:
        deadline = time.time() + 180
        while not ok_rows(cat):
            assert proc.poll() is None, "the run ended before it was killed:\n" + \
                (tmp_path / "run.log").read_text()
            assert time.time() < deadline, "no path set was stored in time"
            time.sleep(0.05)
        os.killpg(proc.pid, signal.SIGKILL)      # the client, its cluster and workers
        proc.wait(timeout=30)
    finally:
        if group_alive(proc.pid):
            os.killpg(proc.pid, signal.SIGKILL)
        log.close()
    deadline = time.time() + 30
    while group_alive(proc.pid) and time.time() < deadline:
        time.sleep(0.1)
    assert not group_alive(proc.pid)

    stored = ok_rows(cat)
    assert len(stored) == 1, "the kill came too late to interrupt the second path set"
    assert not (out / "resume.nc").exists()
    assert "loading paths" in (tmp_path / "run.log").read_text()   # the progress lines
    with Catalogue(cat) as c:
        killed = c.runs()[-1]
    assert killed["finished"] is None                               # the run never ended

    again = execute(study, out, catalogue=cat, progress=False)
    assert again.exit_code == 0
    assert again.reused == [stored[0]["fingerprint"]] and len(again.computed) == 1
    assert again.discarded == []
    assert "2 needed, 1 computed, 1 reused, 0 failed" in summary(again)

    reference = execute(study, tmp_path / "reference", catalogue=tmp_path / "cat2",
                        progress=False)
    assert reference.exit_code == 0 and len(reference.computed) == 2
    resumed, cold = load_cube(again.output), load_cube(reference.output)
    assert (resumed["status"] == "ok").all()
    xr.testing.assert_identical(resumed, cold)
