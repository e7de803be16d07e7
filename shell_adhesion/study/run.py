"""Running a study: validate, plan, take what the catalogue holds, compute the rest on
dask, write the results cube, then its tables and figures (study.products).

The loading of a shell is one task and each of its relaxation paths another; workers only
compute.  This (client) process stores every finished path set in the catalogue at once,
so a run killed at any moment loses only unfinished sets, and it alone writes the
results.  A shell whose paths fail is recorded with its reason and the rest continue.

Exit codes: 0 all requested points evaluated, 1 something failed (the dataset's `status`
says what), 2 the study file is invalid (nothing created).

    python -m shell_adhesion.study.run workflow.yaml --out results [--scheduler ADDRESS] [--catalogue DIR]
"""
import argparse
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
import logging
import os
from pathlib import Path
import sys
import time
import uuid

from tqdm import tqdm

from shell_adhesion import solver
from shell_adhesion.catalogue import Catalogue
from shell_adhesion.catalogue.fingerprint import solver_source_sha256
from shell_adhesion.solver.case import (loading_views, pathset_of, relaxation_starts, relaxation_task,
                         solve_loading)
from shell_adhesion.solver.path import LoadingPath, Settings

from . import dataset
from .config import StudyError, load_study
from .plan import Plan, Shell, make_plan, restrict
from .products import Products, write_products

DEFAULT_OUT = "results"


# -- tasks (run on the workers) ----------------------------------------------------------

def _check_source(source_sha256):
    """A worker must run the solver the key was made for (same source as the client)."""
    if source_sha256 is not None and solver_source_sha256() != source_sha256:
        raise RuntimeError(
            f"the solver source of this worker ({solver_source_sha256()[:12]}) differs from the "
            f"client's ({source_sha256[:12]}): the code changed since one of them started; "
            "restart the client process and the workers")


def loading_task(t, h, interface, mesh, delta_max, settings, source_sha256=None):
    """Loading path of one shell: (loading without displacement fields, relaxation
    starts, info, loading views)."""
    _check_source(source_sha256)
    t0 = time.perf_counter()
    d, loading = solve_loading(t, h, interface, mesh, delta_max, settings)
    starts = relaxation_starts(loading, d.capmesh)
    light = LoadingPath(loading.interface,
                        tuple(replace(s, x=s.x[:0]) for s in loading.states), loading.timer)
    info = dict(dofs=int(d.ndof), elements=int(d.capmesh.mesh.nelements),
                loading_s=time.perf_counter() - t0)
    return light, starts, info, loading_views(d, loading)


def relax_task(t, h, interface, mesh, start, gamma_max, settings, source_sha256=None,
               views=False):
    """One relaxation path: (Relaxation, seconds); `views` keeps its profiles."""
    _check_source(source_sha256)
    t0 = time.perf_counter()
    r = relaxation_task(t, h, interface, mesh, start, gamma_max, settings, views)
    return r, time.perf_counter() - t0


# -- the client side ---------------------------------------------------------------------

def _cpu_count() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


@contextmanager
def connect(scheduler=None, n_workers=None):
    """A dask.distributed Client: to `scheduler` (an address, or a scheduler file), else
    to a new local cluster of processes, one single-threaded worker per core."""
    from distributed import Client, LocalCluster
    if scheduler:
        if Path(scheduler).is_file():
            client = Client(scheduler_file=str(scheduler), timeout="30s")
        else:
            client = Client(scheduler, timeout="30s")
        try:
            yield client
        finally:
            client.close()
        return
    import dask
    # dask's default MALLOC_TRIM_THRESHOLD_=65536 made the solver's many mid-sized array
    # allocations about twice as slow in workers (measured); keep glibc's default
    environ = {k: v for k, v in dask.config.get("distributed.nanny.pre-spawn-environ").items()
               if k != "MALLOC_TRIM_THRESHOLD_"}
    with dask.config.set({"distributed.nanny.pre-spawn-environ": environ}):
        cluster = LocalCluster(n_workers=n_workers or _cpu_count(), threads_per_worker=1,
                               processes=True, dashboard_address=":0",
                               silence_logs=logging.CRITICAL)
    try:
        with Client(cluster) as client:
            yield client
    finally:
        cluster.close()


@dataclass
class _Job:
    """The tasks of one path set in flight."""

    shell: Shell
    t0: float
    loading: object = None
    info: dict = None
    views: tuple = ()
    relaxations: list = None
    seconds: float = 0.0
    remaining: int = 0
    futures: list = field(default_factory=list)
    done: bool = False


def _reason(stage, exc) -> str:
    text = " ".join(f"{type(exc).__name__}: {exc}".split())
    return f"{stage}: {text[:300]}"


def compute(plan: Plan, shells, cat: Catalogue, client, computed: dict, failed: dict,
            progress=True):
    """Compute the path sets of `shells` on `client`, storing each in `cat` when done.

    Fills computed (fingerprint -> PathSet) and failed (fingerprint -> reason) as the sets
    finish, so both stay right if the connection breaks midway.
    """
    from distributed import as_completed
    st = plan.study
    owner = {}                  # future key -> (job, relaxation index or None)
    bar = tqdm(total=len(shells), desc="FE tasks", unit="task", file=sys.stderr,
               disable=not progress, dynamic_ncols=True)
    ac = as_completed()
    for s in shells:
        job = _Job(s, time.perf_counter())
        f = client.submit(loading_task, s.t_over_R, s.h_over_R, st.interface, st.mesh,
                          st.delta_max_over_R, plan.settings, s.key["solver_source"],
                          pure=False,
                          key=f"loading-{s.fingerprint[:12]}-{uuid.uuid4().hex[:8]}")
        owner[f.key] = (job, None)
        job.futures.append(f)
        ac.add(f)

    def fail(job, reason):
        job.done = True
        failed[job.shell.fingerprint] = reason
        client.cancel(job.futures)
        cat.record_failure(job.shell.key, reason, {"wall_s": time.perf_counter() - job.t0},
                           study=st.name)

    def finish(job):
        job.done = True
        s = job.shell
        stats = dict(job.info)
        timer = job.loading.timer
        stats.update(loading_states=len(job.loading.states),
                     loading_newton_iterations=timer.newton_iterations,
                     relaxation_newton_iterations=sum(r.newton_iterations for r in job.relaxations),
                     assembly_s=timer.assembly, linear_solve_s=timer.solve,
                     relaxation_s=job.seconds)
        ps = pathset_of(s.t_over_R, s.h_over_R, st.interface, st.mesh, st.delta_max_over_R,
                        s.gamma_max_hat, job.loading, job.relaxations, stats, job.views)
        cat.store(s.key, ps, {"wall_s": time.perf_counter() - job.t0}, study=st.name)
        computed[s.fingerprint] = ps

    try:
        for f in ac:
            job, k = owner.pop(f.key)
            job.futures.remove(f)
            if job.done or f.status == "cancelled":
                continue
            bar.update(1)
            if f.status == "error":
                stage = "loading" if k is None else f"relaxation {k + 1} of {len(job.relaxations)}"
                fail(job, _reason(stage, f.exception()))
                continue
            s = job.shell
            if k is None:
                job.loading, starts, job.info, job.views = f.result()
                job.relaxations = [None] * len(starts)
                job.remaining = len(starts)
                bar.total += len(starts)
                bar.refresh()
                for i, start in enumerate(starts):
                    g = client.submit(relax_task, s.t_over_R, s.h_over_R, st.interface, st.mesh,
                                      start, s.gamma_max_hat, plan.settings,
                                      s.key["solver_source"], i == len(starts) - 1,
                                      pure=False, key=f"relax-{s.fingerprint[:12]}-{i}-{uuid.uuid4().hex[:8]}")
                    owner[g.key] = (job, i)
                    job.futures.append(g)
                    ac.add(g)
            else:
                job.relaxations[k], seconds = f.result()
                job.seconds += seconds
                job.remaining -= 1
            if job.remaining == 0:
                try:
                    finish(job)
                except Exception as e:      # a set that cannot be stored is a failure too
                    fail(job, _reason("store", e))
    finally:
        bar.close()


# -- the run -----------------------------------------------------------------------------

@dataclass
class Outcome:
    """What a run did."""

    exit_code: int
    output: Path
    plan: Plan
    computed: list          # fingerprints of the path sets computed by this run
    reused: list            # fingerprints of the planned sets served by the catalogue
    failed: dict            # planned fingerprint -> reason
    counts: dict            # points per status
    wall_s: float
    catalogue: Path
    discarded: list         # catalogue entries found corrupt and dropped
    products: Products = None   # tables and figures written from the cube


def run(study_path, out_dir=DEFAULT_OUT, scheduler=None, catalogue_dir=None, progress=True,
        n_workers=None, settings: Settings = None) -> Outcome:
    """Run a study file; raises StudyError (before creating anything) if it is invalid.

    `settings`: solver tolerances (default solver.path.Settings()); part of the FE key.
    """
    t0 = time.perf_counter()
    study = load_study(study_path)
    plan = make_plan(study, settings if settings is not None else Settings())
    out_dir = Path(out_dir)
    output = out_dir / f"{study.name}.nc"
    cat = Catalogue(catalogue_dir)
    try:
        out_dir.mkdir(parents=True, exist_ok=True)      # fail now, not after the FE work
        run_id = cat.start_run(study.name, study.source, study.sha256, output,
                               solver.__version__)
        served, reused, missing = {}, [], []
        for s in plan.shells:
            hit = cat.fetch(s.key)
            if hit is None:
                missing.append(s)
            else:
                entry, ps = hit
                served[s.t_over_R, s.h_over_R] = (entry.fingerprint,
                                                  restrict(ps, study.delta_max_over_R))
                reused.append(s.fingerprint)
        computed, failed = {}, {}
        if missing:
            try:
                with connect(scheduler, n_workers) as client:
                    compute(plan, missing, cat, client, computed, failed, progress)
            except (OSError, TimeoutError) as e:
                where = f"scheduler {scheduler}" if scheduler else "local cluster"
                for s in missing:
                    if s.fingerprint not in computed and s.fingerprint not in failed:
                        failed[s.fingerprint] = _reason(where, e)
        for s in missing:
            if s.fingerprint in computed:
                served[s.t_over_R, s.h_over_R] = (s.fingerprint, computed[s.fingerprint])
        failed_th = {(s.t_over_R, s.h_over_R): failed[s.fingerprint]
                     for s in missing if s.fingerprint in failed}
        history = (f"{time.strftime('%Y-%m-%dT%H:%M:%S%z')} shell-adhesion "
                   f"{solver.__version__}: run_study {study.source}")
        ds = dataset.build(plan, served, failed_th, history)
        dataset.write(ds, output)
        try:
            products = write_products(output)
        except Exception as e:      # the cube is written; a drawing bug must not lose it
            products = Products(skipped={"tables and figures": _reason("products", e)})
        counts = dataset.summary_counts(ds)
        bad = counts["solver failed"] + counts["out of range"]
        code = 1 if failed or bad else 0
        wall = time.perf_counter() - t0
        cat.finish_run(run_id, code, len(computed), len(reused), len(failed), wall)
        return Outcome(code, output, plan, list(computed), reused, failed, counts, wall,
                       cat.dir, list(cat.discarded), products)
    finally:
        cat.close()


def summary(outcome: Outcome, ds=None) -> str:
    """The end-of-run report (one screen)."""
    p, c = outcome.plan, outcome.counts
    ax = p.axes
    lines = [
        f"study {p.study.name} ({p.study.source}): cube C10 {len(ax['C10_MPa'])} x t/R "
        f"{len(ax['t_over_R'])} x h/R {len(ax['h_over_R'])} x gamma {len(ax['gamma_J_m2'])}, "
        f"requested points: {len(p.points)}; interface {p.study.interface}, mesh {p.study.mesh}",
        f"FE path sets: {len(p.shells)} needed, {len(outcome.computed)} computed, "
        f"{len(outcome.reused)} reused, {len(outcome.failed)} failed "
        f"(catalogue {outcome.catalogue})",
        f"points: {c['ok']} ok, {c['out of range']} out of range, {c['solver failed']} "
        f"solver failed, {c['not requested']} not requested",
    ]
    for s in p.shells:
        if s.fingerprint in outcome.failed:
            lines.append(f"  failed t/R={s.t_over_R:g} h/R={s.h_over_R:g}: "
                         f"{outcome.failed[s.fingerprint]}")
    if ds is not None and c["out of range"]:
        bad = ds["status"].values == "out of range"
        shown = 0
        for idx in zip(*bad.nonzero()):
            if shown == 5:
                lines.append(f"  ... {c['out of range'] - 5} more out of range")
                break
            pt = ", ".join(f"{d}={ds[d].values[i]:g}" for d, i in zip(dataset.DIMS, idx))
            lines.append(f"  out of range at {pt}: {ds['reason'].values[idx]}")
            shown += 1
    for d in outcome.discarded:
        lines.append(f"  discarded a corrupt catalogue entry: {d}")
    pr = outcome.products
    if pr is not None:
        if pr.tables:
            lines.append(f"tables: {len(pr.tables)} files in {pr.tables[0].parent}")
        if pr.figures:
            lines.append(f"figures: {len(pr.figures)} files in {pr.figures[0].parent} "
                         f"({pr.seconds.get('total', 0):.1f} s for tables and figures)")
        for name, why in pr.skipped.items():
            lines.append(f"  skipped {name}: {why}")
    lines.append(f"wall time {outcome.wall_s:.1f} s; results in {outcome.output}")
    return "\n".join(lines)


def run_study(path_to_yaml, out_dir=DEFAULT_OUT, scheduler=None, catalogue_dir=None,
              progress=True, n_workers=None) -> int:
    """Run a study file end to end and print a summary; returns the exit code.

    An invalid study prints one line to stderr and returns 2 before creating anything.
    """
    try:
        outcome = run(path_to_yaml, out_dir, scheduler, catalogue_dir, progress, n_workers)
    except StudyError as e:
        print(f"{path_to_yaml}: {e}", file=sys.stderr)
        return 2
    except OSError as e:        # the catalogue or output folder cannot be created
        print(f"{path_to_yaml}: {e}", file=sys.stderr)
        return 2
    import xarray as xr
    with xr.open_dataset(outcome.output) as ds:
        print(summary(outcome, ds.load()))
    return outcome.exit_code


def add_arguments(parser: argparse.ArgumentParser):
    """The options of `run_study` on a command line."""
    parser.add_argument("study", help="study YAML file")
    parser.add_argument("--out", default=DEFAULT_OUT,
                        help="output folder for <name>.nc (default: %(default)s)")
    parser.add_argument("--scheduler", default=None, metavar="ADDRESS",
                        help="dask.distributed scheduler address or scheduler file "
                             "(default: a local cluster of processes)")
    parser.add_argument("--catalogue", default=None, metavar="DIR",
                        help="catalogue folder (default: $SHELL_ADHESION_CATALOGUE or "
                             "./catalogue-data)")
    parser.add_argument("--workers", type=int, default=None, metavar="N",
                        help="local cluster size (default: one per core)")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m shell_adhesion.study.run", description=__doc__.split("\n")[0])
    add_arguments(parser)
    a = parser.parse_args(argv)
    return run_study(a.study, a.out, a.scheduler, a.catalogue, not a.no_progress, a.workers)


if __name__ == "__main__":
    # run the importable module, so that the tasks pickle as shell_adhesion.study.run.*, not __main__.*
    from shell_adhesion.study.run import main as _main
    sys.exit(_main())
