"""The catalogue folder: stored Datasets (FE path sets) and their SQLite index.

    <dir>/index.sqlite                the index (WAL journal): one row per path set, one per
                                      stored part, one per run
    <dir>/pathsets/<fingerprint>.nc   one file per path set (catalogue.files)
    <dir>/parts/<fingerprint>/<part>.nc   finished pieces (relaxation paths) of a set not
                                      yet complete, kept so a killed run loses none of them

The catalogue stores xarray Datasets under the fingerprint of a key made by the caller
(study.keys) and reads the index columns from the key and the caller's summary; it knows
nothing of the solver.

The folder is `--catalogue DIR`, else $SHELL_ADHESION_CATALOGUE, else ./catalogue-data in
the directory the command runs in.

Claims (the `claims` table): a run claims each path set it is about to compute, in one
write transaction, so that of two runs sharing the folder one computes the set and the
other waits for it (study.sharing).  The owner refreshes its claims while it works and
deletes them when it ends; a claim whose process is dead (on this host) or that has not
been refreshed for the claimant's `stale_s` is taken over, so a run that dies blocks
nobody for longer than that.

Trust rule: a path set is used only if its row says 'ok' and the file's sha256 matches the
row; anything else (missing, truncated, altered file) is dropped and recomputed.  A path
set (or part) is stored file first (atomically), row second, both under the index's write lock, so a
process killed at any moment leaves either nothing, an orphan file no row trusts, or a
complete entry; two studies sharing a folder serialise their writes.
"""
from contextlib import contextmanager
from dataclasses import dataclass
from datetime import datetime, timezone
import json
import os
from pathlib import Path
import socket
import sqlite3
import time

import xarray as xr

from . import files
from shell_adhesion.atomic import alive, clean_temporaries
from .fingerprint import canonical_json, family, fingerprint

ENV_VAR = "SHELL_ADHESION_CATALOGUE"
DEFAULT_DIR = "catalogue-data"
INDEX = "index.sqlite"
TIMEOUT_S = 120.0
_REL_TOL = 1e-9

_SCHEMA = """
CREATE TABLE IF NOT EXISTS pathsets (
    fingerprint TEXT PRIMARY KEY,
    family TEXT NOT NULL,
    status TEXT NOT NULL,
    t_over_R REAL NOT NULL,
    h_over_R REAL NOT NULL,
    interface TEXT NOT NULL,
    mesh TEXT NOT NULL,
    delta_max_over_R REAL NOT NULL,
    gamma_max_hat REAL NOT NULL,
    file TEXT,
    sha256 TEXT,
    bytes INTEGER,
    relaxations INTEGER,
    loading_states INTEGER,
    newton_iterations INTEGER,
    loading_s REAL,
    relaxation_s REAL,
    wall_s REAL,
    reason TEXT,
    version TEXT,
    key TEXT NOT NULL,
    stats TEXT,
    study TEXT,
    host TEXT,
    pid INTEGER,
    created TEXT NOT NULL
);
CREATE INDEX IF NOT EXISTS pathsets_family ON pathsets (family, status);
CREATE TABLE IF NOT EXISTS parts (
    owner TEXT NOT NULL,
    part TEXT NOT NULL,
    file TEXT NOT NULL,
    sha256 TEXT NOT NULL,
    bytes INTEGER,
    seconds REAL,
    created TEXT NOT NULL,
    PRIMARY KEY (owner, part)
);
CREATE TABLE IF NOT EXISTS claims (
    fingerprint TEXT PRIMARY KEY,
    run INTEGER NOT NULL,
    study TEXT,
    host TEXT NOT NULL,
    pid INTEGER NOT NULL,
    claimed TEXT NOT NULL,
    refreshed REAL NOT NULL
);
CREATE TABLE IF NOT EXISTS runs (
    id INTEGER PRIMARY KEY AUTOINCREMENT,
    study TEXT,
    study_file TEXT,
    study_sha256 TEXT,
    output TEXT,
    started TEXT,
    finished TEXT,
    exit_code INTEGER,
    computed INTEGER,
    reused INTEGER,
    failed INTEGER,
    wall_s REAL,
    host TEXT,
    pid INTEGER,
    version TEXT
);
"""

# columns list_entries returns, in order
COLUMNS = ("fingerprint", "status", "t_over_R", "h_over_R", "interface", "mesh",
           "delta_max_over_R", "gamma_max_hat", "relaxations", "loading_states",
           "newton_iterations", "loading_s", "relaxation_s", "wall_s", "bytes", "sha256",
           "file", "reason", "version", "study", "host", "created")


def default_dir() -> Path:
    """The catalogue folder used when none is given: $SHELL_ADHESION_CATALOGUE or
    ./catalogue-data."""
    return Path(os.environ.get(ENV_VAR) or DEFAULT_DIR)


def now() -> str:
    return datetime.now(timezone.utc).isoformat(timespec="seconds")


@dataclass(frozen=True)
class Entry:
    """One trusted stored path set."""

    fingerprint: str
    delta_max_over_R: float
    gamma_max_hat: float
    file: Path
    sha256: str


@dataclass(frozen=True)
class Claim:
    """A run computing a path set now: its run id (the runs table), study, host and
    process, when it claimed the set (ISO time, UTC) and its last sign of life
    (time.time())."""

    fingerprint: str
    run: int
    study: str
    host: str
    pid: int
    claimed: str
    refreshed: float

    def stale(self, stale_s: float, now: float = None) -> bool:
        """Its owner is gone: a dead process of this host, or silent for `stale_s` s."""
        now = time.time() if now is None else now
        return ((self.host == socket.gethostname() and not alive(self.pid))
                or now - self.refreshed > stale_s)

    def __str__(self):
        return (f"run {self.run} ({self.study or 'no study'}, pid {self.pid} on {self.host}, "
                f"since {self.claimed})")


class Catalogue:
    """A catalogue folder, opened (and created unless create=False) at `directory`."""

    def __init__(self, directory=None, create: bool = True):
        self.dir = Path(directory) if directory is not None else default_dir()
        self.files = self.dir / "pathsets"
        self.parts_dir = self.dir / "parts"
        index = self.dir / INDEX
        if not create and not index.exists():
            raise FileNotFoundError(f"no catalogue at {self.dir}")
        check_index(self.dir)
        if create:
            self.files.mkdir(parents=True, exist_ok=True)
        self.db = sqlite3.connect(index, timeout=TIMEOUT_S, isolation_level=None)
        self.db.row_factory = sqlite3.Row
        if not create and self.db.execute(
                "SELECT 1 FROM sqlite_master WHERE name = 'pathsets'").fetchone() is None:
            self.db.close()         # another run is creating it: nothing is there yet
            raise FileNotFoundError(f"no catalogue at {self.dir} (its index is being created)")
        if create:
            _journal_wal(self.db)
            self.db.execute("PRAGMA synchronous=FULL")
            with self._write():
                for statement in _SCHEMA.split(";"):
                    if statement.strip():
                        self.db.execute(statement)
            clean_temporaries(self.dir)
        self.discarded = []         # reasons of entries found untrustworthy and dropped
        self.taken_over = []        # stale Claims of other runs this one took over

    def close(self):
        self.db.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @contextmanager
    def _write(self):
        """One write transaction holding the database's write lock."""
        self.db.execute("BEGIN IMMEDIATE")
        try:
            yield
        except BaseException:
            self.db.execute("ROLLBACK")
            raise
        self.db.execute("COMMIT")

    # -- path sets ---------------------------------------------------------------------

    def candidates(self, key: dict) -> list:
        """Rows with status 'ok' that may serve `key` (same family, at least as far),
        nearest first."""
        rows = self.db.execute(
            "SELECT * FROM pathsets WHERE family = ? AND status = 'ok' "
            "AND delta_max_over_R >= ? AND gamma_max_hat >= ? "
            "ORDER BY gamma_max_hat, delta_max_over_R, fingerprint",
            (family(key), key["delta_max_over_R"] * (1 - _REL_TOL),
             key["gamma_max_hat"] * (1 - _REL_TOL))).fetchall()
        exact = fingerprint(key)
        return sorted(rows, key=lambda r: r["fingerprint"] != exact)

    def fetch(self, key: dict):
        """(Entry, Dataset) of the nearest trusted stored set serving `key`, or None.

        Entries whose file fails its checksum or cannot be decoded are removed from the
        index (recorded in self.discarded) so the set is recomputed.
        """
        for row in self.candidates(key):
            for _ in range(3):      # the row may be replaced while we read
                try:
                    ds = files.read(self.dir / row["file"], row["sha256"], row["fingerprint"])
                    return self._entry(row), ds
                except files.CorruptFile as e:
                    fresh = self.db.execute(
                        "SELECT * FROM pathsets WHERE fingerprint = ?", (row["fingerprint"],)
                    ).fetchone()
                    if (fresh is not None and fresh["status"] == "ok"
                            and fresh["sha256"] != row["sha256"]):
                        row = fresh
                        continue
                    with self._write():
                        self.db.execute("DELETE FROM pathsets WHERE fingerprint = ? AND sha256 = ?",
                                        (row["fingerprint"], row["sha256"]))
                    self.discarded.append(str(e))
                    break
        return None

    def locate(self, key: dict):
        """The Entry `fetch` would serve for `key` if its file's bytes match the index
        (hashed, not decoded), else None (then `fetch` sorts it out)."""
        rows = self.candidates(key)
        if not rows or not files.matches(self.dir / rows[0]["file"], rows[0]["sha256"]):
            return None
        return self._entry(rows[0])

    def _entry(self, row) -> Entry:
        """The Entry of an index row."""
        return Entry(row["fingerprint"], row["delta_max_over_R"], row["gamma_max_hat"],
                     self.dir / row["file"], row["sha256"])

    def store(self, key: dict, ds: xr.Dataset, summary: dict = None, timings: dict = None,
              study: str = "") -> Entry:
        """Store a computed Dataset under `key` (file, then index row) and return its entry;
        its stored parts are then dropped.

        `summary`: index columns known to the caller (relaxations, loading_states,
        newton_iterations, loading_s, relaxation_s [s], and `stats`, any JSON-able dict);
        `timings`: {"wall_s": seconds from submission to completion}.
        """
        fp = fingerprint(key)
        rel = f"pathsets/{fp}.nc"
        summary = dict(summary or {})
        timings = timings or {}
        with self._write():
            sha, size = files.write(self.dir / rel, ds, fp, canonical_json(key))
            self._upsert(dict(
                fingerprint=fp, family=family(key), status="ok", file=rel, sha256=sha,
                bytes=size, relaxations=summary.get("relaxations"),
                loading_states=summary.get("loading_states"),
                newton_iterations=summary.get("newton_iterations"),
                loading_s=summary.get("loading_s"), relaxation_s=summary.get("relaxation_s"),
                wall_s=timings.get("wall_s"), reason=None,
                stats=json.dumps(summary.get("stats", {}), sort_keys=True,
                                 default=lambda o: o.item()),
                **self._common(key, study)))
        self.drop_parts(key)
        return Entry(fp, key["delta_max_over_R"], key["gamma_max_hat"], self.dir / rel, sha)

    # -- parts of a set not yet complete -----------------------------------------------

    def store_part(self, key: dict, part: str, ds: xr.Dataset, seconds: float = None):
        """Keep one finished piece `part` (a fingerprint-like name) of the set `key`."""
        owner = fingerprint(key)
        rel = f"parts/{owner}/{part}.nc"
        with self._write():     # the folder too: drop_parts removes it under the lock
            (self.dir / rel).parent.mkdir(parents=True, exist_ok=True)
            sha, size = files.write(self.dir / rel, ds, part, canonical_json(key))
            self.db.execute(
                "INSERT OR REPLACE INTO parts (owner, part, file, sha256, bytes, seconds, "
                "created) VALUES (?, ?, ?, ?, ?, ?, ?)",
                (owner, part, rel, sha, size, seconds, now()))

    def parts(self, key: dict) -> dict:
        """The trusted stored parts of the set `key`: part -> Dataset (damaged ones are
        dropped and recorded in self.discarded)."""
        owner = fingerprint(key)
        rows = self.db.execute("SELECT * FROM parts WHERE owner = ? ORDER BY part",
                               (owner,)).fetchall()
        found = {}
        for row in rows:
            try:
                found[row["part"]] = files.read(self.dir / row["file"], row["sha256"],
                                                row["part"])
            except files.CorruptFile as e:
                with self._write():
                    self.db.execute("DELETE FROM parts WHERE owner = ? AND part = ? "
                                    "AND sha256 = ?", (owner, row["part"], row["sha256"]))
                self.discarded.append(str(e))
        return found

    def count_parts(self, key: dict) -> int:
        """How many parts of the set `key` the index holds (not read)."""
        return self.db.execute("SELECT COUNT(*) FROM parts WHERE owner = ?",
                               (fingerprint(key),)).fetchone()[0]

    def drop_parts(self, key: dict):
        """Forget the parts of the set `key` (rows, then files), under the index's write
        lock: another process storing a part of the same set writes its file under that
        lock too, so none of its files is removed while it writes."""
        owner = fingerprint(key)
        folder = self.parts_dir / owner
        with self._write():
            self.db.execute("DELETE FROM parts WHERE owner = ?", (owner,))
            if folder.is_dir():
                for p in folder.iterdir():
                    p.unlink(missing_ok=True)
                try:
                    folder.rmdir()
                except OSError:
                    pass

    def timings(self, interface: str, mesh: str) -> list:
        """Recorded seconds of the stored sets of this interface and mesh: dicts with
        relaxations, loading_s, relaxation_s, wall_s, delta_max_over_R."""
        rows = self.db.execute(
            "SELECT relaxations, loading_s, relaxation_s, wall_s, delta_max_over_R "
            "FROM pathsets WHERE status = 'ok' AND interface = ? AND mesh = ? "
            "AND loading_s IS NOT NULL", (interface, mesh)).fetchall()
        return [dict(r) for r in rows]

    def record_failure(self, key: dict, reason: str, timings: dict = None, study: str = ""):
        """Record that computing `key` failed (never replaces a stored 'ok' entry)."""
        timings = timings or {}
        row = dict(fingerprint=fingerprint(key), family=family(key), status="failed",
                   reason=reason, wall_s=timings.get("wall_s"), **self._common(key, study))
        with self._write():
            old = self.db.execute("SELECT status FROM pathsets WHERE fingerprint = ?",
                                  (row["fingerprint"],)).fetchone()
            if old is None or old["status"] != "ok":
                self._upsert(row)

    def _common(self, key, study):
        return dict(t_over_R=key["t_over_R"], h_over_R=key["h_over_R"],
                    interface=key["interface"], mesh=key["mesh"],
                    delta_max_over_R=key["delta_max_over_R"], gamma_max_hat=key["gamma_max_hat"],
                    version=key.get("version"), key=canonical_json(key), study=study,
                    host=socket.gethostname(), pid=os.getpid(), created=now())

    def _upsert(self, row: dict):
        names = ", ".join(row)
        marks = ", ".join("?" for _ in row)
        self.db.execute(f"INSERT OR REPLACE INTO pathsets ({names}) VALUES ({marks})",
                        tuple(row.values()))

    def entries(self) -> list:
        """All path-set rows (dicts with COLUMNS and `solid`, the solid and cavity of the
        set's key: `solid_of`), oldest first."""
        rows = self.db.execute(
            f"SELECT {', '.join(COLUMNS)}, key FROM pathsets ORDER BY created, fingerprint"
        ).fetchall()
        return [dict({c: r[c] for c in COLUMNS}, solid=solid_of(r["key"])) for r in rows]

    # -- claims: which run computes a set now ---------------------------------------------

    def claim(self, fingerprints, run: int, study: str, stale_s: float) -> dict:
        """Claim the sets `fingerprints` for run `run` of this process, in one transaction:
        {fingerprint: Claim} of the sets another live run holds; every other one is now
        this run's.  A stale claim (Claim.stale with `stale_s`) is taken over and
        recorded in self.taken_over."""
        held, stamp = {}, time.time()
        with self._write():
            for fp in fingerprints:
                other = self.claim_of(fp)
                if other is not None and other.run != run:
                    if not other.stale(stale_s, stamp):
                        held[fp] = other
                        continue
                    self.taken_over.append(other)
                self.db.execute(
                    "INSERT OR REPLACE INTO claims (fingerprint, run, study, host, pid, "
                    "claimed, refreshed) VALUES (?, ?, ?, ?, ?, ?, ?)",
                    (fp, run, study, socket.gethostname(), os.getpid(), now(), stamp))
        return held

    def claim_of(self, fp: str):
        """The Claim on the set `fp`, or None."""
        row = self.db.execute("SELECT * FROM claims WHERE fingerprint = ?", (fp,)).fetchone()
        return None if row is None else Claim(**dict(row))

    def refresh_claims(self, run: int):
        """A sign of life for every claim of run `run`."""
        with self._write():
            self.db.execute("UPDATE claims SET refreshed = ? WHERE run = ?", (time.time(), run))

    def release_claims(self, run: int, fingerprints=None):
        """Delete the claims of run `run` (only those on `fingerprints` if given)."""
        with self._write():
            if fingerprints is None:
                self.db.execute("DELETE FROM claims WHERE run = ?", (run,))
            else:
                self.db.executemany("DELETE FROM claims WHERE run = ? AND fingerprint = ?",
                                    [(run, fp) for fp in fingerprints])

    def failure_by(self, claim: Claim):
        """The reason the set of `claim` failed, if its owner recorded a failure since it
        claimed the set; else None."""
        row = self.db.execute(
            "SELECT reason FROM pathsets WHERE fingerprint = ? AND status = 'failed' "
            "AND host = ? AND pid = ? AND created >= ?",
            (claim.fingerprint, claim.host, claim.pid, claim.claimed)).fetchone()
        return None if row is None else row["reason"]

    # -- runs --------------------------------------------------------------------------

    def start_run(self, study: str, study_file, study_sha256: str, output, version: str) -> int:
        with self._write():
            cur = self.db.execute(
                "INSERT INTO runs (study, study_file, study_sha256, output, started, host, pid, "
                "version) VALUES (?, ?, ?, ?, ?, ?, ?, ?)",
                (study, str(study_file), study_sha256, str(output), now(), socket.gethostname(),
                 os.getpid(), version))
            return cur.lastrowid

    def finish_run(self, run_id: int, exit_code: int, computed: int, reused: int, failed: int,
                   wall_s: float):
        with self._write():
            self.db.execute(
                "UPDATE runs SET finished = ?, exit_code = ?, computed = ?, reused = ?, "
                "failed = ?, wall_s = ? WHERE id = ?",
                (now(), exit_code, computed, reused, failed, wall_s, run_id))

    def runs(self) -> list:
        return [dict(r) for r in self.db.execute("SELECT * FROM runs ORDER BY id").fetchall()]


def list_entries(catalogue_dir=None) -> list:
    """Rows of the catalogue's path sets (dicts keyed by COLUMNS), oldest first.

    An absent catalogue has no entries (and is not created).
    """
    directory = Path(catalogue_dir) if catalogue_dir is not None else default_dir()
    if not (directory / INDEX).exists():
        return []
    with Catalogue(directory, create=False) as cat:
        return cat.entries()


def solid_of(key_json) -> str:
    """The solid (and closed cavity) a set's key names, in a few characters: 'neo_hooke'
    (the default), else the model with its non-zero ratios to C10; ', sealed' or
    ', pressure p=...' (p / C10) for a closed cavity; ', dugdale lambda=... gamma/(C10
    R)=...' for a cohesive answer."""
    key = json.loads(key_json) if isinstance(key_json, str) else (key_json or {})
    material = key.get("material") or {}
    text = material.get("model", "neo_hooke")
    ratios = [f"{name.replace('_over_C10', '/C10').replace('_times_C10', 'C10')}={value:g}"
              for name, value in material.items()
              if name != "model" and isinstance(value, (int, float)) and value]
    if ratios:
        text += " " + ",".join(ratios)
    cavity = key.get("cavity")
    if cavity:
        text += f", {cavity['mode']}" + (f" p={cavity['p']:g}" if cavity.get("p") else "")
    if key.get("tabor") is not None:        # a cohesive answer (study.cohesive_study)
        text += f", dugdale lambda={key['tabor']:g} gamma/(C10 R)={key['gamma_hat']:.3g}"
    return text


def format_entries(rows) -> str:
    """A plain-text table of list_entries() rows, one line per path set: `FE s` is the
    set's own computing time (its loading and relaxation tasks), `solid` what its key
    names beyond the shape (solid_of)."""
    head = (f"{'fingerprint':<12}  {'status':<6}  {'t/R':>6}  {'h/R':>6}  {'interface':<12}  "
            f"{'mesh':<7}  {'dmax/R':>6}  {'gmax':>7}  {'paths':>5}  {'FE s':>7}  "
            f"{'solid':<22}  created")
    lines = [head]
    for r in rows:
        seconds = [r[c] for c in ("loading_s", "relaxation_s") if r.get(c) is not None]
        fe = f"{sum(seconds):.1f}" if seconds else "-"
        paths = r["relaxations"] if r["relaxations"] is not None else "-"
        line = (f"{r['fingerprint'][:12]:<12}  {r['status']:<6}  {r['t_over_R']:>6g}  "
                f"{r['h_over_R']:>6g}  {r['interface']:<12}  {r['mesh']:<7}  "
                f"{r['delta_max_over_R']:>6g}  {r['gamma_max_hat']:>7g}  {paths:>5}  {fe:>7}  "
                f"{r.get('solid', ''):<22}  {r['created']}")
        if r["status"] != "ok" and r["reason"]:
            line += f"  ({r['reason']})"
        lines.append(line)
    return "\n".join(lines)


# -- the index's health, and rebuilding it from the stored files ---------------------------

class CorruptIndex(ValueError):
    """The index file of a catalogue folder is not a readable catalogue index."""


def _journal_wal(db) -> None:
    """Put the index in WAL mode.  Another run creating the index at the same moment holds
    the lock this needs, and SQLite's busy timeout does not wait for it ("database is
    locked" at once): retried every 50 ms, for at most TIMEOUT_S."""
    deadline = time.monotonic() + TIMEOUT_S
    while True:
        try:
            db.execute("PRAGMA journal_mode=WAL")
            return
        except sqlite3.OperationalError as e:
            if "locked" not in str(e) or time.monotonic() > deadline:
                raise
            time.sleep(0.05)


def check_index(directory) -> None:
    """Raise CorruptIndex unless `directory`'s index is absent or a sound SQLite catalogue
    index.  Reads the file as it is on disk (immutable, read-only): creates nothing."""
    index = Path(directory) / INDEX
    if not index.exists():
        return
    try:
        db = sqlite3.connect(index.resolve().as_uri() + "?mode=ro&immutable=1", uri=True)
        try:
            check = db.execute("PRAGMA quick_check").fetchone()[0]
            tables = {r[0] for r in db.execute("SELECT name FROM sqlite_master "
                                                "WHERE type = 'table'")}
        finally:
            db.close()
    except sqlite3.Error as e:
        check, tables = str(e), set()
    if check == "ok" and tables and "pathsets" not in tables:
        check = "it has no pathsets table"
    if check != "ok":
        raise CorruptIndex(f"{index}: not a catalogue index ({check})")


def rebuild_index(directory) -> tuple:
    """Rebuild the index of `directory` from its stored files: (rows made, [reasons of the
    files left out]).  The old index, if any, is kept beside as index.sqlite.old-<time>
    (the record of past runs is not in the files and stays there).  Not while a study
    writes to the folder."""
    import netCDF4
    import hashlib

    directory = Path(directory)
    stamp = datetime.now(timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    for suffix in ("", "-wal", "-shm"):
        old = directory / (INDEX + suffix)
        if old.exists():
            old.rename(directory / f"{INDEX}.old-{stamp}{suffix}")
    made, skipped = 0, []
    with Catalogue(directory) as cat:
        for path in sorted(cat.files.glob("*.nc")):
            data = path.read_bytes()
            try:
                with netCDF4.Dataset("stored.nc", mode="r", memory=data) as nc:
                    attrs = {k: nc.getncattr(k) for k in nc.ncattrs()}
                    sizes = {k: len(v) for k, v in nc.dimensions.items()}
                    for v in nc.variables.values():
                        v[...]          # every value decodes
                key = json.loads(attrs["key"])
                fp = attrs["fingerprint"]
            except Exception as e:      # any decoding failure: the file cannot be trusted
                skipped.append(f"{path.name}: cannot be read ({type(e).__name__})")
                continue
            if not (fp == path.stem == fingerprint(key)):
                skipped.append(f"{path.name}: its name, fingerprint and key do not agree")
                continue
            stats = json.loads(attrs.get("stats", "{}"))
            with cat._write():
                cat._upsert(dict(
                    fingerprint=fp, family=family(key), status="ok",
                    file=f"{cat.files.name}/{path.name}",
                    sha256=hashlib.sha256(data).hexdigest(), bytes=len(data),
                    relaxations=sizes.get("relaxation"), loading_states=sizes.get("loading_state"),
                    loading_s=stats.get("loading_s"), relaxation_s=stats.get("relaxation_s"),
                    stats=json.dumps(stats, sort_keys=True), reason=None,
                    **cat._common(key, "rebuilt from the stored file")))
            made += 1
    return made, skipped
