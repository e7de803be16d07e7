"""Studies end to end on dask with the real solver (coarse mesh): the local cluster and an
external scheduler give the same numbers, the catalogue serves every rerun and every new C10
or gamma, failures are recorded, and the cube round-trips through netCDF."""
import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
import xarray as xr

from shell_adhesion.catalogue import Catalogue, list_entries
from shell_adhesion.solver.path import Settings
from shell_adhesion.solver.pathset_dataset import from_dataset
from shell_adhesion.study import dataset
from shell_adhesion.study.run import execute, summary

from conftest import ENV

# one shell, 3 C10 x 3 gamma: gamma/(C10 R) from 0.0033 to 0.0075, one set of FE paths
TINY = """\
name: tiny
R_mm: 20
base: {C10_MPa: 0.3, t_over_R: 0.15, h_over_R: 1.0, gamma_J_m2: 30}
grid:
  C10_MPa: [0.2, 0.25, 0.3]
  gamma_J_m2: [20, 25, 30]
mesh: coarse
delta_max_over_R: 0.1
error_bars: false       # one FE set per shell: these tests count them
"""
UNREACHABLE = "tcp://127.0.0.1:9"       # a run that must compute nothing never connects


def write(path, text):
    path.write_text(text)
    return path


def same_results(a: xr.Dataset, b: xr.Dataset):
    """Identical data, coordinates and attributes, apart from the run's history line."""
    a, b = a.copy(), b.copy()
    for ds in (a, b):
        ds.attrs.pop("history")
    xr.testing.assert_identical(a, b)


def load(path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


@pytest.fixture(scope="module")
def local(tmp_path_factory):
    """The tiny study, cold, on the default local cluster."""
    d = tmp_path_factory.mktemp("local")
    study = write(d / "tiny.yaml", TINY)
    outcome = execute(study, d / "results", catalogue=d / "cat", progress=False)
    return outcome, study, d / "cat", load(outcome.output)


@pytest.fixture(scope="module")
def scheduler(tmp_path_factory):
    """A dask scheduler and a worker (2 processes) started as separate processes."""
    d = tmp_path_factory.mktemp("dask")
    sf = d / "scheduler.json"
    procs = []
    log = open(d / "dask.log", "w")

    def start(*args):
        procs.append(subprocess.Popen([sys.executable, "-m", "dask", *args], cwd=d, env=ENV,
                                      stdout=log, stderr=subprocess.STDOUT,
                                      start_new_session=True))
    try:
        start("scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
              "--scheduler-file", str(sf))
        deadline = time.time() + 60
        address = None
        while address is None:
            assert time.time() < deadline, "the dask scheduler did not start"
            assert procs[0].poll() is None, (d / "dask.log").read_text()
            try:
                address = json.loads(sf.read_text())["address"]
            except (OSError, ValueError, KeyError):
                time.sleep(0.1)
        start("worker", "--scheduler-file", str(sf), "--nworkers", "2", "--nthreads", "1",
              "--no-dashboard", "--host", "127.0.0.1")
        from distributed import Client
        with Client(address, timeout="30s") as c:
            c.wait_for_workers(2, timeout=60)
        yield address
    finally:
        for p in reversed(procs):
            try:
                os.killpg(p.pid, signal.SIGTERM)
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
            except ProcessLookupError:
                pass
        log.close()


def test_local_cluster_solves_once(local):
    outcome, _, cat, ds = local
    assert outcome.exit_code == 0
    assert len(outcome.plan.shells) == 1 and len(outcome.computed) == 1
    assert outcome.reused == [] and outcome.failed == {}
    assert outcome.counts == {"ok": 9, "not requested": 0, "solver failed": 0, "out of range": 0}
    assert (ds["status"] == "ok").all()
    P = ds["P_star"].values
    assert np.isfinite(P).all() and (P < 0).all()
    assert np.isfinite(ds["eta"].values).all()
    assert [r["status"] for r in list_entries(cat)] == ["ok"]


@pytest.mark.slow      # CI time: see README (python -m pytest -m slow)
def test_external_scheduler_same_numbers(local, scheduler, tmp_path):
    outcome, study, _, ds = local
    other = execute(study, tmp_path / "results", scheduler=scheduler, catalogue=tmp_path / "cat",
                progress=False)
    assert other.exit_code == 0 and other.computed == outcome.computed
    same_results(load(other.output), ds)


def test_rerun_reads_everything_from_the_catalogue(local, tmp_path):
    outcome, study, cat, ds = local
    again = execute(study, tmp_path / "results", scheduler=UNREACHABLE, catalogue=cat,
                progress=False)
    assert again.exit_code == 0
    assert again.computed == [] and again.reused == outcome.computed
    same_results(load(again.output), ds)


def test_new_c10_and_gamma_compute_nothing(local, tmp_path):
    _, _, cat, ds = local
    study = write(tmp_path / "more.yaml", TINY.replace("[0.2, 0.25, 0.3]", "[0.2, 0.22, 0.25, 0.3]")
                  .replace("[20, 25, 30]", "[20, 25, 27, 30]"))
    more = execute(study, tmp_path / "results", scheduler=UNREACHABLE, catalogue=cat,
               progress=False)
    assert more.exit_code == 0 and more.computed == [] and len(more.reused) == 1
    assert more.counts["ok"] == 16
    big = load(more.output)
    old = big.sel(C10=ds["C10"], gamma=ds["gamma"])
    for v in ("P_star", "delta_star", "a_star", "P_dagger", "a0", "eta", "a_eq_mm", "P_eq"):
        xr.testing.assert_identical(old[v], ds[v])


def test_c10_scales_forces_exactly(local):
    """DESIGN.md section 3: same gamma / (C10 R), same paths, P scaled by C10."""
    ds = local[3]
    a = ds.sel(C10=0.2, gamma=20.0)           # gamma / (C10 R) = 0.005
    b = ds.sel(C10=0.3, gamma=30.0)           # gamma / (C10 R) = 0.005
    np.testing.assert_allclose(b["P_star"], 1.5 * a["P_star"], rtol=1e-9)
    np.testing.assert_allclose(b["P_eq"], 1.5 * a["P_eq"], rtol=1e-9)
    np.testing.assert_allclose(b["a_star"], a["a_star"], rtol=1e-9)
    np.testing.assert_allclose(ds["loading_P"].sel(C10=0.3), 1.5 * ds["loading_P"].sel(C10=0.2),
                               rtol=1e-12)


def test_sweeps_leave_unrequested_points_empty(local, tmp_path):
    _, _, cat, _ = local
    study = write(tmp_path / "sweep.yaml", TINY.replace(
        "grid:\n  C10_MPa: [0.2, 0.25, 0.3]\n  gamma_J_m2: [20, 25, 30]",
        "sweeps:\n  C10_MPa: [0.2, 0.3]\n  gamma_J_m2: [20, 30]"
    ).replace("name: tiny", "name: sweep"))
    out = execute(study, tmp_path / "results", scheduler=UNREACHABLE, catalogue=cat,
              progress=False)
    ds = load(out.output)
    assert out.computed == [] and out.counts["ok"] == 3 and out.counts["not requested"] == 1
    off = ds.sel(C10=0.2, gamma=20.0)
    assert (off["status"] == "not requested").all()
    assert np.isnan(off["P_star"]).all() and np.isnan(off["a_eq_mm"]).all()


def test_point_outside_the_paths_is_recorded(local, tmp_path, capsys):
    """C10 = 1000 MPa gives gamma / (C10 R) = 1e-6: a* is below the first relaxation paths."""
    _, _, cat, _ = local
    study = write(tmp_path / "stiff.yaml", TINY.replace("[0.2, 0.25, 0.3]", "[0.2, 1000.0]"))
    outcome = execute(study, tmp_path / "results", scheduler=UNREACHABLE, catalogue=cat,
                      progress=False)
    assert outcome.exit_code == 1
    text = summary(outcome, outcome.dataset)
    assert "FE path sets: 1 needed, 0 computed, 1 reused, 0 failed" in text
    assert "3 out of range" in text
    ds = load(tmp_path / "results" / "tiny.nc")
    stiff = ds.sel(C10=1000.0)
    assert (stiff["status"] == "out of range").all() and np.isnan(stiff["P_star"]).all()
    assert all("gamma/(C10 R)" in r for r in stiff["reason"].values.ravel())
    assert (ds.sel(C10=0.2)["status"] == "ok").all()


def test_solver_failure_is_recorded(scheduler, tmp_path):
    """Newton limited to one iteration cannot converge: the shell fails, the run goes on."""
    study = write(tmp_path / "fail.yaml", TINY)
    out = execute(study, tmp_path / "results", scheduler=scheduler, catalogue=tmp_path / "cat",
              progress=False, settings=Settings(max_iter=1))
    assert out.exit_code == 1 and len(out.failed) == 1
    assert "ConvergenceError" in next(iter(out.failed.values()))
    ds = load(out.output)
    assert (ds["status"] == "solver failed").all() and np.isnan(ds["P_star"]).all()
    assert "ConvergenceError" in str(ds["reason"].values.ravel()[0])
    rows = list_entries(tmp_path / "cat")
    assert [r["status"] for r in rows] == ["failed"] and "ConvergenceError" in rows[0]["reason"]
    assert "failed t/R=0.15 h/R=1" in summary(out, ds)


def test_dataset_conventions_and_round_trip(local, tmp_path):
    outcome, _, cat, ds = local
    assert ds["P_star"].dims == ("C10", "t_over_R", "h_over_R", "gamma")
    assert ds["a_eq_mm"].dims[-1] == "point"
    assert ds["loading_P"].dims == ("C10", "t_over_R", "h_over_R", "loading_state")
    for name, v in ds.variables.items():
        assert "units" in v.attrs and "long_name" in v.attrs, name
    names = ("C10", "gamma", "P_star", "a_star", "loading_U", "R")
    units = {k: ds[k].attrs["units"] for k in names}
    assert units == dict(C10="MPa", gamma="J/m^2", P_star="N", a_star="mm", loading_U="mJ", R="mm")
    a = ds.attrs
    assert a["Conventions"] == "CF-1.8"
    for k in ("title", "history", "source", "solver_version", "solver_max_iter"):
        assert a[k]
    assert (a["mesh"], a["interface"], a["solver_tol"]) == ("coarse", "no_slip", Settings().tol)
    # the same cube built in memory equals what was read back from netCDF
    plan = outcome.plan
    with Catalogue(cat) as c:
        entry, stored = c.fetch(plan.shells[0].key)
    ps = from_dataset(stored)
    shell = plan.shells[0]
    served = {(shell.t_over_R, shell.h_over_R): (entry.fingerprint, ps)}
    built = dataset.build(plan, served, {}, history=a["history"])
    xr.testing.assert_identical(built, ds)
    dataset.write(built, tmp_path / "again.nc")
    xr.testing.assert_identical(load(tmp_path / "again.nc"), built)


def test_outputs_can_leave_out_the_curves(local, tmp_path):
    _, _, cat, ds = local
    study = write(tmp_path / "lean.yaml", TINY + "outputs:\n  equilibrium_curves: false\n"
                  "  loading_curves: false\n")
    lean = load(execute(study, tmp_path / "results", scheduler=UNREACHABLE, catalogue=cat,
                    progress=False).output)
    assert "point" not in lean.dims and "loading_state" not in lean.dims
    assert "a_eq_mm" not in lean and "loading_P" not in lean
    xr.testing.assert_identical(lean["P_star"], ds["P_star"])


def test_local_cluster_does_not_oversubscribe():
    """One single-threaded worker per core, each with one BLAS/OpenMP thread (issue 11,
    item 5): workers x threads <= cores."""
    import os
    from shell_adhesion.study.run import _cpu_count, _local_cluster
    with _local_cluster() as client:
        threads = client.nthreads()
        env = client.run(lambda: {k: os.environ.get(k) for k in
                                  ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")})
    assert len(threads) == _cpu_count() and set(threads.values()) == {1}
    assert all(set(e.values()) == {"1"} for e in env.values())


def test_rerun_of_the_same_cube_rewrites_nothing(local, tmp_path):
    """A rerun whose cube has the content of the one on disk keeps that cube and its tables
    and figures (a warm run writes nothing); a product deleted since is written again."""
    _, study, cat, ds = local
    run = lambda: execute(study, tmp_path / "results", scheduler=UNREACHABLE, catalogue=cat,
                          progress=False)
    first = run()
    assert not first.products.kept and first.products.figures and first.products.tables
    files = [first.output, *first.products.tables, *first.products.figures]
    written = {f: f.stat().st_mtime_ns for f in files}
    again = run()
    assert again.products.kept and again.exit_code == 0
    assert {f: f.stat().st_mtime_ns for f in files} == written
    assert "kept: the cube's content is unchanged" in summary(again)
    same_results(load(again.output), ds)
    first.products.figures[0].unlink()
    third = run()
    assert not third.products.kept and first.products.figures[0].is_file()


def test_rerun_of_the_same_inputs_builds_nothing(local, tmp_path, monkeypatch):
    """A rerun whose study, settings, sources and stored path sets (catalogue entries and
    their file digests) are those the cube on disk was built from keeps the cube without
    decoding a path set or building it (study.dataset.inputs_sha256); a study that differs
    (another gamma) is built and written."""
    from shell_adhesion.catalogue import files
    _, study, cat, ds = local
    run = lambda s: execute(s, tmp_path / "results", scheduler=UNREACHABLE, catalogue=cat,
                            progress=False)
    first = run(study)
    assert not first.products.kept
    built = []
    build = dataset.build

    def counted(*args, **kwargs):
        built.append(1)
        return build(*args, **kwargs)

    def refused(*args, **kwargs):
        raise AssertionError("a stored path set was decoded")

    read = files.read
    monkeypatch.setattr(dataset, "build", counted)
    monkeypatch.setattr(files, "read", refused)
    again = run(study)
    assert again.products.kept and again.exit_code == first.exit_code == 0 and not built
    assert again.reused == first.reused and again.computed == []
    same_results(again.dataset, ds)
    monkeypatch.setattr(files, "read", read)
    other = write(tmp_path / "tiny.yaml", TINY.replace("[20, 25, 30]", "[15, 20, 25, 30]"))
    changed = run(other)
    assert built and not changed.products.kept
    assert 15 in changed.dataset["gamma_J_m2"].values


def test_content_digest_sees_values_not_history(local):
    ds = local[3]
    other = ds.copy(deep=True)
    other.attrs["history"] = "another run"
    assert dataset.content_sha256(other) == dataset.content_sha256(ds)
    other["P_star"].values[(0,) * other["P_star"].ndim] *= 1 + 1e-15
    assert dataset.content_sha256(other) != dataset.content_sha256(ds)


def test_warm_run_into_a_new_folder_copies_what_the_catalogue_keeps(local, tmp_path,
                                                                     monkeypatch):
    """A run into a new folder whose cube was built before from the same inputs copies it
    and its tables and figures from the catalogue (catalogue.results): nothing decoded,
    built or drawn.  A kept file altered or truncated is not served: what it stood for is
    made again, and kept again (a store cut short: tests/test_catalogue_results.py)."""
    from shell_adhesion.analysis import figures
    from shell_adhesion.analysis.products import products_key
    from shell_adhesion.catalogue import files
    _, study, cat, ds = local
    run = lambda out: execute(study, tmp_path / out, scheduler=UNREACHABLE, catalogue=cat,
                              progress=False)
    first = run("a")            # copies or builds: the module's first run kept them
    refuse = lambda what: lambda *a, **k: (_ for _ in ()).throw(AssertionError(what))
    draw, build, read = figures.write_figures, dataset.build, files.read
    monkeypatch.setattr(dataset, "build", refuse("a cube was built"))
    monkeypatch.setattr(figures, "write_figures", refuse("a figure was drawn"))
    monkeypatch.setattr(files, "read", refuse("a stored path set was decoded"))
    copied = run("b")
    assert copied.products.copied and copied.exit_code == 0
    assert "copied from the catalogue" in summary(copied)
    same_results(copied.dataset, ds)
    made = lambda o: {p.relative_to(o.output.parent): p.read_bytes()
                      for p in [o.output, *o.products.tables, *o.products.figures]}
    assert made(copied) == made(first) and len(made(first)) > 3
    assert run("b").products.kept          # and again into the same folder: kept there

    digest = json.loads(first.output.with_name("tiny_products.json").read_text())
    key = cat / "products" / products_key(digest["content_sha256"])
    figure = next((key / "figures").iterdir())
    figure.write_bytes(figure.read_bytes()[:-1] + b"x")         # altered
    monkeypatch.setattr(figures, "write_figures", draw)
    redrawn = run("c")
    assert not redrawn.products.copied and redrawn.products.figures
    assert {k: v for k, v in made(redrawn).items() if k.suffix != ".png"} == {
        k: v for k, v in made(first).items() if k.suffix != ".png"}
    assert (key / "manifest.json").is_file()                     # kept again
    cube = next((cat / "cubes").glob("*.nc"))
    cube.write_bytes(cube.read_bytes()[: cube.stat().st_size // 2])   # truncated
    monkeypatch.setattr(files, "read", read)
    monkeypatch.setattr(dataset, "build", build)
    rebuilt = run("f")
    assert rebuilt.exit_code == 0 and rebuilt.products.copied
    same_results(rebuilt.dataset, ds)
