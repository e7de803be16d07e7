"""Geometry of the spherical-cap shell, in units of the outer radius R.

The shell is the material between the spheres of radius 1 and 1 - t centred on the
axis at z = 1, cut by the base plane z = h (kept: z <= h).  The outer apex touches
the substrate z = 0 at the origin.  t = 1 is a solid cap (no cavity).
"""
from dataclasses import dataclass
import math

DELTA_MAX_LIMIT = 0.5   # deepest loading delta_max / R the tool accepts


class InputError(ValueError):
    """Bad input: the message names the field, the value and the rule."""


@dataclass(frozen=True)
class Cap:
    """Dimensionless cap: thickness t and depth h, both in units of R."""

    t: float
    h: float

    def __post_init__(self):
        check_cap(self.t, self.h)

    @property
    def solid(self) -> bool:
        return self.t >= 1.0

    @property
    def theta_outer(self) -> float:
        """Polar angle of the outer rim, measured from the downward axis (rad)."""
        return math.acos(1.0 - self.h)

    @property
    def theta_inner(self) -> float:
        return math.acos((1.0 - self.h) / (1.0 - self.t))

    @property
    def rim_outer(self) -> float:
        """Outer rim radius b / R."""
        return math.sqrt(1.0 - (1.0 - self.h) ** 2)

    @property
    def rim_inner(self) -> float:
        return 0.0 if self.solid else math.sqrt((1.0 - self.t) ** 2 - (1.0 - self.h) ** 2)

    @property
    def volume(self) -> float:
        """Volume / R^3 of the cap (outer cap minus the inner cap below z = h)."""
        outer = math.pi * self.h ** 2 * (3.0 - self.h) / 3.0
        if self.solid:
            return outer
        hi = self.h - self.t
        ri = 1.0 - self.t
        return outer - math.pi * hi ** 2 * (3.0 * ri - hi) / 3.0


def check_cap(t_over_R, h_over_R, t_name="t/R", h_name="h/R"):
    """Raise InputError unless 0 < t <= 1 and (t < h <= 1, or t = 1 and 0 < h <= 1)."""
    for name, value in ((t_name, t_over_R), (h_name, h_over_R)):
        if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value):
            raise InputError(f"{name}: {value!r} must be a finite number")
    if not 0.0 < t_over_R <= 1.0:
        raise InputError(f"{t_name}: {t_over_R:g} must satisfy 0 < t <= R")
    if not 0.0 < h_over_R <= 1.0:
        raise InputError(f"{h_name}: {h_over_R:g} must satisfy 0 < h <= R")
    if t_over_R < 1.0 and h_over_R <= t_over_R:
        raise InputError(
            f"{h_name}: {h_over_R:g} must be > t ({t_over_R:g}) unless t = R (solid cap)")


def check_delta_max(delta_max_over_R, h_over_R, name="delta_max/R", h_name="h/R"):
    """Raise InputError unless 0 < delta_max <= DELTA_MAX_LIMIT and delta_max < h (the rim
    stays above the plane), all in units of R."""
    if not 0.0 < delta_max_over_R <= DELTA_MAX_LIMIT:
        rule = "must be > 0" if not delta_max_over_R > 0 else f"must be <= {DELTA_MAX_LIMIT:g}"
        raise InputError(f"{name}: {delta_max_over_R:g} {rule}")
    if not delta_max_over_R < h_over_R:
        raise InputError(f"{name}: {delta_max_over_R:g} must be < h/R ({h_over_R:g}, {h_name})")
