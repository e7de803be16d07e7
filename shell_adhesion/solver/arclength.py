"""Pseudo-arclength continuation of the rim approach delta with a cohesive interface.

Dimensionless as the solver (lengths / R, forces / (C10 R^2)); delta > 0 approach, P > 0
compression.  With finite-range adhesion P(delta) is S-shaped: it folds in delta at the
jump-in on approach and at the fixed-grips pull-off on retraction.  The unknowns are the
free dofs x and delta; besides equilibrium, each state satisfies

    t . (y - y_k) = ds,     y = (x, delta),

t the unit tangent at the last state y_k in the metric |y|^2 = delta^2 + mean over the
free outer nodes of u_z^2 (so a rigid shift of the shell by delta has length about
|delta|).  Each Newton iteration solves two right-hand sides with the free block of the
tangent (bordering), so the path passes the folds, where that block is singular, as long
as no state lands exactly on one.

Contact and cohesion are one smooth interface law (`solver.cohesive`: a stiff penalty
below the plane), so the path has no contact events.  Tangentially the contact is
frictionless, or no_slip: an outer node whose gap is below 0 at a converged state keeps
its radial displacement (a prescribed dof) until a converged state finds its gap above
RELEASE delta_c (it touched within the last step: it is held where that step left it).
The normal-only law lets the cohesive zone beyond the held nodes slide; the mixed-mode law
(an option for no_slip, `Interface.beta`) resists the slip of each outer node from its
anchor, which the loop sets at every converged state (`cohesive.anchors_at`: held nodes and
those beyond the law's reach take their radius); an update that changes the interface
energy is recorded (`ArcState.anchor_jump`: what released anchors dissipate).

The path starts from the shell lifted clear of the plane (delta0 < 0, no interaction: a
rigid shift), approaches to delta_max, turns round and retracts until the shell is out of
the cohesive range again.  Every loop is bounded (`ArcSettings`); a non-finite residual is a failed step.
"""
from dataclasses import dataclass, field, replace
import math
import time

import numpy as np

from shell_adhesion.errors import ConvergenceError

from .cohesive import Interface, anchors_at, scaled
from .contact import INTERFACES, Constraints, constraints, gaps, rim_load
from .forms import Linearisation, lagrangian, strain_energy, tangent
from .linear import Timer
from .path import REFINE_MAX, REFINE_TOL, Settings, _Problem, _chord_pays
from .pocket import PocketOpened


@dataclass(frozen=True)
class ArcSettings:
    """Continuation controls, lengths in units of R."""

    tol: float = 1e-10         # force residual relative to the largest reaction
    atol: float = 1e-13        # residual floor relative to C10 * volume / size
    max_iter: int = 10         # Newton iterations per corrector
    max_steps: int = 3000      # states on the whole path
    ds_min: float = 1e-10      # step-length floor: a failure below it ends the path
    dx_max: float = 0.25       # largest change of any outer gap per step, in delta_c
    dx_travel: float = 0.1     # ... and in delta_max (resolves P where delta_c is long)
    grow: float = 1.5          # step growth after an easy step
    easy: int = 4              # ... one of at most this many Newton iterations (a chord
    #                            iteration counting as 1 / chord_weight of one)
    cos_min: float = 0.9       # least cosine between the tangents of consecutive states
    P_resolve: float = 1e-3    # a retraction step passing a new least P is halved until
    #                            |dP/ds| ds <= P_resolve |P| at both its ends
    max_resolve: int = 20      # ... at most this many times for one least P
    chord: str = "after"       # corrector iterations reuse the newest factorisation
    #                            ("start": from the first, that of the last tangent;
    #                            "after": once a Newton iteration of this corrector; "": never)
    max_chord: int = 30        # ... at most this many chord iterations per corrector
    chord_weight: float = 3.0  # a chord iteration counts as 1 / this of a Newton one
    stall: int = 100           # a path whose a, c and delta reach no new extreme
    #                            (max on the approach, min on the retraction) in this many
    #                            states ends (the contact edge zigzags between nodes, or
    #                            the path went off onto a detached branch); the 33 paths
    #                            that left the cohesive range in the tests and the base
    #                            shell's at lambda 3 (both interfaces, eight elements
    #                            across the zone) passed one within 13 states
    mirror: bool = True        # a conservative path (`conservative`) reads its retraction
    #                            from its approach, reversed: it is the same curve


@dataclass(frozen=True, eq=False)
class ArcState:
    """A converged state of the path."""

    delta: float               # approach / R
    P: float                   # rim load / (C10 R^2), > 0 compression
    a: float                   # contact radius / R: where the gap crosses 0 (0: no contact)
    c: float                   # cohesive-zone radius / R: where the gap reaches delta_c
    U: float                   # strain energy / (C10 R^3)
    Pi: float                  # interface energy / (C10 R^3)
    iterations: int = 0        # Newton and chord iterations of the corrector that found it
    slope: tuple = (math.nan, math.nan)   # (d delta, dP) along the path's tangent there
    x: np.ndarray = field(default=None, repr=False)
    # the mixed-mode law: Pi with the anchors updated at this state minus Pi (C10 R^3; the
    # path after it starts from that energy); 0 with the normal-only law
    anchor_jump: float = 0.0
    # ... and the anchors / R it was solved with (None with the normal-only law)
    anchors: np.ndarray = field(default=None, repr=False)


@dataclass(frozen=True, eq=False)
class ArcPath:
    """The traced equilibrium path, in path order."""

    states: tuple
    turn: int                  # index of the state at which the approach turned round
    ended_by: str
    timer: Timer

    def array(self, name):
        return np.array([getattr(s, name) for s in self.states])


class _Continuation:
    """Newton machinery for one (discretisation, interface, law)."""

    def __init__(self, iface: Interface, interface: str, s: ArcSettings):
        self.iface, self.d, self.interface, self.s = iface, iface.d, interface, s
        self.timer = Timer()
        self.anchors = None          # the mixed-mode law's history (trace sets it)
        # the loading solver's factorisation of the free block and d(residual)/d(delta)
        problem = _Problem(self.d, interface, Settings(), self.timer)
        self.problem = problem
        self.factor, self.solve = problem.factor, problem.solve
        cm = self.d.capmesh
        on_rim = np.isin(cm.outer, cm.rim)
        self.candidates = np.flatnonzero(~on_rim)           # outer nodes that may touch
        self.Z = cm.nodes[1, cm.outer]
        # the metric on x: the u_z of the outer nodes that may touch (a dot product over
        # them alone: one over every dof is a threaded BLAS call beyond 10,000 dofs)
        self.metric = self.d.uz(cm.outer[self.candidates])

    def linearise(self, x):
        t0 = time.perf_counter()
        K, r = self.iface.add(x, *tangent(self.d, x), self.anchors)
        self.timer.assembly += time.perf_counter() - t0
        return K, r

    def residual(self, x):
        """The residual alone (a chord iteration assembles no tangent), and the
        linearisation that gives the tangent at x on demand (`tangent_of`)."""
        t0 = time.perf_counter()
        lin = Linearisation(self.d, x)
        r = lin.r + self.iface.residual(x, self.anchors)
        self.timer.assembly += time.perf_counter() - t0
        return lin, r

    def tangent_of(self, lin, x):
        """(K, r) at x from the linearisation `residual` gave there."""
        t0 = time.perf_counter()
        K, r = self.iface.add(x, *lin.tangent(), self.anchors)
        self.timer.assembly += time.perf_counter() - t0
        return K, r

    def dot(self, u, du, v, dv):
        m = self.metric
        return float(u[m] @ v[m]) + du * dv

    def tangent_at(self, K, c, orient=None, stale=False):
        """Unit tangent (tx, td) at a converged state of tangent K, oriented along `orient`
        (a previous tangent), or towards increasing delta.  `stale`: start from the newest
        factorisation of c (an earlier iterate's) and refine with K (path.REFINE_MAX
        steps to path.REFINE_TOL), factorising K only if that does not converge."""
        e = np.zeros(self.d.ndof)
        e[c.rimz] = 1.0
        dr_dd = -(K @ e)[c.free]
        tx = np.zeros(self.d.ndof)
        lu = self.problem.newest_of(c)[0] if stale else None
        if lu is not None:
            tx[c.free] = self.solve(lu, -dr_dd)
            for _ in range(REFINE_MAX):
                step = self.solve(lu, -dr_dd - (K @ tx)[c.free])
                tx[c.free] += step
                if np.abs(step).max() <= REFINE_TOL * np.abs(tx).max():
                    break
            else:
                lu = None
        if lu is None:
            lu, dr_dd = self.factor(K, c)
            tx[c.free] = self.solve(lu, -dr_dd)
        tx[c.rimz] = -1.0
        td = 1.0
        n = math.sqrt(self.dot(tx, td, tx, td))
        tx, td = tx / n, td / n
        if orient is not None and self.dot(tx, td, *orient) < 0:
            tx, td = -tx, -td
        return tx, td

    def correct(self, c, x0, d0, t, ds):
        """Equilibrium on the hyperplane t . (y - y0) = ds: (x, delta, K, r, iterations).

        With s.chord, an iteration reuses the newest factorisation of c (a chord step: the
        residual alone is assembled) where `path._chord_pays` (the first one: that of the
        tangent at y0); else, and when a chord step fails to cut the residual, full
        Newton.  `iterations` counts both; a step is easy (ds grows) if it converged in at
        most s.easy full-Newton-equivalent iterations, a chord step counting as
        1 / s.chord_weight of one."""
        s, d = self.s, self.d
        tx, td = t
        x = x0 + ds * tx
        delta = d0 + ds * td
        x[c.rimz] = -delta
        history = []
        size = math.sqrt(self.dot(x0, d0, x0, d0))     # round-off scale of the constraint
        lu, dr_dd = (self.problem.newest_of(c) if s.chord == "start" else (None, None))
        full = chord = 0
        tpos = c.free_pos[self.metric]
        m = self.metric[tpos >= 0]          # the metric's free dofs
        tpos = tpos[tpos >= 0]
        for it in range(s.max_iter + s.max_chord + 1):
            with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                lin, r = self.residual(x)
            if not np.all(np.isfinite(r)):
                raise ConvergenceError("non-finite residual")
            res = np.abs(r[c.free]).max()
            goal = s.tol * max(np.abs(r[c.fixed]).max(), 0.0) + s.atol * d.force_scale
            g = self.dot(tx, td, x - x0, delta - d0) - ds
            history.append(res)
            if res <= goal and abs(g) <= 1e-10 * (abs(ds) + size):
                with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                    K, r = self.tangent_of(lin, x)
                if not np.all(np.isfinite(K.data)):
                    raise ConvergenceError("non-finite tangent")
                return x, delta, K, r, (full, chord)
            if full >= s.max_iter or (it > 2 and res > 1e3 * history[1]):
                break
            if (s.chord and lu is not None and chord < s.max_chord
                    and (len(history) == 1 or _chord_pays(history, goal))):
                chord += 1
                self.timer.chord_iterations += 1
            else:
                with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                    K = self.tangent_of(lin, x)[0]
                if not np.all(np.isfinite(K.data)):
                    raise ConvergenceError("non-finite tangent")
                lu, dr_dd = self.factor(K, c)
                full += 1
                self.timer.newton_iterations += 1
            a = self.solve(lu, -r[c.free])
            b = self.solve(lu, -dr_dd)
            dd = (-g - tx[m] @ a[tpos]) / (tx[m] @ b[tpos] + td)
            x[c.free] += a + b * dd
            delta += dd
            x[c.rimz] = -delta
        raise ConvergenceError("corrector did not converge (residuals "
                               + ", ".join(f"{h:.3g}" for h in history[-3:]) + ")")


# a held node lets go where its gap exceeds this fraction of delta_c.  At 0 the node at
# the contact edge flickers in and out on the approach, each release dissipating the shear
# it held (the base shell, lambda 1, coarse, pressed to 2 mm: 6.5e-3 of its largest
# U + Pi lost before the turn); 1e-3, 1e-2, 1e-1 give the same P* to 1e-4
RELEASE = 0.01
# the adhesion-free approach (`trace(adhesion_free_approach=True)`): its law's sigma0 and
# gamma as a fraction of the law's (the same delta_c and penalty: the same contact), and
# the first step of the ramp that switches the law on at the turn (halved on failure down
# to SWITCH_STEP_MIN, where a snap is passed by descent: `_descend`)
SWITCH_OFF = 1e-8
SWITCH_STEP = 0.125
SWITCH_STEP_MIN = 1e-3


def trace(iface: Interface, delta_max: float, delta0: float = None,
          settings: ArcSettings = ArcSettings(), progress=None, a_turn: float = None,
          interface: str = "frictionless", adhesion_free_approach: bool = False) -> ArcPath:
    """The equilibrium path from the shell lifted to delta0 / R (default: twice the law's
    reach above the plane) to delta_max / R (or, sooner, to a contact radius of a_turn / R)
    and back until the shell leaves the cohesive range (or settings.max_steps states);
    `interface` the tangential contact (INTERFACES).  `adhesion_free_approach` (the contact
    history of the energy method's loading; study.cohesive_case's no_slip default
    `history="loading"`): approach with the law
    switched off (`cohesive.scaled` by SWITCH_OFF: contact alone; no_slip nodes held where
    they touch), switch it on at the turn at fixed delta (`_switch_on`; the path's state
    at the turn is the switched-on one, the approach's Pi that of the switched-off law),
    then retract as usual.  A `conservative` path (settings.mirror) that starts out of the
    cohesive range is not traced back: its retraction is its approach reversed
    (`_retraced`), and its approach resolves each least P as a retraction does."""
    if not (math.isfinite(delta_max) and delta_max > 0):
        raise ValueError(f"delta_max: {delta_max!r} must be a finite number > 0 (units of R)")
    if interface not in INTERFACES:
        raise ValueError(f"interface: {interface!r} must be one of {', '.join(INTERFACES)}")
    if iface.beta is not None and interface != "no_slip":
        raise ValueError(f"interface: {interface!r} with the mixed-mode law (beta = "
                         f"{iface.beta:g}): it is for no_slip only")
    s, law, d = settings, iface.law, iface.d
    cn = _Continuation(iface, interface, s)
    if adhesion_free_approach:
        cn.iface = iface.with_law(scaled(law, SWITCH_OFF))
    delta0 = -2.0 * law.reach if delta0 is None else delta0
    free_slip = constraints(d, "frictionless", [])
    c, stuck = free_slip, np.zeros(0, dtype=int)
    x = np.zeros(d.ndof)
    x[d.n2:2 * d.n2] = -delta0                   # rigid shift: every u_z = -delta0
    if iface.beta is not None:
        cn.anchors = iface.radii(x)
    K, r = cn.linearise(x)
    delta = delta0
    t = cn.tangent_at(K, c)
    states = [_state(cn, x, delta, K, r, t, 0)]
    ds = 0.1 * law.delta_c
    turn = -1
    least, halvings = math.inf, 0        # the least P of the retraction (or of a mirrored
    #                                      approach) so far
    ended_by = f"step limit: {s.max_steps} states"
    outer_z = d.uz(d.capmesh.outer[cn.candidates])
    stalled = Stall()
    # (from a first state out of the cohesive range: the reversed approach leaves it)
    mirrored = (s.mirror and conservative(iface, interface, adhesion_free_approach)
                and gaps(d, states[0].x, cn.candidates).min() > law.reach)
    before = None           # a mirrored approach: (t, x, delta, ds, least) before its last step
    looked_back = 0         # ... and the steps it took again (at most s.max_resolve)
    while len(states) < s.max_steps:
        # the step: no outer gap changes by more than dx_max delta_c (or dx_travel
        # delta_max) on the tangent
        ds = min(ds, min(s.dx_max * law.delta_c, s.dx_travel * delta_max)
                 / (np.abs(t[0][outer_z]).max() + abs(t[1])))
        try:
            x_new, d_new, K, r, (full, chord) = cn.correct(c, x, delta, t, ds)
            t_new = cn.tangent_at(K, c, t, stale=bool(s.chord))
            if cn.dot(*t_new, *t) < s.cos_min:
                # the tangent turned too far in one step: the corrector may have crossed
                # to another part of the path (a fold passed, or the branch behind)
                raise ConvergenceError(f"the tangent turned by more than "
                                       f"{math.degrees(math.acos(s.cos_min)):.0f} degrees")
        except ConvergenceError as err:
            ds *= 0.5
            if ds < s.ds_min:
                ended_by = f"step length below {s.ds_min:g} at delta = {delta:.6g} R ({err})"
                break
            continue
        state = _state(cn, x_new, d_new, K, r, t_new, full + chord)
        # (a mirrored path's approach is its retraction: resolved once the law acts)
        resolving = ((turn >= 0 or mirrored and min(states[-1].c, state.c) > 0)
                     and halvings < s.max_resolve and len(states) - 1 > turn
                     and _passes_least(states[-1], state, least))
        if resolving and _coarse(states[-1], state, ds, s):
            ds *= 0.5               # resolve the least P: a corner where the contact is lost
            halvings += 1
            continue
        if (resolving and turn < 0 and before is not None and looked_back < s.max_resolve
                and _coarse(states[-2], states[-1], before[3], s)):
            # the approach reaches a least P through the corner the retraction leaves it
            # by: the step before is taken again, halved, as the retraction's would be
            t, x, delta, ds, least = before[0], before[1], before[2], 0.5 * before[3], before[4]
            states.pop()
            before = None
            looked_back += 1
            continue
        before = (t, x, delta, ds, least) if mirrored else None
        if state.P < least:
            least, halvings = state.P, 0
        t, x, delta = t_new, x_new, d_new
        states.append(state)
        if progress is not None:
            progress(states[-1])
        if full + chord / s.chord_weight <= s.easy:
            ds *= s.grow
        # (a_turn only where the approach advances: behind the jump-in, delta falls)
        if turn < 0 and (delta >= delta_max
                         or a_turn is not None and states[-1].a >= a_turn and t[1] > 0):
            if adhesion_free_approach:
                try:
                    x, K, r, c, stuck, n = _switch_on(cn, iface, c, x, delta, stuck, interface)
                except ConvergenceError as err:
                    ended_by = f"the law did not switch on at delta = {delta:.6g} R ({err})"
                    break
                t = cn.tangent_at(K, c, (np.zeros(d.ndof), -1.0))
                states.append(_state(cn, x, delta, K, r, t, n))
                if progress is not None:
                    progress(states[-1])
            elif mirrored:
                turn = len(states) - 1
                states += _retraced(states, lambda q: gaps(d, q.x, cn.candidates).min()
                                    > law.reach)
                ended_by = "left the cohesive range"
                break
            else:
                t = (-t[0], -t[1])
            turn = len(states) - 1
            least = states[-1].P
        elif turn >= 0 and gaps(d, x, cn.candidates).min() > law.reach:
            ended_by = "left the cohesive range"
            break
        if stalled.after(states[-1].a, states[-1].c, delta, retracting=turn >= 0,
                         new_leg=len(states) - 1 == turn) >= s.stall:
            ended_by = (f"stalled: none of the contact radius, the cohesive-zone radius and "
                        f"delta passed its extreme of the "
                        f"{'retraction' if turn >= 0 else 'approach'} in {s.stall} states")
            break
        if turn < 0 and delta < delta0 and gaps(d, x, cn.candidates).min() > law.reach:
            # below delta0 in contact is the branch behind the jump-in (a compliant shell
            # held by its adhered apex); out of range, the approach went back
            ended_by = f"the approach turned back out of range below delta0 = {delta0:.6g} R"
            break
        if interface == "no_slip":
            g = gaps(d, x, cn.candidates)
            held = (g < 0.0) | (np.isin(cn.candidates, stuck) & (g <= RELEASE * law.delta_c))
            changed = not np.array_equal(cn.candidates[held], stuck)
            if changed:
                stuck = cn.candidates[held]
                c = held_radially(d, free_slip, stuck)
            if cn.anchors is not None:
                before = states[-1].Pi
                cn.anchors = anchors_at(cn.iface, x, cn.anchors, stuck)
                jump = cn.iface.energy(x, cn.anchors) - before
                if jump != 0.0:         # the tangent moved with the anchors
                    states[-1] = replace(states[-1], anchor_jump=jump)
                    K = cn.linearise(x)[0]
                    changed = True
            if changed:
                try:
                    t = cn.tangent_at(K, c, t)
                except ConvergenceError as err:
                    ended_by = f"no tangent after the stuck nodes changed ({err})"
                    break
    return ArcPath(tuple(states), turn, ended_by, cn.timer)


def conservative(iface: Interface, interface: str, adhesion_free_approach: bool) -> bool:
    """True if the path's states depend on delta alone, not on the way there: frictionless
    contact with the normal-only law acting from the first touch (no held nodes, no
    anchors, no switch).  Its equilibrium states form one curve, which the retraction
    follows back from the turn: the approach, reversed."""
    return interface == "frictionless" and iface.beta is None and not adhesion_free_approach


def _retraced(approach: list, out_of_range) -> list:
    """The retraction of a conservative path: the states of `approach` before its last
    (the turn) in reverse order, each tangent reversed, up to the first for which
    `out_of_range(state)` holds (the shell has left the cohesive range), included."""
    back = []
    for q in reversed(approach[:-1]):
        back.append(replace(q, slope=(-q.slope[0], -q.slope[1])))
        if out_of_range(q):
            break
    return back


def _switch_on(cn, iface, c, x, delta, stuck, interface):
    """Switch cn's interface law on to iface's at fixed delta / R, from the converged
    state x of the switched-off law: sigma0 and gamma ramped from 0 to the law's (steps of
    SWITCH_STEP, halved on failure; below SWITCH_STEP_MIN the step is taken by descent,
    `_descend`: a jump-in), each step re-solved with no_slip's held nodes updated as
    `trace` does (a node that touches is held where it is) until they hold; the anchors of
    the mixed-mode law start at every outer node's radius at the switch (no history of
    adhesion).  Returns (x, K, r, constraints, stuck, Newton and chord iterations);
    ConvergenceError if a descent fails."""
    d, law = cn.d, iface.law
    fixed = (np.zeros(d.ndof), 1.0)                 # the hyperplane delta = const
    free_slip = constraints(d, "frictionless", [])
    if cn.anchors is not None:
        cn.anchors = iface.radii(x)
    f, df, its = SWITCH_OFF, SWITCH_STEP, 0
    while f < 1.0:
        g_f = min(1.0, f + df)
        cn.iface = iface.with_law(scaled(law, g_f)) if g_f < 1.0 else iface
        try:
            x_new, stuck_new, c_new, K, r, n = _held_solve(cn, c, x, delta, stuck, interface,
                                                           free_slip, fixed,
                                                           descend=df < SWITCH_STEP_MIN)
        except ConvergenceError:
            if df < SWITCH_STEP_MIN:
                raise
            df *= 0.5
            continue
        x, stuck, c, f, its = x_new, stuck_new, c_new, g_f, its + n
        if df < SWITCH_STEP_MIN:
            df = SWITCH_STEP
        if cn.anchors is not None:
            cn.anchors = anchors_at(cn.iface, x, cn.anchors, stuck)
    return x, K, r, c, stuck, its


def _held_solve(cn, c, x, delta, stuck, interface, free_slip, fixed, max_updates=50,
                descend=False):
    """Equilibrium at fixed delta, the no_slip held nodes updated (`trace`'s rule) and
    re-solved until they hold: (x, stuck, c, K, r, iterations); `descend`: where Newton
    fails, `_descend` first."""
    law, its = cn.iface.law, 0
    for _ in range(max_updates):
        try:
            x, _, K, r, (full, chord) = cn.correct(c, x, delta, fixed, 0.0)
        except ConvergenceError:
            if not descend:
                raise
            x, full = _descend(cn, c, x, early=True)
            x, _, K, r, (n, chord) = cn.correct(c, x, delta, fixed, 0.0)
            full += n
        its += full + chord
        if interface != "no_slip":
            return x, stuck, c, K, r, its
        g = gaps(cn.d, x, cn.candidates)
        held = (g < 0.0) | (np.isin(cn.candidates, stuck) & (g <= RELEASE * law.delta_c))
        if np.array_equal(cn.candidates[held], stuck):
            return x, stuck, c, K, r, its
        stuck = cn.candidates[held]
        c = held_radially(cn.d, free_slip, stuck)
    raise ConvergenceError(f"the held nodes still changed after {max_updates} solves")


def _descend(cn, c, x, max_iter=600, mu0=1e-2, early=False):
    """Pseudo-transient continuation at fixed delta, held nodes and anchors: steps
    (K + mu D) dx = -r on the free dofs, D the mean of |diag K| added to the displacement
    dofs' diagonal only (an overdamped flow of the displacements, the incompressibility
    kept at each step), mu scaled with the residual (switched evolution relaxation: mu
    falls as the flow settles) and raised tenfold where a step fails; returns (x,
    iterations) once a plain Newton corrector (`correct`) converges from a step taken
    with mu <= 1e-6 (or from every tenth step).  Passes a snap (a jump-in at fixed
    delta) that the corrector alone cannot, to the equilibrium the damped flow settles
    in.  A flow that has not settled after max_iter steps creeps away from an unstable
    state (the residual barely changes, and mu with it): up to ESCAPE_STEPS more steps
    (`early`: sooner, once the residual has risen to ESCAPE_RISE times the least it
    reached, or has not halved (STALL) over the last STALL_STEPS steps)
    then lower mu by at least ESCAPE each, every one of them required to lower the
    energy (`forms.lagrangian` plus the interface's; mu raised tenfold where it does
    not).  A sealed gas (the pocket's: `on_gas_law` of d.cavity) stays on its law, its
    unknown set from the volume after each step; a step that loses the pocket's ring, or
    raises the residual more than DESCENT_GROWTH times, is retried with more damping,
    and PocketOpened is raised where even a step damped by MU_OPENS loses the ring.
    ConvergenceError after max_iter + ESCAPE_STEPS steps."""
    d = cn.d
    fixed = (np.zeros(d.ndof), 1.0)
    delta = -x[c.rimz].mean()
    K, r = cn.linearise(x)
    u = c.free[c.free < 2 * d.n2]                       # the free displacement dofs
    lo, hi = K.indptr[u], K.indptr[u + 1]
    slot = np.array([a + np.searchsorted(K.indices[a:b], i) for i, a, b in zip(u, lo, hi)])
    on_gas_law = getattr(d.cavity, "on_gas_law", lambda y: y)
    guarded = hasattr(d.cavity, "on_gas_law") and d.cavity.sealed     # DESCENT_GROWTH
    energy = lambda v: lagrangian(d, v) + cn.iface.energy(v, cn.anchors)     # noqa: E731
    mu, res_before, E, escape_at = mu0, None, None, max_iter
    history = []                                        # the residual at each step
    for it in range(max_iter + ESCAPE_STEPS):
        if it:
            K, r = cn.linearise(x)
        res = float(np.linalg.norm(r[c.free]))
        history.append(res)
        if early and escape_at == max_iter and (
                res > ESCAPE_RISE * min(history)            # creeping off an unstable state
                or it >= STALL_STEPS and res > STALL * history[it - STALL_STEPS]):  # stalled
            escape_at = it
        escaping = it >= escape_at
        if res_before is not None:
            lower = mu * min(res / res_before, ESCAPE) if escaping else mu * res / res_before
            mu = float(np.clip(lower, 1e-9, MU_OPENS))
        res_before = res
        if escaping and E is None:
            E = energy(x)
        D = np.abs(K.data[slot]).mean()
        for _ in range(20):
            Km = K.copy()
            Km.data[slot] += mu * D
            try:
                lu, _ = cn.factor(Km, c)
                dx = cn.solve(lu, -r[c.free])
                y = x.copy()
                y[c.free] += dx
                y = on_gas_law(y)
            except PocketOpened:
                if mu >= MU_OPENS:      # however short the step, the flow opens the pocket
                    raise
                mu *= 10.0
                continue
            except ConvergenceError:
                mu *= 10.0
                continue
            with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                ry = cn.residual(y)[1][c.free]
            if np.all(np.isfinite(ry)) and not (
                    guarded and not np.linalg.norm(ry) <= DESCENT_GROWTH * res):
                E_y = energy(y) if escaping else None
                if not escaping or E_y <= E + DESCENT_ROUNDOFF * abs(E):
                    break
            mu *= 10.0
        else:
            raise ConvergenceError(f"descent: no finite step (mu = {mu:.3g})")
        x, E = y, E_y
        if mu <= 1e-6 or it % 10 == 9:
            try:
                cn.correct(c, x, delta, fixed, 0.0)
                return x, it + 1
            except ConvergenceError:
                pass
    raise ConvergenceError(f"descent: no equilibrium after {it + 1} steps")


DESCENT_GROWTH = 10.0   # `_descend` with a sealed pocket: a step that raises the residual
#                         more than this many times is retried with more damping (t/R 0.02,
#                         coarser mesh: without it the flow cycled through four states for
#                         ever; the loading's jumps without a pocket need such steps: the
#                         sharp contact's flow found no equilibrium with the rule)
ESCAPE = 0.7        # `_descend`, escaping: mu falls at least this much per step
ESCAPE_RISE = 4.0   # `_switch_on`'s descents escape once the residual has risen to this many
#                     times its least, or stalls (the ring's adhesion limit, t/R 0.02: the
#                     flow's residual falls to about 1e-8 in 100 steps, then rises as it
#                     creeps (coarser mesh) or stays there for 500 (coarse); the limit's
#                     switches 33 -> 16 s and 56 -> 37 s, the same brackets.  The jumps of
#                     `snap._jump` keep max_iter: escaping sooner lands them elsewhere)
STALL_STEPS, STALL = 100, 0.5   # ... stalls: not halved over the last STALL_STEPS steps
ESCAPE_STEPS = 600  # `_descend`: the escaping steps after max_iter (the open thin shell,
#                     adhesion switched on at 5 t four times above its ring's limit: the
#                     dimple crept 3e-5 R per step and found no state in 3000 steps of the
#                     residual-scaled flow; escaping, it closes in 130 (coarser mesh))
DESCENT_ROUNDOFF = 1e-10    # `_descend`, escaping: the energy rise (relative) a step may
#                             have: the sealed gas's and the cavity load's energies cancel
#                             to about 1e-14 of theirs
MU_OPENS = 1e6      # `_descend`: the damping above which mu does not fall by itself, and at
#                     which a step that still opens a sealed pocket means the flow opens it


class Stall:
    """Counts the states since the path last passed an extreme of its leg: the largest
    contact radius, cohesive-zone radius or delta on the approach, the least on the
    retraction (a path whose contact edge zigzags between nodes, or that went off onto a
    detached branch, passes none; the jump-in, where delta falls before the contact
    radius grows, passes new cohesive-zone radii)."""

    def __init__(self):
        self.best, self.since = None, 0

    def after(self, a, c, delta, retracting, new_leg=False) -> int:
        """The count after a state of contact radius a, cohesive-zone radius c and
        approach delta (units of R)."""
        sign = -1.0 if retracting else 1.0
        now = np.array([a, c, delta]) * sign
        if self.best is None or new_leg:
            self.best, self.since = now, 0
        elif np.any(now > self.best + 1e-12):
            self.best, self.since = np.maximum(self.best, now), 0
        else:
            self.since += 1
        return self.since


def _passes_least(old: ArcState, new: ArcState, least: float) -> bool:
    """True if the step from `old` to `new` passes a least P (dP/ds turns from < 0 to > 0)
    at or below `least`, the least P of the leg so far."""
    return old.slope[1] < 0 < new.slope[1] and min(old.P, new.P) <= least


def _coarse(old: ArcState, new: ArcState, ds: float, s: ArcSettings) -> bool:
    """True if P may vary across the step from `old` to `new` (arc length ds) by more than
    s.P_resolve |P| (|dP/ds| ds at either end)."""
    return max(abs(old.slope[1]), abs(new.slope[1])) * ds > s.P_resolve * abs(min(old.P, new.P))


def held_radially(d, base: Constraints, outer_index) -> Constraints:
    """`base` with the radial dofs of the outer nodes `outer_index` (into capmesh.outer)
    prescribed too (no_slip contact: they keep their radial displacement)."""
    fixed = np.union1d(base.fixed, d.ur(d.capmesh.outer[outer_index]))
    mask = np.ones(d.ndof, dtype=bool)
    mask[fixed] = False
    free = np.flatnonzero(mask)
    free_pos = np.full(d.ndof, -1)
    free_pos[free] = np.arange(len(free))
    return Constraints(fixed, free, base.rimz, free_pos)


def _state(cn, x, delta, K, r, t, it) -> ArcState:
    d, iface = cn.d, cn.iface
    a = contact_radius(iface, x)
    # the tangent t = (dx, d delta) moves the internal forces by K dx
    return ArcState(delta, rim_load(d, r), a, cohesive_radius(iface, x, a),
                    strain_energy(d, x), iface.energy(x, cn.anchors), it,
                    (float(t[1]), rim_load(d, K @ t[0])), x.copy(),
                    anchors=None if cn.anchors is None else cn.anchors.copy())


def work(path: ArcPath) -> np.ndarray:
    """The work of P from the first state to each state, the integral of P d delta
    (units of C10 R^3; P > 0 compression, delta > 0 approach: the work done on the shell).

    Each step is a cubic Hermite curve in the (delta, P) plane (scaled by the ranges of
    delta and P) through its two states with their path tangents (`ArcState.slope`), its
    parameter the chord length: exact for a cubic arc, and it passes the folds, where P is
    not a function of delta."""
    D, P = path.array("delta"), path.array("P")
    scale = np.array([np.ptp(D), np.ptp(P)])
    if len(D) < 2 or not np.all(scale > 0):
        return np.zeros(len(D))
    y = np.stack([D, P], 1) / scale
    t = np.array([s.slope for s in path.states]) / scale
    t /= np.linalg.norm(t, axis=1)[:, None]
    xi, wq = np.polynomial.legendre.leggauss(3)      # exact: P(u) dD/du is of degree 5
    u = 0.5 * (xi + 1)
    h = np.stack([2 * u ** 3 - 3 * u ** 2 + 1, u ** 3 - 2 * u ** 2 + u,
                  3 * u ** 2 - 2 * u ** 3, u ** 3 - u ** 2])
    dh = np.stack([6 * u ** 2 - 6 * u, 3 * u ** 2 - 4 * u + 1,
                   6 * u - 6 * u ** 2, 3 * u ** 2 - 2 * u])
    W = np.zeros(len(D))
    for k in range(len(D) - 1):
        chord = y[k + 1] - y[k]
        L = float(np.hypot(*chord))
        # each tangent taken along the step (the turn at delta_max reverses the path)
        t0 = t[k] * np.sign(t[k] @ chord)
        t1 = t[k + 1] * np.sign(t[k + 1] @ chord)
        ctrl = np.stack([y[k], L * t0, y[k + 1], L * t1])      # (4, 2)
        Pk = h.T @ ctrl[:, 1]
        dD = dh.T @ ctrl[:, 0]
        W[k + 1] = W[k] + 0.5 * float(np.sum(wq * Pk * dD))
    return W * scale[0] * scale[1]


def _crossing(iface: Interface, x, level: float, a: float = 0.0) -> float:
    """Deformed radius / R at which the outer surface's gap first reaches `level` along
    the meridian from the apex, at or beyond the first point whose radius reaches a
    (linear between quadrature points); 0 if the gap at the apex already reaches it.
    Along the meridian, not sorted by radius: a shell pulled flat beyond 0.9 R curls
    back inward above its contact, and its high points there have radii beyond a."""
    r, z, _ = iface._points(x)
    r, z = r.ravel(), z.ravel()
    past = np.flatnonzero((r >= a) & (z >= level))
    if not len(past):
        return float(r.max())
    j = int(past[0])
    if j == 0:
        return 0.0
    return max(a, float(r[j - 1] + (level - z[j - 1]) * (r[j] - r[j - 1]) / (z[j] - z[j - 1])))


def contact_radius(iface: Interface, x) -> float:
    """Contact radius a / R: where the gap first crosses 0 (0: no contact)."""
    return _crossing(iface, x, 0.0)


def cohesive_radius(iface: Interface, x, a: float) -> float:
    """Cohesive-zone radius c / R: where the gap first reaches delta_c beyond a."""
    return _crossing(iface, x, iface.law.delta_c, a)


@dataclass(frozen=True)
class CohesivePullOff:
    """Pull-off of a retraction (units of R and C10 R^2; P < 0 tension).

    Fixed load: the least P (P_star) with its delta, a and c; fixed grips: the first fold
    in delta after it (delta_dagger) with its P, a and c (NaN if delta has no fold there:
    the fixed-grips retraction then separates without a jump)."""

    P_star: float
    delta_star: float
    a_star: float
    c_star: float
    P_dagger: float
    delta_dagger: float
    a_dagger: float
    c_dagger: float


def pull_off(path: ArcPath) -> CohesivePullOff:
    """The pull-off of the retraction part of `path` (from its turn): each extremum is
    the vertex of the parabola through the sampled extremum and its two neighbours (P
    against delta at the least P; delta against P at the fold), a and c linear between
    the two states around it."""
    if path.turn < 0:
        raise ValueError("the path did not turn round: no retraction")
    s = path.states[path.turn:]
    D = np.array([q.delta for q in s])
    P = np.array([q.P for q in s])
    i, d_star, P_star = least_P(D, P)
    j = next((k for k in range(max(i, 1), len(D) - 1) if D[k] <= D[k - 1] and D[k] < D[k + 1]),
             None)
    if j is None:       # no fold in delta (DMT-like): fixed grips separate smoothly
        dagger = (np.nan,) * 4
    else:
        P_dag, d_dag = _vertex(P[j - 1:j + 2], D[j - 1:j + 2])
        dagger = (P_dag, d_dag, *_between(s, P, j, P_dag))
    return CohesivePullOff(P_star, d_star, *_between(s, D, i, d_star), *dagger)


def least_P(D, P) -> tuple:
    """(i, delta*, P*) of a retraction sampled at (D, P) from its turn: the least sampled
    P at i, and the vertex of the parabola P(delta) through it and its two neighbours.
    ValueError where the least P is at either end (not reached)."""
    i = int(np.argmin(P))
    if i in (0, len(P) - 1):
        raise ValueError("the retraction does not reach its least P")
    d_star, P_star = _vertex(D[i - 1:i + 2], P[i - 1:i + 2])
    return i, d_star, P_star


def _vertex(u, v):
    """(u, v) at the vertex of the parabola v(u) through three points."""
    c2, c1, c0 = np.polyfit(u, v, 2)
    if not c2 > 0:
        k = int(np.argmin(v))
        return float(u[k]), float(v[k])
    u0 = float(np.clip(-c1 / (2 * c2), u.min(), u.max()))
    return u0, float(np.polyval([c2, c1, c0], u0))


def _between(states, key, k, value):
    """(a, c) linear in `key` between state k and its neighbour towards `value`."""
    m = k + 1 if (key[k + 1] - key[k]) * (value - key[k]) > 0 else k - 1
    w = 0.0 if key[m] == key[k] else (value - key[k]) / (key[m] - key[k])
    return tuple((1 - w) * getattr(states[k], n) + w * getattr(states[m], n) for n in "ac")
