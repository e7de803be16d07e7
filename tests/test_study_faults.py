"""Faults of a study run, tried as a user would: a run killed in the middle of a shell keeps
its finished relaxation paths, a lost dask scheduler ends in one line and no cube, a lost
worker changes nothing, and `--dry-run` or bad run arguments create nothing."""
import json
import os
from pathlib import Path
import signal
import sqlite3
import subprocess
import sys
import time

import pytest
import xarray as xr
import yaml

from shell_adhesion.study.run import execute, run_study

from conftest import ENV, REPO

# one thin shell on the coarse mesh: one loading task, then about 20 relaxation paths
STUDY = dict(name="faults", R_mm=20,
             base=dict(C10_MPa=0.3, t_over_R=0.15, h_over_R=1.0, gamma_J_m2=30),
             grid=dict(C10_MPa=[0.2, 0.3], gamma_J_m2=[20, 30]),
             mesh="coarse", delta_max_over_R=0.05, error_bars=False)
VOLATILE = ("history", "study_file", "study_sha256")     # differ between two runs only


def cli(*args, timeout=300, **kw):
    return subprocess.Popen([sys.executable, "-m", "shell_adhesion", "run", *map(str, args)],
                            cwd=kw.pop("cwd", REPO), env=ENV, start_new_session=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)


def finish(proc, timeout=300):
    try:
        out, err = proc.communicate(timeout=timeout)
    finally:
        kill_group(proc)
    return proc.returncode, out, err


def kill_group(proc, sig=signal.SIGKILL):
    try:
        os.killpg(proc.pid, sig)
    except ProcessLookupError:
        pass


def parts(cat: Path) -> int:
    """Relaxation paths stored as parts of unfinished sets."""
    try:
        db = sqlite3.connect(f"file:{cat / 'index.sqlite'}?mode=ro", uri=True, timeout=5)
        try:
            return db.execute("SELECT COUNT(*) FROM parts").fetchone()[0]
        finally:
            db.close()
    except sqlite3.Error:        # not created yet
        return 0


def wait_for_parts(cat, proc, n=1, timeout=240):
    deadline = time.time() + timeout
    while parts(cat) < n:
        assert proc.poll() is None, "the run ended before it was interrupted:\n" + \
            proc.stderr.read()
        assert time.time() < deadline, "no relaxation path was stored in time"
        time.sleep(0.05)


def same_cube(a: xr.Dataset, b: xr.Dataset):
    a, b = a.copy(), b.copy()
    for ds in (a, b):
        for k in VOLATILE:
            ds.attrs.pop(k, None)
    xr.testing.assert_identical(a, b)


def load(path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The study run once, uninterrupted, through the Python API (a dict)."""
    d = tmp_path_factory.mktemp("reference")
    outcome = execute(STUDY, d / "results", catalogue=d / "cat", progress=False, workers=2)
    assert outcome.exit_code == 0 and outcome.relaxations_reused == 0
    return outcome


@pytest.fixture
def dask_cluster(tmp_path):
    """Start a scheduler and `n` single-threaded worker processes; yields (address, procs)."""
    procs = []
    log = open(tmp_path / "dask.log", "w")

    def start(*args):
        p = subprocess.Popen([sys.executable, "-m", "dask", *args], cwd=tmp_path, env=ENV,
                             stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        procs.append(p)
        return p

    def cluster(n_workers):
        sf = tmp_path / "scheduler.json"
        start("scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
              "--scheduler-file", str(sf))
        deadline = time.time() + 60
        address = None
        while address is None:
            assert time.time() < deadline, "the dask scheduler did not start"
            assert procs[0].poll() is None, (tmp_path / "dask.log").read_text()
            try:
                address = json.loads(sf.read_text())["address"]
            except (OSError, ValueError, KeyError):
                time.sleep(0.1)
        for _ in range(n_workers):
            start("worker", "--scheduler-file", str(sf), "--nworkers", "1", "--nthreads", "1",
                  "--no-dashboard", "--host", "127.0.0.1")
        from distributed import Client
        with Client(address, timeout="30s") as c:
            c.wait_for_workers(n_workers, timeout=60)
        return address, procs

    try:
        yield cluster
    finally:
        for p in reversed(procs):
            kill_group(p, signal.SIGTERM)
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                kill_group(p)
                p.wait()
        log.close()


def study_file(tmp_path) -> Path:
    path = tmp_path / "faults.yaml"
    path.write_text(yaml.safe_dump(STUDY))
    return path


def test_api_and_cli_give_the_same_cube(reference, tmp_path):
    """`run_study(dict)` and `shell-adhesion run` are one orchestration: same cube (the
    CLI run reads the API run's catalogue, so it computes nothing)."""
    code, out, err = finish(cli(study_file(tmp_path), "--out", tmp_path / "res", "--catalogue",
                                reference.catalogue, "--scheduler", "tcp://127.0.0.1:9"))
    assert code == 0, err
    assert "1 needed, 0 computed, 1 reused" in out
    same_cube(load(tmp_path / "res" / "faults.nc"), reference.dataset)
    ds = run_study(STUDY, out=tmp_path / "api", catalogue=reference.catalogue, progress=False)
    same_cube(ds, reference.dataset)
    same_cube(ds, load(tmp_path / "api" / "faults.nc"))


def test_killed_in_a_shell_keeps_its_relaxation_paths(reference, tmp_path):
    """kill -9 of the whole run after some relaxation paths are stored: the rerun
    recomputes none of them and writes the same cube."""
    cat, out = tmp_path / "cat", tmp_path / "results"
    proc = cli(study_file(tmp_path), "--out", out, "--catalogue", cat, "--workers", "1")
    try:
        wait_for_parts(cat, proc, 2)
    finally:
        kill_group(proc)
        proc.wait(timeout=30)
    kept = parts(cat)
    total = reference.relaxations_computed
    assert 2 <= kept < total, "the kill came too late to interrupt the shell"
    assert not (out / "faults.nc").exists()
    again = execute(study_file(tmp_path), out, catalogue=cat, progress=False, workers=1)
    assert again.exit_code == 0 and len(again.computed) == 1
    assert again.relaxations_reused == kept
    assert again.relaxations_computed == total - kept
    assert parts(cat) == 0                  # the complete set replaced its parts
    assert not list(cat.rglob("*.tmp*")) and not list((cat / "parts").rglob("*.nc"))
    same_cube(again.dataset, reference.dataset)


def test_dry_run_creates_nothing(tmp_path):
    out, cat = tmp_path / "results", tmp_path / "cat"
    code, text, err = finish(cli(study_file(tmp_path), "--out", out, "--catalogue", cat,
                                 "--dry-run"), timeout=120)
    assert code == 0, err
    assert "1 distinct FE problems" in text and "holds 0 of them, 1 to compute" in text
    assert not out.exists() and not cat.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["faults.yaml"]


def test_dry_run_estimates_from_recorded_timings(reference, tmp_path):
    from shell_adhesion.study.run import dry_run
    text = dry_run(dict(STUDY, delta_max_over_R=0.06), reference.catalogue, workers=2)
    assert "holds 0 of them, 1 to compute" in text
    assert "estimate: about" in text
    assert "mean of 1 recorded sets" in text


@pytest.mark.parametrize("case", ["out is a file", "out not writable", "out under a file",
                                  "scheduler at nothing"])
def test_bad_run_arguments(tmp_path, case):
    """One line naming the flag, the value and the rule; exit 2; nothing created."""
    (tmp_path / "a_file").write_text("x")
    out, flag = tmp_path / "results", "--out"
    extra = []
    if case == "out is a file":
        out = tmp_path / "a_file"
    elif case == "out not writable":
        out = Path("/proc/shell-adhesion-results")
    elif case == "out under a file":
        out = tmp_path / "a_file" / "results"
    else:
        flag, extra = "--scheduler", ["--scheduler", "tcp://127.0.0.1:9"]
    before = sorted(tmp_path.iterdir())
    t0 = time.time()
    code, text, err = finish(cli(study_file(tmp_path), "--out", out, "--catalogue",
                                 tmp_path / "cat", *extra), timeout=120)
    assert code == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err and text == ""
    assert lines[0].startswith(f"shell-adhesion: error: {flag}: ")
    assert (str(out) if flag == "--out" else "tcp://127.0.0.1:9") in lines[0]
    assert sorted(tmp_path.iterdir()) == before + [tmp_path / "faults.yaml"]
    assert not Path("/proc/shell-adhesion-results").exists()
    assert time.time() - t0 < 60


@pytest.mark.slow      # CI time: see README (python -m pytest -m slow)
def test_lost_scheduler_one_line_then_resume(reference, dask_cluster, tmp_path):
    """Kill the scheduler in the middle: one line, non-zero exit, no cube; the rerun (on a
    local cluster) keeps what finished and equals an uninterrupted run."""
    address, procs = dask_cluster(1)
    cat, out = tmp_path / "cat", tmp_path / "results"
    proc = cli(study_file(tmp_path), "--out", out, "--catalogue", cat, "--scheduler", address,
               "--quiet")
    try:
        wait_for_parts(cat, proc, 1)
        kill_group(procs[0])                # the scheduler
        code, text, err = finish(proc, timeout=120)
    finally:
        kill_group(proc)
    assert code == 1
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    assert address in lines[0] and "run again to resume" in lines[0]
    assert "relaxation paths finished and are kept" in lines[0]
    assert not (out / "faults.nc").exists() and not list(out.glob("*"))
    kept = parts(cat)
    assert kept >= 1
    again = execute(study_file(tmp_path), out, catalogue=cat, progress=False, workers=2)
    assert again.exit_code == 0 and again.relaxations_reused == kept
    same_cube(again.dataset, reference.dataset)


@pytest.mark.slow      # CI time: see README (python -m pytest -m slow)
def test_lost_worker_same_results(reference, dask_cluster, tmp_path):
    """One of two workers killed in the middle: the run finishes with the same cube."""
    address, procs = dask_cluster(2)
    cat, out = tmp_path / "cat", tmp_path / "results"
    proc = cli(study_file(tmp_path), "--out", out, "--catalogue", cat, "--scheduler", address)
    try:
        wait_for_parts(cat, proc, 1)
        kill_group(procs[1])                # one worker (its nanny and process)
        code, text, err = finish(proc, timeout=300)
    finally:
        kill_group(proc)
    assert code == 0, err
    same_cube(load(out / "faults.nc"), reference.dataset)


def test_ctrl_c_ends_in_one_line(tmp_path):
    """SIGINT to the run's process group (Ctrl-C in a terminal): exit 130, one line saying
    what is kept, no cube."""
    cat, out = tmp_path / "cat", tmp_path / "results"
    proc = cli(study_file(tmp_path), "--out", out, "--catalogue", cat, "--workers", "1",
               "--quiet")
    try:
        wait_for_parts(cat, proc, 1)
        kill_group(proc, signal.SIGINT)
        code, text, err = finish(proc, timeout=120)
    finally:
        kill_group(proc)
    assert code == 130, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    assert lines[0].startswith("shell-adhesion: interrupted: ")
    assert "relaxation paths finished and are kept" in lines[0] and "run again" in lines[0]
    assert not (out / "faults.nc").exists() and parts(cat) >= 1


def test_taken_dashboard_port_prints_nothing(capfd):
    """The local cluster never asks for dask's default port 8787: with it taken (by this
    test, or by whatever else holds it), starting the cluster warns nothing."""
    import socket
    import warnings
    from shell_adhesion.study.run import _local_cluster
    holder = socket.socket()
    try:
        holder.bind(("", 8787))
        holder.listen()
    except OSError:
        pass                    # taken already: the condition this test needs
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            with _local_cluster(1) as client:
                assert client.submit(sum, [1, 2]).result(timeout=60) == 3
    finally:
        holder.close()
    assert not [w for w in caught if "already in use" in str(w.message)]
    out, err = capfd.readouterr()
    assert "already in use" not in out + err
