"""What a run hands back besides the cube: tables, the analysis summary and the figures,
all read from the results netCDF (never from the solver).

    results/<name>.nc               the cube (study.dataset)
    results/<name>_tables/          cases.{csv,md,tex}, paper.{csv,md,tex}, analysis.txt
    results/<name>_figures/         fig2 ... fig6b as PNG (analysis.figures; PDF on request)
    results/<name>_products.json    digests of the cube's content and file, and the files
                                    written from it

Every file is written atomically (shell_adhesion.atomic).  A run whose cube has the content of
the one already there, with every file the manifest lists present, rewrites nothing.  A run
keeps the drawn files in the catalogue under `products_key` (the cube's content, the drawing
code, the formats; study.run): a cube of the same content elsewhere gets copies of them.
"""
from dataclasses import dataclass, field
import hashlib
import json
from pathlib import Path
import time

import xarray as xr

from shell_adhesion import __version__
from shell_adhesion.atomic import write_text_atomic

from .slices import base_cavity, base_material
from .summary import summary
from .tables import FORMATS, cases_table, comparison_table, render

RUN_FORMATS = ("png",)      # what `shell-adhesion run` draws; PDF on request (`plot --format`)
# the code that draws the products: a change in it draws them again
DRAWING_SOURCES = ("analysis/*.py", "cube.py", "energy.py", "theory.py")


def tables_dir(results_nc) -> Path:
    """results/<name>_tables for results/<name>.nc."""
    path = Path(results_nc)
    return path.with_name(f"{path.stem}_tables")


def figures_dir(results_nc) -> Path:
    """results/<name>_figures for results/<name>.nc."""
    path = Path(results_nc)
    return path.with_name(f"{path.stem}_figures")


@dataclass
class Products:
    """Files written from one cube, what was skipped and why, and the time split (s)."""

    tables: list = field(default_factory=list)
    figures: list = field(default_factory=list)
    skipped: dict = field(default_factory=dict)
    seconds: dict = field(default_factory=dict)
    kept: bool = False      # the files of an earlier run of the same cube, not rewritten
    copied: bool = False    # copied from the catalogue (drawn before from the same content)


def manifest_path(results_nc) -> Path:
    """results/<name>_products.json for results/<name>.nc."""
    path = Path(results_nc)
    return path.with_name(f"{path.stem}_products.json")


def _file_sha256(path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def record_products(results_nc, digest: str, products: Products, inputs: str = None) -> Path:
    """Write the manifest: the digests of the cube's content (study.dataset.content_sha256),
    of its file and of what it was built from (study.dataset.inputs_sha256, if known), and
    the products written from it."""
    text = json.dumps({"content_sha256": digest, "inputs_sha256": inputs,
                       "cube_sha256": _file_sha256(results_nc),
                       "tables": [str(p) for p in products.tables],
                       "figures": [str(p) for p in products.figures],
                       "skipped": products.skipped}, indent=1)
    return write_text_atomic(manifest_path(results_nc), text + "\n")


def recorded_inputs(results_nc):
    """The inputs digest (study.dataset.inputs_sha256) the manifest of `results_nc` records,
    or None."""
    try:
        return json.loads(manifest_path(results_nc).read_text()).get("inputs_sha256")
    except (OSError, ValueError, AttributeError):
        return None


def kept_products(results_nc, digest: str, key: str = "content_sha256"):
    """The products of an earlier run whose cube had content `digest` (Products with
    kept=True), if its manifest says so, the cube at `results_nc` is the file it was
    written for and every listed file exists; else None.  With key="inputs_sha256",
    `digest` is that of the cube's inputs (study.dataset.inputs_sha256) instead."""
    try:
        record = json.loads(manifest_path(results_nc).read_text())
        if digest is None or record.get(key) != digest:
            return None
        if record.get("cube_sha256") != _file_sha256(results_nc):
            return None
    except (OSError, ValueError, AttributeError):
        return None
    tables, figures = ([Path(f) for f in record.get(k, [])] for k in ("tables", "figures"))
    if not all(f.is_file() for f in tables + figures):
        return None
    return Products(tables, figures, dict(record.get("skipped", {})), kept=True)


def write_tables(ds: xr.Dataset, out_dir) -> list:
    """The cases and paper tables in every format, and the analysis summary."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    base = base_material(base_cavity(ds))
    for name, make, cube in (("cases", cases_table, ds), ("paper", comparison_table, base)):
        if name == "paper" and "cavity_mode" in ds.attrs:
            continue        # the paper's values are of an open shell
        table = make(cube)
        for fmt in FORMATS:
            written.append(write_text_atomic(out / f"{name}.{fmt}", render(table, fmt)))
    written.append(write_text_atomic(out / "analysis.txt", summary(base) + "\n"))
    return written


def write_products(results_nc, formats=RUN_FORMATS) -> Products:
    """Tables and figures of the cube at `results_nc`, beside it (figures as PNG; other
    formats on request, e.g. formats=("png", "pdf"))."""
    path = Path(results_nc)
    p = Products()
    t0 = time.perf_counter()
    with xr.open_dataset(path) as ds:
        ds = ds.load()
    t1 = time.perf_counter()
    p.tables = write_tables(ds, tables_dir(path))
    t2 = time.perf_counter()
    from .figures import write_figures      # matplotlib only when drawing (about 0.5 s)
    p.figures, p.skipped = write_figures(base_cavity(ds), figures_dir(path), formats)
    t3 = time.perf_counter()
    p.seconds = dict(read=t1 - t0, tables=t2 - t1, figures=t3 - t2, total=t3 - t0)
    return p


def products_key(digest: str, formats=RUN_FORMATS) -> str:
    """The catalogue key of the products of a cube of content `digest`
    (study.dataset.content_sha256) in `formats`: with this package's version, the source
    of the code that draws them (DRAWING_SOURCES) and matplotlib's version."""
    from importlib.metadata import version
    root = Path(__file__).resolve().parent.parent
    h = hashlib.sha256(repr((digest, tuple(formats), __version__,
                             version("matplotlib"))).encode())
    for pattern in DRAWING_SOURCES:
        for p in sorted(root.glob(pattern)):
            h.update(str(p.relative_to(root)).encode() + b"\0" + p.read_bytes() + b"\0")
    return h.hexdigest()
