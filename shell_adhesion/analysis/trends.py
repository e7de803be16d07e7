"""Trend verdicts on a results cube: does |P*| (or another value) increase, decrease or stay
flat along each sweep, within the mesh uncertainty or the error bars, and does that agree
with the paper (DESIGN.md section 4)?
"""
from dataclasses import dataclass

import numpy as np
import xarray as xr

from shell_adhesion.cube import DIMS

from .results import along

_UNITS_TEXT = {"1": ""}


# relative uncertainty of P* from the mesh: the measured change of P* is 0.32 % from coarse
# to default and 0.18 % from default to fine (README; test_convergence.py's limit is 0.5 %);
# each value is about three times the measured change to the next finer mesh
MESH_UNCERTAINTY = {"coarse": 0.01, "default": 0.005, "fine": 0.0025, "finer": 0.0025}


# the paper's statements about Fig. 6 (DESIGN.md section 4): |P*| grows with C10 and t/R,
# is roughly independent of h/R and linear in gamma
PAPER_TRENDS = {"C10": "increasing", "t_over_R": "increasing", "h_over_R": "flat",
                "gamma": "increasing"}


def mesh_uncertainty(ds: xr.Dataset) -> float:
    """Relative mesh uncertainty of P* for the cube's mesh (the coarse value if unknown)."""
    return MESH_UNCERTAINTY.get(ds.attrs.get("mesh"), max(MESH_UNCERTAINTY.values()))


def trend_of(values, uncertainty: float, errors=None) -> str:
    """Verdict on a series of magnitudes: "increasing", "decreasing", "non-monotonic" or
    "flat".  A step counts only if it exceeds the combined error of its two ends, the sum
    of their error bars (`errors`, absolute; where one is missing, uncertainty * |value|);
    if no step counts but the whole change first -> last does, its sign decides."""
    v = np.abs(np.asarray(values, dtype=float))
    if len(v) < 2:
        raise ValueError("a trend needs at least two values")
    e = uncertainty * v
    if errors is not None:
        given = np.abs(np.asarray(errors, dtype=float))
        e = np.where(np.isfinite(given), given, e)
    steps = np.diff(v)
    real = np.abs(steps) > e[1:] + e[:-1]
    signs = set(np.sign(steps[real]))
    if not signs:
        total = v[-1] - v[0]
        if abs(total) <= e[-1] + e[0]:
            return "flat"
        signs = {np.sign(total)}
    if len(signs) > 1:
        return "non-monotonic"
    return "increasing" if signs.pop() > 0 else "decreasing"


@dataclass(frozen=True)
class Trend:
    """Verdict on |var| along a swept dimension at the base point.

    coords the dimension's values, values |var| there, change (last - first) / first,
    uncertainty the relative mesh uncertainty used, claim the paper's verdict (None if it
    makes none), agrees whether ours matches it (None without a claim), sentence one line
    with numbers and units.
    """
    dim: str
    var: str
    verdict: str
    coords: np.ndarray
    values: np.ndarray
    change: float
    uncertainty: float
    claim: object
    agrees: object
    sentence: str


def _unit(x: xr.DataArray) -> str:
    u = x.attrs.get("units", "")
    return _UNITS_TEXT.get(u, u)


def _with_unit(value, unit):
    return f"{value:.4g} {unit}" if unit else f"{value:.4g}"


def trend(ds: xr.Dataset, dim: str, var: str = "P_star") -> Trend:
    """Verdict on abs(`var`) along `dim` (other dimensions at the base), with the mesh
    uncertainty of `mesh_uncertainty` on each value, and the paper's claim for P*."""
    x = along(ds, var, dim)
    u = mesh_uncertainty(ds)
    coords, values = x[dim].values, np.abs(x.values)
    errors = (along(ds, f"{var}_error", dim).reindex({dim: x[dim]}).values
              if f"{var}_error" in ds else None)
    verdict = trend_of(values, u, errors)
    change = float((values[-1] - values[0]) / values[0])
    claim = PAPER_TRENDS.get(dim) if var == "P_star" else None
    agrees = None if claim is None else verdict == claim
    name = {"P_star": "|P*|"}.get(var, f"|{var}|")
    vu, du = _unit(ds[var]), _unit(ds[dim])
    pts = ", ".join(f"{_with_unit(v, vu)} at {c:g}" for c, v in zip(coords, values))
    if errors is not None and np.isfinite(errors).all():
        pts = ", ".join(f"{_with_unit(v, vu)} +- {e:.2g} at {c:g}"
                        for c, v, e in zip(coords, values, errors))
        basis = "a step counts beyond the sum of its two error bars"
    else:
        basis = f"mesh uncertainty {u:.1%} per value"
    sentence = (f"{name} {verdict} along {dim}{f' [{du}]' if du else ''}: {pts} "
                f"({change:+.2%} in all; {basis})")
    if claim is not None:
        sentence += f"; paper: {claim} ({'agrees' if agrees else 'DISAGREES'})"
    return Trend(dim, var, verdict, coords, values, change, u, claim, agrees, sentence)


def trends(ds: xr.Dataset, var: str = "P_star") -> list:
    """`trend` along every dimension with at least two ok values at the base point."""
    return [trend(ds, d, var) for d in DIMS if along(ds, var, d).size >= 2]
