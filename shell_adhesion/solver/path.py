"""Path following: loading with exact contact events, and relaxation at fixed contact.

All quantities are dimensionless: lengths / R, forces / (C10 R^2), energies / (C10 R^3).
delta > 0 is approach (rim pushed down), P > 0 compression.

Each Newton step solves the symmetric indefinite saddle-point system of the free dofs.
A contact event is located exactly by a bordered Newton: delta becomes an unknown and
"the gap of node k is zero" is added as an equation, so every loaded state in which a
node joins the contact is found without bisection.
"""
from dataclasses import dataclass, field, replace
import math
import time

import numpy as np

from .contact import (Constraints, constraints, contact_reactions, deformed_radius, gaps,
                      rim_load)
from .edge import EdgeAdhesion, carriers, with_edge
from .forms import (Discretisation, Linearisation, deformation, potential_energy, tangent,
                    tangent_pattern)
from .geometry import shown
from .linear import Bordered, LinearSolver, SingularTangent, Timer
from .material import limit_state
from .quality import Quality, clamp_squeeze, quality, worst
from shell_adhesion.errors import ConvergenceError, MaterialLimitError, QualityError


LOCK_UP = 0.99   # (I1bar - 3) / Jm of a Gent state beyond which a failed step means lock-up


@dataclass(frozen=True)
class Settings:
    """Solver tolerances; lengths in units of R."""

    tol: float = 1e-10        # force residual relative to the largest reaction
    atol: float = 1e-13       # residual floor, relative to C10 * volume / size
    gap_tol: float = 1e-9     # penetration allowed before an event is re-located
    max_iter: int = 12
    step_max: float = 0.02    # largest delta increment on loading
    step_min: float = 1e-9
    max_states: int = 20000   # loading states: a bound a failure cannot defeat, never reached
    max_events_per_node: int = 4   # contact events per outer node during loading
    max_relocations: int = 20      # re-located events within one loading step
    max_points: int = 400     # states per relaxation path
    # speed-ups (solver.linear); each can be switched off, the results agree to round-off
    fast_solver: bool = True  # QDLDL LDL^T, symbolic analysis once per path; False: SuperLU
    hermite_predictor: bool = True  # relaxation steps start from the cubic through the
    #                                 last two states (x and dx/ddelta); False: the tangent
    bordered_event_tangent: bool = True  # after a contact event, the tangent from the event
    #                                 solve's factorisation bordered by the newly held dofs;
    #                                 False: a new factorisation
    start_tangent: bool = True    # a relaxation path starts from dx/ddelta and dP/ddelta
    #                               as its loading state holds them; False: from a new
    #                               tangent and factorisation at the start
    modified_newton: bool = True  # in loading and relaxation, a Newton iteration after one
    #                               that cut the residual by CHORD_GAIN keeps its
    #                               factorisation (a chord step, no tangent assembled), and
    #                               a no_slip loading step starts with a chord step from
    #                               the newest factorisation (the retries of a step that
    #                               failed use full Newton); False: every iteration
    #                               factorises
    # relaxation sampling (solver.case.relax_from): steps down to the stop criterion, and
    # the largest step.  The energy method's quintic Hermite splines (U, P, dP/ddelta) make
    # 4 steps of at most 0.05 R as accurate as 8 of 0.02 R, the sampling before them
    # (8 and 0.02: the paths as before; pull-off numbers move by <= 0.05 %, not round-off;
    # against 16 steps of 0.01 R both are within 0.007 % on the base shell)
    relaxation_steps: int = 4
    relaxation_step_max: float = 0.05
    step_energy_tol: float = 1e-4   # a relaxation step is halved (down to a thousandth of
    #                                 the path's step, where it is taken) while the work of
    #                                 P over it (two-point Hermite rule) misses the change of
    #                                 the strain energy by more than this share (solver.
    #                                 path.step_mismatch): a step from near a fold no longer
    #                                 lands on another equilibrium, and U_E's spline is as
    #                                 accurate on thin shells as on thick ones (1e-2 left G
    #                                 noisy: P* of t/R 0.02, h/R 0.2 moved 2 %)
    step_stiffness_tol: float = 0.5  # a relaxation step is also halved (as above) while
    #                                 dP/ddelta changes over it by more than this share of
    #                                 its larger end value (`stiffness_change`): the energy
    #                                 check sees the step's work only, and a step over a
    #                                 knee of P(delta) can pass it while U_E's spline misses
    #                                 the knee (t/R 0.01, h/R 0.2, fine mesh: one path
    #                                 stepped 0.05 R past a stiffening x16 where its
    #                                 neighbours took 12 states; its two pairs put P* at 1.9x
    #                                 the curve's minimum)


CHORD_GAIN = 1e-2    # the residual cut of an iteration after which the next is a chord step
CHORD_LEFT = 3       # or: chord steps at the last cut's rate reach the tolerance in this many
STIFFNESS_FLOOR = 0.1  # stiffness_change's floor: this share of the path's first dP/ddelta
REFINE_MAX = 6        # iterative refinement of the tangent direction from a stale factorisation
REFINE_TOL = 1e-10    # its last correction relative to the direction


@dataclass(frozen=True, eq=False)
class State:
    """A converged equilibrium state."""

    delta: float
    P: float
    U: float                  # strain energy
    a: float                  # deformed radius of the outermost held node
    held: tuple               # held outer nodes (indices into CapMesh.outer)
    joined: int               # outer node that joined in this state, -1 if none
    x: np.ndarray = field(repr=False)
    dP_ddelta: float = np.nan  # dP/ddelta with this state's held set (right derivative)
    residuals: tuple = ()     # Newton residual history of the solve that produced it
    dP_ddelta_left: float = np.nan  # dP/ddelta before the joining node was held
    quality: Quality = None   # element quality of the state (solver.quality)
    centre_off: bool = False  # the centre of the contact zone has left (or is pulled off) the plane
    V: float = np.nan         # cavity: enclosed volume / R^3 (solver.cavity; NaN if open)
    p: float = np.nan         # cavity: gauge pressure / C10
    dx_ddelta: np.ndarray = field(default=None, repr=False)  # dx/ddelta with this state's
    #                           held set (rim dofs -1), where dP_ddelta was computed
    da_ddelta: float = np.nan  # d a / d delta of a relaxation state at its held set (0 where
    #                           the held nodes cannot slide; frictionless: the edge slides)
    dA_dgamma: float = 0.0    # a frictionless relaxation state: d(covered area / R^2) /
    #                           d(gamma / (C10 R)) at fixed delta and held set (solver.edge)


@dataclass(frozen=True, eq=False)
class LoadingPath:
    """Loading without adhesion from delta = 0; states at every event and step."""

    interface: str
    states: tuple
    timer: Timer
    stopped_by: str = ""      # why loading ended before delta_max ("": it reached delta_max
    #                           or the contact radius asked for)
    reached_a: bool = False   # it ended at the contact radius asked for (`load`'s a_stop)

    @property
    def delta_reached(self) -> float:
        """The deepest delta / R loaded (delta_max unless `stopped_by` says why not)."""
        return float(self.states[-1].delta)

    @property
    def events(self):
        return tuple(s for s in self.states if s.joined >= 0)

    def array(self, name):
        return np.array([getattr(s, name) for s in self.states])

    @property
    def quality(self) -> Quality:
        """Worst element quality over the loading states."""
        return worst(*(s.quality for s in self.states))

    @property
    def inversion(self):
        """The first state whose contact centre has left the plane, or None."""
        return next((s for s in self.states if s.centre_off), None)


@dataclass(frozen=True, eq=False)
class RelaxationPath:
    """delta lowered from a loaded state with its contact zone held."""

    interface: str
    start: State
    states: tuple
    ended_by: str
    penetration: bool         # a node outside the held zone touched the plane
    centre_lifts: bool        # the plane had to pull the centre down while pushing elsewhere
    timer: Timer
    inversion_delta: float = np.nan   # first delta at which centre_lifts became true

    def array(self, name):
        return np.array([getattr(s, name) for s in self.states])

    @property
    def quality(self) -> Quality:
        """Worst element quality over the path (its start included)."""
        return worst(*(s.quality for s in self.states))


class _Problem:
    """Newton machinery on one discretisation (no state kept between calls)."""

    def __init__(self, d: Discretisation, interface: str, settings: Settings, timer: Timer):
        self.d, self.interface, self.s, self.timer = d, interface, settings, timer
        cm = d.capmesh
        self.Z = cm.nodes[1, cm.outer]
        self.linear = LinearSolver(*tangent_pattern(d), settings.fast_solver, timer)
        self.newest = (None, None, None)  # the last factorisation, its constraints, dr/ddelta

    def assemble(self, x):
        t0 = time.perf_counter()
        K, r = tangent(self.d, x)
        self.timer.assembly += time.perf_counter() - t0
        return K, r

    def linearise(self, x) -> Linearisation:
        t0 = time.perf_counter()
        lin = Linearisation(self.d, x)
        self.timer.assembly += time.perf_counter() - t0
        return lin

    def tangent(self, lin: Linearisation):
        t0 = time.perf_counter()
        K, r = lin.tangent()
        self.timer.assembly += time.perf_counter() - t0
        return K, r

    def factor(self, K, c: Constraints):
        """Factorisation of the free block of K, and d(residual of the free dofs)/d(delta)."""
        try:
            lu = self.linear.factor(K, c)
        except SingularTangent as err:
            raise ConvergenceError(f"singular tangent ({err})") from None
        e = np.zeros(self.d.ndof)
        e[c.rimz] = 1.0
        dr_ddelta = -(K @ e)[c.free]
        self.newest = (lu, c, dr_ddelta)
        return lu, dr_ddelta

    def bordered(self, lu, c_before, c):
        """Solves with the free block of c from `lu` of c_before's (solver.linear.Bordered),
        or None (then the caller factorises)."""
        t0 = time.perf_counter()
        try:
            return Bordered(lu, c_before, c)
        except (SingularTangent, ValueError, np.linalg.LinAlgError):
            return None
        finally:
            self.timer.factor += time.perf_counter() - t0

    def solve(self, lu, rhs):
        try:
            return lu.solve(rhs)
        except SingularTangent as err:
            raise ConvergenceError(f"singular tangent ({err})") from None

    def converged(self, r, c):
        """(residual, tolerance) of the free dofs (max norms)."""
        res = np.abs(r[c.free]).max()
        scale = np.abs(r[c.fixed]).max()
        return res, self.s.tol * scale + self.s.atol * self.d.force_scale

    def newton(self, c: Constraints, x, delta, target=None, modified=False,
               chord_start=False):
        """Equilibrium at fixed delta, or (target = outer node) where its gap is zero.

        Returns (x, delta, K, r, history).  Raises ConvergenceError.  The time of the
        bordered solves (target given) is counted as event location.  `modified`: an
        iteration is a chord step (no tangent assembled) with the last factorisation if
        `_chord_pays`, and with `chord_start` the first one is too if the newest
        factorisation is of c (of a nearby state: the last step's); else full Newton.
        """
        if target is None:
            return self._newton(c, x, delta, None, modified, chord_start)
        t0 = time.perf_counter()
        try:
            return self._newton(c, x, delta, target, modified, chord_start)
        finally:
            self.timer.event += time.perf_counter() - t0

    def newest_of(self, c):
        """(factorisation, dr/ddelta) of the newest factorisation if it is of the
        constraints c, else (None, None): QDLDL keeps only the newest one of a pattern."""
        lu, c_lu, dr_dd = self.newest
        return (lu, dr_dd) if lu is not None and c_lu is c else (None, None)

    def _newton(self, c: Constraints, x, delta, target, modified, chord_start):
        d = self.d
        if not (math.isfinite(delta) and np.all(np.isfinite(x))):
            raise ConvergenceError(f"non-finite start of Newton (delta = {shown(delta)})")
        x = x.copy()
        x[c.rimz] = -delta
        if target is not None:
            kdof = d.uz(d.capmesh.outer[target])
            kpos = c.free_pos[kdof]
        history = []
        lu, dr_dd = self.newest_of(c) if modified and chord_start else (None, None)
        b = b_of = None           # the delta column solved with the factorisation b_of
        for _ in range(self.s.max_iter):
            with np.errstate(invalid="ignore", divide="ignore"):  # an inverted trial iterate
                lin = self.linearise(x)
            r = lin.r
            if not np.all(np.isfinite(r)):
                raise ConvergenceError("non-finite residual (element inverted)")
            res, goal = self.converged(r, c)
            ok = res <= goal
            history.append(res)
            if ok and (target is None or abs(x[kdof] + self.Z[target]) <= 1e-3 * self.s.gap_tol):
                self.last_lu = lu if history[1:] else None
                K, r = self.tangent(lin)
                return x, delta, K, r, tuple(history)
            if len(history) > 3 and res > 1e3 * history[1]:
                break
            if modified and lu is not None and (len(history) == 1
                                                or _chord_pays(history, goal)):
                self.timer.chord_iterations += 1    # the last Jacobian is good enough
            else:
                lu, dr_dd = self.factor(self.tangent(lin)[0], c)
                self.timer.newton_iterations += 1
            a = self.solve(lu, -r[c.free])
            if target is None:
                dx = a
            else:
                if b_of is not lu:    # a chord step reuses it
                    b, b_of = self.solve(lu, -dr_dd), lu
                dd = (-(x[kdof] + self.Z[target]) - a[kpos]) / b[kpos]
                dx = a + b * dd
                delta += dd
                x[c.rimz] = -delta
            x[c.free] += dx
        raise ConvergenceError("Newton did not converge (residuals "
                               + ", ".join(f"{h:.3g}" for h in history[-3:]) + ")")

    def tangent_direction(self, K, c, lu=None):
        """dx/ddelta (full vector) and dP/ddelta at the state of K (`lu`: solve_free)."""
        e = np.zeros(self.d.ndof)
        e[c.rimz] = 1.0
        dr_dd = -(K @ e)[c.free]
        dx = np.zeros(self.d.ndof)
        dx[c.free] = self.solve_free(K, c, -dr_dd, lu)
        dx[c.rimz] = -1.0
        dP = -float(np.sum(K[c.rimz] @ dx))
        return dx, dP

    def area_compliance(self, K, c, edge: EdgeAdhesion, x) -> float:
        """c = g . K_ff^-1 g at the state x of K: the covered area's growth per unit gamma
        at fixed delta and held set (solver.edge; g = edge.gradient on the free dofs),
        solved with the newest factorisation of c (solve_free)."""
        g = np.zeros(self.d.ndof)
        g[edge.dofs] = edge.gradient(x)
        rhs = g[c.free]
        return float(rhs @ self.solve_free(K, c, rhs, self.newest_of(c)[0]))

    def solve_free(self, K, c, rhs, lu=None):
        """K_ff^-1 rhs on the free dofs of c.

        `lu` may be the factorisation of an earlier Newton iterate (same constraints, or
        bordered to them): iterative refinement with K then makes the solution as accurate
        as K's own factorisation would (each step multiplies the error by about the
        relative change of the tangent since); if REFINE_MAX steps do not, K is factorised.
        """
        if lu is not None:
            y = self.solve(lu, rhs)
            if self._refined(K, c, lu, rhs, y):
                return y
        lu, _ = self.factor(K, c)
        return self.solve(lu, rhs)

    def _refined(self, K, c, lu, rhs, y) -> bool:
        """Iterative refinement of y (K_ff y = rhs) in place; False if REFINE_MAX steps do
        not bring the last correction below REFINE_TOL."""
        z = np.zeros(self.d.ndof)
        for _ in range(REFINE_MAX):
            z[c.free] = y
            step = self.solve(lu, rhs - (K @ z)[c.free])
            y += step
            if np.abs(step).max() <= REFINE_TOL * np.abs(y).max():
                return True
        return False

    def state(self, x, delta, r, held, joined, history, dP=np.nan, centre_off=False,
              check_J=True, U=None):
        """The converged state; raises QualityError if its elements fail the quality
        check (`check_J`: the pointwise J range counts too).  `U`: its potential energy
        if already known."""
        d = self.d
        q = quality(d, x)
        problem = q.problem(check_J)
        a = float(deformed_radius(d, x, max(held))) if len(held) else 0.0
        if problem:
            cm = d.capmesh
            hint = (clamp_squeeze(d, x, q, a)
                    or "try a finer mesh or a smaller delta_max")
            raise QualityError(
                f"element quality: {problem} at delta = {delta:.4g} R on the {cm.spec.name} "
                f"mesh of t/R = {cm.cap.t:g}, h/R = {cm.cap.h:g}; {hint}")
        V, p = (np.nan, np.nan) if d.cavity is None else d.cavity.measure(x)  # solver.cavity
        U = potential_energy(d, x) if U is None else U
        return State(delta, rim_load(d, r), U, a, tuple(held), joined,
                     x.copy(), dP, history, quality=q, centre_off=centre_off, V=V, p=p)


def load(d: Discretisation, interface: str, delta_max: float,
         settings: Settings = Settings(), progress=None, x0=None,
         stop_at_limit: bool = False, a_stop: float = None) -> LoadingPath:
    """Push the rim down from delta = 0 to delta_max, locating every contact event.

    With `a_stop` the loading ends at the first contact event whose contact radius a / R
    reaches it (`reached_a`), if that comes before delta_max.  The states are those of a
    loading to delta_max up to there, so a loading with a larger a_stop continues the
    same sequence of states.
    `progress(delta)` is called after each converged state if given.  `x0`: the state at
    delta = 0 touching the plane at the apex (a pressurised cavity, solver.cavity), else
    the undeformed shell.  A state refused by the element-quality check (QualityError) or
    a step that Newton cannot take even at settings.step_min (ConvergenceError) ends the
    loading: with `stop_at_limit` the states converged so far are kept and the path says
    why it stopped (`stopped_by`, `delta_reached`); without, or if no node beyond the apex
    has joined the contact yet (nothing to relax), the error is raised.
    """
    if not (math.isfinite(delta_max) and delta_max > 0):
        raise ValueError(f"delta_max: {shown(delta_max)} must be a finite number > 0 "
                         "(units of R)")
    timer = Timer()
    pb = _Problem(d, interface, settings, timer)
    n_outer = len(d.capmesh.outer)
    max_events = settings.max_events_per_node * n_outer
    held = [0]
    x = np.zeros(d.ndof) if x0 is None else np.array(x0, dtype=float)
    delta = 0.0
    c = constraints(d, interface, held)
    K, r = pb.assemble(x)
    states = [pb.state(x, delta, r, held, 0, ())]
    step_cap = settings.step_max
    reuse = None
    events = 0
    modified = True     # off for the retries of a failed step: full Newton is the fallback
    while delta < delta_max * (1 - 1e-12):
        if len(states) >= settings.max_states or events >= max_events:
            raise ConvergenceError(
                f"loading stopped at delta = {delta:.6g} R: {len(states)} states and {events} "
                f"contact events without reaching delta_max = {delta_max:.6g} R (limits "
                f"{settings.max_states} states, {max_events} events)")
        dx, dP = pb.tangent_direction(K, c, reuse)
        states[-1] = _with_stiffness(states[-1], dP, dx)
        free_nodes = np.setdiff1d(np.arange(n_outer), held)
        g = gaps(d, x, free_nodes)
        dg = dx[d.uz(d.capmesh.outer[free_nodes])]
        with np.errstate(divide="ignore", invalid="ignore"):
            to_touch = np.where(dg < 0, -g / dg, np.inf)
        k = int(np.argmin(to_touch))
        step = min(step_cap, delta_max - delta)
        target = int(free_nodes[k]) if to_touch[k] <= step else None
        step = to_touch[k] if target is not None else step
        try:
            xn, dn, Kn, rn, hist, target = _advance(pb, c, x, delta, dx, free_nodes, target,
                                                    step, delta_max, modified)
        except ConvergenceError as err:
            _check_lock_up(d, x, delta)
            modified = False
            # the cap never grows on failure, so repeated failures end at step_min
            step_cap = min(step_cap, step) / 2
            if step_cap < settings.step_min:
                stall = ConvergenceError(
                    f"loading stalled at delta = {delta:.6g} R: Newton fails even for a step "
                    f"of {settings.step_min:g} R ({err})")
                if not (stop_at_limit and _has_event(states)):
                    raise stall from None
                return LoadingPath(interface, tuple(states), timer, str(stall))
            continue
        modified = True
        step_cap = min(settings.step_max, 2 * step_cap)
        x, delta, K, r = xn, dn, Kn, rn
        _, dP_left = pb.tangent_direction(K, c, pb.last_lu)
        # the newest factorisation of c (the step's last, or K's if refinement needed it):
        # QDLDL has dropped any older one
        live = pb.newest_of(c)[0]
        reuse = live if target is None else None
        joined = -1
        if target is not None:
            events += 1
            held = held + [target]
            x[d.uz(d.capmesh.outer[target])] = -pb.Z[target]
            joined = target
            c_event, c = c, constraints(d, interface, held)
            if settings.bordered_event_tangent and live is not None:
                reuse = pb.bordered(live, c_event, c)
                if reuse is not None:   # solves with c from it (dr/ddelta: its rows)
                    pb.newest = (reuse, c, pb.newest[2][reuse.keep])
        released = []
        if interface == "frictionless":
            before = held
            x, K, r, held, c, hist = _release_tensile(pb, x, delta, K, r, held, c, hist)
            released = sorted(set(before) - set(held))
            if released:
                reuse = None
        # the centre left the plane: a held node inside the zone let go, or the plane
        # pulls the centre while pushing elsewhere (no_slip holds it down)
        off = (bool(released) and released[0] < max(held)) or centre_pulled(d, r, held)
        try:
            new = pb.state(x, delta, r, held, joined, hist, centre_off=off)
        except QualityError as err:
            if not (stop_at_limit and _has_event(states)):
                raise
            return LoadingPath(interface, tuple(states), timer, str(err))
        states.append(replace(new, dP_ddelta_left=dP_left))
        if progress is not None:
            progress(delta)
        if a_stop is not None and joined > 0 and new.a >= a_stop:
            break
    dx, dP = pb.tangent_direction(K, c)
    states[-1] = _with_stiffness(states[-1], dP, dx)
    return LoadingPath(interface, tuple(states), timer,
                       reached_a=delta < delta_max * (1 - 1e-12))


def _chord_pays(history, goal) -> bool:
    """The next iteration is a chord step: the last cut the residual by CHORD_GAIN, or
    CHORD_LEFT more cuts at its rate reach the tolerance `goal` (a chord step costs about
    a sixth of a Newton iteration with its assembly and factorisation on the base shell)."""
    rate = history[-1] / history[-2]
    return rate <= CHORD_GAIN or (rate < 1 and history[-1] * rate ** CHORD_LEFT <= goal)


def _check_lock_up(d: Discretisation, x, delta):
    """Raise MaterialLimitError if the converged state x is within LOCK_UP of a Gent
    solid's limit: its tangent is then >= 1e4 times the initial one at that point, and
    smaller steps only creep towards the limit."""
    near = limit_state(deformation(d, x)[0], d.material)
    if near is not None and near[0] >= LOCK_UP:
        raise MaterialLimitError(delta, d.material.Jm, *near)
def _has_event(states) -> bool:
    """A node beyond the apex has joined the contact in one of the states."""
    return any(s.joined > 0 for s in states)


def _advance(pb, c, x, delta, dx, free_nodes, target, step, delta_max, modified=True):
    """One loading step from the converged (x, delta): to delta + step, or to the event of
    `target` predicted near there.  Returns (x, delta, K, r, history, target).
    `modified`: settings.modified_newton applies (else full Newton, no chord start).

    If another free node ends up below the plane, its event lies inside the step just
    taken: it is re-located from a secant guess between the two converged states, never
    from the tangent prediction (which can lie far beyond the step that failed).  Each
    re-location therefore shrinks the step, so the search ends.
    """
    d, s = pb.d, pb.s
    # no_slip steps start from the newest factorisation; frictionless ones do not: whether
    # a node just joined is released hangs on the sign of a reaction near zero, which a
    # state converged by chord steps (different within the tolerance) can flip, and then
    # the node joins and leaves again (seen in the Hertz test at delta ~ 1e-6 R)
    modified = modified and s.modified_newton
    chord_start = modified and pb.interface == "no_slip"
    g0 = gaps(d, x, free_nodes)
    guess = x + dx * step
    for _ in range(s.max_relocations):
        xn, dn, Kn, rn, hist = pb.newton(c, guess, delta + step, target, modified,
                                         chord_start)
        if target is not None and dn > delta_max:
            # the event lies beyond the end of the path: stop at delta_max instead
            target, step = None, delta_max - delta
            xn, dn, Kn, rn, hist = pb.newton(c, x + dx * step, delta_max, None,
                                             modified, chord_start)
        if dn < delta * (1 - 1e-12):
            raise ConvergenceError(f"the event of outer node {target} was located behind the "
                                   f"last state (delta = {dn:.6g} < {delta:.6g} R)")
        gn = gaps(d, xn, free_nodes)
        gn[free_nodes == target] = 0.0
        j = int(np.argmin(gn))
        if gn[j] >= -s.gap_tol:
            return xn, dn, Kn, rn, hist, target
        frac = float(np.clip(g0[j] / (g0[j] - gn[j]), 0.0, 1.0))
        target, step = int(free_nodes[j]), (dn - delta) * frac
        guess = x + (xn - x) * frac
    raise ConvergenceError(f"contact front not resolved after {s.max_relocations} "
                           f"re-located events from delta = {delta:.6g} R")


def _with_stiffness(s: State, dP, dx=None):
    left = dP if s.joined < 0 and np.isnan(s.dP_ddelta_left) else s.dP_ddelta_left
    return replace(s, dP_ddelta=dP, dP_ddelta_left=left, dx_ddelta=dx)


def _release_tensile(pb, x, delta, K, r, held, c, hist):
    """Unilateral contact: release held nodes pulled by the plane, re-solve, repeat.

    The node on the axis is never released on its own: with the 2 pi r weight it carries
    no area, so the sign of its reaction is round-off, not lift-off.
    """
    d = pb.d
    while len(held) > 1:
        react = contact_reactions(d, r, held)
        scale = max(np.abs(react).max(), 1e-30)
        react = np.where(np.asarray(held) == 0, np.inf, react)
        worst = int(np.argmin(react))
        if react[worst] >= -1e-8 * scale:
            break
        held = [h for i, h in enumerate(held) if i != worst]
        c = constraints(d, pb.interface, held)
        x, delta, K, r, hist = pb.newton(c, x, delta, None, pb.s.modified_newton)
    return x, K, r, held, c, hist


def relax(d: Discretisation, interface: str, start: State, stop, step: float,
          settings: Settings = Settings(), gamma_edge: float = 0.0,
          edge_width: float = 0.0) -> RelaxationPath:
    """Lower delta from `start` with its held nodes kept, in steps of about `step`.

    `gamma_edge` > 0 (gamma / (C10 R), frictionless only): the held edge carries the
    adhesive edge force (solver.edge); the path then starts with the loaded state
    re-equilibrated under it at the same delta, and each state's U is U_E - gamma pi r^2;
    `edge_width` > 0 spreads the force over that arc / R inside the edge, and then r (the
    states' `a`, their `da_ddelta` its slope) is the covered radius sqrt(<r^2>) (solver.edge).

    `stop(state)` ends the path when it returns True (the state is kept).  A step is
    halved while it is not energy-consistent (`step_mismatch` above
    settings.step_energy_tol) or dP/ddelta changes over it by more than
    settings.step_stiffness_tol of its larger end value (`stiffness_change`), down to
    step / 1000, where it is taken as it is.  The path
    also ends, with the reason in `ended_by`, when Newton fails below step / 1000 or after
    `settings.max_points` states.
    """
    if not (math.isfinite(step) and step > 0):
        raise ValueError(f"relaxation step: {shown(step)} must be a finite number > 0 (units of R)")
    timer = Timer()
    held = list(start.held)
    if gamma_edge > 0:
        if interface != "frictionless":
            raise ValueError(f"gamma_edge: {gamma_edge:g} needs the frictionless interface "
                             f"(held nodes of {interface} do not slide)")
        d = with_edge(d, held, gamma_edge, edge_width)
    pb = _Problem(d, interface, settings, timer)
    c = constraints(d, interface, held)
    x, delta = start.x.copy(), start.delta
    if gamma_edge > 0:          # the loaded state, re-equilibrated with the edge force
        x, _, K, r, hist = pb.newton(c, x, delta)
        dx, dP = pb.tangent_direction(K, c, pb.last_lu)
        start = replace(pb.state(x, delta, r, held, start.joined, hist, dP,
                                 centre_off=centre_pulled(d, r, held), check_J=False),
                        dx_ddelta=dx, dP_ddelta_left=dP)
    else:
        K = None
    if settings.start_tangent and start.dx_ddelta is not None:
        dx, dP = start.dx_ddelta, start.dP_ddelta     # the loading's, with these held nodes
    else:
        K = pb.assemble(x)[0]
        dx, dP = pb.tangent_direction(K, c)
    edge = _edge_radius(d, held)
    compliance = _area_compliance(pb, c, held)
    states = [replace(_with_stiffness(start, dP, dx), **edge(x, dx),
                      **compliance(lambda: pb.assemble(x)[0] if K is None else K, x))]
    outside = np.setdiff1d(np.arange(len(d.capmesh.outer)), held)
    h = step
    penetration = centre_lifts = False
    inversion_delta = np.nan
    ended_by = f"point limit: {settings.max_points} states"
    last = None               # the state before (delta, x, dx/ddelta), for the predictor
    modified = True           # off for the retries of a failed step: full Newton is the fallback
    while len(states) < settings.max_points:
        try:
            xn, dn, Kn, rn, hist = _relaxation_step(pb, c, last, (delta, x, dx), h, modified)
        except ConvergenceError:
            modified = False
            h /= 2
            if h < step * 1e-3:
                ended_by = f"no convergence below delta = {delta:.6g} R"
                break
            continue
        dxn, dPn = pb.tangent_direction(Kn, c, pb.last_lu)
        Un = potential_energy(d, xn)
        miss = step_mismatch(states[-1], dn, rim_load(d, rn), Un, dPn)
        bend = stiffness_change(states[-1].dP_ddelta, dPn, states[0].dP_ddelta)
        if (not (miss <= settings.step_energy_tol and bend <= settings.step_stiffness_tol)
                and h / 2 >= step * 1e-3):                                  # NaN too
            modified = False        # the step outran its cubic or left the branch: shorter
            h /= 2
            continue
        last = (delta, x, dx)
        modified = True
        x, delta, K, r = xn, dn, Kn, rn
        dx, dP = dxn, dPn
        pulled = centre_pulled(d, r, held)
        # the held zone's edge is a crack tip: pointwise J there is not a quality measure;
        # a folded element, or material across the axis, ends the path (its states so far
        # stay: the energy method uses what was reached)
        try:
            s = pb.state(x, delta, r, held, -1, hist, dP, centre_off=pulled, check_J=False,
                         U=Un)
            s = replace(s, **edge(x, dx), **compliance(lambda: K, x))
        except QualityError as err:
            ended_by = str(err)
            break
        states.append(s)
        if len(outside) and gaps(d, x, outside).min() < -settings.gap_tol:
            penetration = True
        if pulled and not centre_lifts:
            centre_lifts, inversion_delta = True, delta
        if stop(s):
            ended_by = "stop criterion"
            break
        h = min(step, 2 * h)
    return RelaxationPath(interface, start, tuple(states), ended_by, penetration,
                          centre_lifts, timer, inversion_delta)


def step_mismatch(s0: State, delta, P, U, dP) -> float:
    """|U - U0 - W| / |W|-scale of one relaxation step from the state s0 to (delta, P, U,
    dP/ddelta): W is the work of P over the step by the two-point Hermite rule (P and its
    slope at both ends, exact for a cubic P(delta)).  Near 0 on a smooth path; O(1) when
    Newton converged to another equilibrium (a branch jump: a different state at the same
    delta has a different energy)."""
    h = delta - s0.delta
    W = h * (s0.P + P) / 2 - h * h * (dP - s0.dP_ddelta) / 12
    scale = abs(h) * (abs(s0.P) + abs(P)) / 2 + h * h * (abs(s0.dP_ddelta) + abs(dP)) / 12
    return abs(U - s0.U - W) / max(scale, 1e-300)


def stiffness_change(dP0, dP1, dP_start) -> float:
    """|dP1 - dP0| / max(|dP0|, |dP1|, STIFFNESS_FLOOR |dP_start|): how much the slope
    dP/ddelta changes over one relaxation step, as a share of its larger end value (the
    floor, a share of the path's first slope, keeps a slope crossing zero from halving a
    step without end).  Small where U_E's quintic spline through (U, P, dP/ddelta) follows
    the path between the two states; near 1 or more over a knee of P(delta).  NaN if a
    slope is not finite (the step is then halved)."""
    scale = max(abs(dP0), abs(dP1), STIFFNESS_FLOOR * abs(dP_start))
    change = abs(dP1 - dP0)
    if not (math.isfinite(change) and math.isfinite(scale)):
        return math.nan
    return change / scale if scale > 0 else 0.0


def _relaxation_step(pb, c, last, now, h, modified=True):
    """Newton from `now` = (delta, x, dx/ddelta) to delta - h (pb.newton's result).

    The start is the cubic (Hermite) extrapolation through `last` and `now` if
    settings.hermite_predictor and there is a `last`, else the tangent; a failed cubic start
    is retried from the tangent, so the predictor never makes a step fail.  `modified`:
    settings.modified_newton applies (else full Newton)."""
    delta, x, dx = now
    modified = modified and pb.s.modified_newton
    if pb.s.hermite_predictor and last is not None:
        try:
            return pb.newton(c, _hermite(last, now, delta - h), delta - h, None, modified)
        except ConvergenceError:
            pass
    return pb.newton(c, x - dx * h, delta - h, None, modified)


def _hermite(a, b, t):
    """The cubic through the states a, b = (delta, x, dx/ddelta) at delta = t."""
    (t0, x0, m0), (t1, x1, m1) = a, b
    L = t1 - t0
    s = (t - t0) / L
    return ((2 * s**3 - 3 * s**2 + 1) * x0 + (s**3 - 2 * s**2 + s) * L * m0
            + (-2 * s**3 + 3 * s**2) * x1 + (s**3 - s**2) * L * m1)


def _area_compliance(pb: _Problem, c: Constraints, held):
    """(tangent, x) -> {"dA_dgamma": the covered area's compliance} of a frictionless held
    set (_Problem.area_compliance: the carriers of the path's edge force, or its edge
    node; `tangent()` gives K at x), {} where the held nodes cannot slide."""
    if pb.interface != "frictionless" or not len(held):
        return lambda tangent, x: {}
    edge = pb.d.edge if pb.d.edge is not None else carriers(pb.d, held)
    return lambda tangent, x: {"dA_dgamma": pb.area_compliance(tangent(), c, edge, x)}


def _edge_radius(d: Discretisation, held):
    """(x, dx/ddelta) -> {"da_ddelta": the held edge's radial slope} (no edge force, or
    one on the edge node), or also {"a": the covered radius} of a spread edge force."""
    if d.edge is None or len(d.edge.dofs) == 1:
        edge_ur = d.ur(d.capmesh.outer[max(held)])
        return lambda x, dx: {"da_ddelta": float(dx[edge_ur])}
    return lambda x, dx: {"a": d.edge.radius(x), "da_ddelta": d.edge.slope(x, dx)}


def edge_forces(d: Discretisation, r_int, held):
    """Plane reactions gathered per held outer edge (corner nodes shared half and half),
    > 0 compression.  Per-node Q2 reactions alternate in size; per-edge sums do not."""
    n = max(held) + 1
    react = np.zeros(n)
    react[list(held)] = contact_reactions(d, r_int, held)
    n_edges = (n - 1) // 2
    j = np.arange(n_edges)
    return 0.5 * react[2 * j] + react[2 * j + 1] + 0.5 * react[2 * j + 2]


def centre_pulled(d: Discretisation, r_int, held) -> bool:
    """The centre wants to lift: the plane pulls the first edge while pushing another.

    In JKR-like contact a tensile centre means a tensile zone throughout, so this is the
    signature of the buckled (ring) contact of the paper's discussion.
    """
    f = edge_forces(d, r_int, held)
    return len(f) > 1 and f[0] < 0 and f.max() > 0
