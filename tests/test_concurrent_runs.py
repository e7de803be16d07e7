"""Two runs on one catalogue compute each path set once: one claims it, the other waits
for it; a claim of a run that died is taken over; every run's row gets its exit code."""
import os
import subprocess
import sys
from types import SimpleNamespace

import pytest
import xarray as xr

from shell_adhesion.catalogue import Catalogue, fingerprint
from shell_adhesion.study import run, sharing
from shell_adhesion.study.keys import pathset_key
from shell_adhesion.study.progress import Progress

from conftest import ENV, REPO, load_cube

# one shell, 2 C10 x 2 gamma: one path set (coarse mesh, shallow loading)
STUDY = """\
name: twice
R_mm: 20
base: {C10_MPa: 0.3, t_over_R: 0.15, h_over_R: 1.0, gamma_J_m2: 30}
grid:
  C10_MPa: [0.2, 0.3]
  gamma_J_m2: [20, 30]
mesh: coarse
delta_max_over_R: 0.1
error_bars: false
"""
RUN_TIMEOUT_S = 300     # a run that hangs fails the test instead of stalling the suite


@pytest.fixture(autouse=True)
def short_waits(monkeypatch):
    """A claim that is wrongly never taken over ends a waiting test in seconds, not hours."""
    monkeypatch.setattr(sharing, "WAIT_LIMIT_S", 3.0)
    monkeypatch.setattr(sharing, "POLL_S", 0.1)


def shell(t_over_R=0.15):
    key = pathset_key(t_over_R, 1.0, "no_slip", "coarse", 0.1, 0.01)
    return SimpleNamespace(key=key, fingerprint=fingerprint(key))


def quiet():
    return Progress([("loading paths", 2, "shells"), ("relaxation paths", 2, "shells")],
                    enabled=False)


def die_holding(directory, fp, run_id):
    """Claim the set `fp` in the catalogue at `directory` for run `run_id` of another
    process, which then dies without releasing it."""
    code = ("import os, sys; from shell_adhesion.catalogue import Catalogue; "
            "Catalogue(sys.argv[1]).claim([sys.argv[2]], int(sys.argv[3]), 'dies', 60); "
            "os._exit(9)")
    proc = subprocess.run([sys.executable, "-c", code, str(directory), fp, str(run_id)],
                          cwd=REPO, env=ENV, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 9, proc.stderr


def test_two_runs_started_together_compute_each_set_once(tmp_path):
    (tmp_path / "twice.yaml").write_text(STUDY)
    cat = tmp_path / "cat"
    procs = [subprocess.Popen(
        [sys.executable, "-m", "shell_adhesion", "run", str(tmp_path / "twice.yaml"),
         "--out", str(tmp_path / out), "--catalogue", str(cat), "--workers", "1"],
        cwd=REPO, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        for out in ("a", "b")]
    ended = []
    try:
        for p in procs:
            ended.append(p.communicate(timeout=RUN_TIMEOUT_S))
    finally:
        for p in procs:
            if p.poll() is None:
                p.kill()
                p.wait()
    for p, (stdout, stderr) in zip(procs, ended):
        assert "Traceback" not in stderr, stderr
        assert p.returncode == 0, stderr
    with Catalogue(cat) as c:
        runs = c.runs()
        stored = [e for e in c.entries() if e["status"] == "ok"]
        assert c.db.execute("SELECT COUNT(*) FROM claims").fetchone()[0] == 0
    assert [r["exit_code"] for r in runs] == [0, 0]
    assert len(stored) == 1
    assert sorted(r["computed"] for r in runs) == [0, 1]    # the set was computed once
    assert sorted(r["reused"] for r in runs) == [0, 1]
    xr.testing.assert_identical(load_cube(tmp_path / "a" / "twice.nc"),
                                load_cube(tmp_path / "b" / "twice.nc"))


def test_a_claim_is_exclusive_until_its_run_is_gone(tmp_path):
    fp = shell().fingerprint
    with Catalogue(tmp_path) as cat:
        assert cat.claim([fp], 1, "first", stale_s=60) == {}
        held = cat.claim([fp], 2, "second", stale_s=60)      # this process: alive
        assert held[fp].run == 1 and held[fp].pid == os.getpid()
        assert held[fp].stale(60, now=held[fp].refreshed + 61)   # silent too long
        assert cat.taken_over == []
        cat.release_claims(1)
        assert cat.claim([fp], 2, "second", stale_s=60) == {}
        cat.release_claims(2)
        die_holding(tmp_path, fp, 3)
        assert cat.claim_of(fp).run == 3
        assert cat.claim([fp], 4, "fourth", stale_s=60) == {}    # taken over
        assert [c.run for c in cat.taken_over] == [3]
        assert cat.claim_of(fp).run == 4


def test_a_waiting_run_takes_what_another_stored(tmp_path):
    s = shell()
    with Catalogue(tmp_path) as cat:
        cat.store(s.key, xr.Dataset({"x": ("i", [1.0, 2.0])}))
        cat.claim([s.fingerprint], 1, "first", 60)      # its owner has not released it yet
        computed = []
        shared = sharing.settle([s], sharing.Claims(cat, 2, "second", 60), computed.extend,
                                quiet(), run.Tally())
    assert computed == [] and list(shared) == [s.fingerprint]
    assert shared[s.fingerprint][1]["x"].values.tolist() == [1.0, 2.0]


def test_the_claim_of_a_dead_run_is_taken_over(tmp_path):
    dead, alive = shell(0.15), shell(0.2)
    die_holding(tmp_path, dead.fingerprint, 1)
    with Catalogue(tmp_path) as cat:
        computed = []

        def compute(shells):
            computed.extend(s.fingerprint for s in shells)
            for s in shells:
                cat.store(s.key, xr.Dataset({"x": ("i", [3.0])}))

        claims = sharing.Claims(cat, 2, "second", 60)
        assert sharing.settle([dead, alive], claims, compute, quiet(), run.Tally()) == {}
        claims.release()
        assert computed == [dead.fingerprint, alive.fingerprint]
        assert cat.db.execute("SELECT COUNT(*) FROM claims").fetchone()[0] == 0


def test_a_failure_of_the_owner_is_reported_not_recomputed(tmp_path):
    s = shell()
    with Catalogue(tmp_path) as cat:
        cat.claim([s.fingerprint], 1, "first", 60)
        claim = cat.claim_of(s.fingerprint)
        cat.record_failure(s.key, "loading: it broke")
        cat.release_claims(1)
        tally = run.Tally()
        left = sharing._wait([s], {s.fingerprint: claim}, sharing.Claims(cat, 2, "w", 60),
                             quiet(), tally, {})
    assert left == [] and "loading: it broke" in tally.failed[s.fingerprint]


def test_a_run_that_breaks_records_its_exit_code(tmp_path, monkeypatch):
    def broken(*args):
        raise RuntimeError("a bug")

    monkeypatch.setattr(sharing, "settle", broken)
    (tmp_path / "twice.yaml").write_text(STUDY)
    with pytest.raises(RuntimeError, match="a bug"):
        run.execute(tmp_path / "twice.yaml", tmp_path / "out", catalogue=tmp_path / "cat",
                    progress=False)
    with Catalogue(tmp_path / "cat") as cat:
        assert [r["exit_code"] for r in cat.runs()] == [1]
        assert cat.db.execute("SELECT COUNT(*) FROM claims").fetchone()[0] == 0


def test_an_index_another_run_is_still_creating_reads_as_no_catalogue(tmp_path):
    """The index file exists before its tables do (another run is creating it): a reader
    finds no catalogue there instead of failing on a missing table (it did, one run in
    four started together, with a traceback)."""
    from shell_adhesion.catalogue.store import INDEX
    from shell_adhesion.study.plan import make_plan
    from shell_adhesion.study.config import load_study
    (tmp_path / "cat").mkdir()
    (tmp_path / "cat" / INDEX).touch()                 # as sqlite3.connect leaves it
    with pytest.raises(FileNotFoundError, match="being created"):
        Catalogue(tmp_path / "cat", create=False)
    (tmp_path / "twice.yaml").write_text(STUDY)
    plan = make_plan(load_study(tmp_path / "twice.yaml"))
    assert run._held_by_index(plan, tmp_path / "cat") == 0
    with Catalogue(tmp_path / "cat") as cat:           # a creator finishes the job
        assert cat.candidates(plan.shells[0].key) == []

