"""One stored path set as a netCDF file (the only module that knows this file layout).

Dimensionless, as the solver computes it: lengths / R, forces / (C10 R^2), energies /
(C10 R^3).  Loading states along `loading_state`; the relaxation paths are one CF
contiguous ragged array: path k holds `relaxation_length[k]` consecutive samples of
`relaxation_state`, delta decreasing from its loaded state.  The views kept for figures:
deformed profiles along `profile` (outer and inner surface nodes), and stress maps along
`stress_map` (deformed nodes, nodal von Mises / C10) over one triangulation.

Files are written atomically (catalogue.atomic) and read from one in-memory copy, so the bytes checked against the
index's sha256 are the bytes decoded.
"""
from dataclasses import fields
import hashlib
import json
from pathlib import Path

import netCDF4
import numpy as np
import xarray as xr

from shell_adhesion.solver.case import PathSet, Relaxation
from shell_adhesion.solver.postprocess import Profile, StressMap

from .atomic import atomic_path
from .fingerprint import LAYOUT, canonical_json


class CorruptFile(Exception):
    """A stored file is missing, truncated, altered or not the expected path set."""


# descriptions of known fields; a field the solver adds later is stored all the same
_LONG_NAMES = {
    "loading_delta": "rim displacement delta / R (approach > 0)",
    "loading_P": "rim force P / (C10 R^2) (compression > 0)",
    "loading_a": "contact radius a / R",
    "loading_U": "strain energy U / (C10 R^3)",
    "loading_joined": "outer node joining the contact in this state (-1: none)",
    "relaxation_a": "held contact radius a / R of the path",
    "relaxation_delta": "rim displacement delta / R",
    "relaxation_P": "rim force P / (C10 R^2)",
    "relaxation_U": "strain energy U / (C10 R^3)",
    "relaxation_dP_ddelta": "stiffness dP/d(delta) / (C10 R)",
    "relaxation_ended_by": "why the path ended",
    "relaxation_penetration": "a node outside the held zone touched the plane (0/1)",
    "relaxation_centre_lifts": "the plane pulled the centre down (0/1)",
    "relaxation_newton_iterations": "Newton iterations of the path",
    "profile_stage": "loading, or relaxation at the fixed contact radius profile_a",
    "profile_a": "contact radius a / R of the state",
    "profile_delta": "rim displacement delta / R of the state",
    "profile_P": "rim force P / (C10 R^2) of the state",
    "profile_outer_r": "deformed r / R of the outer-surface nodes, from the axis",
    "profile_outer_z": "deformed z / R of the outer-surface nodes (plane at z = 0)",
    "profile_inner_r": "deformed r / R of the inner-surface nodes, from the axis",
    "profile_inner_z": "deformed z / R of the inner-surface nodes",
    "map_stage": "loading, or relaxation at the fixed contact radius map_a",
    "map_a": "contact radius a / R of the state",
    "map_delta": "rim displacement delta / R of the state",
    "map_P": "rim force P / (C10 R^2) of the state",
    "map_r": "deformed r / R of every node",
    "map_z": "deformed z / R of every node",
    "map_von_mises": "von Mises stress / C10 at the nodes (mean over the elements holding each)",
    "map_triangles": "node indices of the triangles (8 per Q2 element)",
}
_VIEW_SCALARS = ("stage", "a", "delta", "P")
_ATTRS = {"t": "t_over_R", "h": "h_over_R", "interface": "interface", "mesh": "mesh",
          "delta_max": "delta_max_over_R", "gamma_max": "gamma_max_hat"}


def _stored(cls):
    """The fields stored as columns (views have their own variables)."""
    return [f for f in fields(cls) if f.name != "views"]


def _is_array(f) -> bool:
    return f.type in (np.ndarray, "np.ndarray")


def _var(name, dims, data, **attrs):
    return (dims, data, dict(units="1", long_name=_LONG_NAMES.get(name, name), **attrs))


def _column(values, kind):
    """Per-path scalars as a netCDF-able array (bools as int8, strings as text)."""
    if kind in (bool, "bool"):
        return np.array(values, dtype=np.int8)
    if kind in (str, "str"):
        return np.array(values, dtype=object)
    if kind in (int, "int"):
        return np.array(values, dtype=np.int64)
    return np.array(values, dtype=float)


def to_dataset(ps: PathSet, key: dict, fp: str) -> xr.Dataset:
    """The path set as an xarray Dataset in the stored layout."""
    rel = ps.relaxations
    data = {}
    for f in fields(PathSet):
        if _is_array(f):
            data[f.name] = _var(f.name, "loading_state", np.asarray(getattr(ps, f.name)))
    for f in _stored(Relaxation):
        name = f"relaxation_{f.name}"
        if _is_array(f):
            values = [np.asarray(getattr(r, f.name)) for r in rel]
            data[name] = _var(name, "relaxation_state",
                              np.concatenate(values) if rel else np.zeros(0))
        else:
            column = _column([getattr(r, f.name) for r in rel], f.type)
            data[name] = _var(name, "relaxation", column)
    data["relaxation_length"] = _var(
        "relaxation_length", "relaxation", np.array([len(r.delta) for r in rel], dtype=np.int64),
        sample_dimension="relaxation_state")
    data["relaxation_length"][2]["long_name"] = "samples of the path along relaxation_state"
    data.update(_views_data(ps.views))
    attrs = dict(
        title="shell-adhesion FE path set (dimensionless: lengths / R, forces / (C10 R^2), "
              "energies / (C10 R^3))",
        Conventions="CF-1.8", layout=LAYOUT, fingerprint=fp, key=canonical_json(key),
        stats=json.dumps(ps.stats, sort_keys=True, default=lambda o: o.item()),
        **{a: getattr(ps, f) for f, a in _ATTRS.items()})
    return xr.Dataset(data, attrs=attrs)


def from_dataset(ds: xr.Dataset) -> PathSet:
    """The PathSet stored in `ds` (the inverse of to_dataset)."""
    lengths = ds["relaxation_length"].values
    ends = np.cumsum(lengths)
    starts = ends - lengths
    rel = []
    for k, (s, e) in enumerate(zip(starts, ends)):
        kw = {}
        for f in _stored(Relaxation):
            v = ds[f"relaxation_{f.name}"].values
            if _is_array(f):
                kw[f.name] = v[s:e]
            else:
                kind = {"bool": bool, "str": str, "int": int, "float": float}.get(f.type, f.type)
                kw[f.name] = kind(v[k])
        rel.append(Relaxation(**kw))
    kw = {f: ds.attrs[a] for f, a in _ATTRS.items()}
    kw = {f: (str(v) if f in ("interface", "mesh") else float(v)) for f, v in kw.items()}
    for f in fields(PathSet):
        if _is_array(f):
            kw[f.name] = ds[f.name].values
    return PathSet(relaxations=tuple(rel), stats=json.loads(ds.attrs["stats"]),
                   views=_views_of(ds), **kw)


def _views_data(views) -> dict:
    profiles = [v for v in views if isinstance(v, Profile)]
    maps = [v for v in views if isinstance(v, StressMap)]
    data = {}
    for kind, items, dim in (("profile", profiles, "profile"), ("map", maps, "stress_map")):
        for k in _VIEW_SCALARS:
            column = [getattr(v, k) for v in items]
            data[f"{kind}_{k}"] = _var(f"{kind}_{k}", dim, np.array(
                column, dtype=object if k == "stage" else float))
    for side in ("outer", "inner"):
        for i, c in enumerate("rz"):
            name = f"profile_{side}_{c}"
            width = getattr(profiles[0], side).shape[1] if profiles else 0
            arr = np.array([getattr(p, side)[i] for p in profiles]).reshape(len(profiles), width)
            data[name] = _var(name, ("profile", f"{side}_node"), arr)
    n = maps[0].nodes.shape[1] if maps else 0
    for name, of in (("map_r", lambda m: m.nodes[0]), ("map_z", lambda m: m.nodes[1]),
                     ("map_von_mises", lambda m: m.von_mises)):
        data[name] = _var(name, ("stress_map", "node"),
                          np.array([of(m) for m in maps]).reshape(len(maps), n))
    tri = maps[0].triangles if maps else np.zeros((0, 3), dtype=np.int64)
    if any(not np.array_equal(m.triangles, tri) for m in maps):
        raise ValueError("the stress maps of a path set must share one triangulation")
    data["map_triangles"] = _var("map_triangles", ("triangle", "vertex"), tri.astype(np.int64))
    return data


def _views_of(ds: xr.Dataset) -> tuple:
    if "profile_stage" not in ds:
        return ()
    views = []
    for j in range(ds.sizes.get("profile", 0)):
        sc = [ds[f"profile_{k}"].values[j] for k in _VIEW_SCALARS]
        views.append(Profile(str(sc[0]), *map(float, sc[1:]),
                             np.stack([ds["profile_outer_r"].values[j], ds["profile_outer_z"].values[j]]),
                             np.stack([ds["profile_inner_r"].values[j], ds["profile_inner_z"].values[j]])))
    tri = ds["map_triangles"].values
    for j in range(ds.sizes.get("stress_map", 0)):
        sc = [ds[f"map_{k}"].values[j] for k in _VIEW_SCALARS]
        views.append(StressMap(str(sc[0]), *map(float, sc[1:]),
                               np.stack([ds["map_r"].values[j], ds["map_z"].values[j]]),
                               ds["map_von_mises"].values[j], tri))
    return tuple(views)


def write_atomic(ds: xr.Dataset, path, encoding=None) -> tuple:
    """Write `ds` to `path` atomically (catalogue.atomic); returns (sha256 hex, size in
    bytes) of the bytes written."""
    with atomic_path(path) as tmp:
        ds.to_netcdf(tmp, engine="netcdf4", format="NETCDF4", encoding=encoding)
        data = Path(tmp).read_bytes()
    return hashlib.sha256(data).hexdigest(), len(data)


def write(path, ps: PathSet, key: dict, fp: str) -> tuple:
    """Store a path set at `path` atomically: (sha256 hex, size in bytes)."""
    ds = to_dataset(ps, key, fp)
    enc = {v: {"zlib": True, "complevel": 4} for v in ds.data_vars
           if ds[v].dtype.kind == "f" and ds[v].size > 0}
    return write_atomic(ds, path, enc)


def read(path, sha256: str, fp: str) -> PathSet:
    """The path set stored at `path`; CorruptFile unless its bytes match `sha256` and
    its fingerprint is `fp`."""
    try:
        data = Path(path).read_bytes()
    except OSError as e:
        raise CorruptFile(f"{path}: {e.strerror or e}") from None
    if hashlib.sha256(data).hexdigest() != sha256:
        raise CorruptFile(f"{path}: checksum mismatch")
    try:
        nc = netCDF4.Dataset("pathset.nc", mode="r", memory=data)
        try:
            ds = xr.open_dataset(xr.backends.NetCDF4DataStore(nc)).load()
        finally:
            nc.close()
        if ds.attrs.get("fingerprint") != fp or int(ds.attrs.get("layout", -1)) != LAYOUT:
            raise CorruptFile(f"{path}: not the path set {fp[:12]}")
        return from_dataset(ds)
    except CorruptFile:
        raise
    except Exception as e:      # any decoding failure means the file cannot be trusted
        raise CorruptFile(f"{path}: cannot be read ({type(e).__name__}: {e})") from None
