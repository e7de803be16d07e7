"""Fitting the FE paths of one shell to a request (DESIGN.md section 9).

A request is what a set of paths must answer: every gamma / (C10 R) of a ladder up to the
largest asked (`Request.serving`: another C10, R or a nearby gamma shares the set) and,
optionally, an explicit deepest loading delta_max / R.  From it follow, before any FE solve
(`initial_fit`):
- the evenly meshed zone: it must hold every pull-off radius (a*, a_dagger) with its
  curve's support, since beyond it the grading biases G in a way the error bar cannot see
  (`even_arc`, from `a_star_estimate`, a measured table);
- the loading depth: without an explicit delta_max the loading goes on to the contact
  radius the pull-offs need (TURN x the estimate of a*), bounded by
  solver.geometry.delta_bound (the domain's delta bound for the shell, below the cap's
  depth).
After a solve, `next_fit` reads what the paths answer and says what to do once more, if
anything: load deeper (a curve still falling at its large-a end), mesh evenly further (a
pull-off radius beyond UNIFORM_SHARE of the even zone) or relax further (a pair of paths
near a pull-off stopped before G reached gamma).  Each is bounded (MAX_ROUNDS, MAX_REMESH,
MAX_REACH), so the loop ends whatever the paths do.  `solve_request` runs the loop in one
process; a study runs the same steps as dask tasks (study.run.compute).

Dimensionless: lengths / R, gamma / (C10 R).  Pure functions (no files, no printing).
"""
from dataclasses import dataclass, field, replace
import math

import numpy as np

from .case import UNIFORM_SHARE, PathSet, solve_paths, start_key
from .cavity import OPEN, Cavity
from shell_adhesion.energy import Bridged, InGradedZone, NotBracketed, OutOfRange
from .geometry import GAMMA_MAX, Cap, delta_bound
from .material import NEO_HOOKE, Material
from .mesh import mesh_spec
from .path import Settings

# The contact radius a* of the fixed-load pull-off over JKR's, (9 pi gamma / 64)^(1/3) R for
# a solid hemisphere (E* = 8 C10), measured on the coarse mesh with the cap meshed evenly
# and loaded deep (benchmarks/a_star_survey.py), rounded up: rows t / R (A_STAR_T), then
# h / R (A_STAR_H: <= 0.35, 0.5, 1), columns gamma / (C10 R) (A_STAR_G).  A shell's a*
# jumps to a larger contact radius above a gamma that falls with t (a second minimum of
# P along the equilibrium curve: t/R 0.1 between 0.002 and 0.005, 0.15 between 0.01 and
# 0.015), so the estimate takes the largest ratio of the bracketing rows in t and columns
# in gamma (linear in h) and A_STAR_MARGIN over it (`a_star_estimate`).
A_STAR_T = (0.02, 0.05, 0.1, 0.125, 0.15, 0.175, 0.2, 0.25, 0.35, 0.5, 1.0)
A_STAR_H = (0.3, 0.5, 1.0)
A_STAR_G = (0.001, 0.002, 0.005, 0.01, 0.015, 0.02, 0.03)
A_STAR_RATIO = (
    ((5.0, 4.35, 3.51, 2.95, 2.65, 2.46, 2.2), (5.41, 5.28, 4.89, 4.26, 3.88, 3.62, 3.27),
     (5.38, 5.14, 4.71, 4.41, 3.88, 3.62, 3.27)),
    ((2.3, 1.91, 2.56, 2.31, 2.17, 2.1, 2.13), (2.95, 3.3, 3.53, 3.44, 3.26, 3.11, 2.88),
     (2.95, 3.26, 3.37, 3.29, 3.22, 3.11, 2.88)),
    ((0.76, 0.76, 2.14, 1.74, 1.84, 1.83, 1.72), (0.73, 0.71, 1.88, 2.22, 2.28, 2.28, 2.22),
     (0.72, 0.7, 1.79, 2.15, 2.24, 2.28, 2.33)),
    ((0.8, 0.77, 0.83, 1.52, 1.69, 1.74, 1.76), (0.79, 0.75, 0.78, 1.64, 1.87, 1.93, 1.95),
     (0.8, 0.75, 0.76, 1.54, 1.84, 1.94, 2.03)),
    ((0.87, 0.83, 0.81, 1.01, 1.37, 1.52, 1.61), (0.85, 0.8, 0.77, 0.9, 1.33, 1.56, 1.7),
     (0.84, 0.79, 0.76, 0.83, 1.19, 1.5, 1.74)),
    ((0.91, 0.88, 0.84, 0.89, 1.07, 1.28, 1.45), (0.89, 0.85, 0.81, 0.81, 0.91, 1.12, 1.4),
     (0.89, 0.85, 0.79, 0.79, 0.84, 0.99, 1.33)),
    ((0.99, 1.0, 1.02, 1.04, 1.04, 1.04, 1.12), (0.92, 0.89, 0.84, 0.83, 0.85, 0.9, 1.12),
     (0.92, 0.88, 0.82, 0.8, 0.8, 0.83, 0.99)),
    ((0.98, 0.97, 0.97, 0.98, 1.01, 1.04, 1.1), (0.97, 0.95, 0.91, 0.88, 0.88, 0.88, 0.92),
     (0.95, 0.93, 0.89, 0.85, 0.84, 0.83, 0.85)),
    ((0.99, 0.99, 0.98, 0.97, 0.96, 0.96, 0.97), (0.99, 0.99, 0.98, 0.97, 0.96, 0.96, 0.97),
     (0.99, 0.98, 0.96, 0.94, 0.93, 0.92, 0.9)),
    ((0.99, 0.99, 1.0, 1.01, 1.01, 1.02, 1.03), (0.99, 0.99, 1.0, 1.01, 1.01, 1.02, 1.03),
     (0.99, 0.99, 0.99, 0.98, 0.98, 0.98, 0.97)),
    ((1.0, 1.01, 1.02, 1.02, 1.01, 1.0, 0.99), (1.0, 1.0, 1.01, 1.01, 1.02, 1.02, 1.03),
     (1.0, 1.01, 1.02, 1.02, 1.02, 1.02, 1.03)),
)
A_STAR_MARGIN = 1.1     # over the measured ratio (the default mesh's a* differs by < 2 %)
A_MARGIN = 1.15         # the even zone holds a_need * A_MARGIN within UNIFORM_SHARE of it
TURN = 1.3              # the loading goes on to TURN x the pull-off radius (the curve turns)
DEEPER = 1.4            # a loading that did not reach that goes on to DEEPER x its end
TURN_POINTS = 3         # and at least this many equilibrium points beyond a*
MAX_ROUNDS = 5          # solves of one request in all
MAX_REMESH = 2          # re-meshings (each a new solve of every path)
MAX_REACH = 2           # times one path is relaxed further
REACH_FACTOR = 3.0      # how much further each time (its stop rule's G x REACH_FACTOR)


LADDER = (1, 1.5, 2, 3, 5, 7)   # x 10^k: the gamma / (C10 R) a set of paths serves up to
_REL_TOL = 1e-9
GAMMA_FLOOR = 1e-4      # a set is fitted to the ladder's values from its top down to this


def gamma_bucket(g: float) -> float:
    """The smallest value of LADDER x 10^k that is >= g (to 1e-9 relative): the gamma /
    (C10 R) the paths of a request for g serve up to, so that nearby requests (another C10
    or R, a nearby gamma) share one set of paths."""
    if not (math.isfinite(g) and g > 0):
        raise ValueError(f"gamma/(C10 R) = {g!r} must be a finite number > 0")
    k = math.floor(math.log10(g)) - 1
    while True:
        for m in LADDER:
            v = float(f"{m}e{k}")
            if v >= g * (1 - _REL_TOL):
                return v
        k += 1


def ladder_gammas(top: float) -> tuple:
    """The gamma / (C10 R) values a set serving up to `top` is fitted to answer: the
    LADDER values from `top` (capped at the domain's GAMMA_MAX) down to GAMMA_FLOOR, and
    `top` itself (smaller gammas pull off at smaller contact radii still, JKR-like)."""
    top = min(top, GAMMA_MAX)
    floor = min(GAMMA_FLOOR, top)
    out, k = {top}, math.floor(math.log10(top)) + 1
    while float(f"{LADDER[-1]}e{k}") >= floor * (1 - _REL_TOL):
        for m in LADDER:
            v = float(f"{m}e{k}")
            if floor * (1 - _REL_TOL) <= v <= top * (1 + _REL_TOL):
                out.add(v)
        k -= 1
    return tuple(sorted(out))


@dataclass(frozen=True)
class Request:
    """What one path set must answer: `gammas`, the gamma / (C10 R) asked (empty: the
    loading only), and `delta_max`, an explicit deepest delta / R (None: as deep as the
    gammas need, within `depth_bound`)."""

    gammas: tuple = ()
    delta_max: float = None

    @classmethod
    def serving(cls, gamma_max: float = None, delta_max: float = None) -> "Request":
        """The request of a set serving gammas up to `gamma_max` (None: the loading only):
        its ladder (`ladder_gammas`)."""
        return cls(() if gamma_max is None else ladder_gammas(gamma_max), delta_max)


@dataclass(frozen=True)
class Fit:
    """How the paths are fitted to a request: the mesh's even arc / R, the contact radius /
    R at which the loading ends (None: at delta_max), the depth bound delta_max / R, each
    path's reach beyond the default (start_key without reach -> reach), and the solves so
    far."""

    uniform: float
    a_stop: float
    delta_max: float
    reach: dict = field(default_factory=dict)
    rounds: int = 1
    remeshed: int = 0

    def reach_of(self, start) -> float:
        """The reach of the path from the loaded state `start` (relax_from)."""
        return self.reach.get(start_key(start)[:2], 1.0)


def rules() -> dict:
    """The constants of the fit (part of a stored set's identity)."""
    return dict(LADDER=list(LADDER), GAMMA_FLOOR=GAMMA_FLOOR, A_STAR_T=list(A_STAR_T),
                A_STAR_H=list(A_STAR_H), A_STAR_G=list(A_STAR_G),
                A_STAR_RATIO=np.array(A_STAR_RATIO).tolist(), A_STAR_MARGIN=A_STAR_MARGIN,
                A_MARGIN=A_MARGIN, TURN=TURN,
                DEEPER=DEEPER, TURN_POINTS=TURN_POINTS, MAX_ROUNDS=MAX_ROUNDS,
                MAX_REMESH=MAX_REMESH, MAX_REACH=MAX_REACH, REACH_FACTOR=REACH_FACTOR)


def a_jkr(gamma: float) -> float:
    """a* / R of JKR for a solid hemisphere of the incompressible neo-Hookean solid."""
    return (9 * math.pi * gamma / 64) ** (1 / 3)


def a_star_estimate(cap: Cap, gamma: float) -> float:
    """An upper estimate of the fixed-load pull-off radius a* / R of `cap` at gamma /
    (C10 R): a_jkr(gamma) times the largest A_STAR_RATIO of the table's rows bracketing
    t / R and columns bracketing gamma (linear in h / R), times A_STAR_MARGIN."""
    def bracket(grid, x):
        k = int(np.searchsorted(grid, x))
        if k < len(grid) and math.isclose(grid[k], x, rel_tol=1e-9):
            return [k]
        return sorted({max(k - 1, 0), min(k, len(grid) - 1)})

    table = np.array(A_STAR_RATIO)                  # (t, h, gamma)
    h = min(max(cap.h, A_STAR_H[0]), A_STAR_H[-1])
    by_h = np.array([np.interp(h, A_STAR_H, table[i, :, j]) for i in range(len(A_STAR_T))
                     for j in range(len(A_STAR_G))]).reshape(len(A_STAR_T), len(A_STAR_G))
    rows, cols = bracket(A_STAR_T, cap.t), bracket(A_STAR_G, gamma)
    return a_jkr(gamma) * A_STAR_MARGIN * float(by_h[np.ix_(rows, cols)].max())


def even_arc(cap: Cap, a_need: float, base: float = None) -> float:
    """The arc / R to mesh evenly so that a_need * A_MARGIN lies within UNIFORM_SHARE of
    the even zone's radius: at least the family's `base` arc, at most the cap's."""
    base = mesh_spec("default").uniform if base is None else base
    radius = min(a_need * A_MARGIN / UNIFORM_SHARE, 1.0)
    return float(min(max(math.asin(radius), base), cap.theta_outer))


def initial_fit(cap: Cap, request: Request) -> Fit:
    """The mesh and loading depth of a request before any solve."""
    bound = delta_bound(cap) if request.delta_max is None else request.delta_max
    if not request.gammas:
        return Fit(even_arc(cap, 0.0), None, bound)
    a_need = max(a_star_estimate(cap, g) for g in request.gammas)
    a_stop = None if request.delta_max is not None else TURN * a_need
    return Fit(even_arc(cap, a_need), a_stop, bound)


def answers(ps: PathSet, gammas, strict: bool = False) -> dict:
    """gamma -> (Equilibrium, PullOff), or the OutOfRange that refuses it (`strict`: a
    fixed-grips point the paths cannot vouch for refuses the whole, PathSet.pull_off)."""
    surface = ps.surface() if len(ps.usable()) >= 2 else None
    out = {}
    for g in gammas:
        try:
            if surface is None:
                raise NotBracketed(f"gamma/(C10 R) = {g:g}: fewer than 2 usable relaxation "
                                   "paths", few=True)
            out[g] = ps.pull_off(g, surface, strict)
        except OutOfRange as e:
            out[g] = e
    return out


def next_fit(ps: PathSet, fit: Fit, request: Request):
    """The fit of the next solve, or None when the paths answer what they can.

    A pull-off radius beyond the even zone, or a curve that has not turned with a margin
    (TURN, TURN_POINTS) at its large-a end while the loading ended at its target contact
    radius (not at the depth bound or a quality limit), asks for a deeper loading and an
    even zone that holds what it reaches: the zone grows (a new mesh, at most MAX_REMESH
    times) when it would not, else the loading goes on (DEEPER x its end).  Otherwise pairs
    of paths bridged near a pull-off are relaxed further (each path at most MAX_REACH times,
    REACH_FACTOR further each).  At most MAX_ROUNDS solves in all.
    """
    if fit.rounds >= MAX_ROUNDS:
        return None
    cap = Cap(ps.t, ps.h)
    got = answers(ps, request.gammas, strict=True)
    graded = [e.a for e in got.values() if isinstance(e, InGradedZone)]
    can_go_on = fit.a_stop is not None and ps.stats.get("loading_reached_a", False)
    a_end = float(ps.loading_a[-1])
    want = []                   # contact radii the loading should reach
    hold = list(graded)         # contact radii the even zone must hold
    if can_go_on:
        for r in got.values():
            if isinstance(r, NotBracketed) and (r.side == "large" or r.few):
                want.append(DEEPER * a_end)         # a* lies beyond: about as far as this
                hold.append(DEEPER * a_end / TURN)
            elif not isinstance(r, OutOfRange):
                eq, po = r
                beyond = eq.a[eq.a > po.a_star]
                if len(beyond) < TURN_POINTS or eq.a[-1] < TURN * po.a_star:
                    want.append(max(TURN * po.a_star, DEEPER * a_end))
                    hold.append(po.a_star)
    a_stop = max(want) if want else fit.a_stop
    if graded and fit.a_stop is not None:
        a_stop = max(a_stop, TURN * max(graded))
    if hold and fit.remeshed < MAX_REMESH:
        if even_arc(cap, max(hold), base=fit.uniform) > fit.uniform * (1 + 1e-9):
            # room for one more extension on the new mesh
            arc = even_arc(cap, DEEPER * max(hold), base=fit.uniform)
            return replace(fit, uniform=arc, a_stop=a_stop, reach={}, rounds=fit.rounds + 1,
                           remeshed=fit.remeshed + 1)
    if want:
        return replace(fit, a_stop=a_stop, rounds=fit.rounds + 1)
    short = set()               # radii of pairs whose G falls short of a gamma they serve
    a_pair, G = ps.G_reached()
    for g, r in got.items():
        if isinstance(r, Bridged):
            short.update(r.a_pairs)
        elif isinstance(r, NotBracketed) and (r.side == "small" or r.few):
            # the curve starts late (small a) or barely exists: the pairs below its start
            # that did not reach gamma
            below = a_pair <= (r.a_end if r.side == "small" else a_end)
            short.update(a_pair[below & ~(G >= g)])
    reach = dict(fit.reach)
    usable = ps.usable()
    a_use = np.array([r.a for r in usable])
    for a in short:
        k = int(np.searchsorted(a_use, a))          # the pair's paths: k - 1 and k
        for r in usable[max(k - 1, 0):k + 1]:
            key = (float(r.delta[0]), float(r.a))
            level = reach.get(key, 1.0)
            if level < REACH_FACTOR ** MAX_REACH and not r.centre_lifts:
                reach[key] = level * REACH_FACTOR
    if reach != fit.reach:
        return replace(fit, reach=reach, rounds=fit.rounds + 1)
    return None


def solve_request(t: float, h: float, request: Request, gamma_max: float,
                  interface: str = "no_slip", mesh: str = "default",
                  settings: Settings = Settings(), material: Material = NEO_HOOKE,
                  cavity: Cavity = OPEN, map=None, progress=None, path_progress=None,
                  family: str = None):
    """The paths of one shell fitted to `request`: (PathSet, Discretisation, LoadingPath).

    Solves with `initial_fit`, then again as `next_fit` says (at most MAX_ROUNDS solves;
    paths already relaxed on the same mesh are not solved again).  `gamma_max` is the
    largest gamma / (C10 R) the set serves; the rest as `solver.case.solve_paths`.  The
    set's stats gain `fit` (the even arc, the loading's contact radius target, the solves,
    the re-meshings and the paths taken further); `family` as in `solve_paths`.
    """
    cap = Cap(t, h)
    fit = initial_fit(cap, request)
    known = {}
    while True:
        ps, d, loading = solve_paths(t, h, interface, mesh, fit.delta_max, gamma_max, settings,
                                     relax_paths=bool(request.gammas), progress=progress,
                                     map=map, path_progress=path_progress, material=material,
                                     cavity=cavity, uniform=fit.uniform, a_stop=fit.a_stop,
                                     reach=fit.reach_of, known=known, family=family)
        following = next_fit(ps, fit, request) if request.gammas else None
        if following is None:
            break
        if following.uniform != fit.uniform:
            known = {}                      # a new mesh: nothing carries over
        fit = following
    ps.stats["fit"] = fit_stats(fit)
    return ps, d, loading


def fit_stats(fit: Fit) -> dict:
    """What the fit did, for provenance (dimensionless)."""
    return dict(uniform_arc=fit.uniform, a_stop=fit.a_stop, delta_bound=fit.delta_max,
                solves=fit.rounds, remeshed=fit.remeshed,
                paths_taken_further=len(fit.reach))
