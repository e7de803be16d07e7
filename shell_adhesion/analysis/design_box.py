"""The box a design searches: the user's bounds on the thickness t and the depth h (mm)
met with what the pull-off map covers (t/R, h/R, gamma/(C10 R)) for one size.

The size is the radius of curvature R (mm) or the rim radius b of the cap's base (mm); with
b, R follows from the depth: b = R sqrt(y (2 - y)), y = h/R <= 1, so that h = b sqrt(y / (2 -
y)) and R = b / sqrt(y (2 - y)), R falling as y grows.  gamma/(C10 R) takes gamma in J/m^2,
C10 in MPa and R in mm (a factor 1e-3).  A bound or a gamma that leaves no shell on the map
raises `OffMap` naming the argument, its value and the map's range for this size.
"""
from dataclasses import dataclass
import math

from .pull_off_map import MapError

ROUND_OFF = 1e-12       # relative slack at the map's edges (as PullOffMap.check_inside)


class OffMap(MapError):
    """A design's argument (``t_mm``, ``h_mm`` or ``gamma_J_m2``) that leaves no shell on
    the map; `detail` names its value and the map's range for this size."""

    def __init__(self, argument: str, detail: str):
        super().__init__(f"{argument}: {detail}")
        self.argument = argument
        self.detail = detail


@dataclass(frozen=True)
class Box:
    """The search box in mm: (least, greatest) thickness and depth."""
    t_mm: tuple
    h_mm: tuple


def y_of_h(h_mm: float, b_mm: float) -> float:
    """h/R of the cap of rim radius b and depth h (both mm)."""
    q = (h_mm / b_mm) ** 2
    return 2 * q / (1 + q)


def h_of_y(y: float, b_mm: float) -> float:
    """Depth [mm] of the cap of rim radius b [mm] at h/R = y."""
    return b_mm * math.sqrt(y / (2 - y))


def R_of_h(h_mm: float, R_mm=None, b_mm=None) -> float:
    """The radius of curvature [mm]: R itself, or that of the cap of rim radius b, depth h."""
    if R_mm is not None:
        return float(R_mm)
    y = y_of_h(h_mm, b_mm)
    return b_mm / math.sqrt(y * (2 - y))


def _y_of_R(R_mm: float, b_mm: float) -> float:
    """h/R (<= 1) of the cap of rim radius b whose radius is R (mm); NaN if R < b."""
    s = b_mm / R_mm
    return 1 - math.sqrt(1 - s * s) if s <= 1 else math.nan


def _text(pair) -> str:
    lo, hi = pair
    return f"{lo:g}" if lo == hi else f"{lo:g} to {hi:g}"


def _meet(given, covered):
    """The overlap of two (lo, hi) ranges, the covered one widened by ROUND_OFF; None if empty."""
    lo = max(given[0], covered[0] * (1 - ROUND_OFF))
    hi = min(given[1], covered[1] * (1 + ROUND_OFF))
    return (lo, hi) if lo <= hi else None


def search_box(bounds: dict, C10_MPa: float, gamma_J_m2: float, R_mm=None, b_mm=None,
               t_mm=(0.0, math.inf), h_mm=(0.0, math.inf)) -> Box:
    """The part of the user's (t, h) bounds [mm] that the map `bounds` (PullOffMap.bounds)
    can answer for this size and gamma; `OffMap` naming gamma, h or t (in that order) if
    none is left."""
    (tlo, thi), (ylo, yhi), (glo, ghi) = (bounds[a] for a in ("t_over_R", "h_over_R",
                                                             "gamma_hat"))
    k = gamma_J_m2 * 1e-3 / C10_MPa              # gamma/(C10 R) = k / R, R in mm
    map_ratios = f"the map's t/R {tlo:.4g} to {thi:.4g}, h/R {ylo:.4g} to {yhi:.4g}"
    if R_mm is not None:
        size = f"R {R_mm:g} mm"
        g = k / R_mm
        if _meet((g, g), (glo, ghi)) is None:
            raise OffMap("gamma_J_m2", f"{gamma_J_m2:g} J/m^2 is gamma/(C10 R) = {g:.4g}, "
                         f"outside the map's {glo:.4g} to {ghi:.4g} (gamma from "
                         f"{glo * C10_MPa * R_mm * 1e3:.4g} to {ghi * C10_MPa * R_mm * 1e3:.4g} "
                         f"J/m^2 for C10 {C10_MPa:g} MPa and {size})")
        h_map = (ylo * R_mm, yhi * R_mm)
    else:
        size = f"b {b_mm:g} mm"
        # gamma/(C10 R) inside the map <=> R from k/ghi to k/glo <=> y within these
        y_lo = max(ylo, _y_of_R(k / glo, b_mm)) if k / glo >= b_mm else math.nan
        y_hi = min(yhi, _y_of_R(k / ghi, b_mm)) if k / ghi >= b_mm else yhi
        if not y_lo <= y_hi * (1 + ROUND_OFF):
            g_at = [k * math.sqrt(y * (2 - y)) / b_mm for y in (ylo, yhi)]
            raise OffMap("gamma_J_m2", f"{gamma_J_m2:g} J/m^2 with C10 {C10_MPa:g} MPa and "
                         f"{size} is gamma/(C10 R) = {g_at[0]:.4g} to {g_at[1]:.4g} over the "
                         f"map's h/R, outside the map's {glo:.4g} to {ghi:.4g}")
        h_map = (h_of_y(y_lo, b_mm), h_of_y(min(y_hi, 1.0), b_mm))
    h = _meet(tuple(h_mm), h_map)
    if h is None:
        raise OffMap("h_mm", f"{_text(h_mm)} mm is outside the map: h from {h_map[0]:.4g} to "
                     f"{h_map[1]:.4g} mm for {size} ({map_ratios}, and gamma/(C10 R) "
                     f"{glo:.4g} to {ghi:.4g})")
    R_range = sorted(R_of_h(x, R_mm, b_mm) for x in h)
    t_map = (tlo * R_range[0], thi * R_range[1])
    t = _meet(tuple(t_mm), t_map)
    if t is None:
        where = size if R_mm is not None else f"{size} and h from {h[0]:.4g} to {h[1]:.4g} mm"
        raise OffMap("t_mm", f"{_text(t_mm)} mm is outside the map: t from {t_map[0]:.4g} to "
                     f"{t_map[1]:.4g} mm for {where} ({map_ratios})")
    return Box(t, h)
