"""Geometry of the spherical-cap shell, in units of the outer radius R.

The shell is the material between the spheres of radius 1 and 1 - t centred on the
axis at z = 1, cut by the base plane z = h (kept: z <= h).  The outer apex touches
the substrate z = 0 at the origin.  t = 1 is a solid cap (no cavity).
"""
from dataclasses import dataclass
import math
import numbers

from shell_adhesion.errors import InputError


def shown(value) -> str:
    """A value as message text: a number (a numpy scalar too) as a plain Python number,
    anything else by its repr (never ``np.float64(...)``)."""
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        return repr(int(value))
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return repr(float(value))
    return repr(value)


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


# The supported domain (DESIGN.md section 8): requests outside it are refused before any
# computation.  Dimensionless: lengths / R, gamma / (C10 R).
T_MIN = 0.02          # thinnest shell, t / R
H_MIN = 0.2           # shallowest cap, h / R (and h > t for a shell)
DELTA_MAX = 0.25      # deepest loading, delta / R
DELTA_MAX_THIN = 0.9  # deepest loading of a thin shell (t < THIN_T), delta / R, and below
THIN_T = 0.15         # 0.9 h (DEPTH_SHARE): it flattens onto the plane straining little and
#                       pulls off at contact radii up to 0.77 R (t/R = 0.02, h/R = 0.5,
#                       gamma/(C10 R) = 0.03), which a loading to 0.25 R does not reach
#                       (a = 0.70 R there); where a curve has not turned by 0.5 R (t/R 0.02,
#                       h/R 1) the loading goes on until the hemisphere snaps flat (a from
#                       0.79 to 0.98 R) and the paths beyond invert, with its checks passing
GAMMA_MAX = 0.03      # largest gamma / (C10 R) the relaxation paths serve


def _finite(name, value):
    if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value):
        raise InputError(f"{name}: {shown(value)} must be a finite number")


def check_cap(t_over_R, h_over_R, t_name="t/R", h_name="h/R"):
    """Raise InputError unless the cap is valid and inside the supported domain.

    Valid: 0 < t <= 1, h <= 1 and t < h (or t = 1, a solid cap).  Supported:
    t/R in [T_MIN, 1] and h/R in [max(t/R, H_MIN), 1] (a solid cap, t = 1, any h/R in
    [H_MIN, 1]).
    """
    for name, value in ((t_name, t_over_R), (h_name, h_over_R)):
        _finite(name, value)
    if not 0.0 < t_over_R <= 1.0:
        raise InputError(f"{t_name}: {t_over_R:g} must satisfy 0 < t <= R")
    if not 0.0 < h_over_R <= 1.0:
        raise InputError(f"{h_name}: {h_over_R:g} must satisfy 0 < h <= R")
    if t_over_R < 1.0 and h_over_R <= t_over_R:
        raise InputError(
            f"{h_name}: {h_over_R:g} must be > t ({t_over_R:g}) unless t = R (solid cap)")
    if t_over_R < T_MIN:
        raise InputError(f"{t_name}: {t_over_R:g} is outside the supported domain "
                         f"t/R >= {T_MIN:g} (thinner shells are not solved reliably)")
    if h_over_R < H_MIN:
        raise InputError(f"{h_name}: {h_over_R:g} is outside the supported domain "
                         f"h/R >= {H_MIN:g} (shallower caps are not solved reliably)")


DEPTH_SHARE = 0.9     # a loading without an explicit delta_max stops above 0.9 of the cap's depth


def domain_delta_max(t_over_R: float = 1.0) -> float:
    """The supported domain's deepest delta / R for a shell of thickness t / R: DELTA_MAX,
    DELTA_MAX_THIN for a thin shell (t < THIN_T)."""
    return DELTA_MAX_THIN if t_over_R < THIN_T else DELTA_MAX


def delta_bound(cap: "Cap") -> float:
    """The deepest delta / R a loading of `cap` may reach without an explicit delta_max:
    the domain's (domain_delta_max), below DEPTH_SHARE of the cap's depth."""
    return min(domain_delta_max(cap.t), DEPTH_SHARE * cap.h)


def check_delta_max(delta_max_over_R, h_over_R=None, name="delta_max/R", h_name="h/R",
                    t_over_R=1.0):
    """Raise InputError unless 0 < delta_max/R <= the domain's bound for t/R
    (domain_delta_max), and < h/R if given (the rim stays above the plane)."""
    _finite(name, delta_max_over_R)
    if not delta_max_over_R > 0:
        raise InputError(f"{name}: {delta_max_over_R:g} must be > 0")
    bound = domain_delta_max(t_over_R)
    if delta_max_over_R > bound * (1 + 1e-12):
        thin = f" for t/R = {t_over_R:g}" if t_over_R < 1.0 else ""
        raise InputError(f"{name}: {delta_max_over_R:g} is outside the supported domain "
                         f"delta/R <= {bound:g}{thin}")
    if h_over_R is not None and delta_max_over_R >= h_over_R:
        raise InputError(f"{name}: {delta_max_over_R:g} must be < h/R ({h_over_R:g}, {h_name})")


def check_gamma(gamma_hat, gamma_max=GAMMA_MAX, name="gamma/(C10 R)", given="", scales=""):
    """Raise InputError unless 0 < gamma / (C10 R) <= gamma_max (at most GAMMA_MAX, the
    supported domain; less for paths built for a smaller range).

    `name` is the caller's field, `given` the value as the user wrote it (e.g. "900 J/m^2")
    and `scales` what made it dimensionless (e.g. "with C10 = 0.3 MPa and R = 20 mm").
    """
    _finite(name, gamma_hat)
    if not gamma_hat > 0:
        raise InputError(f"{name}: {given or format(gamma_hat, 'g')} must be > 0")
    limit = min(gamma_max, GAMMA_MAX)
    if gamma_hat > limit * (1 + 1e-12):
        shown = f"{gamma_hat:.4g}"
        if given:
            shown = " ".join(w for w in (given, scales) if w) + f" gives gamma/(C10 R) = {shown}"
        why = ("the supported domain" if limit == GAMMA_MAX
               else "the range these relaxation paths serve")
        raise InputError(f"{name}: {shown}, which must be <= {limit:g} ({why})")
