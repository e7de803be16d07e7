"""Atomic file writes: a reader sees the old file or the complete new one, never a part.

The data go to a temporary file `<name>.tmp<random>` in the target's folder, are fsynced,
get ordinary permissions (rw-r--r-- less the umask; mkstemp makes files private) and
replace the target with os.replace; the folder is then fsynced.  After a crash at most a
`<name>.tmp*` file is left behind.
"""
from contextlib import contextmanager
import os
from pathlib import Path
import tempfile


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


@contextmanager
def atomic_path(path):
    """A temporary path to write `path`'s new content to; on leaving the block without
    an error it replaces `path`, otherwise it is removed."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".tmp", dir=path.parent)
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


def write_text_atomic(path, text: str) -> Path:
    """Write `text` (UTF-8) to `path` atomically."""
    with atomic_path(path) as tmp:
        Path(tmp).write_text(text, encoding="utf-8", newline="")
    return Path(path)
