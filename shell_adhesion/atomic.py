"""Atomic file writes: a reader sees the old file or the complete new one, never a part.

The data go to a temporary file `<name>.tmp-<host>-<pid>-<random>` in the target's folder,
are fsynced, get ordinary permissions (rw-r--r-- less the umask; mkstemp makes files
private) and replace the target with os.replace; the folder is then fsynced.  After a
crash at most such a temporary file is left behind; `clean_temporaries` removes those of
writers that are gone.
"""
from contextlib import contextmanager
import os
from pathlib import Path
import socket
import tempfile
import time

STALE_S = 3600.0        # a temporary file of another host is left alone this long


def fsync_dir(directory):
    fd = os.open(directory, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _host() -> str:
    return socket.gethostname().replace("-", "_")


@contextmanager
def atomic_path(path):
    """A temporary path to write `path`'s new content to; on leaving the block without
    an error it replaces `path`, otherwise it is removed."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f"{path.name}.tmp-{_host()}-{os.getpid()}-",
                               dir=path.parent)
    os.close(fd)
    try:
        yield tmp
        fd = os.open(tmp, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    fsync_dir(path.parent)


def alive(pid: int) -> bool:
    """A process `pid` of this host exists (one of another user counts)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _orphan(p: Path) -> bool:
    """A temporary file whose writer is gone: a dead process of this host, else older
    than STALE_S."""
    parts = p.name.rsplit(".tmp-", 1)[-1].split("-")
    if len(parts) >= 3 and parts[0] == _host() and parts[1].isdigit():
        return int(parts[1]) != os.getpid() and not alive(int(parts[1]))
    return time.time() - p.stat().st_mtime > STALE_S


def clean_temporaries(folder) -> int:
    """Remove the temporary files of writers that are gone below `folder`; returns how
    many were removed."""
    removed = 0
    for p in Path(folder).rglob("*.tmp*"):
        try:
            if p.is_file() and _orphan(p):
                p.unlink()
                removed += 1
        except OSError:
            pass
    return removed


def write_text_atomic(path, text: str) -> Path:
    """Write `text` (UTF-8) to `path` atomically."""
    with atomic_path(path) as tmp:
        Path(tmp).write_text(text, encoding="utf-8", newline="")
    return Path(path)
