"""Running a study: validate, plan, take what the catalogue holds, compute the rest on
dask, write the results cube, then its tables and figures (analysis.products).

The loading of a shell is one task and each of its relaxation paths another; workers only
compute.  This (client) process stores every finished relaxation path in the catalogue at
once (a part of its shell's set) and the whole set when its last path arrives, so a run
killed at any moment loses only the tasks still running; it alone writes the results.  A
shell whose paths fail is recorded with its reason and the rest continue.  Runs sharing a
catalogue compute each set once: a set another run is computing is waited for
(study.sharing).

`run_study` is the one entry point (the `shell-adhesion run` command calls it).
"""
from concurrent.futures import CancelledError
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass, field, replace
import hashlib
import importlib
import importlib.util
import json
import logging
import os
from pathlib import Path
import signal
import socket
import tempfile
import threading
import time
import uuid

from shell_adhesion import solver
from shell_adhesion.catalogue import Catalogue, default_dir
from shell_adhesion.atomic import clean_temporaries
from shell_adhesion.catalogue.store import INDEX
from shell_adhesion.cube import DIMS
from shell_adhesion.solver.case import (cavity_lift, loading_views, pathset_of,
                                        relaxation_starts, relaxation_task, solve_loading,
                                        start_family, start_key, timing_stats)
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.request import fit_stats, initial_fit, next_fit
from shell_adhesion.solver.cavity import OPEN
from shell_adhesion.solver.material import NEO_HOOKE
from shell_adhesion.solver.path import Settings
from shell_adhesion.solver.pathset_dataset import (from_dataset, relaxation_from_dataset,
                                                   relaxation_to_dataset, to_dataset)

from . import dataset, interrupt, sharing
from .config import StudyError, load_study, validate
from .keys import relaxation_part, solver_source_sha256
from .plan import Plan, Shell, make_plan, served_key
from shell_adhesion.analysis.products import (RUN_FORMATS, Products, figures_dir,
                                              kept_products, products_key, record_products,
                                              recorded_inputs, tables_dir, write_products)
from shell_adhesion.catalogue import results as stored
from .cost import estimate_s, shell_size
from .progress import Progress, path_eta

DEFAULT_OUT = "results"
CONNECT_TIMEOUT_S = 10.0    # a scheduler that does not answer in this time is not there
LOST_AFTER_S = 10.0         # a scheduler unreachable this long is lost
CLOSE_TIMEOUT_S = 10.0      # shutting down the local cluster takes at most this (each part)
# shells in progress at once, per worker: each open shell's relaxation tasks carry their
# start states (displacement fields), held by the driver and the scheduler until they
# run; with every shell open the default-mesh map (72 sets, ~6600 paths) grew the driver
# to 23 GB and was killed for memory
OPEN_SHELLS_PER_WORKER = 2

STAGES = ("loading paths", "relaxation paths", "energy method", "cube")


class RunInputError(StudyError):
    """A run argument that cannot work (checked before anything is created).

    `flag` is its command-line name (--out), `detail` the value and the rule.
    """

    def __init__(self, name: str, detail: str):
        self.flag, self.detail = f"--{name}", detail
        super().__init__(f"{name}: {detail}")


class SchedulerLost(RuntimeError):
    """The dask scheduler went away during the run; finished work is in the catalogue."""


class Interrupted(KeyboardInterrupt):
    """Ctrl-C during the run; the message says what finished and is kept."""

    def __str__(self):
        return self.args[0] if self.args else "interrupted"


# -- tasks (run on the workers) ----------------------------------------------------------

def _check_source(source_sha256):
    """A worker must run the solver the key was made for (same source as the client)."""
    if source_sha256 is not None and solver_source_sha256() != source_sha256:
        raise RuntimeError(
            f"the solver source of this worker ({solver_source_sha256()[:12]}) differs from the "
            f"client's ({source_sha256[:12]}): the code changed since one of them started; "
            "restart the client process and the workers")


class TaskTimeout(RuntimeError):
    """A task ran past the study's task_timeout_s (checked after every converged state)."""


def _deadline(timeout_s, what):
    """progress(delta) callback raising TaskTimeout once `timeout_s` seconds have passed."""
    if timeout_s is None:
        return None
    t0 = time.perf_counter()

    def check(delta):
        if time.perf_counter() - t0 > timeout_s:
            raise TaskTimeout(f"{what} ran past task_timeout_s = {timeout_s:g} s "
                              f"(at delta/R = {delta:.4g})")
    return check


def loading_task(t, h, interface, mesh, delta_max, settings, source_sha256=None,
                 material=NEO_HOOKE, timeout_s=None, cavity=OPEN, uniform=None, a_stop=None,
                 family=None):
    """Loading path of one shell of `material` and `cavity` on the mesh even out to
    `uniform` of arc, to delta_max or the contact radius `a_stop` (solver.request):
    (loading without displacement fields, relaxation starts ending on the node type
    `family`, None: the larger, solver.case.relaxation_starts, info, loading views); a closed
    cavity's info holds `cavity_lift` (solver.case.cavity_lift), which its relaxation tasks
    need.  TaskTimeout past `timeout_s` seconds."""
    _check_source(source_sha256)
    t0 = time.perf_counter()
    d, loading = solve_loading(t, h, interface, mesh, delta_max, settings,
                               _deadline(timeout_s, "the loading"), material, cavity=cavity,
                               stop_at_limit=True, uniform=uniform, a_stop=a_stop)
    starts = relaxation_starts(loading, d.capmesh, family)
    # the driver needs the loading's numbers only: its fields stay here (a shell's states
    # would otherwise be held by the driver for the whole run)
    light = replace(loading, states=tuple(replace(s, x=s.x[:0], dx_ddelta=None)
                                          for s in loading.states))
    info = dict(dofs=int(d.ndof), elements=int(d.capmesh.mesh.nelements),
                loading_s=time.perf_counter() - t0,
                relaxation_family=start_family(starts, d.capmesh))
    if cavity.closed:
        info["cavity_lift"] = cavity_lift(d)
    return light, starts, info, loading_views(d, loading)


def relax_task(t, h, interface, mesh, start, gamma_max, settings, source_sha256=None,
               views=False, material=NEO_HOOKE, timeout_s=None, cavity=OPEN, lift=0.0,
               uniform=None, reach=1.0):
    """One relaxation path: (Relaxation, seconds); `views` keeps its profiles; a closed
    `cavity` needs its loading's `lift`; `uniform` and `reach` as the shell's fit says
    (solver.request).  TaskTimeout past `timeout_s` seconds."""
    _check_source(source_sha256)
    t0 = time.perf_counter()
    r = relaxation_task(t, h, interface, mesh, start, gamma_max, settings, views,
                        material=material, cavity=cavity, lift=lift,
                        progress=_deadline(timeout_s, "a relaxation path"), uniform=uniform,
                        reach=reach)
    return r, time.perf_counter() - t0


# -- checks made before anything is created ----------------------------------------------

def _study_of(study):
    """A validated Study from a path or a dict of the YAML schema."""
    if isinstance(study, dict):
        text = json.dumps(study, sort_keys=True, default=str)
        return validate(study, source="<dict>", sha256=hashlib.sha256(text.encode()).hexdigest())
    if isinstance(study, (str, os.PathLike)):
        return load_study(study)
    raise StudyError(f"study: a {type(study).__name__} must be a path to a YAML file or a dict")


def _writable_folder(name: str, folder) -> Path:
    """`folder` if it is (or can be made) a writable folder; RunInputError naming the
    argument `name` otherwise.  Creates nothing that stays."""
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise RunInputError(name, f"{str(folder)!r} is an existing file; it must be a folder "
                                  "(existing or new)")
    probe = folder
    while not probe.exists() and probe != probe.parent:
        probe = probe.parent
    if not probe.is_dir():
        raise RunInputError(name, f"{str(folder)!r} cannot be made: {str(probe)!r} is a "
                                  "file, not a folder")
    try:
        with tempfile.TemporaryFile(dir=probe):
            pass
    except OSError as e:
        what = "is" if probe == folder else f"would be made in {str(probe)!r}, which is"
        raise RunInputError(name, f"{str(folder)!r} {what} not writable "
                                  f"({e.strerror or e}); it must be a writable folder") from None
    return folder


def check_out(out) -> Path:
    """The output folder (see _writable_folder)."""
    return _writable_folder("out", out)


LOW_LEVEL_LOG = 8      # messages dask keeps per comm (its default 1000; see _local_cluster)


def _cpu_count() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def _connect_external(scheduler):
    """A Client of the scheduler at `scheduler` (an address or a scheduler file);
    RunInputError if none answers within CONNECT_TIMEOUT_S."""
    import dask
    from distributed import Client
    _refused(scheduler)
    try:
        # this side's message log bounded as in _local_cluster (the scheduler's is its own)
        with dask.config.set({"distributed.admin.low-level-log-length": LOW_LEVEL_LOG}):
            if Path(scheduler).is_file():
                return Client(scheduler_file=str(scheduler), timeout=CONNECT_TIMEOUT_S)
            return Client(scheduler, timeout=CONNECT_TIMEOUT_S)
    except (OSError, TimeoutError, ValueError, TypeError) as e:
        why = " ".join(str(e).split())[:120] or type(e).__name__
        raise RunInputError(
            "scheduler", f"{scheduler!r}: no dask scheduler answered within "
                         f"{CONNECT_TIMEOUT_S:g} s ({why}); it must be the address or "
                         "scheduler file of a running dask scheduler") from None



def _refused(scheduler):
    """RunInputError at once if `scheduler` is a tcp address whose port refuses a
    connection (nothing listens there: dask's Client would retry for CONNECT_TIMEOUT_S)."""
    if Path(scheduler).is_file():
        return
    host, _, port = str(scheduler).removeprefix("tcp://").rpartition(":")
    if not (host and port.isdigit()):
        return                                  # not host:port: dask says what is wrong
    try:
        socket.create_connection((host.strip("[]"), int(port)), CONNECT_TIMEOUT_S).close()
    except ConnectionRefusedError:
        raise RunInputError("scheduler", f"{scheduler!r}: nothing listens at that address "
                            "(connection refused); it must be the address or scheduler "
                            "file of a running dask scheduler") from None
    except OSError:
        return                                  # unreachable, slow, ...: dask's timeout


@contextmanager
def _local_cluster(n_workers=None):
    """A Client of a new local cluster of processes, one single-threaded worker per core."""
    import dask
    from distributed import Client, LocalCluster
    # dask's default MALLOC_TRIM_THRESHOLD_=65536 made the solver's many mid-sized array
    # allocations about twice as slow in workers (measured); keep glibc's default
    environ = {k: v for k, v in dask.config.get("distributed.nanny.pre-spawn-environ").items()
               if k != "MALLOC_TRIM_THRESHOLD_"}
    # the worker processes start with SIGINT ignored (inherited): Ctrl-C in a terminal
    # reaches the whole process group, and only this process must answer it
    main = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if main else None
    # dask keeps the last low-level-log-length messages of every comm for debugging, and
    # with them each task's arguments (a relaxation's start state: its displacement
    # fields): at 1000 the driver grew by about 10 MB per relaxation path on fitted meshes
    # (a 4000-path study passed 20 GB); at LOW_LEVEL_LOG it holds a few states
    logs = {"distributed.admin.low-level-log-length": LOW_LEVEL_LOG}
    try:
        with dask.config.set({"distributed.nanny.pre-spawn-environ": environ, **logs}):
            cluster = LocalCluster(n_workers=n_workers or _cpu_count(), threads_per_worker=1,
                                   processes=True,
                                   # a free port: dask's HTTP server starts even
                                   # without bokeh, and on 8787 (taken) it warns
                                   dashboard_address=":0",
                                   silence_logs=logging.CRITICAL)
    finally:
        if main:
            signal.signal(signal.SIGINT, previous)
    client = None
    try:
        with dask.config.set(logs):
            client = Client(cluster)
        yield client
    finally:
        # bounded: after Ctrl-C a worker may be deep in a factorisation
        for closing in ((client.close,) if client is not None else ()) + (cluster.close,):
            try:
                closing(timeout=CLOSE_TIMEOUT_S)
            except Exception:       # what is left is ended with this process
                pass


def _has_bokeh() -> bool:
    return importlib.util.find_spec("bokeh") is not None   # the optional `dashboard` extra


# -- computing the missing path sets -----------------------------------------------------

@dataclass
class _Job:
    """The tasks of one path set in flight, fitted to its request (solver.request): each
    solve of the fit is a loading task and the relaxation tasks of its new starts."""

    shell: Shell
    t0: float
    fit: object = None          # solver.request.Fit of the solve in flight
    loading: object = None
    info: dict = None
    views: tuple = ()
    starts: tuple = ()
    relaxations: list = None
    known: dict = field(default_factory=dict)   # start_key -> Relaxation, on this mesh
    seconds: float = 0.0
    remaining: int = 0
    opened: bool = False        # its first loading submitted (study.run: a bounded few at once)
    done: bool = False
    expected: int = 0           # relaxation paths the cost model expects before its loading
    family: str = None          # a companion: its answer's node type (opened once known)


@dataclass
class Tally:
    """What the computing part of a run did (kept right if it stops midway)."""

    computed: dict = field(default_factory=dict)    # fingerprint -> PathSet
    failed: dict = field(default_factory=dict)      # fingerprint -> reason
    relaxations_computed: int = 0                   # relaxation paths solved and stored
    relaxations_reused: int = 0                     # relaxation paths read from parts
    loadings: int = 0                               # loading paths solved
    shared: list = field(default_factory=list)      # fingerprints another run stored meanwhile


def _reason(stage, exc) -> str:
    text = " ".join(f"{type(exc).__name__}: {exc}".split())
    return f"{stage}: {text[:300]}"


def _kept(tally: Tally, cat) -> str:
    return (f"{len(tally.computed)} path sets and {tally.relaxations_computed} relaxation "
            f"paths finished and are kept in the catalogue {cat.dir}")


def compute(plan: Plan, shells, cat: Catalogue, client, tally: Tally, progress: Progress,
            external: bool = False, claims: sharing.Claims = None):
    """Compute the path sets of `shells` on `client`, storing each relaxation path (a part)
    and each complete set in `cat` as it arrives.  Each set is fitted to its shell's
    request (solver.request.next_fit: a deeper loading, a wider even zone or paths relaxed
    further, each bounded) before it is stored.  `claims` (this run's, study.sharing) are
    refreshed while it works and released set by set.  SchedulerLost if the scheduler of
    an `external` client stops answering.  The progress counts advance from where they
    are (a run may compute in rounds)."""
    from distributed import wait
    st = plan.study
    owner = {}                  # future -> (job, relaxation index or None)
    pending = set()

    answers = {s.fingerprint: s for s in plan.shells}
    families = {}               # answer fingerprint -> the node type its set relaxed

    def answer_family(job):
        """(node type, None) of the set of a companion's answer; (None, reason) where
        that set failed; (None, None) while it is not stored."""
        fp = job.shell.answer
        if fp in families:
            return families[fp], None
        if fp in tally.failed:
            return None, f"no error bars: its answer's set failed ({tally.failed[fp]})"
        if fp in tally.computed:
            families[fp] = tally.computed[fp].stats.get("relaxation_family")
            return families[fp], None
        if any(j.shell.fingerprint == fp for j in jobs):
            return None, None       # computed here: wait for it
        hit = cat.fetch(answers[fp].key)    # stored before, or by another run
        if hit is None:
            return None, None
        families[fp] = json.loads(hit[1].attrs["stats"]).get("relaxation_family")
        return families[fp], None

    def open_more():
        """Open waiting shells up to OPEN_SHELLS_PER_WORKER per worker (the workers of
        now: an external cluster may grow); an error-bar companion once its answer's set
        is stored (it relaxes that set's node type: study.plan)."""
        workers = len(client.scheduler_info().get("workers", {}))
        in_progress = sum(1 for j in jobs if j.opened and not j.done)
        room = OPEN_SHELLS_PER_WORKER * max(1, workers) - in_progress
        for job in list(reversed(waiting)):     # in order: the answers come first
            family, why = answer_family(job) if job.shell.answer else (None, None)
            if why is not None:
                waiting.remove(job)
                job.opened = job.done = True
                tally.failed[job.shell.fingerprint] = why
                if claims is not None:
                    claims.settled(job.shell.fingerprint)
                progress.update("loading paths", advance=1)
                progress.update("relaxation paths", advance=1)
            elif room > 0 and (job.shell.answer is None or job.shell.answer in families):
                waiting.remove(job)
                job.opened, job.t0, job.family = True, time.perf_counter(), family
                room -= 1
                load(job)

    def load(job):
        s, fit = job.shell, job.fit
        f = client.submit(loading_task, s.t_over_R, s.h_over_R, st.interface, s.key["mesh"],
                          fit.delta_max, plan.settings, s.key["solver_source"],
                          s.material, st.task_timeout_s, pure=False, cavity=s.cavity,
                          uniform=fit.uniform, a_stop=fit.a_stop, family=job.family,
                          key=f"loading-{s.fingerprint[:12]}-{uuid.uuid4().hex[:8]}")
        owner[f] = (job, None)
        pending.add(f)

    jobs, first_path = [], {}   # first_path: when the first relaxation path came in
    for s in shells:
        cap = Cap(s.t_over_R, s.h_over_R)
        job = _Job(s, time.perf_counter(), initial_fit(cap, s.request))
        job.expected = shell_size(cap, job.fit, s.key["mesh"])[1]
        jobs.append(job)
    waiting = list(reversed(jobs))      # opened in order as others close
    open_more()
    progress.update("loading paths")

    def relax_note():
        # the paths of a set are known once its loading is in, and may grow while it is
        # fitted further (solver.request): the total is an estimate until every set is done
        done = tally.relaxations_computed + tally.relaxations_reused
        total = max(done, sum(len(j.starts) if j.loading is not None else j.expected
                              for j in jobs if not j.done) + sum(
            len(j.relaxations or ()) for j in jobs if j.done))
        note = f"{done}/{'' if all(j.done for j in jobs) else '~'}{total} paths"
        if tally.relaxations_reused:
            note += f" ({tally.relaxations_reused} kept from an earlier run)"
        if tally.relaxations_computed and not first_path:
            first_path.update(t=time.perf_counter(), n=tally.relaxations_computed)
        # the pace of the paths since the first one came in (the loadings go before it)
        return note + path_eta(first_path.get("t"),
                               tally.relaxations_computed - first_path.get("n", 0),
                               total - done)


    def close(job):
        job.done = True
        job.starts, job.known = (), {}      # its states (displacement fields) are not needed
        if claims is not None:
            claims.settled(job.shell.fingerprint)
        for g, (j, _) in list(owner.items()):
            if j is job:
                g.cancel()
                owner.pop(g)
                pending.discard(g)
        open_more()
        progress.update("relaxation paths", advance=1, note=relax_note())

    def fail(job, reason):
        tally.failed[job.shell.fingerprint] = reason
        cat.record_failure(job.shell.key, reason, {"wall_s": time.perf_counter() - job.t0},
                           study=st.name)
        close(job)

    def pathset(job):
        s = job.shell
        stats = dict(job.info)
        timer = job.loading.timer
        stats.update(loading_states=len(job.loading.states),
                     loading_newton_iterations=timer.newton_iterations,
                     relaxation_newton_iterations=sum(r.newton_iterations for r in job.relaxations),
                     assembly_s=timer.assembly, linear_solve_s=timer.factor + timer.solve,
                     relaxation_s=job.seconds, timing=timing_stats(timer, job.relaxations),
                     fit=fit_stats(job.fit))
        return pathset_of(s.t_over_R, s.h_over_R, st.interface, s.key["mesh"],
                          job.fit.delta_max, s.gamma_max_hat, job.loading, job.relaxations,
                          stats, job.views, cavity=s.cavity,
                          lift=job.info.get("cavity_lift", 0.0), uniform=job.fit.uniform)

    def finish(job):
        s = job.shell
        ps = pathset(job)
        following = next_fit(ps, job.fit, s.request)
        if following is not None:           # fit the paths further: solve again
            if following.uniform != job.fit.uniform:
                job.known = {}
            job.fit = following
            load(job)
            return
        summary = dict(relaxations=len(ps.relaxations), loading_states=len(ps.loading_delta),
                       newton_iterations=ps.stats["loading_newton_iterations"]
                       + ps.stats["relaxation_newton_iterations"],
                       loading_s=ps.stats["loading_s"], relaxation_s=ps.stats["relaxation_s"],
                       stats=ps.stats)
        cat.store(s.key, to_dataset(ps), summary, {"wall_s": time.perf_counter() - job.t0},
                  study=st.name)
        tally.computed[s.fingerprint] = ps
        close(job)

    def arrived(f):
        job, k = owner.pop(f)
        if job.done:
            return
        if f.status == "error":
            stage = "loading" if k is None else f"relaxation {k[0] + 1} of {len(job.relaxations)}"
            if k is None:
                progress.update("loading paths", advance=1)
            fail(job, _reason(stage, f.exception()))
            return
        s, fit = job.shell, job.fit
        if k is None:
            first = job.loading is None
            job.loading, job.starts, job.info, job.views = f.result()
            if first:
                tally.loadings += 1
                progress.update("loading paths", advance=1)
            held = cat.parts(s.key)
            job.relaxations = [None] * len(job.starts)
            last = len(job.starts) - 1
            for i, start in enumerate(job.starts):
                reach, views = fit.reach_of(start), i == last
                r = job.known.get(start_key(start, reach))
                if r is not None and (not views or r.views):
                    job.relaxations[i] = replace(r, views=()) if r.views and not views else r
                    continue
                part = relaxation_part(start, views, reach, fit.uniform)
                if part in held:
                    try:
                        job.relaxations[i], seconds = relaxation_from_dataset(held[part])
                    except (ValueError, KeyError):
                        pass
                    else:
                        job.seconds += seconds
                        job.known[start_key(start, reach)] = job.relaxations[i]
                        tally.relaxations_reused += 1
                        continue
                g = client.submit(relax_task, s.t_over_R, s.h_over_R, st.interface, s.key["mesh"],
                                  start, s.gamma_max_hat, plan.settings,
                                  s.key["solver_source"], views, s.material,
                                  st.task_timeout_s, pure=False, cavity=s.cavity,
                                  lift=job.info.get("cavity_lift", 0.0), uniform=fit.uniform,
                                  reach=reach,
                                  key=f"relax-{s.fingerprint[:12]}-{i}-{uuid.uuid4().hex[:8]}")
                owner[g] = (job, (i, part, reach))
                pending.add(g)
                job.remaining += 1
        else:
            i, part, reach = k
            r, seconds = f.result()
            job.relaxations[i] = r
            job.known[start_key(job.starts[i], reach)] = r
            job.seconds += seconds
            job.remaining -= 1
            cat.store_part(s.key, part, relaxation_to_dataset(r, seconds), seconds)
            tally.relaxations_computed += 1
        progress.update("relaxation paths", note=relax_note())
        if job.remaining == 0:
            try:
                finish(job)
            except Exception as e:      # a set that cannot be stored is a failure too
                fail(job, _reason("store", e))

    unreachable_since = None
    waited = time.monotonic()
    while pending or waiting:
        interrupt.check()           # Ctrl-C is taken here, never inside dask or a write
        if claims is not None:
            claims.refresh()
        if not pending:             # companions whose answers another run computes
            if time.monotonic() - waited > sharing.WAIT_LIMIT_S:
                for job in waiting:
                    tally.failed[job.shell.fingerprint] = (
                        "no error bars: its answer's set was not stored in "
                        f"{sharing.WAIT_LIMIT_S:g} s; run again")
                break
            time.sleep(sharing.POLL_S)
            open_more()
            continue
        waited = time.monotonic()
        try:
            done, _ = wait(list(pending), timeout=1.0, return_when="FIRST_COMPLETED")
        except TimeoutError:
            done = set()
        stuck = False
        for f in done:
            pending.discard(f)
            if f in owner:
                if f.status in ("lost", "cancelled") and external:
                    pending.add(f)          # decided below: the scheduler may be gone
                    stuck = True
                    continue
                arrived(f)
        if stuck:
            time.sleep(0.5)
        if external:
            if client.status == "running" and not any(f.status == "cancelled" for f in pending):
                unreachable_since = None
            elif unreachable_since is None:
                unreachable_since = time.perf_counter()
            elif time.perf_counter() - unreachable_since > LOST_AFTER_S:
                raise SchedulerLost("the scheduler stopped answering")
    progress.update("relaxation paths", note=relax_note())


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
    relaxations_computed: int = 0   # relaxation paths solved by this run
    relaxations_reused: int = 0     # relaxation paths kept from an interrupted run
    dataset: object = None          # the cube as written (xarray.Dataset)
    shared: list = field(default_factory=list)  # reused sets another run stored meanwhile


def _held_by_index(plan: Plan, catalogue) -> int:
    """How many of the plan's sets the catalogue's index holds (read only; 0 if absent)."""
    directory = Path(catalogue) if catalogue is not None else default_dir()
    try:
        cat = Catalogue(directory, create=False)
    except FileNotFoundError:       # absent, or another run is creating it
        return 0
    with cat:
        return sum(bool(cat.candidates(s.key)) for s in plan.all_shells)


def execute(study, out=None, catalogue=None, scheduler=None, progress=True, workers=None,
            settings: Settings = None) -> Outcome:
    """Run a study; the orchestration behind `run_study` (see there), with the details
    of what was computed and reused (a cohesive study: study.cohesive_study's outcome).
    Raises StudyError (RunInputError for --out and --scheduler) before creating anything,
    SchedulerLost or Interrupted (after keeping all finished work in the catalogue,
    writing no cube)."""
    t0 = time.perf_counter()
    study = _study_of(study)
    if study.cohesive:
        return _execute_cohesive(study, out, catalogue, scheduler, progress, workers)
    plan = make_plan(study, settings if settings is not None else Settings())
    out_dir = check_out(out if out is not None else DEFAULT_OUT)
    _writable_folder("catalogue", catalogue if catalogue is not None else default_dir())
    output = out_dir / f"{study.name}.nc"
    all_held = _held_by_index(plan, catalogue) == len(plan.all_shells)
    with _quiet_dask(needed=not all_held):
        client = None
        if scheduler and not all_held:
            client = _connect_external(scheduler)       # before anything is created
        try:
            with interrupt.watched():
                return _execute(plan, out_dir, output, catalogue, scheduler, client, progress,
                                workers, t0)
        finally:
            _close_quietly(client)


def _execute_cohesive(study, out, catalogue, scheduler, show, workers):
    """A study with `adhesion: {model: dugdale}`: study.cohesive_study on the same dask
    cluster (local, or the scheduler's) and catalogue as an energy-method study."""
    from . import cohesive_study
    out_dir = check_out(out if out is not None else DEFAULT_OUT)
    _writable_folder("catalogue", catalogue if catalogue is not None else default_dir())
    output = out_dir / f"{study.name}.nc"

    @contextmanager
    def client_of():
        if external is not None:
            yield external
        else:
            with _local_cluster(workers) as local:
                yield local

    with _quiet_dask():
        # an external scheduler is reached before anything is created (RunInputError)
        external = _connect_external(scheduler) if scheduler else None
        try:
            with interrupt.watched():
                return cohesive_study.execute(study, out_dir, output, catalogue, client_of,
                                              show)
        except KeyboardInterrupt:
            raise Interrupted("interrupted: the finished cohesive points are kept in the "
                              "catalogue; no cube written; run again to resume") from None
        finally:
            _close_quietly(external)


def _close_quietly(client):
    """Close a Client of an external scheduler (None: nothing to close)."""
    if client is not None:
        try:
            client.close(timeout=5)
        except Exception:       # a lost scheduler cannot be told goodbye
            pass


@contextmanager
def _quiet_dask(needed=True):
    """dask.distributed's own log lines (its tracebacks of a lost connection) are not
    shown: the run reports what happened in one line.  Not `needed` (the catalogue's index
    holds every set): distributed is not imported (1 s); should a set turn out unreadable
    and be computed after all, dask's log lines are then not silenced."""
    if not needed:
        yield
        return
    importlib.import_module("distributed")      # its import configures its loggers
    names = ["distributed"] + [n for n in logging.root.manager.loggerDict
                               if n.startswith("distributed.")]
    loggers = [logging.getLogger(n) for n in names]
    levels = [lg.level for lg in loggers]
    for lg in loggers:
        lg.setLevel(logging.CRITICAL + 1)
    try:
        yield
    finally:
        for lg, level in zip(loggers, levels):
            lg.setLevel(level)


def _execute(plan, out_dir, output, catalogue, scheduler, client, show, workers, t0):
    study = plan.study
    out_dir.mkdir(parents=True, exist_ok=True)
    clean_temporaries(out_dir)          # left by a killed run (the catalogue cleans its own)
    cat = Catalogue(catalogue)
    tally = Tally()
    run_id = None
    try:
        run_id = cat.start_run(study.name, study.source, study.sha256, output,
                               solver.__version__)
        # every set stored and the cube on disk built from these very inputs: keep it;
        # built elsewhere from them (kept in the catalogue): copy it and its products
        inputs = _inputs(plan, cat)
        products = kept_products(output, inputs, key="inputs_sha256")
        if products is not None:
            return _kept_run(plan, output, products, cat, run_id, t0)
        cube = stored.fetch_cube(cat.dir, inputs)
        if cube is not None:
            products = _copy_cube(output, *cube, inputs, cat.dir)
            return _kept_run(plan, output, products, cat, run_id, t0)
        served, reused, missing = {}, [], []
        for s in plan.all_shells:
            hit = cat.fetch(s.key)
            if hit is None:
                missing.append(s)
            else:
                entry, ds = hit
                served[served_key(s, plan)] = (entry.fingerprint, from_dataset(ds))
                reused.append(s.fingerprint)
        progress = Progress([("loading paths", len(missing), "shells"),
                             ("relaxation paths", len(missing), "shells"),
                             ("energy method", len(plan.points), "points"),
                             ("cube", 1, "file")], enabled=show)
        if missing:
            claims = sharing.Claims(cat, run_id, study.name,
                                    sharing.stale_after(study.task_timeout_s))
            try:
                with ExitStack() as cluster:
                    computing = _computing(plan, cat, client, scheduler, workers, cluster,
                                           tally, progress, claims)
                    shared = sharing.settle(missing, claims, computing, progress, tally)
            finally:
                claims.release()
            for s in missing:
                if s.fingerprint in shared:
                    entry, ds = shared[s.fingerprint]
                    served[served_key(s, plan)] = (entry.fingerprint, from_dataset(ds))
                    reused.append(s.fingerprint)
                    tally.shared.append(s.fingerprint)
        for s in missing:
            if s.fingerprint in tally.computed:
                served[served_key(s, plan)] = (s.fingerprint, tally.computed[s.fingerprint])
        failed_th = {served_key(s, plan): tally.failed[s.fingerprint]
                     for s in missing if s.fingerprint in tally.failed}
        history = (f"{time.strftime('%Y-%m-%dT%H:%M:%S%z')} shell-adhesion "
                   f"{solver.__version__}: run_study {study.source}")
        progress.start("energy method")
        ds = dataset.build(plan, served, failed_th, history)
        progress.update("energy method", len(plan.points))
        progress.start("cube")
        digest = dataset.content_sha256(ds)
        products = kept_products(output, digest)    # the same cube: nothing to rewrite
        if inputs is None:      # recorded, so that a rerun builds nothing
            inputs = _inputs(plan, cat)
        if products is None:
            dataset.write(ds, output)
            if inputs is not None:
                try:
                    stored.store_cube(cat.dir, inputs, output, digest)
                except OSError:         # not kept: the next run into a new folder builds it
                    pass
            products = _products(output, digest, inputs, cat.dir)
        elif inputs != recorded_inputs(output):
            record_products(output, digest, products, inputs)
        progress.update("cube", 1, note=str(output))
        counts = dataset.summary_counts(ds)
        code = 1 if tally.failed else exit_code(ds)
        wall = time.perf_counter() - t0
        cat.finish_run(run_id, code, len(tally.computed), len(reused), len(tally.failed), wall)
        return Outcome(code, output, plan, list(tally.computed), reused, tally.failed, counts,
                       wall, cat.dir, list(cat.discarded), products,
                       tally.relaxations_computed, tally.relaxations_reused, _written(output),
                       shared=tally.shared)
    except KeyboardInterrupt:
        _finish_broken(cat, run_id, 130, tally, t0)
        raise Interrupted(f"interrupted: {_kept(tally, cat)}; run again to resume") from None
    except SchedulerLost as e:
        _finish_broken(cat, run_id, 1, tally, t0)
        raise SchedulerLost(f"{e}: {_kept(tally, cat)}; no cube written; run again to "
                            "resume") from None
    except BaseException:       # any other end still gets its exit code in the runs table
        _finish_broken(cat, run_id, 1, tally, t0)
        raise
    finally:
        cat.close()


def _computing(plan, cat, client, scheduler, workers, cluster: ExitStack, tally, progress,
               claims):
    """compute(shells) on the external `client`, else on a local cluster started the first
    time it is needed (entered in `cluster`, so it lasts while the run computes or waits)."""
    local = []

    def computing(shells):
        if client is not None:
            address = getattr(client.scheduler, "address", None) or scheduler
            try:
                with interrupt.deferred():
                    compute(plan, shells, cat, client, tally, progress, external=True,
                            claims=claims)
            except (SchedulerLost, OSError, TimeoutError, CancelledError) as e:
                why = (f"no answer for {LOST_AFTER_S:g} s" if isinstance(e, SchedulerLost)
                       else type(e).__name__)
                raise SchedulerLost(f"lost the dask scheduler {address} ({why})") from None
            return
        if not local:
            local.append(cluster.enter_context(_local_cluster(workers)))
            if _has_bokeh():
                progress.say(f"dask dashboard: {local[0].dashboard_link}")
        with interrupt.deferred():
            compute(plan, shells, cat, client=local[0], tally=tally, progress=progress,
                    claims=claims)
    return computing


def _inputs(plan, cat):
    """study.dataset.inputs_sha256 of the plan with the catalogue's stored sets, or None
    if one is not stored (or its file does not match the index)."""
    entries = [cat.locate(s.key) for s in plan.all_shells]
    return dataset.inputs_sha256(plan, entries) if all(entries) else None


def _groups(results_nc) -> dict:
    """Where each group of products of the cube at `results_nc` goes."""
    return {"tables": tables_dir(results_nc), "figures": figures_dir(results_nc)}


def _catalogued_products(results_nc, digest: str, catalogue_dir,
                        formats=RUN_FORMATS) -> Products:
    """The tables and figures of the cube at `results_nc` (content `digest`): copied from
    the catalogue at `catalogue_dir` if it holds them for this content and drawing code
    (each file's digest checked; Products.copied), else drawn (write_products) and kept
    there.  A catalogue that cannot keep them costs nothing but the next copy."""
    t0 = time.perf_counter()
    key = products_key(digest, formats)
    found = stored.fetch_products(catalogue_dir, key)
    groups = _groups(results_nc)
    if found is not None:
        files, skipped = found
        p = Products(skipped=skipped, copied=True)
        for rel, data in sorted(files.items()):
            group, name = rel.split("/", 1)
            written = stored.write_bytes_atomic(groups[group] / name, data)
            (p.tables if group == "tables" else p.figures).append(written)
        p.seconds = dict(copy=time.perf_counter() - t0, total=time.perf_counter() - t0)
        return p
    p = write_products(results_nc, formats)
    files = {f"{group}/{Path(f).relative_to(groups[group]).as_posix()}": f
             for group, made in (("tables", p.tables), ("figures", p.figures)) for f in made}
    try:
        stored.store_products(catalogue_dir, key, files, p.skipped)
    except OSError:
        pass
    return p


def _products(output, digest, inputs, catalogue_dir) -> Products:
    """The tables and figures of the cube written at `output` (content `digest`), copied
    from the catalogue or drawn (_catalogued_products), and the manifest
    that lets a rerun keep them."""
    try:
        products = _catalogued_products(output, digest, catalogue_dir)
        record_products(output, digest, products, inputs)
    except Exception as e:      # the cube is written; a drawing bug must not lose it
        products = Products(skipped={"tables and figures": _reason("products", e)})
    return products


def _copy_cube(output, data: bytes, digest: str, inputs: str, catalogue_dir):
    """Write the cube `data` (content `digest`) kept in the catalogue for `inputs` to
    `output`, then its products."""
    stored.write_bytes_atomic(output, data)
    return _products(output, digest, inputs, catalogue_dir)


def _kept_run(plan, output, products, cat, run_id, t0) -> Outcome:
    """The Outcome of a run whose every path set is stored and whose cube on disk was
    built from the same inputs (study.dataset.inputs_sha256), or copied there from the
    catalogue (_copy_cube): nothing is built."""
    written = _written(output)
    counts = dataset.summary_counts(written)
    code = exit_code(written)
    reused = [s.fingerprint for s in plan.all_shells]
    wall = time.perf_counter() - t0
    cat.finish_run(run_id, code, 0, len(reused), 0, wall)
    return Outcome(code, output, plan, [], reused, {}, counts, wall, cat.dir,
                   list(cat.discarded), products, dataset=written)


def _written(output):
    """The cube as written at `output` (loaded, the file closed)."""
    import xarray as xr
    with xr.open_dataset(output) as written:
        return written.load()


def _finish_broken(cat, run_id, code, tally, t0):
    if run_id is None:
        return
    try:
        cat.finish_run(run_id, code, len(tally.computed), 0, len(tally.failed),
                       time.perf_counter() - t0)
    except Exception:           # the record of a broken run is not worth a second error
        pass


def run_study(study, *, out=None, catalogue=None, scheduler=None, progress=True,
              workers=None, settings: Settings = None):
    """Run a study end to end: its cube (netCDF), tables and figures in `out`.

    Every FE path set the study needs is taken from the catalogue if stored there, else
    computed on dask and stored as it finishes (each relaxation path too), so a rerun,
    or a run after an interruption, recomputes nothing that finished.

    Parameters
    ----------
    study : str, path-like or dict
        A study YAML file, or a dict of the same schema (see "Parameter studies"): R_mm [mm],
        C10_MPa [MPa], t_over_R and h_over_R [1], gamma_J_m2 [J/m^2], ...
    out : str or path-like, optional
        Output folder (created if needed; default ``results``).  The cube is
        ``<out>/<name>.nc``, tables and figures go beside it.
    catalogue : str or path-like, optional
        Catalogue folder (default ``$SHELL_ADHESION_CATALOGUE`` or ``./catalogue-data``).
    scheduler : str, optional
        Address (``tcp://host:port``) or scheduler file of a running dask.distributed
        scheduler; default: a local cluster of processes, one per core.
    progress : bool
        Print one line per stage (loading paths, relaxation paths, energy method, cube)
        with done/total and elapsed time to stderr, and the summary to stdout.
    workers : int, optional
        Size of the local cluster (ignored with `scheduler`).
    settings : shell_adhesion.solver.path.Settings, optional
        Solver tolerances (part of the catalogue key).

    Returns
    -------
    xarray.Dataset
        The results cube as written: dims C10 [MPa], t_over_R, h_over_R, gamma [J m-2];
        forces in N, lengths in mm, energies in mJ; `status` says, per point, ok, not
        requested, solver failed or out of range.  A study with `adhesion: {model:
        dugdale}` gives study.cohesive_study's cube (dimension `tabor` too).

    Raises
    ------
    StudyError
        (a ValueError) an invalid study or argument, with a one-line message naming the
        key, the value and the rule; raised before anything is created.
    SchedulerLost
        The dask scheduler stopped answering; finished work is kept, no cube is written.
    Interrupted
        (a KeyboardInterrupt) Ctrl-C; finished work is kept, no cube is written.
    """
    outcome = execute(study, out, catalogue, scheduler, progress, workers, settings)
    if progress:
        if isinstance(outcome, Outcome):
            print(summary(outcome, outcome.dataset))
        else:
            from .cohesive_study import summary as cohesive_summary
            print(cohesive_summary(outcome))
    return outcome.dataset


def exit_code(ds) -> int:
    """0 if every requested point of the cube was evaluated, else 1."""
    if ds.attrs.get("adhesion") == "dugdale":       # study.cohesive_study's cube
        from .cohesive_study import exit_code as cohesive_exit_code
        return cohesive_exit_code(ds)
    counts = dataset.summary_counts(ds)
    return 1 if counts["solver failed"] + counts["out of range"] else 0


def summary(outcome: Outcome, ds=None) -> str:
    """The end-of-run report (one screen)."""
    p, c = outcome.plan, outcome.counts
    ax = p.axes
    lines = [
        f"study {p.study.name} ({p.study.source}): cube C10 {len(ax['C10_MPa'])} x t/R "
        f"{len(ax['t_over_R'])} x h/R {len(ax['h_over_R'])} x gamma {len(ax['gamma_J_m2'])}, "
        f"requested points: {len(p.points)}; interface {p.study.interface}, mesh {p.study.mesh}",
        *_cavity_lines(p),
        f"FE path sets: {len(p.all_shells)} needed, {len(outcome.computed)} computed, "
        f"{len(outcome.reused)} reused"
        + (f" ({len(outcome.shared)} stored by another run meanwhile)" if outcome.shared else "")
        + f", {len(outcome.failed)} failed (catalogue {outcome.catalogue})",
        f"points: {c['ok']} ok, {c['out of range']} out of range, {c['solver failed']} "
        f"solver failed, {c['not requested']} not requested",
    ]
    if outcome.relaxations_reused:
        lines.append(f"relaxation paths: {outcome.relaxations_computed} solved, "
                     f"{outcome.relaxations_reused} kept from an interrupted run")
    for s in p.all_shells:
        if s.fingerprint in outcome.failed:
            companion = " (coarser mesh, error bars)" if s in p.error_shells else ""
            lines.append(f"  failed t/R={s.t_over_R:g} h/R={s.h_over_R:g}{companion}: "
                         f"{outcome.failed[s.fingerprint]}")
    if ds is not None and c["out of range"]:
        bad = ds["status"].values == "out of range"
        shown = 0
        for idx in zip(*bad.nonzero()):
            if shown == 5:
                lines.append(f"  ... {c['out of range'] - 5} more out of range")
                break
            pt = ", ".join(f"{d}={ds[d].values[i]:g}" for d, i in zip(DIMS, idx))
            lines.append(f"  out of range at {pt}: {ds['reason'].values[idx]}")
            shown += 1
    for d in outcome.discarded:
        lines.append(f"  discarded a corrupt catalogue entry: {d}")
    pr = outcome.products
    if pr is not None:
        kept = (" (kept: the cube's content is unchanged)" if pr.kept else
                " (copied from the catalogue: drawn before from the same cube content)"
                if pr.copied else "")
        if pr.tables:
            lines.append(f"tables: {len(pr.tables)} files in {pr.tables[0].parent}{kept}")
        if pr.figures:
            lines.append(f"figures: {len(pr.figures)} files in {pr.figures[0].parent} "
                         + (kept.strip() if kept else
                            f"({pr.seconds.get('total', 0):.1f} s for tables and figures)"))
        for name, why in pr.skipped.items():
            lines.append(f"  skipped {name}: {why}")
    lines.append(f"wall time {outcome.wall_s:.1f} s; results in {outcome.output}")
    return "\n".join(lines)


# -- the plan without running it ---------------------------------------------------------

def _cavity_lines(plan: Plan) -> list:
    """What a closed cavity does to the plan (one line; none if open)."""
    if not plan.cavities:
        return []
    mode = plan.study.cavity["mode"]
    shells = len({(s.t_over_R, s.h_over_R) for s in plan.shells})
    return [f"closed cavity ({mode}): p/C10, p_atm/C10"
            + (", p0/C10 and the gas exponent" if mode == "sealed" else "")
            + " are FE parameters, so a C10 sweep is not post-processing: one path set per "
              "C10" + (" and p_kPa" if plan.cavity_axes else "")
            + f" ({len(plan.shells)} set{'s' if len(plan.shells) != 1 else ''} for {shells} "
              "t/R, h/R)"]


def dry_run(study, catalogue=None, workers=None, scheduler=None) -> str:
    """What `run` would do, as text: the distinct FE problems, how many the catalogue
    holds (by its index), and an estimate of the time from the timings it recorded.
    Computes nothing, creates nothing."""
    study = _study_of(study)
    directory = Path(catalogue) if catalogue is not None else default_dir()
    if study.cohesive:
        from .cohesive_study import dry_run as cohesive_dry_run
        return cohesive_dry_run(study, directory)
    plan = make_plan(study, Settings())
    missing, parts, times = list(plan.all_shells), 0, []
    if (directory / INDEX).exists():
        with Catalogue(directory, create=False) as cat:
            missing = [s for s in plan.all_shells if not cat.candidates(s.key)]
            parts = sum(cat.count_parts(s.key) for s in missing)
            times = cat.timings(study.interface, study.mesh)
    todo = len(missing)
    held = len(plan.all_shells) - todo
    lines = [f"study {study.name} ({study.source}): {len(plan.points)} requested points, "
             f"{len(plan.all_shells)} distinct FE problems (path sets of one t/R, h/R each); "
             f"interface {study.interface}, mesh {study.mesh}, "
             + (f"delta_max/R {study.delta_max_over_R:g}" if study.delta_max_over_R is not None
                else "loading as deep as the pull-offs need"),
             *_cavity_lines(plan),
             f"catalogue {directory}: holds {held} of them, {todo} to compute"
             + (f" ({parts} relaxation paths kept from an interrupted run)" if parts else "")]
    if todo == 0:
        lines.append("estimate: nothing to compute (no cluster is started)")
    elif times and study.delta_max_over_R is not None:
        # cost of a set ~ its loading + relaxations, scaled by delta_max/R (more states)
        per = [(r["loading_s"] + (r["relaxation_s"] or 0.0))
               * study.delta_max_over_R / r["delta_max_over_R"] for r in times]
        cpu = sum(per) / len(per) * todo
        n = workers or (None if scheduler else _cpu_count())
        lines.append(f"estimate: about {cpu:.0f} s of FE work (mean of {len(times)} recorded "
                     "sets of this mesh and interface, scaled by delta_max/R)"
                     + (f", at best {cpu / n:.0f} s on {n} workers" if n else ""))
    else:
        cpu, dofs, paths = estimate_s(missing)
        n = workers or (None if scheduler else _cpu_count())
        lines.append(f"estimate: about {cpu:.0f} s of FE work from the cost model ({dofs} dofs "
                     f"and about {paths} relaxation paths in all; no timing of this mesh and "
                     "interface recorded in the catalogue)"
                     + (f", at best {cpu / n:.0f} s on {n} workers" if n else ""))
    return "\n".join(lines)

