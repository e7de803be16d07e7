"""Path sets and relaxation paths as xarray Datasets (the stored layout), and back.

Dimensionless, as the solver computes it: lengths / R, forces / (C10 R^2), energies /
(C10 R^3).  Loading states along `loading_state`; the relaxation paths are one CF
contiguous ragged array: path k holds `relaxation_length[k]` consecutive samples of
`relaxation_state`, delta decreasing from its loaded state.  The views kept for figures:
deformed profiles along `profile` (outer and inner surface nodes), and stress maps along
`stress_map` (deformed nodes, nodal von Mises / C10) over one triangulation.

Pure conversions (no files): the catalogue stores these Datasets as they are.
"""
from dataclasses import fields
import json

import numpy as np
import xarray as xr

from .case import PathSet, Relaxation
from .cavity import Cavity
from .postprocess import Profile, StressMap

LAYOUT = 5          # version of this layout (part of the catalogue key of a path set)


# descriptions of known fields; a field the solver adds later is stored all the same
_LONG_NAMES = {
    "loading_delta": "rim displacement delta / R (approach > 0)",
    "loading_P": "rim force P / (C10 R^2) (compression > 0)",
    "loading_a": "contact radius a / R",
    "loading_U": "strain energy U / (C10 R^3)",
    "loading_joined": "outer node joining the contact in this state (-1: none)",
    "loading_V": "cavity volume V / R^3 (NaN: open)",
    "loading_p": "cavity gauge pressure p / C10 (NaN: open)",
    "relaxation_V": "cavity volume V / R^3 (NaN: open)",
    "relaxation_p": "cavity gauge pressure p / C10 (NaN: open)",
    "relaxation_a": "held contact radius a / R of the path",
    "relaxation_a_edge": "deformed radius / R of the held edge (covered radius) along the path",
    "relaxation_da_ddelta": "its slope d a_edge / d delta along the path",
    "relaxation_dA_dgamma": "covered area's compliance d(A / R^2) / d(gamma / (C10 R)) at "
                            "fixed delta along the path (0: the edge cannot slide)",
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
_TITLE = "shell-adhesion FE path set"
_VIEW_SCALARS = ("stage", "a", "delta", "P")
_ATTRS = {"t": "t_over_R", "h": "h_over_R", "interface": "interface", "mesh": "mesh",
          "delta_max": "delta_max_over_R", "gamma_max": "gamma_max_hat"}


def _stored(cls):
    """The fields stored as columns (views have their own variables; a path's timing is
    summed into the set's stats)."""
    return [f for f in fields(cls) if f.name not in ("views", "timing")]


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


def _relaxation_data(rel) -> dict:
    """The relaxation paths `rel` as one contiguous ragged array."""
    data = {}
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
    return data


def _relaxations_of(ds: xr.Dataset, views=()) -> tuple:
    lengths = ds["relaxation_length"].values
    ends = np.cumsum(lengths)
    starts = ends - lengths
    # fields stored before the cavity existed are absent: an open shell
    columns = {f: ds[f"relaxation_{f.name}"].values for f in _stored(Relaxation)
               if f"relaxation_{f.name}" in ds or f.name not in _CAVITY_FIELDS}
    rel = []
    for k, (s, e) in enumerate(zip(starts, ends)):
        kw = {}
        for f, v in columns.items():
            if _is_array(f):
                kw[f.name] = v[s:e]
            else:
                kind = {"bool": bool, "str": str, "int": int, "float": float}.get(f.type, f.type)
                kw[f.name] = kind(v[k])
        rel.append(Relaxation(views=views, **kw))
    return tuple(rel)


_CAVITY_FIELDS = ("V", "p", "loading_V", "loading_p")


def _json_stats(stats) -> str:
    return json.dumps(stats, sort_keys=True, default=lambda o: o.item())


def to_dataset(ps: PathSet) -> xr.Dataset:
    """The path set as an xarray Dataset in the stored layout (dimensionless)."""
    data = {}
    for f in fields(PathSet):
        if _is_array(f):
            data[f.name] = _var(f.name, "loading_state", np.asarray(getattr(ps, f.name)))
    data.update(_relaxation_data(ps.relaxations))
    data.update(_views_data(ps.views))
    attrs = dict(
        title=_TITLE + " (dimensionless: lengths / R, forces / (C10 R^2), energies / (C10 R^3))",
        Conventions="CF-1.8", layout=LAYOUT, stats=_json_stats(ps.stats),
        cavity=json.dumps(ps.cavity.as_dict(), sort_keys=True),
        **{a: getattr(ps, f) for f, a in _ATTRS.items()})
    if ps.uniform is not None:      # the even arc the set was meshed with (solver.request)
        attrs["uniform_arc_over_R"] = float(ps.uniform)
    return xr.Dataset(data, attrs=attrs)


def from_dataset(ds: xr.Dataset) -> PathSet:
    """The PathSet stored in `ds` (the inverse of to_dataset); ValueError if `ds` is not
    a path set of this layout."""
    if not str(ds.attrs.get("title", "")).startswith(_TITLE) \
            or int(ds.attrs.get("layout", -1)) != LAYOUT:
        raise ValueError(f"not a path set of layout {LAYOUT}")
    kw = {f: ds.attrs[a] for f, a in _ATTRS.items()}
    kw = {f: (str(v) if f in ("interface", "mesh") else float(v)) for f, v in kw.items()}
    for f in fields(PathSet):
        if _is_array(f) and (f.name in ds or f.name not in _CAVITY_FIELDS):
            kw[f.name] = ds[f.name].values
    if "cavity" in ds.attrs:
        kw["cavity"] = Cavity(**json.loads(ds.attrs["cavity"]))
    if "uniform_arc_over_R" in ds.attrs:
        kw["uniform"] = float(ds.attrs["uniform_arc_over_R"])
    return PathSet(relaxations=_relaxations_of(ds), stats=json.loads(ds.attrs["stats"]),
                   views=_views_of(ds), **kw)


def relaxation_to_dataset(r: Relaxation, seconds: float = 0.0) -> xr.Dataset:
    """One relaxation path (with its views) as a Dataset; `seconds`: its solve time [s]."""
    data = _relaxation_data((r,))
    data.update(_views_data(r.views))
    return xr.Dataset(data, attrs=dict(
        title="shell-adhesion FE relaxation path (dimensionless, as in a path set)",
        Conventions="CF-1.8", layout=LAYOUT, seconds=float(seconds)))


def relaxation_from_dataset(ds: xr.Dataset) -> tuple:
    """(Relaxation, seconds [s]) stored by relaxation_to_dataset; ValueError if `ds` is
    not one relaxation path of this layout."""
    if int(ds.attrs.get("layout", -1)) != LAYOUT or ds.sizes.get("relaxation") != 1:
        raise ValueError(f"not a relaxation path of layout {LAYOUT}")
    (r,) = _relaxations_of(ds, _views_of(ds))
    return r, float(ds.attrs["seconds"])


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
