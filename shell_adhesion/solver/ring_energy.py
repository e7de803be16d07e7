"""The energy method at a ring contact's two edges: G of each edge, and the adhesion a
mirror-buckled ring survives, from zero-range adhesion.

A ring state of a frictionless loading without adhesion (solver.snap, penalty contact)
is turned into a held ring (its outer nodes below the plane held on it, sliding in r,
as a frictionless relaxation holds its contact zone: solver.path), and the ring is grown
at fixed delta one element edge at a time, inward (the inner edge zips toward the apex,
the dimple closes) or outward: each added outer node is pulled onto the plane in a few
prescribed steps and held there.  Each ring ends on element corners at both edges
(a ring ending on a midside node holds part of the next edge: G would oscillate).

With held rings (j, k) (the pressed ring grown by j element edges inward and k outward),
the strain energy U(j, k) and the covered area A = pi (r_out^2 - r_in^2) (deformed radii
of the edge nodes) give each edge's energy release rate between neighbours,
G = dU / dA at fixed delta (the energy it costs to hold one more element edge on the
plane, per area).  Adhesion gamma moves an edge while that lowers F = U - gamma A: a
discrete descent over (j, k) (`settle`) ends on the nearest local minimum, or with the
ring closed (the inner edge at the apex: the dimple pulled flat).  The largest gamma whose
descent ends on a ring around a lifted apex is gamma_c (`zip_limit`).  `unload` raises
the rim with the held ring kept and lets both edges settle after each step (growing or,
`RingLattice(shrink=True)`, letting element edges go).  A discretisation bound to a
sealed pocket (solver.pocket) adds the gas's energy to U.  Every held ring passes the
element-quality check of a relaxation (solver.quality; a ring that fails raises
QualityError).  The adhesive edge force of a frictionless held set (solver.edge) is left
out: G is first order.

Dimensionless as the solver: lengths / R, energies / (C10 R^3), gamma and G / (C10 R),
forces / (C10 R^2) (> 0 compression).
"""
from dataclasses import dataclass, field
import math

import numpy as np

from shell_adhesion.errors import ConvergenceError, QualityError
from shell_adhesion.solver.contact import (constraints, contact_reactions, deformed_radius,
                                           gaps, rim_load)
from shell_adhesion.solver.forms import potential_energy
from shell_adhesion.solver.linear import Timer
from shell_adhesion.solver.path import Settings, _Problem, _release_tensile
from shell_adhesion.solver.quality import Quality, quality
from shell_adhesion.solver.snap import SnapSettings, SnapState

PULL_STEPS = 4        # prescribed steps that bring an added node onto the plane, each
PULL_SHARE = 0.25     # at most this many thicknesses; where Newton fails, twice as many,
PULL_RETRIES = 3      # at most this many times
MAX_ROUNDS = 10       # `held_ring`: rounds of holding nodes that the released ones press on
BISECTIONS = 40       # `zip_limit`: a bound the bisection never reaches (rel >= 1e-6)
WIDEN_MAX = 4         # `zip_limit`: moves of a bracket whose ends are on one side
# held nodes sit this far (/ R) below the plane, so that where the surface crosses it (a
# sealed pocket's seal: solver.pocket) is inside the element edge next to the held ring,
# not on its end node; the energy it adds is below the solver's tolerance
HOLD_DEPTH = 1e-10


@dataclass(frozen=True, eq=False)
class HeldRing:
    """An equilibrium at fixed delta with the outer nodes `held` (one run, indices into
    CapMesh.outer) on the plane, sliding radially."""

    delta: float
    held: tuple
    r_in: float              # deformed radius / R of the innermost held node
    r_out: float             # and of the outermost
    U: float                 # strain energy / (C10 R^3), with a sealed pocket's gas energy
    P: float                 # rim load / (C10 R^2), > 0 compression
    apex_gap: float          # height / R of the apex above the plane
    tension: float           # least z reaction on the held nodes (C10 R^2; < 0: pulled)
    free_gap: float          # least height / R of the outer nodes not held (< 0: through
    #                          the plane: contact the held set leaves out)
    quality: Quality = None  # element quality (solver.quality; passed, J not counted)
    x: np.ndarray = field(repr=False, default=None)

    @property
    def A(self) -> float:
        """The covered area / R^2, pi (r_out^2 - r_in^2) (pi r_out^2 for a disc)."""
        return math.pi * (self.r_out ** 2 - self.r_in ** 2)

    @property
    def disc(self) -> bool:
        return self.held[0] == 0


@dataclass(frozen=True)
class Settled:
    """Where adhesion gamma takes a held ring (`settle`): the last ring, its (j, k) in
    element edges grown inward and outward, and whether the dimple closed."""

    gamma: float
    ring: HeldRing
    j: int
    k: int
    closed: bool
    moves: int
    why: str = ""            # how it closed where no ring past the last was found, or
    #                          how it detached
    detached: bool = False   # the ring let go of the plane (its last ring is `ring`)


class Beyond(ValueError):
    """A ring grown past the apex or the mesh's last outer node."""


class Detached(ValueError):
    """A ring shrunk to nothing: the shell has left the plane."""


class Inadmissible(ValueError):
    """A ring shrunk where the released nodes would press through the plane."""


DETACH = (None, None)     # `settle`'s move off the plane


class RingLattice:
    """The held rings (j, k) grown from one held ring, (0, 0), solved on demand and kept
    (all at its delta; j, k element edges inward and outward, >= 0, or, with `shrink`,
    also < 0: element edges released at that edge).

    `start`: a ring state of a loading (solver.snap, turned into a held ring on element
    corners by `held_ring`) or a HeldRing on element corners."""

    def __init__(self, d, start, settings: Settings = Settings(), shrink: bool = False):
        self.d = d
        self.pb = _Problem(d, "frictionless", settings, Timer())
        self.corner = d.capmesh.outer_corner
        self.shrink = shrink
        self.solves = 0           # rings solved (each node pulled onto the plane or let go)
        if isinstance(start, HeldRing):
            ring = start
            if not (self.corner[ring.held[0]] and self.corner[ring.held[-1]]):
                raise ValueError(f"RingLattice: the held ring {ring.held[0]}-{ring.held[-1]} "
                                 "does not end on element corners")
        else:
            ring = held_ring(d, start, self.pb)
            # both edges on element corners: grow the edge that ends on a midside node
            if not self.corner[ring.held[0]]:
                ring = self._pull(ring, ring.held[0] - 1)
            if not self.corner[ring.held[-1]]:
                ring = self._pull(ring, ring.held[-1] + 1)
        self.rings = {(0, 0): ring}

    def __call__(self, j: int, k: int) -> HeldRing:
        """The ring (j, k); ConvergenceError where it cannot be reached, Beyond where it
        runs past the apex or the mesh's outer surface, Detached where it shrinks to
        nothing, Inadmissible where a node it lets go would press through the plane."""
        if not self.shrink and (j < 0 or k < 0):
            raise ValueError(f"ring ({j}, {k}): this lattice only grows (j, k >= 0)")
        if (j, k) not in self.rings:
            outward = k != 0
            n = k if outward else j
            back = 1 if n > 0 else -1           # the neighbour one element edge nearer (0, 0)
            base = self(j, k - back) if outward else self(j - back, 0)
            if n > 0:
                edge, step = (base.held[-1], 1) if outward else (base.held[0], -1)
                if not 0 <= edge + 2 * step < len(self.corner):
                    raise Beyond(f"ring ({j}, {k}): beyond the {'rim' if outward else 'apex'}")
                ring = self._pull(self._pull(base, edge + step), edge + 2 * step)
            else:
                if len(base.held) < 3:
                    raise Detached(f"ring ({j}, {k}): nothing left to hold")
                let_go = base.held[-2:] if outward else base.held[:2]
                ring = self._release(base, let_go)
            self.rings[(j, k)] = ring
        return self.rings[(j, k)]

    def _release(self, ring: HeldRing, nodes) -> HeldRing:
        """The ring with the outer nodes `nodes` (at one edge) let go."""
        d, pb = self.d, self.pb
        held = [h for h in ring.held if h not in set(nodes)]
        c = constraints(d, "frictionless", held)
        x, _, K, r, _ = pb.newton(c, ring.x.copy(), ring.delta, None, pb.s.modified_newton)
        if gaps(d, x, list(nodes)).min() < -pb.s.gap_tol:
            raise Inadmissible(f"outer nodes {list(nodes)} let go press through the plane")
        self.solves += 1
        return _held_state(d, x, ring.delta, r, held)

    def _pull(self, ring: HeldRing, node: int) -> HeldRing:
        """The ring with the outer node `node` pulled onto the plane and held."""
        d, pb = self.d, self.pb
        held = sorted((*ring.held, node))
        c = constraints(d, "frictionless", held)
        dof = d.uz(d.capmesh.outer[node])
        z0 = float(gaps(d, ring.x, [node])[0]) + HOLD_DEPTH
        steps = max(PULL_STEPS, math.ceil(z0 / (PULL_SHARE * d.capmesh.cap.t)))
        for attempt in range(PULL_RETRIES + 1):
            x = ring.x.copy()
            try:
                for _ in range(steps):
                    x[dof] -= z0 / steps
                    x, _, K, r, _ = pb.newton(c, x, ring.delta, None, pb.s.modified_newton)
                break
            except ConvergenceError as err:
                if attempt == PULL_RETRIES:
                    raise ConvergenceError(f"outer node {node} not pulled onto the plane in "
                                           f"{steps} steps ({err})") from None
                steps *= 2
        self.solves += 1
        return _held_state(d, x, ring.delta, r, held)

    def G(self, a: tuple, b: tuple) -> float:
        """dU/dA between the rings a and b = (j, k), neighbours (gamma / (C10 R))."""
        ra, rb = self(*a), self(*b)
        return (rb.U - ra.U) / (rb.A - ra.A)


def held_ring(d, state: SnapState, pb=None) -> HeldRing:
    """The penalty-contact ring `state` as a held ring at its delta: its outer nodes below
    the plane held on it (one run, not touching the axis), re-equilibrated; nodes the
    plane pulls are released and nodes that then press through it are held, for at most
    MAX_ROUNDS rounds.  ValueError if the nodes below the plane are not one ring."""
    pb = pb or _Problem(d, "frictionless", Settings(), Timer())
    cm = d.capmesh
    held = [int(i) for i in np.flatnonzero(gaps(d, state.x) <= 0.0)]
    if not held or held[0] == 0 or held[-1] - held[0] + 1 != len(held):
        raise ValueError(f"held_ring: the outer nodes below the plane ({held}) are not one "
                         "ring around the apex")
    x = state.x.copy()
    for _ in range(MAX_ROUNDS):
        x[d.uz(cm.outer[held])] = -cm.nodes[1, cm.outer[held]] - HOLD_DEPTH
        c = constraints(d, "frictionless", held)
        x, _, K, r, hist = pb.newton(c, x, state.delta, None, pb.s.modified_newton)
        x, K, r, held, c, _ = _release_tensile(pb, x, state.delta, K, r, held, c, hist)
        held = [int(h) for h in held]
        outside = np.setdiff1d(np.arange(len(cm.outer)), held)
        through = outside[gaps(d, x, outside) < -pb.s.gap_tol]
        if not len(through):
            break
        held = sorted(set(held) | set(int(i) for i in through))
    else:
        raise ConvergenceError(f"held_ring: the contact set did not settle in {MAX_ROUNDS} "
                               "rounds")
    if held[0] == 0 or held[-1] - held[0] + 1 != len(held):
        raise ValueError(f"held_ring: the held contact ({held}) is not one ring")
    return _held_state(d, x, state.delta, r, held)


def _held_state(d, x, delta, r, held) -> HeldRing:
    """The converged held ring; QualityError (a ConvergenceError) where an element folds
    or distorts beyond solver.quality's thresholds (the pointwise J range is not counted:
    the held edges are crack tips, as in a relaxation)."""
    q = quality(d, x)
    problem = q.problem(check_J=False)
    if problem:
        raise QualityError(f"element quality: {problem} at delta = {delta:.4g} R with outer "
                           f"nodes {held[0]}-{held[-1]} held")
    free = np.setdiff1d(np.arange(len(d.capmesh.outer)), held)
    return HeldRing(delta, tuple(held), float(deformed_radius(d, x, held[0])),
                    float(deformed_radius(d, x, held[-1])), potential_energy(d, x),
                    rim_load(d, r), float(gaps(d, x, [0])[0]),
                    float(contact_reactions(d, r, held).min()),
                    float(gaps(d, x, free).min()), q, x)


def settle(lattice: RingLattice, gamma: float, lift: float = None) -> Settled:
    """Adhesion gamma switched on at the lattice's ring (0, 0): move one edge by one
    element edge (grow it, or shrink it: below (0, 0) only with the lattice's `shrink`)
    while that lowers F = U - gamma A most, until no move does (a ring) or:

    - the ring closes: the held set reaches the apex, a node it leaves free inside comes
      through the plane, or, after the inner edge has passed the largest G of its moves
      inward (beyond it G falls toward the apex, and falls as the outer edge grows: every
      move on lowers F, measured on the meshes of the docs), a neighbouring ring has no
      equilibrium (the rest of the dimple gives way);
    - the ring detaches (`shrink`, delta <= 0): letting go of its last element edge lowers
      F to that of the shell off the plane, 0 (the gas of a sealed pocket escapes).

    `lift`: a ring whose apex is lifted by no more than this / R counts as closed
    (default SnapSettings.seal_lift t).  At most 4 moves per outer node.  Any other
    neighbour that cannot be solved raises ConvergenceError (naming it): the descent
    cannot say where it would go."""
    if not (math.isfinite(gamma) and gamma >= 0):
        raise ValueError(f"settle: gamma {gamma!r} must be a finite number >= 0")
    lift = SnapSettings().seal_lift * lattice.d.capmesh.cap.t if lift is None else lift
    gap_tol = lattice.pb.s.gap_tol
    off_plane = lattice(0, 0).delta <= 0
    F = lambda jk: lattice(*jk).U - gamma * lattice(*jk).A
    jk, moves = (0, 0), 0
    G_top = G_last = 0.0        # of the moves inward so far: the largest G, the last
    for moves in range(4 * len(lattice.corner)):
        j, k = jk
        best, best_F = None, F(jk)
        for nb in ((j + 1, k), (j, k + 1), (j - 1, k), (j, k - 1)):
            if min(nb) < 0 and not lattice.shrink:
                continue
            try:
                f = F(nb)
            except Beyond:
                if nb[0] > j:           # past the apex: the dimple is closed
                    return Settled(gamma, lattice(*jk), j, k, True, moves)
                continue
            except Detached:
                if not off_plane:
                    continue
                f, nb = 0.0, DETACH
            except Inadmissible:
                continue
            except ConvergenceError as err:
                if G_last < G_top:
                    return Settled(gamma, lattice(*jk), j, k, True, moves,
                                   f"no held ring {nb} after the inner edge passed its "
                                   "largest G")
                raise ConvergenceError(f"settle at gamma {gamma:g}: the held ring {nb} (element "
                                       f"edges grown inward, outward) was not found "
                                       f"({err})") from None
            if f < best_F - 1e-12 * abs(best_F):
                best, best_F = nb, f
        if best is DETACH:
            return Settled(gamma, lattice(*jk), j, k, False, moves + 1,
                           "detached: letting go of the last element edge lowers F",
                           detached=True)
        if best is None:
            break
        if best[0] > j:
            G_last = lattice.G(jk, best)
            G_top = max(G_top, G_last)
        jk = best
        if lattice(*jk).free_gap < -gap_tol:
            break               # the dimple came down onto the plane inside the ring
    ring = lattice(*jk)
    closed = ring.disc or ring.apex_gap <= lift or ring.free_gap < -gap_tol
    return Settled(gamma, ring, *jk, closed, moves)


def zip_limit(lattice: RingLattice, gamma_lo: float, gamma_hi: float,
              rel: float = 0.01, widen: float = None) -> tuple:
    """Bracket gamma_c, the largest gamma at which `settle` ends on a ring (not closed),
    by bisection between gamma_lo (must hold) and gamma_hi (must close) until
    gamma_hi / gamma_lo <= 1 + rel.  `widen` (> 1): where an end is on the wrong side,
    the bracket moves by that factor (at most WIDEN_MAX times) instead.  Returns (lo, hi)
    as Settled results."""
    if not (0 < gamma_lo < gamma_hi and 1e-6 <= rel and (widen is None or widen > 1)):
        raise ValueError(f"zip_limit: need 0 < gamma_lo ({gamma_lo!r}) < gamma_hi "
                         f"({gamma_hi!r}), rel ({rel!r}) >= 1e-6 and widen ({widen!r}) > 1")
    lo, hi = settle(lattice, gamma_lo), settle(lattice, gamma_hi)
    for _ in range(WIDEN_MAX if widen else 0):
        if lo.closed:
            lo, hi = settle(lattice, lo.gamma / widen), lo
        elif not hi.closed:
            lo, hi = hi, settle(lattice, hi.gamma * widen)
    if lo.closed:
        raise ValueError(f"zip_limit: the ring closes at gamma_lo = {lo.gamma:g}")
    if not hi.closed:
        raise ValueError(f"zip_limit: the ring still holds at gamma_hi = {hi.gamma:g}")
    for _ in range(BISECTIONS):
        if hi.gamma <= lo.gamma * (1 + rel):
            break
        mid = settle(lattice, math.sqrt(lo.gamma * hi.gamma))
        lo, hi = (lo, mid) if mid.closed else (mid, hi)
    return lo, hi


def release_rates(lattice: RingLattice, side: str, edges: int, other: int = 0) -> tuple:
    """(radius, G) of one edge grown by 1..`edges` element edges with the other edge
    grown by `other`: the edge's radius / R midway and dU/dA over each element edge
    (stops early, with what it has, at the apex or the mesh's end)."""
    if side not in ("in", "out"):
        raise ValueError(f"release_rates: side {side!r} must be 'in' or 'out'")
    at = (lambda n: (n, other)) if side == "in" else (lambda n: (other, n))
    radius, G = [], []
    for n in range(edges):
        try:
            a, b = lattice(*at(n)), lattice(*at(n + 1))
        except ValueError:
            break
        edge = "r_in" if side == "in" else "r_out"
        radius.append(0.5 * (getattr(a, edge) + getattr(b, edge)))
        G.append((b.U - a.U) / (b.A - a.A))
    return np.array(radius), np.array(G)


MOVE_HALVINGS = 6     # `unload`: a rim move that Newton cannot make is halved this often


@dataclass(frozen=True)
class Unloading:
    """`unload`'s path: the settled ring at each delta (the first at the start's delta),
    why it ended, and its least P (the pull-off under displacement control, where the
    ring detached or closed after it)."""

    gamma: float
    rings: tuple
    ended_by: str
    moved: tuple = ()        # each rim move's end, before the edges settle (the ring
    #                          before it held: rings[i] -> moved[i] at fixed held set)

    @property
    def P_star(self) -> float:
        return min(r.P for r in self.rings)

    def array(self, name):
        return np.array([getattr(r, name) for r in self.rings])

    def move_misses(self) -> list:
        """|U after - U before - work of P| of each rim move (trapezoidal rule over the
        move, at the held set; C10 R^3)."""
        return [abs(b.U - a.U + 0.5 * (a.P + b.P) * (a.delta - b.delta))
                for a, b in zip(self.rings, self.moved)]

    def energy_miss(self) -> float:
        """The energy balance of the rim moves: the largest `move_misses` / max U."""
        return max(self.move_misses(), default=0.0) / max(r.U for r in self.rings)


def unload(d, start, gamma: float, delta_end: float, step: float,
           settings: Settings = Settings()) -> Unloading:
    """Raise the rim from the ring state `start` (a loading state, as RingLattice) to
    delta_end / R in steps of `step` / R, with adhesion gamma by the energy method: at the
    start and after each rim move (the held ring kept, as a relaxation), `settle` moves
    both edges (grow or shrink).  Ends at delta_end, or where the ring detaches (delta
    <= 0) or closes (the dimple pulled flat: the contact is no longer a ring; not
    followed further), or shrinks to one node at delta > 0 (letting it go there would
    need the shell off the plane, not built), or where a rim move fails after
    MOVE_HALVINGS halvings (ConvergenceError's text).  A discretisation bound to a
    sealed pocket (solver.pocket.seal) carries its gas."""
    if not (math.isfinite(delta_end) and delta_end < start.delta and step > 0):
        raise ValueError(f"unload: need delta_end ({delta_end!r}) < the start's delta "
                         f"({start.delta:g}) and step ({step!r}) > 0")
    lattice = RingLattice(d, start, settings)
    s = settle(lattice, gamma)
    rings, pb = [s.ring], lattice.pb
    if s.closed:
        return Unloading(gamma, tuple(rings), "closed at the start: " + (s.why or "the "
                                                                           "dimple closed"))
    ring, moved = s.ring, []
    while ring.delta > delta_end:
        c = constraints(d, "frictionless", list(ring.held))
        h = min(step, ring.delta - delta_end)
        for _ in range(MOVE_HALVINGS + 1):
            try:
                x, _, K, r, _ = pb.newton(c, ring.x.copy(), ring.delta - h, None,
                                          pb.s.modified_newton)
                break
            except ConvergenceError as err:
                why = str(err)
                h /= 2
        else:
            return Unloading(gamma, tuple(rings), f"the rim move from delta "
                             f"{ring.delta:.6g} R failed ({why})", tuple(moved))
        moved.append(_held_state(d, x, ring.delta - h, r, list(ring.held)))
        s = settle(RingLattice(d, moved[-1], settings, shrink=True), gamma)
        rings.append(s.ring)
        if s.detached or s.closed:
            return Unloading(gamma, tuple(rings), ("detached" if s.detached else "closed")
                             + f" at delta {s.ring.delta:.6g} R" + (f" ({s.why})" if s.why
                                                                   else ""), tuple(moved))
        if len(s.ring.held) < 3 and s.ring.delta > 0:
            return Unloading(gamma, tuple(rings), f"the ring shrank to one node at delta "
                             f"{s.ring.delta:.6g} R > 0, where letting it go is not built "
                             "(the shell off the plane there)", tuple(moved))
        ring = s.ring
    return Unloading(gamma, tuple(rings), "", tuple(moved))
