"""The catalogue: stored path sets round-trip exactly, serve what they cover, and are never
trusted when their file is damaged; concurrent writers do not corrupt it."""
from concurrent.futures import ProcessPoolExecutor
from dataclasses import fields
import functools
import json
import multiprocessing
import sqlite3

import numpy as np
import pytest

from shell_adhesion.catalogue import Catalogue, format_entries, list_entries
from shell_adhesion.solver.case import PathSet, Relaxation, solve_paths
from shell_adhesion.solver.pathset_dataset import from_dataset, to_dataset
from shell_adhesion.study.keys import pathset_key

SHELL = (0.15, 1.0, "no_slip", "coarse", 0.1, 0.01)


@functools.lru_cache(maxsize=None)
def pathset():
    return solve_paths(*SHELL)[0]


def store(cat, key, ps, timings=None, study=""):
    return cat.store(key, to_dataset(ps), {"relaxations": len(ps.relaxations)}, timings, study)


def fetch(cat, key):
    hit = cat.fetch(key)
    return None if hit is None else (hit[0], from_dataset(hit[1]))


def key(**change):
    k = pathset_key(*SHELL)
    return dict(k, **change)


def assert_same_pathset(a: PathSet, b: PathSet):
    for f in fields(PathSet):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if f.name == "relaxations":
            assert len(x) == len(y)
            for r, s in zip(x, y):
                for g in fields(Relaxation):
                    np.testing.assert_array_equal(getattr(r, g.name), getattr(s, g.name))
        elif f.name == "views":
            assert len(x) == len(y) > 0
            for v, w in zip(x, y):
                assert type(v) is type(w)
                for g in fields(v):
                    np.testing.assert_array_equal(getattr(v, g.name), getattr(w, g.name))
        elif isinstance(x, np.ndarray):
            np.testing.assert_array_equal(x, y)
        else:
            assert x == y, f.name


def test_store_and_fetch_round_trip(tmp_path):
    ps = pathset()
    with Catalogue(tmp_path / "cat") as cat:
        entry = store(cat, key(), ps, {"wall_s": 1.0}, study="t")
        hit = fetch(cat, key())
    assert hit is not None and hit[0].fingerprint == entry.fingerprint
    assert_same_pathset(ps, hit[1])
    g = 0.005
    assert hit[1].pull_off(g)[1] == ps.pull_off(g)[1]
    assert not list((tmp_path / "cat" / "pathsets").glob("*.tmp*"))
    rows = list_entries(tmp_path / "cat")
    assert [r["status"] for r in rows] == ["ok"]
    assert rows[0]["relaxations"] == len(ps.relaxations) and rows[0]["sha256"] == entry.sha256
    assert "0.15" in format_entries(rows)


def test_a_set_reaching_further_serves(tmp_path):
    with Catalogue(tmp_path) as cat:
        stored = store(cat, key(), pathset())
        assert fetch(cat, key(gamma_max_hat=0.005))[0].fingerprint == stored.fingerprint
        assert fetch(cat, key(delta_max_over_R=0.05))[0].fingerprint == stored.fingerprint
        assert fetch(cat, key(gamma_max_hat=0.02)) is None
        assert fetch(cat, key(delta_max_over_R=0.2)) is None
        assert fetch(cat, key(interface="frictionless")) is None
        assert fetch(cat, key(h_over_R=0.9)) is None
        exact = store(cat, key(gamma_max_hat=0.005), pathset())
        assert fetch(cat, key(gamma_max_hat=0.005))[0].fingerprint == exact.fingerprint


@pytest.mark.parametrize("damage", ["truncate", "flip", "delete", "garbage"])
def test_damaged_file_is_not_trusted(tmp_path, damage):
    with Catalogue(tmp_path) as cat:
        entry = store(cat, key(), pathset())
        data = entry.file.read_bytes()
        if damage == "truncate":
            entry.file.write_bytes(data[: len(data) // 2])
        elif damage == "flip":
            i = len(data) // 2
            entry.file.write_bytes(data[:i] + bytes([data[i] ^ 0xFF]) + data[i + 1:])
        elif damage == "delete":
            entry.file.unlink()
        else:
            entry.file.write_bytes(b"not a netCDF file")
        assert fetch(cat, key()) is None
        assert len(cat.discarded) == 1
        assert list_entries(tmp_path) == []          # the untrusted row is gone
        store(cat, key(), pathset())                  # and a recomputed set replaces it
        assert_same_pathset(fetch(cat, key())[1], pathset())


def test_file_without_row_is_not_trusted(tmp_path):
    """A writer killed between the file and the index row leaves nothing a rerun trusts."""
    with Catalogue(tmp_path / "a") as a:
        entry = store(a, key(), pathset())
    with Catalogue(tmp_path / "b") as b:
        (b.files / entry.file.name).write_bytes(entry.file.read_bytes())
        assert fetch(b, key()) is None


def test_failure_never_replaces_a_good_entry(tmp_path):
    with Catalogue(tmp_path) as cat:
        cat.record_failure(key(), "loading: ConvergenceError: test")
        assert [r["status"] for r in cat.entries()] == ["failed"]
        assert fetch(cat, key()) is None
        store(cat, key(), pathset())
        cat.record_failure(key(), "later failure")
        assert [r["status"] for r in cat.entries()] == ["ok"]


def test_list_entries_of_absent_catalogue(tmp_path):
    assert list_entries(tmp_path / "none") == []
    assert not (tmp_path / "none").exists()


def test_index_is_wal(tmp_path):
    Catalogue(tmp_path).close()
    db = sqlite3.connect(tmp_path / "index.sqlite")
    assert db.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
    db.close()


def _store_many(directory, ps, t_values):
    with Catalogue(directory) as cat:
        for t in t_values:
            store(cat, key(t_over_R=t), ps, study=f"writer {t_values[0]}")
    return len(t_values)


def test_concurrent_writers(tmp_path):
    ps = pathset()
    ts = [[0.11, 0.12, 0.13], [0.21, 0.22, 0.23], [0.11, 0.12, 0.31]]   # writers 1, 3 overlap
    ctx = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(3, mp_context=ctx) as pool:
        assert sum(pool.map(_store_many, [tmp_path] * 3, [ps] * 3, ts)) == 9
    rows = list_entries(tmp_path)
    assert len(rows) == 7 and all(r["status"] == "ok" for r in rows)
    with Catalogue(tmp_path) as cat:
        for t in sorted({t for group in ts for t in group}):
            hit = fetch(cat, key(t_over_R=t))
            assert hit is not None
            assert_same_pathset(hit[1], ps)
        assert cat.discarded == []


def test_parts_are_kept_until_the_set_is_stored(tmp_path):
    """A finished relaxation path is kept as a part of its set; storing the set drops it."""
    from shell_adhesion.solver.pathset_dataset import (relaxation_from_dataset,
                                                       relaxation_to_dataset)
    ps = pathset()
    r = ps.relaxations[0]
    with Catalogue(tmp_path) as cat:
        cat.store_part(key(), "p0", relaxation_to_dataset(r, 1.5), 1.5)
        assert cat.count_parts(key()) == 1 and cat.parts(key(gamma_max_hat=0.02)) == {}
        back, seconds = relaxation_from_dataset(cat.parts(key())["p0"])
        assert seconds == 1.5 and back.a == r.a
        np.testing.assert_array_equal(back.P, r.P)
        store(cat, key(), ps)
        assert cat.parts(key()) == {} and not list((tmp_path / "parts").rglob("*.nc"))


def test_catalogue_imports_nothing_from_the_solver(tmp_path):
    """catalogue stores Datasets under a fingerprint; a subprocess in which importing
    shell_adhesion.solver fails stores and reads one (the package's own __init__, which
    exports the solver's API, is not run)."""
    import subprocess
    import sys
    from conftest import ENV, REPO
    code = f"""
import sys
class Block:
    def find_spec(self, name, path=None, target=None):
        if name == "shell_adhesion.solver" or name.startswith("shell_adhesion.solver."):
            raise ImportError("blocked: " + name)
sys.meta_path.insert(0, Block())
import types                # the package without its __init__ (which exports the API)
pkg = types.ModuleType("shell_adhesion")
pkg.__path__ = [{str(REPO / "shell_adhesion")!r}]
sys.modules["shell_adhesion"] = pkg
import xarray as xr, numpy as np
from shell_adhesion.catalogue import Catalogue, list_entries
key = dict(t_over_R=0.1, h_over_R=1.0, interface="no_slip", mesh="coarse",
           delta_max_over_R=0.1, gamma_max_hat=0.01)
ds = xr.Dataset({{"x": ("n", np.arange(3.0))}})
with Catalogue({str(tmp_path)!r}) as cat:
    cat.store(key, ds, {{"relaxations": 0}})
    entry, back = cat.fetch(key)
    cat.store_part(key, "p", ds)
assert back["x"].values.tolist() == [0.0, 1.0, 2.0]
assert not [m for m in sys.modules if m.startswith("shell_adhesion.solver")]
print(len(list_entries({str(tmp_path)!r})))
"""
    out = subprocess.run([sys.executable, "-c", code], cwd=REPO, env=ENV, capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "1"


def test_temporaries_of_dead_writers_are_removed_on_open(tmp_path):
    import os
    import subprocess
    import sys
    from shell_adhesion.atomic import _host
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True, timeout=60).stdout.strip()
    (tmp_path / "pathsets").mkdir()
    orphan = tmp_path / "pathsets" / f"x.nc.tmp-{_host()}-{dead}-abc"
    mine = tmp_path / "pathsets" / f"y.nc.tmp-{_host()}-{os.getpid()}-abc"
    other = tmp_path / "pathsets" / "z.nc.tmp-otherhost-1-abc"        # recent: kept
    for p in (orphan, mine, other):
        p.write_bytes(b"partial")
    Catalogue(tmp_path).close()
    assert not orphan.exists() and mine.exists() and other.exists()


def test_list_shows_each_sets_own_time_and_solid(tmp_path):
    """`catalogue list`: the FE seconds of the set itself (not the time since its study
    started) and the solid and cavity of its key, so sets differing only in material
    are told apart."""
    from shell_adhesion.catalogue.store import solid_of
    ps = pathset()
    with Catalogue(tmp_path / "cat") as cat:
        cat.store(key(), to_dataset(ps), dict(relaxations=len(ps.relaxations), loading_s=1.25,
                                              relaxation_s=2.5), {"wall_s": 600.0}, study="t")
    text = format_entries(list_entries(tmp_path / "cat"))
    assert "FE s" in text and "3.8" in text and "600.0" not in text and "neo_hooke" in text
    mr = {"material": {"model": "mooney_rivlin", "C01_over_C10": 0.2, "C20_over_C10": 0.0,
                       "D1_times_C10": 0.0, "Jm": None}, "cavity": {"mode": "sealed", "p": 0.0}}
    assert solid_of(json.dumps(mr)) == "mooney_rivlin C01/C10=0.2, sealed"
    assert solid_of("{}") == "neo_hooke"
