"""The shell (t, h) that sticks best, searched on a pull-off map.

For a material (C10 in MPa, gamma in J/m^2) and a size (the radius of curvature R, or the
rim radius b of the cap's base, in mm), the search runs over the map's t/R x h/R inside the
user's bounds (mm) and maximises one objective:

- ``pull_off``: ``|P*|`` in N;
- ``per_preload``: ``|P*|`` / preload, the preload being the rim force on the loading curve at
  the contact radius a* (the least compression after which P* is reached), dimensionless;
- ``per_volume``: ``|P*|`` / V in N/mm^3, V the volume of the cap's material.

A dense grid of the interpolant first, then Nelder-Mead from its best point (scipy).
Reads only the map (no FE); `shell_adhesion.study.design` confirms with one FE case.
"""
from dataclasses import dataclass, field
import math

import numpy as np
from scipy.optimize import minimize

from .pull_off_map import MapError, PullOffMap

OBJECTIVES = {"pull_off": "|P*| [N]", "per_preload": "|P*| / preload [1]",
              "per_volume": "|P*| / volume [N/mm^3]"}
GRID_POINTS = 41            # per axis, before the local refinement
MAX_ITERATIONS = 200        # of Nelder-Mead
ON_BOUND = 1e-3             # relative distance to a bound that counts as on it


def cap_volume_mm3(R_mm: float, t_mm: float, h_mm: float) -> float:
    """Volume of a spherical-cap shell (outer radius R, thickness t, depth h from the apex
    to the base plane) in mm^3: the outer cap less the inner one (depth h - t)."""
    def cap(r, depth):
        return math.pi * depth ** 2 * (3 * r - depth) / 3 if depth > 0 else 0.0
    return cap(R_mm, h_mm) - cap(R_mm - t_mm, h_mm - t_mm)


def R_of(h_over_R: float, R_mm=None, b_mm=None) -> float:
    """The radius of curvature [mm]: R itself, or from the rim radius b = R sqrt(y (2 - y))."""
    if R_mm is not None:
        return float(R_mm)
    return float(b_mm) / math.sqrt(h_over_R * (2 - h_over_R))


@dataclass(frozen=True)
class Design:
    """The best shell found on the map and what the map says of it (units in the names)."""
    objective: str
    objective_value: float
    R_mm: float
    t_mm: float
    h_mm: float
    answers: dict                       # name_unit -> (value, error), from PullOffMap.shell
    on_bounds: tuple = field(default=())    # which bounds the optimum lies on (text)
    evaluated: int = 0                  # interpolant evaluations


def _objective(pm: PullOffMap, objective, C10, gamma, R_mm, b_mm, t_range, h_range):
    """f(ln t/R, h/R) to minimise (-objective), or None outside the bounds / the map."""
    def value(z):
        x, y = math.exp(z[0]), z[1]
        R = R_of(y, R_mm, b_mm)
        t, h = x * R, y * R
        if not (t_range[0] <= t <= t_range[1] and h_range[0] <= h <= h_range[1]):
            return None
        try:
            out = pm.shell(R, t, h, C10, gamma)
        except MapError:
            return None
        P = abs(out["P_star_N"][0])
        if objective == "pull_off":
            return P, out, (R, t, h)
        if objective == "per_preload":
            pre = out.get("preload_N", (math.nan,))[0]
            return (P / pre if pre > 0 else None), out, (R, t, h)
        return P / cap_volume_mm3(R, t, h), out, (R, t, h)
    return value


def search(pm: PullOffMap, C10_MPa: float, gamma_J_m2: float, objective="pull_off", *,
           R_mm=None, b_mm=None, t_mm=(0.0, math.inf), h_mm=(0.0, math.inf)) -> Design:
    """The (t, h) inside the bounds and the map that maximises the objective; ValueError if
    no shell inside the bounds lies on the map."""
    if objective not in OBJECTIVES:
        raise ValueError(f"objective: {objective!r} must be one of {', '.join(OBJECTIVES)}")
    if (R_mm is None) == (b_mm is None):
        raise ValueError("give the size as R_mm or as b_mm (the rim radius), not both")
    f = _objective(pm, objective, C10_MPa, gamma_J_m2, R_mm, b_mm, t_mm, h_mm)
    (tlo, thi), (hlo, hhi) = pm.bounds["t_over_R"], pm.bounds["h_over_R"]
    box = [(math.log(tlo), math.log(thi)), (hlo, hhi)]
    count = 0
    best = None
    for z0 in np.linspace(*box[0], GRID_POINTS):
        for z1 in np.linspace(*box[1], GRID_POINTS):
            got = f((z0, z1))
            count += 1
            if got is not None and got[0] is not None and (best is None or got[0] > best[1][0]):
                best = ((z0, z1), got)
    if best is None:
        raise MapError("no shell inside the bounds lies on the map (t/R "
                         f"{tlo:.3g}-{thi:.3g}, h/R {hlo:.3g}-{hhi:.3g}, gamma/(C10 R) "
                         f"{pm.bounds['gamma_hat'][0]:.3g}-{pm.bounds['gamma_hat'][1]:.3g})")

    def loss(z):
        got = f(z)
        return math.inf if got is None or got[0] is None else -got[0]
    res = minimize(loss, np.array(best[0]), method="Nelder-Mead", bounds=box,
                   options=dict(maxiter=MAX_ITERATIONS, xatol=1e-4, fatol=1e-10))
    count += res.nfev
    z = res.x if np.isfinite(res.fun) and -res.fun >= best[1][0] else np.array(best[0])
    value, answers, (R, t, h) = f(z)
    return Design(objective, value, R, t, h, answers,
                  _on_bounds(t, h, R, t_mm, h_mm, pm), count)


def _on_bounds(t, h, R, t_mm, h_mm, pm):
    said = [f"{name} fixed at {lo:.4g} mm (your bounds)"
            for name, (lo, hi) in (("t", t_mm), ("h", h_mm)) if lo == hi]
    for name, v, (lo, hi), unit in (("t", t, t_mm, "mm"), ("h", h, h_mm, "mm"),
                                    ("t/R", t / R, pm.bounds["t_over_R"], "the map's"),
                                    ("h/R", h / R, pm.bounds["h_over_R"], "the map's")):
        if unit == "mm" and lo == hi:
            continue
        for which, b in (("lower", lo), ("upper", hi)):
            if math.isfinite(b) and b > 0 and abs(v - b) <= ON_BOUND * b:
                where = f"{b:.4g} mm (your bound)" if unit == "mm" else f"{b:.4g} ({unit} edge)"
                said.append(f"{name} at its {which} bound {where}")
    return tuple(said)
