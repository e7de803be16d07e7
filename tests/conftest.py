"""Shared, cached solutions (the real solver; coarse meshes unless a test needs more)."""
import contextlib
import functools
import multiprocessing
import os
from pathlib import Path
from concurrent.futures import ProcessPoolExecutor

try:
    import fcntl            # the small study's lock (POSIX)
except ImportError:
    fcntl = None

import pytest

from shell_adhesion.solver import solve_paths

REPO = Path(__file__).resolve().parents[1]
# environment for subprocesses that must import this checkout
ENV = dict(os.environ, PYTHONPATH=os.pathsep.join(
    p for p in (str(REPO), os.environ.get("PYTHONPATH")) if p))

BASE = dict(t=0.15, h=1.0)          # paper base case: t = 3 mm, h = R = 20 mm
R_MM, C10_MPA, GAMMA = 20.0, 0.3, 30.0
GAMMA_HAT = GAMMA * 1e-3 / (C10_MPA * R_MM)


def energy_roundoff(d, *energies) -> float:
    """Absolute floor of an energy check on the discretisation d (units of C10 R^3): the
    round-off of integrating W = C10 (I1bar - 3) with I1bar near 3 over the body (3 times
    its volume), and of the energies compared, 16 units of round-off each.  A relative
    check of an energy near 0 (the first apex state: 5e-13) holds to this floor instead."""
    import numpy as np
    scale = 3.0 * float(d.w.sum()) + max((float(np.max(np.abs(e))) for e in energies),
                                         default=0.0)
    return 16 * np.finfo(float).eps * scale


@functools.lru_cache(maxsize=None)
def _pool():
    # relaxation paths are independent tasks; spawn, so no thread state is forked
    return ProcessPoolExecutor(max_workers=2, mp_context=multiprocessing.get_context("spawn"))


@functools.lru_cache(maxsize=None)
def base_case(mesh="coarse", interface="no_slip", gamma_max=0.006, delta_max=0.25):
    """Loading and relaxation paths of the paper's base shell: (PathSet, d, loading)."""
    return solve_paths(BASE["t"], BASE["h"], interface, mesh, delta_max, gamma_max,
                       map=_pool().map)


@pytest.fixture(scope="session")
def base_coarse():
    return base_case("coarse")


# a small real study (coarse mesh): the paper's base shell with a short sweep of each
# parameter; 3 FE path sets, read by the analysis, table and figure tests
SMALL_STUDY = """\
name: small
description: small coarse study around the paper's base shell (tests)
R_mm: 20
base: {C10_MPa: 0.3, t_over_R: 0.15, h_over_R: 1.0, gamma_J_m2: 30}
sweeps:
  C10_MPa: [0.2, 0.3, 0.5]
  t_over_R: [0.15, 0.2]
  h_over_R: [0.9, 1.0]
  gamma_J_m2: [20, 30, 40]
mesh: coarse
delta_max_over_R: 0.1
error_bars: false
"""


@pytest.fixture(scope="session")
def small_study(tmp_path_factory):
    """Path of the small study's results netCDF, computed once per test session: under
    pytest-xdist the workers share one run (the first to take the lock computes it, the
    others read its cube), where each worker used to compute its own."""
    from shell_adhesion.study.run import execute
    base = tmp_path_factory.getbasetemp()
    workers_share = os.environ.get("PYTEST_XDIST_WORKER") and fcntl is not None
    d = (base.parent if workers_share else base) / "small-study"
    d.mkdir(exist_ok=True)
    with _exclusive(d / ".lock"):
        output = d / "results" / "small.nc"
        if not output.exists():
            (d / "small.yaml").write_text(SMALL_STUDY)
            outcome = execute(d / "small.yaml", d / "results", catalogue=d / "cat",
                              progress=False)
            assert outcome.exit_code == 0, outcome.failed
            assert outcome.output == output, outcome.output
    return output


@contextlib.contextmanager
def _exclusive(path):
    """Hold an exclusive lock on the file `path` (POSIX; elsewhere no lock, and each worker
    of a parallel run computes in its own folder)."""
    if fcntl is None:
        yield
        return
    with open(path, "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)


# names through which the finite-element solver can be entered (as defined and as imported)
FE_ENTRY_POINTS = {
    "shell_adhesion.solver.path": ("load", "relax", "tangent"),
    "shell_adhesion.solver.forms": ("tangent",),
    "shell_adhesion.solver.case": ("load", "relax", "solve_paths", "solve_loading", "relaxation_task"),
    "shell_adhesion.solver": ("solve_paths", "solve_loading", "relaxation_task"),
    "shell_adhesion.solver.request": ("solve_paths", "solve_request"),
    "shell_adhesion.study.case": ("solve_request",),
    "shell_adhesion.study.run": ("solve_loading", "relaxation_task"),
}


@pytest.fixture
def forbid_fe(monkeypatch):
    """Make every entry into the FE solver raise (for code that must only read results)."""
    forbid_fe_with(monkeypatch)


def forbid_fe_with(monkeypatch):
    """forbid_fe's work on a pytest MonkeyPatch: undone by its undo(), leaving nothing."""
    import importlib

    def forbidden(name):
        def call(*args, **kwargs):
            raise AssertionError(f"{name} was called: this code must not run the FE solver")
        return call

    # import every module before patching any: a module first imported while another is
    # patched would bind the forbidden stand-in (`from .x import name`) for the rest of the
    # session, where monkeypatch's undo restores it as that module's original
    modules = {module: importlib.import_module(module) for module in FE_ENTRY_POINTS}
    for module, names in FE_ENTRY_POINTS.items():
        for name in names:
            monkeypatch.setattr(modules[module], name, forbidden(f"{module}.{name}"))


def load_cube(path):
    """A study's cube read into memory, without its history attribute (which names the
    run): for comparing the cubes of two runs."""
    import xarray as xr
    with xr.open_dataset(path) as ds:
        ds = ds.load()
    ds.attrs.pop("history")
    return ds
