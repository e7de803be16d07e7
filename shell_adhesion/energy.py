"""Maugis' energy ("graphical") method on loading and relaxation paths.

Dimensionless throughout: lengths / R, forces / (C10 R^2), energies / (C10 R^3),
gamma / (C10 R).  For each held set k (the contact zone of one loading state),
U_E(delta) is a quintic Hermite spline in delta through U_E, P = dU_E/ddelta and
dP/ddelta at every state (its delta-derivative is P_rel exactly; error O(step^6)), and the
area it covers, A_k(delta) = pi r_k(delta)^2, is a cubic Hermite spline through the held
edge's deformed radius r_k and its slope (DESIGN.md section 10).  Where the held nodes
cannot slide (no_slip) r_k is the loading state's a; frictionless, the edge slides.

The total potential of held set k is Pi_k(delta) = U_E(delta) - gamma A_k(delta) (fixed
grips; - P delta more at fixed load).  Its -gamma A_k pulls a sliding edge outward (the
adhesive edge force); the paths are relaxed without it, and it is taken to second order
in gamma through the covered area's compliance c_k(delta) = dA/dgamma each frictionless
path records (solver.edge, a cubic spline in delta): the state of gamma covers
A_k + gamma c_k and Pi_k = U_E - gamma A_k - gamma^2 c_k / 2.  G(A, delta) = dU_E/dA at
fixed delta, of the states of gamma, is the difference between neighbouring held sets at
the same delta, second-order accurate at the midpoint in A (without compliances it does
not depend on gamma and is built once per shell).  Equilibrium is G = gamma; there P =
dPi/ddelta and a is the covered radius at that delta.  Every gamma is then a root search
along each pair and a smooth interpolation of the equilibrium curve in a (pull-off points
are extrema of smooth curves, not nodes).
"""
from dataclasses import dataclass, replace

import numpy as np
from scipy.interpolate import BPoly, CubicHermiteSpline, CubicSpline


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
    a: np.ndarray          # (n,) held contact radii (deformed, at the loaded state), increasing
    delta1: np.ndarray     # (n,) loaded state of each path
    P1: np.ndarray
    delta_lo: np.ndarray   # (n,) lowest delta reached by each path
    splines: tuple         # Pi_e(delta) = U_E - gamma_e A per path (its own P, dP/ddelta)
    grid: np.ndarray       # (m,) delta grid
    a_pair: np.ndarray     # (n-1,) radius of the midpoint in A of paths k and k+1 (loaded)
    G: np.ndarray          # (n-1, m) dU_E/dA at fixed delta, A the areas covered at that
    #                        delta; NaN where the pair does not overlap
    edges: tuple = ()      # r_k(delta) per path: the held edge's deformed radius (the
    #                        covered radius); () where no path's edge moves
    gamma_edge: np.ndarray = None   # (n,) gamma_e each path was relaxed with (solver.edge)
    compliances: tuple = ()         # c_k(delta) = dA/dgamma per path (solver.edge: the
    #                                 second order); () where no edge slides
    grids: tuple = ()      # (Pi_e, A, c) of every path on `grid` (n, m), NaN outside it

    @property
    def A(self):
        return np.pi * self.a ** 2

    def _g(self, k):
        return 0.0 if self.gamma_edge is None else float(self.gamma_edge[k])

    def A_covered(self, k, delta, order=0, gamma=None):
        """The area held set k covers at delta in its state of gamma (None: the gamma_e
        it was relaxed with), pi r_k(delta)^2 + (gamma - gamma_e) c_k(delta), or its
        `order`-th derivative in delta (1, 2)."""
        if not self.edges:
            return np.full(np.shape(delta), self.A[k] if order == 0 else 0.0)[()]
        e = self.edges[k]
        if order == 0:
            A = np.pi * e(delta) ** 2
        elif order == 1:
            A = 2 * np.pi * e(delta) * e(delta, 1)
        else:
            A = 2 * np.pi * (e(delta, 1) ** 2 + e(delta) * e(delta, 2))
        if gamma is None or not self.compliances:
            return A
        return A + (gamma - self._g(k)) * self.compliances[k](delta, order)

    def Pi(self, k, delta, gamma=0.0, order=0):
        """Pi = U_E - gamma A of held set k at delta (fixed grips), or its `order`-th
        derivative in delta: order 1 is P = P_rel - gamma dA/ddelta - ..., the rim force
        with the adhesive edge force of a sliding edge (exact at the path's own gamma_e;
        elsewhere to second order in gamma - gamma_e where the paths carry their
        compliances c = dA/dgamma: - (gamma - gamma_e)^2 c / 2, else to first)."""
        out = (self.splines[k](delta, order)
               + (self._g(k) - gamma) * self.A_covered(k, delta, order))
        if self.compliances:
            out = out - 0.5 * (gamma - self._g(k)) ** 2 * self.compliances[k](delta, order)
        return out

    def G_at(self, gamma: float) -> np.ndarray:
        """(n-1, m) G on `grid` of the states of gamma: dU_E/dA at fixed delta between
        neighbouring held sets, U_E and A those of the states of gamma (second order:
        they move with gamma where the edges slide); `G` itself without compliances."""
        if not self.compliances:
            return self.G
        Pi_e, A_e, c = self.grids
        step = gamma - np.asarray(self.gamma_edge)[:, None]
        A = A_e + step * c
        U = Pi_e - step * A_e - 0.5 * step ** 2 * c + gamma * A
        return (U[1:] - U[:-1]) / (A[1:] - A[:-1])

    def U_E(self, k, delta):
        return self.Pi(k, delta)

    def P_pair(self, k, delta, gamma=0.0):
        """P = dPi/ddelta at the pair midpoint (mean of the two paths: second order in A)."""
        return 0.5 * (self.Pi(k, delta, gamma, 1) + self.Pi(k + 1, delta, gamma, 1))

    def a_pair_at(self, k, delta, gamma=None):
        """Covered radius of the pair's midpoint in A at delta (in the states of gamma;
        None: as relaxed)."""
        return np.sqrt(0.5 * (self.A_covered(k, delta, 0, gamma)
                              + self.A_covered(k + 1, delta, 0, gamma)) / np.pi)


def energy_surface(paths, n_grid=2000) -> EnergySurface:
    """Build U_E(a, delta) and G(a, delta) from relaxation paths of increasing a.

    `paths` is a sequence of (a, delta[], P[], U[], dP_ddelta[]) with delta decreasing
    from delta1, each optionally followed by (a_edge[], da_edge_ddelta[], gamma_e): the held
    edge's deformed radius along the path, its slope and the gamma / (C10 R) of the edge
    force the path was relaxed with (its U is then U_E - gamma_e pi a_edge^2 and its P
    includes that force; absent: the edge stays at a, gamma_e = 0), and (dA_dgamma[]): the
    covered area's compliance along the path (solver.edge; absent or all 0: the energy
    method is first order in gamma - gamma_e).
    """
    a = np.array([p[0] for p in paths])
    if np.any(np.diff(a) <= 0):
        raise ValueError("relaxation paths must have increasing contact radii")
    splines, edges, lo, d1, P1, comply = [], [], [], [], [], []
    for path in paths:
        _, delta, P, U, dP = path[:5]
        order = np.argsort(delta)
        splines.append(hermite_quintic(delta[order], U[order], P[order], dP[order]))
        if len(path) > 5:
            r, dr = (np.asarray(v, dtype=float)[order] for v in path[5:7])
            edges.append(CubicHermiteSpline(delta[order], r, dr) if len(r) > 1 else None)
        if len(path) > 8 and len(delta) > 1:
            comply.append(CubicSpline(delta[order], np.asarray(path[8], dtype=float)[order]))
        lo.append(delta.min())
        d1.append(delta[0])
        P1.append(P[0])
    gamma_edge = np.array([float(p[7]) if len(p) > 7 else 0.0 for p in paths])
    moves = any(np.any(np.asarray(p[6]) != 0) for p in paths if len(p) > 5)
    if not moves or any(e is None for e in edges) or len(edges) != len(paths):
        if np.any(gamma_edge > 0):
            raise ValueError("paths relaxed with an edge force need their edge radii")
        edges = []
    if not edges or len(comply) != len(paths) or not any(np.any(np.asarray(p[8]) != 0)
                                                         for p in paths if len(p) > 8):
        comply = []
    lo, d1 = np.array(lo), np.array(d1)
    surface = EnergySurface(a, d1, np.array(P1), lo, tuple(splines), np.zeros(0),
                            np.zeros(0), np.zeros((0, 0)), tuple(edges), gamma_edge,
                            tuple(comply))
    grid = np.linspace(lo.min(), d1.max(), n_grid)
    Pi_e, A, c = (np.full((len(a), n_grid), np.nan) for _ in range(3))
    for k in range(len(a)):
        inside = (grid >= lo[k]) & (grid <= d1[k])
        Pi_e[k, inside] = splines[k](grid[inside])
        A[k, inside] = surface.A_covered(k, grid[inside])
        c[k, inside] = comply[k](grid[inside]) if comply else 0.0
    A_loaded = np.pi * a ** 2
    a_pair = np.sqrt(0.5 * (A_loaded[1:] + A_loaded[:-1]) / np.pi)
    surface = replace(surface, grid=grid, a_pair=a_pair, grids=(Pi_e, A, c))
    if not comply:      # U_E = Pi_e + gamma_e A: G does not depend on gamma
        U = Pi_e + gamma_edge[:, None] * A
        return replace(surface, G=(U[1:] - U[:-1]) / (A[1:] - A[:-1]))
    return replace(surface, G=surface.G_at(0.0))


@dataclass(frozen=True, eq=False)
class Equilibrium:
    """Equilibrium curve G = gamma: one point per pair of neighbouring contact radii."""

    gamma: float
    a: np.ndarray
    delta: np.ndarray
    P: np.ndarray
    stable_fixed_load: np.ndarray   # dP/da > 0 along the curve
    stable_fixed_grips: np.ndarray  # d(delta)/da > 0 along the curve
    growth: np.ndarray = None       # (A_gamma - A_0) / A_0 of each point: how far the edge
    #                                 force moves the covered area (second order; 0: none)


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
    edge_growth: float = 0.0    # Equilibrium.growth at a*


def equilibrium(surface: EnergySurface, gamma: float) -> Equilibrium:
    """Points (a, delta, P) where G = gamma, one per pair of neighbouring paths, the first
    reached when delta is lowered from the pair's loaded states."""
    a, dl, Pl, grow = [], [], [], []
    grid = surface.grid
    G = surface.G_at(gamma)
    for k in range(len(surface.a_pair)):
        g = G[k]
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
        a.append(float(surface.a_pair_at(k, delta, gamma)))
        dl.append(delta)
        Pl.append(float(surface.P_pair(k, delta, gamma)))
        grow.append(float(surface.a_pair_at(k, delta, gamma) ** 2
                          / surface.a_pair_at(k, delta, 0.0) ** 2 - 1))
    a, dl, Pl, grow = map(np.array, (a, dl, Pl, grow))
    if len(a) < 4:
        raise NotBracketed(f"gamma/(C10 R) = {gamma:g}: fewer than 4 relaxation paths reach "
                           "equilibrium; the paths are too short for this gamma", few=True)
    if np.any(np.diff(a) <= 0):     # no deeper loading or longer path mends this
        raise OutOfRange(f"gamma/(C10 R) = {gamma:g}: the covered radii of the equilibrium "
                         "points are not increasing: the held edges slide past each other")
    sP, sd = CubicSpline(a, Pl), CubicSpline(a, dl)
    return Equilibrium(gamma, a, dl, Pl, sP(a, 1) > 0, sd(a, 1) > 0, grow)


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
    growth = 0.0 if eq.growth is None else float(np.interp(star[0], eq.a, eq.growth))
    return PullOff(eq.gamma, star[1], float(sd(star[0])), star[0],
                   float(sP(dagger[0])), dagger[1], dagger[0], a0, edge_growth=growth)


def total_energy_fixed_load(surface: EnergySurface, gamma: float, P: float):
    """U_T(A; P) = U_E - P delta - gamma A on each path where its P (EnergySurface.Pi)
    reaches P: (A, U_T), A the area covered there."""
    A, UT = [], []
    for k in range(len(surface.a)):
        lo, hi = surface.delta_lo[k], surface.delta1[k]
        d = np.linspace(lo, hi, 400)
        Pk = surface.Pi(k, d, gamma, 1)
        if not (Pk.min() <= P <= Pk.max()):
            continue
        dj = d[np.argmin(np.abs(Pk - P))]
        for _ in range(5):      # Newton polish on the splines
            dj -= (surface.Pi(k, dj, gamma, 1) - P) / surface.Pi(k, dj, gamma, 2)
        A.append(float(surface.A_covered(k, dj, 0, gamma)))
        UT.append(float(surface.Pi(k, dj, gamma) - P * dj))
    return np.array(A), np.array(UT)


def total_energy_fixed_grips(surface: EnergySurface, gamma: float, delta: float):
    """U_T(A; delta) = U_E - gamma A on each path whose range holds delta: (A, U_T), A the
    area covered at delta."""
    k = np.flatnonzero((surface.delta_lo <= delta) & (surface.delta1 >= delta))
    A = np.array([surface.A_covered(i, delta, 0, gamma) for i in k], dtype=float)
    return A, np.array([surface.Pi(i, delta, gamma) for i in k], dtype=float)
