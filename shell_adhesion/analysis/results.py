"""Reading a results cube: open and check the file, the study's base point, and the values
along a sweep, at a point or over the evaluated cases.

Reads a Dataset written by `study.dataset` (its names are in `shell_adhesion.cube`) and
never runs the finite-element solver.  Units as in the cube: lengths mm, forces N, C10 MPa,
gamma J/m^2.
"""
import math
from pathlib import Path

import numpy as np
import xarray as xr

from shell_adhesion.cube import DIMS, base_attr
from shell_adhesion.errors import InputError

_REQUIRED = ("P_star", "status", "eta")


class NotACube(InputError):
    """A file that cannot be read as a shell-adhesion results cube (bad input: exit 2)."""


def open_results(path) -> xr.Dataset:
    """The results cube at `path`, loaded into memory; NotACube names the file otherwise."""
    path = Path(path)
    if not path.is_file():
        raise NotACube(f"{path}: " + ("not a file" if path.exists() else "no such file"))
    try:
        with xr.open_dataset(path) as ds:
            ds = ds.load()
    except Exception as e:        # netCDF4, h5netcdf and the engine guess raise many kinds
        raise NotACube(f"{path}: cannot be read as netCDF ({type(e).__name__})") from None
    try:
        check_cube(ds)
    except NotACube as e:
        raise NotACube(f"{path}: {e}") from None
    return ds


def check_cube(ds: xr.Dataset) -> None:
    """Raise NotACube unless `ds` has the cube's dimensions, variables and study record
    (R_mm and the base values as numbers)."""
    if ds.attrs.get("adhesion") == "dugdale":
        raise NotACube("a cohesive (adhesion: dugdale) study's cube: the tables and analysis "
                       "are for the energy method's cubes; `run` wrote its table and figures "
                       "beside it, and xarray reads it (docs/studies.md, finite-range "
                       "adhesion)")
    missing = [d for d in DIMS if d not in ds.dims] + [v for v in _REQUIRED if v not in ds]
    if missing:
        raise NotACube("not a shell-adhesion results cube (missing " + ", ".join(missing) + ")")
    try:
        [float(ds.attrs[a]) for a in ("R_mm", *(base_attr(d) for d in DIMS
                                               if base_attr(d) in ds.attrs))]
    except (KeyError, TypeError, ValueError):
        raise NotACube("not a shell-adhesion results cube (no study record: R_mm and "
                       "base_* attributes)") from None


def base_point(ds: xr.Dataset) -> dict:
    """The study's base values by dimension name: C10 [MPa], t_over_R, h_over_R, gamma [J/m^2].

    A factor the study's base leaves out (a grid-only factor) takes the middle value of
    its axis."""
    return {d: float(ds.attrs[base_attr(d)]) if base_attr(d) in ds.attrs
            else float(ds[d].values[(ds.sizes[d] - 1) // 2]) for d in DIMS}


def R_mm(ds: xr.Dataset) -> float:
    """Outer radius of curvature R of the study, mm."""
    return float(ds["R"]) if "R" in ds.coords else float(ds.attrs["R_mm"])


def select(x, **at):
    """`x` at the given coordinate values (nearest within a relative 1e-9)."""
    for d, v in at.items():
        x = x.sel({d: v}, method="nearest", tolerance=1e-9 * max(1.0, abs(v)))
    return x


def along(ds: xr.Dataset, var: str, dim: str, **at) -> xr.DataArray:
    """`var` along `dim` with the other dimensions at the base point (or at `at`), keeping
    only points with status "ok" and a finite value."""
    point = {**base_point(ds), **at}
    point.pop(dim)
    sel = {d: v for d, v in point.items() if d in ds[var].dims}
    x = select(ds[var].where(ds["status"] == "ok"), **sel)
    return x.dropna(dim)


def value_at(ds, var, **at):
    """A pull-off value at a point (the base completed by `at`); NaN unless status ok."""
    point = {**base_point(ds), **at}
    try:
        x = select(ds[var].where(ds["status"] == "ok"), **point)
    except KeyError:
        return math.nan
    return float(x)


def ok_cases(ds: xr.Dataset, where=None) -> xr.Dataset:
    """The points with status "ok" (and `where`, a boolean DataArray over the cube's
    dimensions, if given) as one Dataset along ``case``, labelled by C10, t_over_R,
    h_over_R, gamma, t_mm and h_mm; only variables on exactly the cube's dimensions."""
    dims = ds["status"].dims        # DIMS, and any swept material ratio (C01_over_C10, ...)
    names = [v for v in ds.data_vars if set(ds[v].dims) == set(dims)]
    mask = ds["status"] == "ok"
    if where is not None:
        mask = mask & where
    flat = ds[names].stack(case=dims)
    keep = np.flatnonzero(mask.broadcast_like(ds["status"]).stack(case=dims).values)
    return flat.isel(case=keep).reset_index("case")
