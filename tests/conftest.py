"""Shared, cached solutions (the real solver; coarse meshes unless a test needs more)."""
import functools
import multiprocessing
import os
from pathlib import Path
from concurrent.futures import ProcessPoolExecutor

import pytest

from solver import solve_paths

REPO = Path(__file__).resolve().parents[1]
# environment for subprocesses that must import this checkout
ENV = dict(os.environ, PYTHONPATH=os.pathsep.join(
    p for p in (str(REPO), os.environ.get("PYTHONPATH")) if p))

BASE = dict(t=0.15, h=1.0)          # paper base case: t = 3 mm, h = R = 20 mm
R_MM, C10_MPA, GAMMA = 20.0, 0.3, 30.0
GAMMA_HAT = GAMMA * 1e-3 / (C10_MPA * R_MM)


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
