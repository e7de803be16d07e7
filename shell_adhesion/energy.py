"""Maugis' energy ("graphical") method on loading and relaxation paths.

Dimensionless throughout: lengths / R, forces / (C10 R^2), energies / (C10 R^3),
gamma / (C10 R).  For each held contact radius a, U_E(a, delta) is a quintic Hermite
spline in delta through U_E, P = dU_E/ddelta and dP/ddelta at every state (its
delta-derivative is P_rel exactly; error O(step^6), so a path needs few states).  G(A, delta) = dU_E/dA at fixed
delta is the central difference between neighbouring paths, which is second-order
accurate at the midpoint in A = pi a^2 of the pair and needs only the two paths to
overlap in delta.  G does not depend on gamma, so it is built once per shell; every gamma
is then a root search along each pair (equilibrium G = gamma) and a smooth interpolation
of the equilibrium curve in a (pull-off points are extrema of smooth curves, not nodes).
"""
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import BPoly, CubicSpline


class OutOfRange(ValueError):
    """The requested gamma is outside what the stored paths cover."""


class NotBracketed(OutOfRange):
    """The equilibrium curve does not bracket the pull-off: it is still falling at its end
    `a_end` / R on the `side` "large" (the pull-off lies beyond the largest contact radius
    relaxed: load deeper) or "small"; or (`few`) too few paths reach equilibrium."""

    def __init__(self, text, side="large", a_end=float("nan"), few=False):
        super().__init__(text)
        self.side, self.a_end, self.few = side, a_end, few


class InGradedZone(OutOfRange):
    """A pull-off radius `a` / R lies beyond `limit` / R, where the mesh's elements grow."""

    def __init__(self, text, a, limit):
        super().__init__(text)
        self.a, self.limit = a, limit


class Bridged(OutOfRange):
    """Near a pull-off radius, the pairs of paths at `a_pairs` / R stopped before G
    reached gamma: the equilibrium curve is bridged there."""

    def __init__(self, text, a_pairs):
        super().__init__(text)
        self.a_pairs = tuple(a_pairs)


def hermite_quintic(x, y, dy, d2y) -> BPoly:
    """The piecewise quintic through y and its first two derivatives at increasing x
    (Bernstein coefficients of each interval from the end values, as
    BPoly.from_derivatives gives them, for all intervals at once)."""
    x, y, dy, d2y = (np.asarray(v, dtype=float) for v in (x, y, dy, d2y))
    h = np.diff(x)
    c = np.empty((6, len(h)))
    c[0], c[5] = y[:-1], y[1:]
    c[1] = y[:-1] + h * dy[:-1] / 5
    c[4] = y[1:] - h * dy[1:] / 5
    c[2] = y[:-1] + 2 * h * dy[:-1] / 5 + h ** 2 * d2y[:-1] / 20
    c[3] = y[1:] - 2 * h * dy[1:] / 5 + h ** 2 * d2y[1:] / 20
    return BPoly(c, x)


@dataclass(frozen=True, eq=False)
class EnergySurface:
    a: np.ndarray          # (n,) held contact radii (deformed), increasing
    delta1: np.ndarray     # (n,) loaded state of each path
    P1: np.ndarray
    delta_lo: np.ndarray   # (n,) lowest delta reached by each path
    splines: tuple         # U_E(delta) per path
    grid: np.ndarray       # (m,) delta grid
    a_pair: np.ndarray     # (n-1,) radius of the midpoint in A of paths k and k+1
    G: np.ndarray          # (n-1, m) dU_E/dA at a_pair, NaN where the pair does not overlap

    @property
    def A(self):
        return np.pi * self.a ** 2

    def U_E(self, k, delta):
        return self.splines[k](delta)

    def P_rel(self, k, delta):
        return self.splines[k](delta, 1)

    def P_pair(self, k, delta):
        """P at the pair midpoint (mean of the two paths: second order in A)."""
        return 0.5 * (self.P_rel(k, delta) + self.P_rel(k + 1, delta))


def energy_surface(paths, n_grid=2000) -> EnergySurface:
    """Build U_E(a, delta) and G(a, delta) from relaxation paths of increasing a.

    `paths` is a sequence of (a, delta[], P[], U[], dP_ddelta[]) with delta decreasing
    from delta1.
    """
    a = np.array([p[0] for p in paths])
    if np.any(np.diff(a) <= 0):
        raise ValueError("relaxation paths must have increasing contact radii")
    splines, lo, d1, P1 = [], [], [], []
    for _, delta, P, U, dP in paths:
        order = np.argsort(delta)
        splines.append(hermite_quintic(delta[order], U[order], P[order], dP[order]))
        lo.append(delta.min())
        d1.append(delta[0])
        P1.append(P[0])
    lo, d1 = np.array(lo), np.array(d1)
    grid = np.linspace(lo.min(), d1.max(), n_grid)
    U = np.full((len(a), n_grid), np.nan)
    for k, spl in enumerate(splines):
        inside = (grid >= lo[k]) & (grid <= d1[k])
        U[k, inside] = spl(grid[inside])
    A = np.pi * a ** 2
    G = (U[1:] - U[:-1]) / np.diff(A)[:, None]
    a_pair = np.sqrt(0.5 * (A[1:] + A[:-1]) / np.pi)
    return EnergySurface(a, d1, np.array(P1), lo, tuple(splines), grid, a_pair, G)


@dataclass(frozen=True, eq=False)
class Equilibrium:
    """Equilibrium curve G = gamma: one point per pair of neighbouring contact radii."""

    gamma: float
    a: np.ndarray
    delta: np.ndarray
    P: np.ndarray
    stable_fixed_load: np.ndarray   # dP/da > 0 along the curve
    stable_fixed_grips: np.ndarray  # d(delta)/da > 0 along the curve


@dataclass(frozen=True)
class PullOff:
    gamma: float
    P_star: float
    delta_star: float
    a_star: float
    P_dagger: float
    delta_dagger: float
    a_dagger: float
    a0: float
    note: str = ""      # why the fixed-grips values are NaN while the fixed-load ones are given


def equilibrium(surface: EnergySurface, gamma: float) -> Equilibrium:
    """Points (a, delta, P) where G = gamma, one per pair of neighbouring paths, the first
    reached when delta is lowered from the pair's loaded states."""
    a, dl, Pl = [], [], []
    grid = surface.grid
    for k in range(len(surface.a_pair)):
        g = surface.G[k]
        ok = np.flatnonzero(~np.isnan(g))
        if len(ok) < 2:
            continue
        gk, xk = g[ok][::-1], grid[ok][::-1]        # from delta1 downward
        above = np.flatnonzero(gk >= gamma)
        if len(above) == 0 or above[0] == 0:
            continue
        j = above[0]
        t = (gamma - gk[j - 1]) / (gk[j] - gk[j - 1])
        delta = xk[j - 1] + t * (xk[j] - xk[j - 1])
        a.append(surface.a_pair[k])
        dl.append(delta)
        Pl.append(float(surface.P_pair(k, delta)))
    a, dl, Pl = map(np.array, (a, dl, Pl))
    if len(a) < 4:
        raise NotBracketed(f"gamma/(C10 R) = {gamma:g}: fewer than 4 relaxation paths reach "
                           "equilibrium; the paths are too short for this gamma", few=True)
    sP, sd = CubicSpline(a, Pl), CubicSpline(a, dl)
    return Equilibrium(gamma, a, dl, Pl, sP(a, 1) > 0, sd(a, 1) > 0)


def _interior_min(x, y):
    """(x, y) of the lowest interior local minimum of the cubic spline through (x, y)."""
    s = CubicSpline(x, y)
    crit = s.derivative().roots(extrapolate=False)
    crit = crit[(crit > x[0]) & (crit < x[-1]) & (s(crit, 2) > 0)]
    if len(crit) == 0:
        return None
    best = crit[np.argmin(s(crit))]
    return float(best), float(s(best))


def pull_off(eq: Equilibrium) -> PullOff:
    """Fixed-load (min P) and fixed-grips (min delta) pull-off, and a0 (P = 0).

    Each is the lowest interior minimum of the curve, and it must lie below both ends of
    the curve: where an end is lower, the curve is still falling there, so the true
    pull-off lies beyond the contact radii the paths reach (a local dip inside, e.g. from
    noise, would otherwise be returned as the pull-off).
    """
    star = _interior_min(eq.a, eq.P)
    dagger = _interior_min(eq.a, eq.delta)
    if star is None or dagger is None:
        y = eq.P if star is None else eq.delta
        side = "large" if y[-1] <= y[0] else "small"
        raise NotBracketed(f"gamma/(C10 R) = {eq.gamma:g}: pull-off is not bracketed by the "
                           f"equilibrium curve (a from {eq.a[0]:.4g} to {eq.a[-1]:.4g} R)",
                           side, eq.a[-1] if side == "large" else eq.a[0])
    for name, y, (_, low) in (("P", eq.P, star), ("delta", eq.delta, dagger)):
        if min(y[0], y[-1]) < low:
            side = "small" if y[0] < y[-1] else "large"
            end = eq.a[0] if side == "small" else eq.a[-1]
            raise NotBracketed(f"gamma/(C10 R) = {eq.gamma:g}: the equilibrium curve's "
                               f"{name} is still falling at its end a = {end:.4g} R, below its "
                               f"lowest interior minimum: the pull-off lies beyond the contact "
                               f"radii reached", side, end)
    sP, sd = CubicSpline(eq.a, eq.P), CubicSpline(eq.a, eq.delta)
    zeros = sP.roots(extrapolate=False)
    zeros = zeros[zeros > star[0]]
    a0 = float(zeros.min()) if len(zeros) else np.nan
    return PullOff(eq.gamma, star[1], float(sd(star[0])), star[0],
                   float(sP(dagger[0])), dagger[1], dagger[0], a0)


def total_energy_fixed_load(surface: EnergySurface, gamma: float, P: float):
    """U_T(A; P) = U_E - P delta - gamma A on each path where P_rel reaches P: (A, U_T)."""
    A, UT = [], []
    for k in range(len(surface.a)):
        lo, hi = surface.delta_lo[k], surface.delta1[k]
        d = np.linspace(lo, hi, 400)
        Pk = surface.P_rel(k, d)
        if not (Pk.min() <= P <= Pk.max()):
            continue
        j = np.argmin(np.abs(Pk - P))
        # Newton polish on the Hermite spline
        dj = d[j]
        for _ in range(5):
            dj -= (surface.P_rel(k, dj) - P) / surface.splines[k](dj, 2)
        A.append(surface.A[k])
        UT.append(float(surface.U_E(k, dj) - P * dj - gamma * surface.A[k]))
    return np.array(A), np.array(UT)


def total_energy_fixed_grips(surface: EnergySurface, gamma: float, delta: float):
    """U_T(A; delta) = U_E - gamma A on each path whose range holds delta: (A, U_T)."""
    k = np.flatnonzero((surface.delta_lo <= delta) & (surface.delta1 >= delta))
    U = np.array([surface.U_E(i, delta) for i in k])
    return surface.A[k], U - gamma * surface.A[k]
