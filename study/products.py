"""What a run hands back besides the cube: tables, the analysis summary and the figures,
all read from the results netCDF (never from the solver).

    results/<name>.nc               the cube (study.dataset)
    results/<name>_tables/          cases.{csv,md,tex}, paper.{csv,md,tex}, analysis.txt
    results/<name>_figures/         fig2 ... fig6b as PNG and PDF (study.figures)

Every file is written atomically: a reader sees the old file or the complete new one.
"""
from contextlib import contextmanager
from dataclasses import dataclass, field
import os
from pathlib import Path
import tempfile
import time

import xarray as xr

TABLE_FORMATS = ("csv", "md", "tex")


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


@contextmanager
def atomic_path(path):
    """A temporary path in the folder of `path` to write to; on success it replaces
    `path` (mode rw-r--r-- less the umask), on failure it is removed."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    os.close(fd)
    try:
        yield tmp
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def write_text_atomic(path, text: str) -> Path:
    """Write `text` to `path` atomically (see `atomic_path`)."""
    with atomic_path(path) as tmp:
        with open(tmp, "w", encoding="utf-8", newline="") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
    return Path(path)


@dataclass
class Products:
    """Files written from one cube, what was skipped and why, and the time split (s)."""

    tables: list = field(default_factory=list)
    figures: list = field(default_factory=list)
    skipped: dict = field(default_factory=dict)
    seconds: dict = field(default_factory=dict)


def write_tables(ds: xr.Dataset, out_dir) -> list:
    """The cases and paper tables in every format, and the analysis summary."""
    from .analysis import summary
    from .tables import cases_table, comparison_table, render
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name, make in (("cases", cases_table), ("paper", comparison_table)):
        table = make(ds)
        for fmt in TABLE_FORMATS:
            written.append(write_text_atomic(out / f"{name}.{fmt}", render(table, fmt)))
    written.append(write_text_atomic(out / "analysis.txt", summary(ds) + "\n"))
    return written


def write_products(results_nc, formats=("png", "pdf")) -> Products:
    """Tables and figures of the cube at `results_nc`, beside it."""
    from .figures import write_figures
    path = Path(results_nc)
    stem = path.with_suffix("")
    p = Products()
    t0 = time.perf_counter()
    with xr.open_dataset(path) as ds:
        ds = ds.load()
    t1 = time.perf_counter()
    p.tables = write_tables(ds, f"{stem}_tables")
    t2 = time.perf_counter()
    p.figures, p.skipped = write_figures(ds, f"{stem}_figures", formats)
    t3 = time.perf_counter()
    p.seconds = dict(read=t1 - t0, tables=t2 - t1, figures=t3 - t2, total=t3 - t0)
    return p
