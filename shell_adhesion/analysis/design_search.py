"""The shell (t, h) that sticks best, searched on a pull-off map.

For a material (C10 in MPa, gamma in J/m^2) and a size (the radius of curvature R, or the
rim radius b of the cap's base, in mm), the search runs over the map's t/R x h/R inside the
user's bounds (mm) and maximises one objective:

- ``pull_off``: ``|P*|`` in N;
- ``per_preload``: ``|P*|`` / preload, the preload being the rim force on the loading curve at
  the contact radius a* (the least compression after which P* is reached), dimensionless;
- ``per_volume``: ``|P*|`` / V in N/mm^3, V the volume of the cap's material.

A dense grid of the interpolant over the bounds met with the map (`design_box`; a fixed
t or h is one grid line), then Nelder-Mead from its best point (scipy), in (ln t, h).
Reads only the map (no FE); `shell_adhesion.study.design` confirms with one FE case.
"""
from dataclasses import dataclass, field
import math

import numpy as np
from scipy.optimize import minimize

from .design_box import Box, R_of_h, search_box
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


def _objective(pm: PullOffMap, objective, C10, gamma, R_mm, b_mm, box: Box):
    """f(ln t, h) to minimise (-objective), t and h in mm held inside `box`; None off the
    map."""
    def value(z):
        t = min(max(math.exp(z[0]), box.t_mm[0]), box.t_mm[1])
        h = min(max(z[1], box.h_mm[0]), box.h_mm[1])
        R = R_of_h(h, R_mm, b_mm)
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


def grid_size(box: Box) -> int:
    """How many map evaluations the search's first grid makes over `box`."""
    return _points(box.t_mm) * _points(box.h_mm)


def _points(pair) -> int:
    return 1 if pair[0] == pair[1] else GRID_POINTS


def search(pm: PullOffMap, C10_MPa: float, gamma_J_m2: float, objective="pull_off", *,
           R_mm=None, b_mm=None, t_mm=(0.0, math.inf), h_mm=(0.0, math.inf),
           on_grid=None) -> Design:
    """The (t, h) inside the bounds and the map that maximises the objective.

    A bound (or gamma) that leaves no shell on the map raises `OffMap` naming it with the
    map's range; equal bounds fix t or h.  ``on_grid(done, total)`` is called as the first
    grid is evaluated (progress)."""
    if objective not in OBJECTIVES:
        raise ValueError(f"objective: {objective!r} must be one of {', '.join(OBJECTIVES)}")
    if (R_mm is None) == (b_mm is None):
        raise ValueError("give the size as R_mm or as b_mm (the rim radius), not both")
    box = search_box(pm.bounds, C10_MPa, gamma_J_m2, R_mm, b_mm, t_mm, h_mm)
    f = _objective(pm, objective, C10_MPa, gamma_J_m2, R_mm, b_mm, box)
    bounds = [(math.log(box.t_mm[0]), math.log(box.t_mm[1])), box.h_mm]
    axes = [np.linspace(lo, hi, _points((lo, hi))) for lo, hi in bounds]
    total, count, best = len(axes[0]) * len(axes[1]), 0, None
    for z0 in axes[0]:
        for z1 in axes[1]:
            got = f((z0, z1))
            count += 1
            if got is not None and got[0] is not None and (best is None or got[0] > best[1][0]):
                best = ((z0, z1), got)
            if on_grid is not None:
                on_grid(count, total)
    if best is None:
        raise MapError(f"no shell with t {box.t_mm[0]:.4g} to {box.t_mm[1]:.4g} mm and h "
                       f"{box.h_mm[0]:.4g} to {box.h_mm[1]:.4g} mm lies on the map (t/R "
                       f"{pm.bounds['t_over_R'][0]:.3g}-{pm.bounds['t_over_R'][1]:.3g}, h/R "
                       f"{pm.bounds['h_over_R'][0]:.3g}-{pm.bounds['h_over_R'][1]:.3g})")

    def loss(z):
        got = f(z)
        return math.inf if got is None or got[0] is None else -got[0]
    res = minimize(loss, np.array(best[0]), method="Nelder-Mead", bounds=bounds,
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
