"""Stored study results: cubes and the files drawn from them, kept so that a run into a new
folder copies what an earlier run made from the same data instead of building it again.

    <dir>/cubes/<inputs>.nc              a cube, named by the digest of all it is built
    <dir>/cubes/<inputs>.json            from (study.dataset.inputs_sha256): its file's
                                         sha256 and its content digest
    <dir>/products/<key>/<group>/<name>  tables and figures of one cube content, `key` the
    <dir>/products/<key>/manifest.json   caller's digest of that content and of the code
                                         that draws them; the manifest lists each file's
                                         sha256 and what was skipped

Trust rule (as for path sets): a stored file is served only if its manifest is there and
its bytes match the sha256 the manifest records; files are written first (atomically) and
the manifest last, so a run killed while storing leaves nothing that is served.  Anything
else (missing, truncated, altered) is ignored and made again.  Nothing here knows what a
cube or a figure holds.
"""
import hashlib
import json
from pathlib import Path

from shell_adhesion.atomic import atomic_path, write_text_atomic

CUBES = "cubes"
PRODUCTS = "products"
MANIFEST = "manifest.json"


def _sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def write_bytes_atomic(path, data: bytes) -> Path:
    """Write `data` to `path` atomically (shell_adhesion.atomic), its folder made if needed."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_path(path) as tmp:
        Path(tmp).write_bytes(data)
    return path


def _record(path) -> dict:
    try:
        record = json.loads(Path(path).read_text())
    except (OSError, ValueError):
        return None
    return record if isinstance(record, dict) else None


def fetch_cube(directory, inputs: str):
    """(bytes of the cube stored for `inputs`, its content digest), verified against its
    record; None if absent or not to be trusted."""
    if not inputs:
        return None
    base = Path(directory) / CUBES
    record = _record(base / f"{inputs}.json")
    if record is None:
        return None
    try:
        data = (base / f"{inputs}.nc").read_bytes()
    except OSError:
        return None
    if _sha256(data) != record.get("sha256") or not record.get("content_sha256"):
        return None
    return data, record["content_sha256"]


def store_cube(directory, inputs: str, cube_path, content_sha256: str) -> None:
    """Keep the cube file at `cube_path` (content digest `content_sha256`) under `inputs`."""
    base = Path(directory) / CUBES
    data = Path(cube_path).read_bytes()
    write_bytes_atomic(base / f"{inputs}.nc", data)
    write_text_atomic(base / f"{inputs}.json", json.dumps(
        {"sha256": _sha256(data), "content_sha256": content_sha256}, indent=1) + "\n")


def fetch_products(directory, key: str):
    """({"group/name": bytes}, skipped) of the products stored under `key`, every file
    verified against the manifest; None if absent or any file is not to be trusted."""
    base = Path(directory) / PRODUCTS / key
    record = _record(base / MANIFEST)
    if record is None or not isinstance(record.get("files"), dict):
        return None
    found = {}
    for rel, sha in record["files"].items():
        path = base / rel
        if Path(rel).is_absolute() or ".." in Path(rel).parts:
            return None
        try:
            data = path.read_bytes()
        except OSError:
            return None
        if _sha256(data) != sha:
            return None
        found[rel] = data
    return found, dict(record.get("skipped", {}))


def store_products(directory, key: str, files: dict, skipped: dict) -> None:
    """Keep `files` ({"group/name": path of a file written}) and `skipped` ({what: why})
    under `key`: the files first, the manifest last."""
    base = Path(directory) / PRODUCTS / key
    digests = {}
    for rel, path in files.items():
        data = Path(path).read_bytes()
        write_bytes_atomic(base / rel, data)
        digests[rel] = _sha256(data)
    write_text_atomic(base / MANIFEST, json.dumps(
        {"files": digests, "skipped": skipped}, indent=1, sort_keys=True) + "\n")
