"""Maugis-Dugdale adhesion of an elastic sphere on a rigid flat (Maugis 1992), closed form.

Small-strain half-space theory, in Maugis' units (all dimensionless):

    A = a (K / (pi gamma R^2))^(1/3)            contact radius
    Pbar = P / (pi gamma R)                     load, > 0 compression
    Dbar = delta (K^2 / (pi^2 gamma^2 R))^(1/3) approach, > 0 towards the flat
    lambda = 2 sigma0 (R / (pi gamma K^2))^(1/3)  Tabor-Maugis parameter
    m = c / a > 1                               c: outer edge of the cohesive (Dugdale) zone

with K = 4 E* / 3 (E* = 8 C10 for the incompressible neo-Hookean solid).  The Dugdale law
pulls with sigma0 wherever the gap is below delta_c = gamma / sigma0.  With
s = sqrt(m^2 - 1) and T = atan(s), each m gives one equilibrium state:

    (lambda A^2 / 2) [s + (m^2 - 2) T] + (4 lambda^2 A / 3) [s T - m + 1] = 1
    Pbar = A^3 - lambda A^2 [s + m^2 T]
    Dbar = A^2 - (4/3) lambda A s

The first is a quadratic in A with one positive root.  The fixed-load pull-off Pbar* is the
minimum of Pbar along the curve: -2 (DMT, lambda -> 0) to -1.5 (JKR, lambda -> infinity).
"""
from dataclasses import dataclass
import math

import numpy as np
from scipy.optimize import minimize_scalar

# the curve is scanned over log10(m - 1) in this range (then refined): m - 1 = 1e-9 is
# deep in the JKR-like branch (A large), 1e9 the DMT-like one (A -> 0)
LOG_M1_RANGE = (-9.0, 9.0)
SCAN_POINTS = 721


@dataclass(frozen=True)
class MDState:
    """One Maugis-Dugdale equilibrium state, in Maugis' units."""

    m: float       # c / a
    A: float       # contact radius
    P: float       # Pbar, > 0 compression
    D: float       # Dbar, > 0 approach

    @property
    def C(self) -> float:
        """Edge of the cohesive zone, c in the units of A."""
        return self.m * self.A


def _check_lambda(lam):
    if not (math.isfinite(lam) and lam > 0):
        raise ValueError(f"lambda: {lam!r} must be a finite number > 0")


def state(lam: float, m: float) -> MDState:
    """The equilibrium state of Tabor parameter `lam` with c / a = m (> 1)."""
    _check_lambda(lam)
    if not (math.isfinite(m) and m > 1):
        raise ValueError(f"m = c/a: {m!r} must be a finite number > 1")
    # s and m - 1 from m^2 - 1 = (m - 1)(m + 1): no cancellation near m = 1
    s = math.sqrt((m - 1.0) * (m + 1.0))
    T = math.atan(s)
    # s + (s^2 - 1) atan(s) cancels to (4/3) s^3 at small s: its series there
    S1 = s + (m * m - 2.0) * T if s > 1e-2 else _s1_series(s)
    S2 = s * T - (m - 1.0)
    alpha, beta = 0.5 * lam * S1, 4.0 / 3.0 * lam * lam * S2
    # positive root of alpha A^2 + beta A - 1 = 0, in the form without cancellation
    A = 2.0 / (beta + math.sqrt(beta * beta + 4.0 * alpha))
    P = A ** 3 - lam * A * A * (s + m * m * T)
    D = A * A - 4.0 / 3.0 * lam * A * s
    return MDState(m, A, P, D)


def _s1_series(s):
    """s + (s^2 - 1) atan(s) = (4/3) s^3 - (8/15) s^5 + (12/35) s^7 - ... (s < 1e-2:
    relative error below 1e-11)."""
    s2 = s * s
    return s * s2 * (4.0 / 3.0 - s2 * (8.0 / 15.0 - s2 * 12.0 / 35.0))


def curve(lam: float, log_m1=None) -> list:
    """The equilibrium curve: states at m = 1 + 10**log_m1 (default: the scan grid)."""
    if log_m1 is None:
        log_m1 = np.linspace(*LOG_M1_RANGE, SCAN_POINTS)
    return [state(lam, 1.0 + 10.0 ** q) for q in log_m1]


def pull_off(lam: float) -> MDState:
    """The fixed-load pull-off: the state of least Pbar (most tensile load).

    A scan of the curve brackets the minimum, a bounded Brent search refines it (at most
    200 evaluations).  A minimum at the end of the scan (A -> 0, the DMT limit at tiny
    lambda) is returned as found there.
    """
    _check_lambda(lam)
    q = np.linspace(*LOG_M1_RANGE, SCAN_POINTS)
    P = np.array([s.P for s in curve(lam, q)])
    if not np.all(np.isfinite(P)):
        raise ArithmeticError(f"Maugis-Dugdale curve not finite at lambda = {lam:g}")
    i = int(np.argmin(P))
    if i in (0, len(q) - 1):
        return state(lam, 1.0 + 10.0 ** q[i])
    res = minimize_scalar(lambda u: state(lam, 1.0 + 10.0 ** u).P,
                          bounds=(q[i - 1], q[i + 1]), method="bounded",
                          options=dict(xatol=1e-10, maxiter=200))
    best = state(lam, 1.0 + 10.0 ** res.x)
    return best if best.P <= P[i] else state(lam, 1.0 + 10.0 ** q[i])


def tabor_parameter(sigma0, gamma, R, K):
    """lambda = 2 sigma0 (R / (pi gamma K^2))^(1/3) in any consistent units (e.g. MPa,
    N/mm, mm, MPa; or the solver's C10, C10 R, R, C10)."""
    return 2.0 * sigma0 * (R / (math.pi * gamma * K * K)) ** (1.0 / 3.0)


def sigma0_of(lam, gamma, R, K):
    """The cohesive stress sigma0 of Tabor parameter `lam` (units as `tabor_parameter`)."""
    return 0.5 * lam * (math.pi * gamma * K * K / R) ** (1.0 / 3.0)


def scales(gamma, R, K) -> dict:
    """Maugis' units in the units of the inputs: a = A * length, delta = Dbar * approach,
    P = Pbar * force."""
    return dict(length=(math.pi * gamma * R * R / K) ** (1.0 / 3.0),
                approach=(math.pi ** 2 * gamma ** 2 * R / K ** 2) ** (1.0 / 3.0),
                force=math.pi * gamma * R)


def zero_range(lambdas, P):
    """The zero-range (JKR-like) limit P0 of pull-offs P at Tabor parameters `lambdas`
    (any force unit), under P = P0 + C / lambda^2 (a sphere's Maugis-Dugdale excess over
    JKR falls so: lambda^2 times it is 10.06, 10.41, 10.58 % at lambda 3, 4, 5):
    (P0 from the two largest lambdas, P0 by least squares over all of them)."""
    lam = np.asarray(lambdas, dtype=float)
    P = np.asarray(P, dtype=float)
    if lam.shape != P.shape or len(lam) < 2 or len(set(lam.tolist())) < 2:
        raise ValueError(f"zero_range: needs at least two distinct lambdas with one P each "
                         f"(got lambdas {lam.tolist()}, P {P.tolist()})")
    order = np.argsort(lam)
    l1, l2 = lam[order[-2:]]
    p1, p2 = P[order[-2:]]
    two = (l2 ** 2 * p2 - l1 ** 2 * p1) / (l2 ** 2 - l1 ** 2)
    A = np.column_stack([np.ones_like(lam), lam ** -2.0])
    return float(two), float(np.linalg.lstsq(A, P, rcond=None)[0][0])
