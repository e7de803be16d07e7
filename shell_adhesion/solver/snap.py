"""Loading through folds: the frictionless loading without adhesion continued by arc
length, with a contact set of any shape along the meridian (a disc, a ring, a disc and a
ring).

Dimensionless as the solver (lengths / R, forces / (C10 R^2), energies / (C10 R^3));
delta > 0 approach, P > 0 compression.

A thin deep shell pressed by a plane first flattens (Reissner, P = 16 C10 t^2 delta / R),
then its flat region inverts into a dimple (Pogorelov's mirror buckling): the apex lifts
off and the contact becomes a ring, P growing about as delta^(1/2).  Under displacement
control the transition is a snap.  `solver.path.load` cannot pass it: it follows delta
and keeps the axis node on the plane.  Here the path is traced by the cohesive paths'
pseudo-arclength continuation (`solver.arclength._Continuation`: y = (x, delta), one
bordered Newton per step on t . (y - y_k) = ds), so it passes the folds of P(delta).

Contact is the cohesive interface's penalty alone (`PenaltyContact`, no adhesion): below
the plane the surface is pushed back at `stiffness` C10 / R per unit penetration, its
slope rising from 0 over the first `onset` / R; the force is never tensile.  A point of the
outer surface joins the contact where its gap closes and leaves where its pressure falls
to zero, evaluated at the edge's quadrature points: node-wise unilateral contact of the
Q2 surface chatters (solver.cohesive: a node at the edge of a held zone carries a tensile
reaction under a compressive pressure; on a flattened thin shell the axis node's reaction
turns tensile while the pressure is compressive everywhere, and a ring's inner edge node
joins and leaves in a closed cycle).  The contact set of a state is the runs of the
outer surface below the plane (by quadrature point), with the radii where the gap crosses
zero.  The work of P equals U + Pi (strain energy plus the penalty's): the path is
conservative.  Every loop is bounded (`SnapSettings`).

Where the snap falls depends on the regularisation.  The flattened
centre carries almost no pressure, and the penalty's slope vanishes with the pressure, so
a soft contact lets the centre lift early: the shell's loss of stability (a bifurcation
where the centre lifts off) becomes a fold reached sooner, as an imperfection would make
it.  t/R 0.02, h/R 1, coarser mesh: with an onset of 1e-4, 7e-5, 5e-5 R the traced jump
is at 4.37, 4.61, 4.89 t (at 1e-4 R: 4.83 t on the coarse mesh, 4.90 t on the default);
with a sharp contact (1e-5, 3e-6, 1e-6 R) the loading stops at 6.27, 6.325, 6.331 t
(3e-6 R: coarse 6.337, default 6.339 t), where delta and P stand still while the centre
lifts, and no arc step beyond converges: the converged snap is there, about 6.33 t, and
the jump traced with the default onset comes 24 % early on the coarse mesh.  Where the
loading stalls so, it jumps as a displacement-controlled test does (`_jump`,
SnapSettings.jump_push): the rim pushed on a little, the shell let settle by damped
descent, the state it settles in brought back to the same delta on its branch; the
energy the jump dissipates is recorded (the state before's anchor_jump) and the path
goes on (`SnapState.landed`; at t/R 0.02: P to 0.40 of its value, from two rings to one
ring around a dimple, 41 % of the strain energy dissipated).  Only
stiffness / onset counts (the penetration stays within the onset).  The
branch after the jump hardly depends on it (Pogorelov slope 0.583 at all three onsets).

Unloading and the pocket: `trace_loading(..., unload_to=)` turns at delta_max and follows
the path on with delta decreasing.  A discretisation bound to a `solver.pocket.Pocket`
carries the gas of the pocket between a ring contact and the plane: sealed, from the
first ring around an apex lifted by `SnapSettings.seal_lift` t (or from the turn), the
gas's gauge pressure loads the shell and the energy balance gains the gas's energy
(`SnapState.E_gas`); the path ends where the ring around the pocket is lost.

Sticking (`interface="no_slip"`): a quadrature point of the outer surface in contact is
held radially at its radius at the last converged state before it touched, by a
tangential penalty of the normal one's stiffness whose weight rises with the penetration
as the normal slope does (`PenaltyContact.mixed`; the anchors per quadrature point,
`cohesive.point_anchors_at`, move only where a point is off the plane, where the
tangential penalty and its first two derivatives vanish, so the path stays conservative
and `SnapState.anchor_jump` is 0).  With gamma = 0 it carries no tension: a point lets go
as it lifts off.  `SnapSettings.stick_at_turn`: frictionless through the snap, sticking
from the turn.  A step whose chord leaves the tangents at its two ends (both agreeing)
cut across a loop of the path where the stuck ring peels; sticking, it is refused (the
step halves down to ds_corner), else the energy the ring stored is lost with the loop
(SnapSettings.cos_min_stick).
"""
from dataclasses import dataclass, field
import dataclasses
import math
import time

import numpy as np

from shell_adhesion.errors import ConvergenceError, InputError

from .arclength import (SWITCH_OFF, ArcSettings, _Continuation, _descend, _switch_on, least_P,
                        work as arc_work)
from .cohesive import CohesiveLaw, Interface, point_anchors_at, scaled
from .contact import INTERFACES, constraints, gaps, rim_load
from .forms import Discretisation, discretise, potential_energy, strain_energy
from .geometry import T_MIN, Cap, check_cap, check_delta_max
from .lid import LID_THROUGH, own_lid
from .penalty import CONTACT_ONSET, CONTACT_STIFFNESS, penalty
from .mesh import cap_mesh, mesh_spec
from .linear import Timer
from .pocket import PocketLoad, PocketOpened, seal


@dataclass(frozen=True)
class PenaltyContact:
    """Non-penetration without adhesion, as a law of the gap g / R for
    `solver.cohesive.Interface`: energy, stress (> 0 pulls towards the plane, so < 0
    here: the plane pushes) and slope.  `stiffness` in C10 / R, `onset` / R."""

    stiffness: float = CONTACT_STIFFNESS
    onset: float = CONTACT_ONSET

    @property
    def delta_c(self) -> float:     # the scale `arclength` steps by: the onset
        return self.onset

    @property
    def reach(self) -> float:       # beyond the plane nothing acts
        return 0.0

    def __call__(self, g):
        return penalty(np.asarray(g, dtype=float), self.stiffness, self.onset)

    def mixed(self, beta, g, s):
        """The sticking penalty (no_slip): the normal penalty plus a tangential one,
        1/2 beta k w(g) s^2, on the radial slip s / R of a point from its anchor (the
        radius where it touched); w = 10 u^3 - 15 u^4 + 6 u^5, u = clip(-g / onset, 0, 1),
        rises with the penetration as the normal slope does (w = 1 beyond the onset, 0 off
        the plane with its first two derivatives: a point that lifts off carries nothing).
        (Phi, Phi_g, Phi_s, Phi_gg, Phi_gs, Phi_ss) as cohesive.mixed: Phi_g the normal
        traction (> 0 attractive), Phi_s the tangential one (opposes s)."""
        g, s = np.asarray(g, dtype=float), np.asarray(s, dtype=float)
        e, k = self.onset, beta * self.stiffness
        u = np.clip(-g / e, 0.0, 1.0)
        w = u ** 3 * (10 - 15 * u + 6 * u * u)
        w_g = -30 * u * u * (1 - u) ** 2 / e
        w_gg = 60 * u * (1 - u) * (1 - 2 * u) / (e * e)
        pe, ps, pk = self(g)
        half = 0.5 * k * s * s
        return (pe + half * w, ps + half * w_g, k * w * s, pk + half * w_gg, k * w_g * s,
                k * w)


@dataclass(frozen=True)
class SnapSettings:
    """Continuation controls; lengths in units of R."""

    ds_first: float = 1e-4     # first arc step
    ds_max: float = 0.01       # largest arc step
    dz_share: float = 0.3      # largest change of any outer gap per step, in thicknesses
    ds_min: float = 1e-10      # a failure below this step ends the path
    ds_corner: float = 1e-6    # a step this short is taken even if the tangent turns by
    #                            more than cos_min allows: a corner of the path (the
    #                            penalty's onset, a point touching at the snap), not a
    #                            branch jump (the energy balance of the path checks it)
    grow: float = 1.5          # step growth after an easy step
    easy: int = 4              # ... one of at most this many Newton iterations
    cos_min: float = 0.95      # least cosine between the tangents of consecutive states
    cos_min_stick: float = 0.99  # ... while the contact sticks, also between the tangents
    #                            and the chord (the ring rolls by points touching and
    #                            peeling: kinks of P(delta) that coarser steps integrate
    #                            badly; vented unloading to 3 t: the work of P misses
    #                            U + Pi by 1.4e-4 of max U at 0.95, 7.9e-5 at 0.99)
    max_iter: int = 12         # Newton iterations per corrector
    tol: float = 1e-9          # force residual relative to the largest reaction (at the
    #                            snap's fold of t/R 0.02, coarser mesh, 1e-10 is below the
    #                            round-off floor of the residual: 2e-13 to 7e-12 of 1.5e-3)
    max_states: int = 4000     # states on the whole path
    stiffness: float = CONTACT_STIFFNESS   # the contact penalty (PenaltyContact), C10 / R
    open_ds: float = 1e-6      # a sealed pocket's opening is resolved to this arc step
    seal_lift: float = 0.1     # a sealed pocket closes at the first ring whose apex is
    #                            lifted by more than this many thicknesses (the soft
    #                            penalty lifts the flattened centre by 1e-3 t: no pocket)
    seal_at_turn: bool = False  # ... or at the turn to the unloading (press, then seal)
    stick_at_turn: bool = False  # interface no_slip: the contact sticks from the turn to
    #                            the unloading (frictionless before: press past the snap,
    #                            then grip), not from the first touch
    jump_push: float = 0.01    # where the loading stops short (no step converges above
    #                            ds_min: the sharp contact's loss of stability), the rim
    #                            is pushed on by this many thicknesses and the shell let
    #                            settle (`_jump`: a displacement-controlled jump); 0: the
    #                            path ends there instead
    jump_descent: int = 3000   # ... the damped descent's bound on steps
    onset: float = CONTACT_ONSET   # ... and its onset / R: the contact force rises as the
    #                            square of the penetration over this depth.  The sharpest
    #                            the continuation passes the snap with (t/R 0.02; 4e-5
    #                            turns back along the path, 3e-5 and below stop where the
    #                            centre lifts off); it makes the jump early (24 % at t/R
    #                            0.02): module docstring


@dataclass(frozen=True, eq=False)
class SnapState:
    """A converged state of the loading."""

    delta: float               # approach / R
    P: float                   # rim load / (C10 R^2), > 0 compression
    U: float                   # strain energy / (C10 R^3)
    Pi: float                  # contact penalty energy / (C10 R^3)
    intervals: tuple           # runs of the surface below the plane: ((first, last) edge, ...)
    radii: tuple               # the deformed radii / R where they meet the plane
    apex_gap: float            # height / R of the apex above the plane (< 0 pressed in)
    iterations: int            # Newton iterations of the corrector that found it
    slope: tuple               # (d delta, dP) per unit arc length, along the path
    seconds: float = 0.0       # wall time of the step that found it
    x: np.ndarray = field(default=None, repr=False)
    # the pocket (solver.pocket; a discretisation bound to one): its volume / R^3, gauge
    # pressure / C10, seal radius / R (the inner edge of the outermost contact run; NaN:
    # no ring), the gas's energy / (C10 R^3) (with the shell's own cavity under pressure,
    # plus its load's -p_c (V_c - V_c0)), and whether the gas is sealed
    V: float = math.nan
    p: float = 0.0
    r_seal: float = math.nan
    E_gas: float = 0.0
    sealed: bool = False
    # no_slip: the sticking penalty's energy with the anchors updated at this state minus
    # Pi (C10 R^3; the path after it starts from that energy, as ArcState.anchor_jump).
    # Anchors change only where a point is off the plane, where the tangential penalty
    # and its derivatives vanish: 0 by construction, recorded to be checked
    anchor_jump: float = 0.0
    # reached by a displacement-controlled jump from the state before, at its delta (the
    # energy the jump dissipates is that state's anchor_jump, < 0)
    landed: bool = False

    @property
    def ring(self) -> bool:
        """The apex is off the plane while the shell touches it: a ring."""
        return bool(self.radii) and self.radii[0][0] > 0.0

    @property
    def contact(self) -> str:
        """The contact set as radii / R, e.g. 'disc 0-0.21' or 'ring 0.30-0.34'."""
        return self.contact_in(1.0)

    def contact_in(self, R: float) -> str:
        """The contact set with its radii times R (e.g. R in mm: radii in mm)."""
        return " + ".join(("disc" if r0 == 0.0 else "ring") + f" {R * r0:.4g}-{R * r1:.4g}"
                          for r0, r1 in self.radii) or "none"


@dataclass(frozen=True)
class Jump:
    """The displacement-controlled jump from a fold at which delta turns back: the state
    `i_from` at delta has no neighbour beyond it, and the shell jumps at the same delta to
    the path's next stable part (between states `i_to - 1` and `i_to`, P linear there);
    or the jump to a landed state `i_to` (`SnapState.landed`), at delta or, where the
    return from the push found the branch it left, at the push's delta."""

    delta: float
    P_from: float
    P_to: float
    contact_from: str
    contact_to: str
    i_from: int
    i_to: int


@dataclass(frozen=True, eq=False)
class SnapPath:
    """The loading traced by arc length, in path order."""

    states: tuple
    ended_by: str              # "" if it reached delta_max (and unload_to)
    timer: Timer
    turn: int = -1             # the state at which the loading turned to unload (-1: none)

    def array(self, name):
        return np.array([getattr(s, name) for s in self.states])

    def first_ring(self, lift: float = 0.0):
        """Index of the first state whose contact set starts with a ring and whose apex
        is more than `lift` / R above the plane, or None."""
        return next((i for i, s in enumerate(self.states) if s.ring and s.apex_gap > lift),
                    None)

    def jumps(self) -> tuple:
        """The displacement-controlled jumps: one per fold at which delta turns back and
        is passed again later on the path, and one per state the loading landed on by a
        jump where it could not go on (`SnapState.landed`)."""
        D, P = self.array("delta"), self.array("P")
        out = [Jump(float(D[i - 1]), float(P[i - 1]), float(P[i]), self.states[i - 1].contact,
                    self.states[i].contact, i - 1, i)
               for i, s in enumerate(self.states) if s.landed]
        for i in range(1, len(D) - 1):
            if not (D[i] >= D[i - 1] and D[i] > D[i + 1]):
                continue
            j = next((k for k in range(i + 2, len(D)) if D[k] >= D[i] > D[k - 1]), None)
            if j is None:
                continue
            w = (D[i] - D[j - 1]) / (D[j] - D[j - 1])
            out.append(Jump(float(D[i]), float(P[i]), float((1 - w) * P[j - 1] + w * P[j]),
                            self.states[i].contact, self.states[j].contact, i, j))
        return tuple(sorted(out, key=lambda jump: jump.i_from))

    def work(self) -> np.ndarray:
        """The work of P from the first state to each (integral of P d delta, C10 R^3),
        along the path through its folds (`arclength.work`); over a step at fixed delta
        (a law switched on at the turn) nothing, over a jump that lands beyond its delta
        `push_work`."""
        D = self.array("delta")
        cuts = [0] + [k + 1 for k in range(len(D) - 1)
                      if D[k + 1] == D[k] or self.states[k + 1].landed] + [len(D)]
        W, done = np.zeros(len(D)), 0.0
        for a, b in zip(cuts[:-1], cuts[1:]):
            if a > 0:
                done += push_work(self.states[a - 1], self.states[a])
            part = arc_work(dataclasses.replace(self, states=self.states[a:b]))
            W[a:b] = done + part
            done = W[b - 1]
        return W

    def energy_miss(self) -> float:
        """The energy balance: max |W - dU - dPi - dE_gas + J| / max |dU| along the path,
        W the work of P, d the change from the first state, J the energy added at fixed
        delta before each state (anchor_jump)."""
        U = self.array("U") - self.states[0].U
        J = np.concatenate([[0.0], np.cumsum(self.array("anchor_jump"))[:-1]])
        miss = (self.work() - U - (self.array("Pi") - self.states[0].Pi)
                - (self.array("E_gas") - self.states[0].E_gas) + J)
        return float(np.abs(miss).max() / max(np.abs(U).max(), 1e-300))


def contact_set(iface: Interface, x) -> tuple:
    """(edges, radii): runs of the outer surface below the plane, as (first, last) outer
    edges (from the apex; each edge spans three outer nodes) and the deformed radii / R
    where the surface crosses the plane at each run's ends (linear in the gap between
    neighbouring quadrature points; 0 at the axis)."""
    r, z, _ = iface._points(x)                  # (n_edges, Q), along the meridian
    n_q = r.shape[1]
    r, z = r.ravel(), z.ravel()
    inside = z < 0.0
    edges, radii = [], []
    k = 0
    while k < len(z):
        if not inside[k]:
            k += 1
            continue
        a = k
        while k + 1 < len(z) and inside[k + 1]:
            k += 1
        b = k
        r0 = 0.0 if a == 0 else float(r[a - 1] + (r[a] - r[a - 1]) * z[a - 1] / (z[a - 1] - z[a]))
        r1 = (float(r[b]) if b + 1 == len(z)
              else float(r[b] + (r[b + 1] - r[b]) * z[b] / (z[b] - z[b + 1])))
        edges.append((a // n_q, b // n_q))
        radii.append((r0, r1))
        k += 1
    return tuple(edges), tuple(radii)


def trace_loading(d: Discretisation, delta_max: float, settings: SnapSettings = SnapSettings(),
                  progress=None, unload_to: float = None,
                  interface: str = "frictionless", adhesion: CohesiveLaw = None,
                  x0: np.ndarray = None, delta0: float = 0.0) -> SnapPath:
    """The frictionless loading without adhesion from delta = 0 to delta_max / R, by arc
    length through every fold (module docstring), and, with `unload_to`, the unloading
    from there on by the same continuation (delta decreasing) to unload_to / R (< 0: a pull).

    A discretisation bound to a pocket (solver.pocket.bind) carries its gas: sealed, the
    pocket seals at the first state whose contact set is a ring around an apex lifted by
    settings.seal_lift t, or at the turn with settings.seal_at_turn (ambient pressure at
    its volume then) and the path ends where the pocket opens again
    (no contact ring left around a gap; resolved to settings.open_ds of arc).

    Ends (`SnapPath.ended_by`) at delta_max or unload_to (""), where a sealed pocket opens
    ("pocket opened ..."), or when a step fails below settings.ds_min, or at
    settings.max_states states.  A loading (frictionless, no sealed pocket, no adhesion)
    whose step fails below ds_min jumps instead (`_jump`, settings.jump_push > 0): the
    state it lands on, at the same delta, follows with `landed` set, and the energy the
    jump dissipated is the state before's anchor_jump (a stall right after a landing ends
    the path).  A loading that comes back off the plane (the continuation turned round
    onto the branch it came along) returns to where it turned and pushes the rim on from
    there (`_jump`, onward: a jump where the energy falls, else the state settled at
    delta + push, itself `landed` where it lost more energy than the push's work brought,
    `_jumped_beyond`, and its dissipation recorded beyond that work); so does a loading
    from a depressurised start whose rim load fell to nothing (lifted off: the cavity
    holds the dimple off the plane).  The cavity's rigid lid at the rim stops the inner
    surface (solver.lid, a contact penalty); a state whose inner surface has passed it
    by more than lid.LID_THROUGH anyway ends the path before it ("through the cavity's
    lid ...": not an equilibrium).  `progress(state)` is called after each state if
    given.

    `x0` the state at delta = 0 (default the undeformed one): the free shell under its
    cavity's pressure, just touching the plane (cavity.first_touch, on its moved mesh);
    or, with `delta0` / R, an equilibrium at delta0 from which the path goes on (with
    delta0 = delta_max: the unloading from there, the first state the turn).

    `interface` the tangential contact (contact.INTERFACES): "frictionless", or
    "no_slip": a quadrature point in contact is held radially at its radius at the last
    converged state before it touched, by a tangential penalty of the normal one's
    stiffness (`PenaltyContact.mixed`; anchors per quadrature point, updated at converged
    states, `cohesive.point_anchors_at`); it lets go as it lifts off (gamma = 0: the
    contact carries no tension).

    `adhesion` (a `cohesive.CohesiveLaw`, frictionless, with unload_to): finite-range
    adhesion switched on at the turn at fixed delta (`arclength._switch_on`: pressed
    without adhesion, as the energy method's loading, then the law ramped in; the
    contact penalty becomes the law's own).  The energy the switch adds at fixed delta
    (U + Pi + E_gas after minus before; no work of P) is recorded as the turn state's
    `anchor_jump`, and the switched state follows it at the same delta (`SnapPath.work`
    adds nothing over a step at fixed delta).  The unloading steps change no outer gap by
    more than ArcSettings.dx_max delta_c or dx_travel delta_max (as `arclength.trace`),
    and the path ends ("") where every outer point is beyond the law's reach (detached)
    or at unload_to.  Where the unloading passes a fold of delta (delta would rise again)
    it jumps as under displacement control (`_jump` with the rim pushed back by
    jump_push t, onward; so too where no step converges above ds_min, unless right after
    a landing), the jump landing `landed` and its dissipation recorded as
    above; a jump that leaves the law's reach ends the path (""), one that loses the ring
    around a sealed pocket ends it "pocket opened: in the jump ..." (the descent keeps
    the gas on its law: `arclength._descend`)."""
    if adhesion is not None and (unload_to is None or interface != "frictionless"):
        raise ValueError("adhesion: a cohesive law needs an unloading (unload_to) and the "
                         "frictionless interface")
    if not (math.isfinite(delta_max) and delta_max > 0):
        raise ValueError(f"delta_max: {delta_max!r} must be a finite number > 0 (units of R)")
    if unload_to is not None and not (math.isfinite(unload_to) and unload_to < delta_max):
        raise ValueError(f"unload_to: {unload_to!r} must be a finite number < delta_max "
                         f"({delta_max:g} R)")
    _check_interface(interface)
    s = settings
    law = PenaltyContact(s.stiffness, s.onset)
    beta = 1.0 if interface == "no_slip" and not s.stick_at_turn else None
    pocket = _pocket_of(d)
    arc = ArcSettings(tol=s.tol, max_iter=s.max_iter)
    cn = _Continuation(Interface(d, law, beta), "frictionless", arc)
    if beta is not None:
        cn.anchors = point_anchors_at(cn.iface, np.zeros(d.ndof) if x0 is None else x0)
    timers = [cn.timer]
    c = constraints(d, "frictionless", [])
    outer_z = d.uz(d.capmesh.outer[cn.candidates])
    dz_max = s.dz_share * d.capmesh.cap.t
    x = np.zeros(d.ndof) if x0 is None else np.array(x0, dtype=float)
    if x.shape != (d.ndof,):
        raise ValueError(f"x0: shape {x.shape} must be ({d.ndof},)")
    if not (math.isfinite(delta0) and 0 <= delta0 <= delta_max) or (delta0 and x0 is None) \
            or (delta0 == delta_max and unload_to is None):
        raise ValueError(f"delta0: {delta0!r} must be in [0, delta_max] and given with x0 "
                         "(at delta_max: the unloading from there, with unload_to)")
    delta = float(delta0)
    K, r = cn.linearise(x)
    t = cn.tangent_at(K, c)
    states = [_state(cn, x, delta, K, r, t, 0, 0.0)]
    ds = s.ds_first
    turn = -1
    if delta0 == delta_max:         # the unloading from x0
        turn = 0
        t = (-t[0], -t[1])
    ended_by = f"state limit: {s.max_states} states"
    if adhesion is not None and turn == 0:      # switched on where the unloading starts
        try:
            cn, x, K, r, c, t, dz_max = _adhesion_on(cn, adhesion, c, x, delta, arc, states,
                                                     timers, dz_max, delta_max)
        except ConvergenceError as err:
            return SnapPath(tuple(states), _no_switch(delta, err), _sum(timers), turn)
        turn = 1
        ds = min(ds, dz_max)
        if progress is not None:
            progress(states[-1])
    clock = time.perf_counter()
    lid = own_lid(d)
    while len(states) < s.max_states:
        if _through_lid(lid, states):
            ended_by = _lid_ends(states)
            break
        ds = min(ds, s.ds_max, dz_max / (np.abs(t[0][outer_z]).max() + abs(t[1])))
        jump_from = ""
        try:
            xn, dn, Kn, rn, it = _correct(cn, c, x, delta, t, ds)
            if cn.d.cavity is not None and cn.d.cavity.sealed and _opens(cn, xn):
                raise PocketOpened("the pocket opens")
            L = math.sqrt(cn.dot(xn - x, dn - delta, xn - x, dn - delta))
            chord = ((xn - x) / L, (dn - delta) / L)
            tn = cn.tangent_at(Kn, c, chord)
            cos_min = s.cos_min if beta is None else s.cos_min_stick
            if cn.dot(*tn, *t) < cos_min and ds > s.ds_corner:
                raise ConvergenceError("the tangent turned by more than "
                                       f"{math.degrees(math.acos(cos_min)):.0f} degrees")
            if beta is not None and cn.dot(*tn, *chord) < cos_min and ds > s.ds_corner:
                # sticking: both tangents agree but the chord does not: the step cut
                # across a loop of the path (the stuck ring peeling)
                raise ConvergenceError("the chord left the tangents by more than "
                                       f"{math.degrees(math.acos(cos_min)):.0f} degrees")
            if turn < 0 and dn < 0.0:
                # the loading came back off the plane: the continuation turned round
                # onto the branch it came along (seen on the fine mesh of t/R 0.02, h/R 1
                # at 4.91 t, where the soft contact's fold lies on coarser meshes)
                raise _TurnedBack("the path turned back onto its own branch")
            if adhesion is not None and 0 <= turn < len(states) - 1 and dn > delta \
                    and s.jump_push > 0:
                # the adhesive unloading passed a fold of delta: under displacement
                # control the shell jumps there, from the state before it
                raise _FoldPassed("the unloading passed a fold of delta")
        except _FoldPassed:
            jump_from = "the unloading passed a fold of delta"
        except ConvergenceError as err:
            ds *= 0.5
            if isinstance(err, _TurnedBack):
                # back to where it turned; the rim pushed on from there (`_jump`, onward)
                k = _fold(states)
                del states[k + 1:]
                x, delta = states[k].x.copy(), states[k].delta
                ds = s.ds_min / 4
                err = _TurnedBack(f"{err} from delta = {delta:.6g} R")
            if (cn.d.cavity is not None and cn.d.cavity.sealed and ds < s.open_ds
                    and (isinstance(err, PocketOpened) or not _sealed_ahead(cn, x, t, ds))):
                ended_by = (f"pocket opened: the contact ring around it is lost between "
                            f"delta = {delta:.6g} R and {delta + 2 * ds * t[1]:.6g} R")
                break
            if ds < s.ds_min and turn < 0 and _lifted_off(cn.d, states):
                if not (s.jump_push > 0 and delta < delta_max):
                    ended_by = (f"lifted off at delta = {delta:.6g} R: P fell to "
                                f"{states[-1].P:.3g} C10 R^2; the cavity's pressure holds "
                                "the shell's dimple off the plane on its own (a free "
                                "equilibrium)")
                    break
                # the rim pushed on and the shell let settle (`_jump`, onward), as under
                # displacement control
                err = _LiftedOff(f"lifted off at delta = {delta:.6g} R")
            if (ds < s.ds_min and adhesion is not None and 0 <= turn < len(states) - 1
                    and s.jump_push > 0 and not states[-1].landed):
                # the adhesive unloading finds no state ahead (Newton does not converge
                # however short the step: t/R 0.02, h/R 0.5, sealed, coarser mesh): as at
                # a fold, the shell jumps under displacement control
                jump_from = f"step below {s.ds_min:g} ({err})"
            elif ds < s.ds_min:
                ended_by = f"step below {s.ds_min:g} at delta = {delta:.6g} R ({err})"
                if not (s.jump_push > 0 and turn < 0 and beta is None and adhesion is None
                        and (cn.d.cavity is None or not cn.d.cavity.sealed)
                        and delta < delta_max and not states[-1].landed):
                    break
                try:
                    lifted = isinstance(err, _LiftedOff)
                    x, delta, K, r, it, landed = _jump(
                        cn, c, x, delta, s.jump_push * d.capmesh.cap.t,
                        LIFT_DESCENT if lifted else s.jump_descent,
                        onward=lifted or isinstance(err, _TurnedBack))
                except ConvergenceError as why:
                    ended_by += f"; no jump from there: {why}"
                    break
                t = cn.tangent_at(K, c)
                now = time.perf_counter()
                _append_landing(states, _state(cn, x, delta, K, r, t, it, now - clock),
                                landed)
                clock = now
                if progress is not None:
                    progress(states[-1])
                ds = s.ds_first
                ended_by = f"state limit: {s.max_states} states"
            if not jump_from:
                continue
        if jump_from:
            # the adhesive unloading jumps under displacement control from the state
            # before (the rim pushed back by jump_push t, `_jump`, onward)
            before = delta
            try:
                x, delta, K, r, it, landed = _jump(cn, c, x, delta,
                                                   -s.jump_push * d.capmesh.cap.t,
                                                   s.jump_descent, onward=True)
                if cn.d.cavity is not None and cn.d.cavity.sealed and _opens(cn, x):
                    raise PocketOpened("landed with no ring around the pocket")
            except PocketOpened:
                ended_by = (f"pocket opened: in the jump from delta = {before:.6g} R "
                            f"({jump_from}), the contact ring around it is lost")
                break
            except ConvergenceError as why:
                ended_by = (f"{jump_from} at delta = {before:.6g} R; no jump from there: "
                            f"{why}")
                break
            if gaps(d, x, cn.candidates).min() > adhesion.reach:
                ended_by = ""       # the jump leaves the law's reach: detached
                break
            t = cn.tangent_at(K, c, (np.zeros(d.ndof), -1.0))
            now = time.perf_counter()
            _append_landing(states, _state(cn, x, delta, K, r, t, it, now - clock), landed)
            clock = now
            if progress is not None:
                progress(states[-1])
            ds = s.ds_first
            ended_by = f"state limit: {s.max_states} states"
            continue
        slope = None
        if cn.dot(*tn, *chord) < s.cos_min:
            # a corner (a step shorter than ds_corner taken): the tangent K^-1 dr/ddelta is
            # there dominated by a mode whose sign flips as the path passes it (a
            # bifurcation); the path goes on along the chord, which follows the branch
            tn = chord
            slope = (chord[1], (rim_load(d, rn) - rim_load(d, r)) / L)
        x, delta, K, r, t = xn, dn, Kn, rn, tn
        now = time.perf_counter()
        states.append(_state(cn, x, delta, K, r, t, it, now - clock, slope))
        clock = now
        if cn.anchors is not None:
            cn.anchors = point_anchors_at(cn.iface, x, cn.anchors)
            jump = cn.iface.energy(x, cn.anchors) - states[-1].Pi
            if jump != 0.0:
                states[-1] = dataclasses.replace(states[-1], anchor_jump=jump)
        if progress is not None:
            progress(states[-1])
        if turn < 0 and delta >= delta_max:
            if unload_to is None:
                ended_by = ""
                break
            turn = len(states) - 1
            t = (-t[0], -t[1])
        elif turn >= 0 and delta <= unload_to:
            ended_by = ""
            break
        elif (adhesion is not None and turn >= 0 and len(states) - 1 > turn
              and gaps(d, x, cn.candidates).min() > adhesion.reach):
            ended_by = ""           # detached: out of the law's reach
            break
        seals = pocket is not None and pocket.sealed and not cn.d.cavity.sealed and (
            turn == len(states) - 1 if s.seal_at_turn
            else states[-1].ring and states[-1].apex_gap > s.seal_lift * d.capmesh.cap.t)
        sticks = interface == "no_slip" and beta is None and turn == len(states) - 1
        if seals or sticks:
            # the ring closes: the gas is sealed at ambient pressure, and / or (at the
            # turn, stick_at_turn) the contact starts sticking where it is; the path goes
            # on with the new stiffness (the state is the same: p = 0, no slip, no force)
            anchors = cn.anchors
            if sticks:
                beta = 1.0
                anchors = point_anchors_at(cn.iface, x)
            try:
                sealed = seal(cn.d, x) if seals else cn.d
            except ValueError:      # the shell is off the plane (a collapsed dimple)
                ended_by = (f"nothing to seal at delta = {delta:.6g} R: no contact ring "
                            "encloses a gap")
                break
            cn = _Continuation(Interface(sealed, cn.iface.law, beta), "frictionless", arc)
            cn.anchors = anchors
            timers.append(cn.timer)
            c = constraints(cn.d, "frictionless", [])
            K, r = cn.linearise(x)
            t = cn.tangent_at(K, c, t)
            states[-1] = _state(cn, x, delta, K, r, t, it, states[-1].seconds, slope)
        if adhesion is not None and turn == len(states) - 1:
            try:
                cn, x, K, r, c, t, dz_max = _adhesion_on(cn, adhesion, c, x, delta, arc,
                                                         states, timers, dz_max, delta_max)
            except ConvergenceError as err:
                ended_by = _no_switch(delta, err)
                break
            turn = len(states) - 1
            ds = min(ds, dz_max)
            if progress is not None:
                progress(states[-1])
        if it <= s.easy:
            ds *= s.grow
    if _through_lid(lid, states):
        ended_by = _lid_ends(states)
    return SnapPath(tuple(states), ended_by, _sum(timers), turn)


def _through_lid(lid, states) -> bool:
    """Whether the last state's inner surface has passed `lid` (`lid.Lid.through`; None:
    no cavity of the shell's own)."""
    return lid is not None and len(states) > 1 and lid.through(states[-1].x)


def _lid_ends(states) -> str:
    """Drop the last state (through the lid) and say where the path ends."""
    states.pop()
    states[-1] = dataclasses.replace(states[-1], anchor_jump=0.0)
    return (f"through the cavity's lid from delta = {states[-1].delta:.6g} R: the next "
            f"state's inner surface passed the rigid lid by more than {LID_THROUGH:g} R "
            "(its contact penalty did not hold it)")


def _append(states, after: SnapState, jumped: bool):
    """Append `after` to the path's states; `jumped` (a jump, or a law switched on at
    fixed delta): the energy it adds beyond the work of P over it (`push_work`: none at
    the same delta), U + Pi + E_gas after minus before less that work (< 0 dissipated),
    becomes the last state's anchor_jump."""
    before = states[-1]
    states.append(after)
    if jumped:
        states[-2] = dataclasses.replace(before, anchor_jump=before.anchor_jump + (
            after.U + after.Pi + after.E_gas - before.U - before.Pi - before.E_gas
            - push_work(before, after)))


def _append_landing(states, after: SnapState, landed: bool):
    """Append the state `_jump` returned: landed (at its delta), or, settled at the
    push's delta, landed if `_jumped_beyond`; a landing's dissipation as `_append`."""
    landed = landed or _jumped_beyond(states, after)
    _append(states, dataclasses.replace(after, landed=landed), jumped=landed)


def push_work(before: SnapState, after: SnapState) -> float:
    """The work of P over a jump from `before` to `after` (C10 R^3): the rim pushed from
    one's delta to the other's against the mean of their P (0 at the same delta)."""
    return 0.5 * (before.P + after.P) * (after.delta - before.delta)


def _jumped_beyond(states, after: SnapState) -> bool:
    """Whether the state a push settled in beyond the last state's delta (`_jump`,
    onward, where the return to delta found the branch it left) was reached by a jump:
    it holds less energy than the push's work brought, by more than JUMP_DEFICIT of the
    path's largest change of U so far (the same branch: the trapezoid's error, 3.6e-6 of
    it at most on the pushes of the t/R 0.02 unloading at gamma 2e-5 C10 R, coarser mesh;
    the jump there: 6.0e-4)."""
    before = states[-1]
    deficit = (before.U + before.Pi + before.E_gas + push_work(before, after)
               - after.U - after.Pi - after.E_gas)
    dU = max(abs(st.U - states[0].U) for st in states)
    return deficit > JUMP_DEFICIT * dU


def _fold(states) -> int:
    """The index of the last state at the largest delta of a loading."""
    D = np.array([st.delta for st in states])
    return int(np.flatnonzero(D == D.max())[-1])


def _jump(cn, c, x, delta, push, steps, onward=False):
    """The displacement-controlled jump from the state x at delta / R where the loading
    cannot go on: the rim pushed on by `push` / R, the shell let settle there by damped
    descent (`arclength._descend`, at most `steps` steps and its escape), and the state
    it settles in brought back to delta on its own branch (Newton at fixed delta).
    Returns (x, delta, K, r, iterations, landed): landed True, at delta.  Where the
    shell settles back on the branch it was on (its energy at delta, U + Pi + the gas's
    and the cavity load's (`forms.potential_energy`), not below the start's by
    JUMP_GAIN), that branch goes on past delta: with `onward`, the settled state at
    delta + push is returned (landed False), else ConvergenceError; ConvergenceError
    also if it does not settle or finds no state at delta."""
    fixed = (np.zeros(cn.d.ndof), 1.0)
    y = x.copy()
    y[c.rimz] = -(delta + push)
    y, n = _descend(cn, c, y, steps)        # ends where a corrector at delta + push converges
    try:
        z = y.copy()
        z[c.rimz] = -delta
        z, _, K, r, (full, chord) = cn.correct(c, z, delta, fixed, 0.0)
    except ConvergenceError:
        # back to delta along the branch it settled on: Newton at fixed delta in steps of
        # 1 / RETURN_STEPS of the push, a step that fails halved (down to RETURN_STEP_MIN)
        z, full, chord, f, df = y, 0, 0, 1.0, 1.0 / RETURN_STEPS
        while f > 0.0:
            g = max(f - df, 0.0)
            w = z.copy()
            w[c.rimz] = -(delta + g * push)
            try:
                w, _, K, r, (more, chords) = cn.correct(c, w, delta + g * push, fixed, 0.0)
            except ConvergenceError:
                if df <= RETURN_STEP_MIN:
                    raise
                df *= 0.5
                continue
            z, f, full, chord = w, g, full + more, chord + chords
    energy = lambda v: potential_energy(cn.d, v) + cn.iface.energy(v, cn.anchors)   # noqa: E731
    e_x = energy(x)
    if energy(z) < e_x - JUMP_GAIN * abs(e_x):
        return z, delta, K, r, n + full + chord, True
    if not onward:
        raise ConvergenceError("the shell settled back where it was")
    y, _, K, r, (more, chords) = cn.correct(c, y, delta + push, fixed, 0.0)
    return y, delta + push, K, r, n + full + chord + more + chords, False


RETURN_STEPS = 4    # `_jump`: steps back to delta where one Newton solve does not get there
RETURN_STEP_MIN = 1.0 / 64  # ... the shortest, as a share of the push (t/R 0.02, coarse,
#                             unloaded at 2e-5: the closing jump at 3.66 t lands, for a
#                             change of round-off in the descent, where four steps back
#                             met a non-finite residual)
JUMP_GAIN = 1e-9    # a jump lands on another state only if it lowers the energy by this
#                     share (the jumps measured dissipate 0.4 of it; the same state found
#                     again differs by round-off)
JUMP_DEFICIT = 1e-4  # `_jumped_beyond`: the share of the path's largest change of U a
#                      push must lose to be a jump (the energy balance's tolerance)


def _adhere(d, law, c, x, delta, arc):
    """Switch finite-range adhesion (`law`) on at fixed delta, from the state x on the
    discretisation d: a new continuation on the cohesive interface, the law ramped in
    from SWITCH_OFF (`arclength._switch_on`).  Returns (continuation, x, K, r,
    constraints, tangent oriented to unload, iterations); ConvergenceError where no
    equilibrium is found."""
    iface = Interface(d, law, None)
    new = _Continuation(iface.with_law(scaled(law, SWITCH_OFF)), "frictionless", arc)
    x, K, r, c, _, n = _switch_on(new, iface, c, x, delta, np.zeros(0, dtype=int),
                                  "frictionless")
    t = new.tangent_at(K, c, (np.zeros(d.ndof), -1.0))
    return new, x, K, r, c, t, n


def _adhesion_on(cn, law, c, x, delta, arc, states, timers, dz_max, delta_max):
    """`_adhere` at the state x (delta / R) of the path, the switched state appended at the
    same delta (its energy the state before's anchor_jump) and its timer kept: (cn, x, K,
    r, c, t, dz_max), the step bound now also the law's (ArcSettings.dx_max delta_c,
    dx_travel delta_max)."""
    cn, x, K, r, c, t, n = _adhere(cn.d, law, c, x, delta, arc)
    timers.append(cn.timer)
    _append(states, _state(cn, x, delta, K, r, t, n, 0.0), jumped=True)
    return cn, x, K, r, c, t, min(dz_max, arc.dx_max * law.delta_c, arc.dx_travel * delta_max)


def _no_switch(delta, err) -> str:
    return f"the adhesion did not switch on at delta = {delta:.6g} R ({err})"


def adhesive_pull_off(path: SnapPath) -> tuple:
    """(P*, delta*) of the unloading (from the turn): the least P, the vertex of the
    parabola through the least sampled P and its two neighbours (units of C10 R^2 and R;
    P* < 0 a tensile pull-off).  ValueError where the unloading does not reach it."""
    if path.turn < 0:
        raise ValueError("the path did not turn: no unloading")
    _, d_star, P_star = least_P(path.array("delta")[path.turn:], path.array("P")[path.turn:])
    return P_star, d_star


def _check_interface(interface):
    if interface not in INTERFACES:
        raise InputError(f"interface: {interface!r} must be one of {', '.join(INTERFACES)}")


class _FoldPassed(Exception):
    """An adhesive unloading step passed a fold of delta (delta rises again)."""


class _LiftedOff(ConvergenceError):
    """A loading whose rim load fell to nothing: the cavity holds the dimple off the plane."""


class _TurnedBack(ConvergenceError):
    """A loading step came back off the plane: the path turned round onto its own branch."""


def _pocket_of(d):
    """The Pocket a discretisation is bound to, or None."""
    return d.cavity.pocket if isinstance(d.cavity, PocketLoad) else None


LIFT_SHARE = 1e-4   # `_lifted_off`: P below this share of its largest on the path
LIFT_DESCENT = 600  # `_jump` from a lift-off: the residual-scaled descent's steps before it
#                     escapes (`arclength.ESCAPE_STEPS`): the lifted-off dimple is a free
#                     state the suction destabilises, its flow creeps from the start (t/R
#                     0.02, h/R 1, 0.2 p_cl, coarser mesh: with 3000 the same landing, 19 s
#                     against 4 s)


def _lifted_off(d, states) -> bool:
    """A loading from a pressurised start whose rim load has fallen to nothing (below
    LIFT_SHARE of its largest): the shell's own cavity (suction) holds the dimple."""
    shell = getattr(d.cavity, "shell", None)
    P = [st.P for st in states]
    return shell is not None and max(P) > 0 and P[-1] <= LIFT_SHARE * max(P)


def _opens(cn, x) -> bool:
    """A sealed pocket is open in state x: no run of the contact penalty (its quadrature
    points below the plane) off the axis is left to seal it, or no ring around a gap."""
    return cn.d.cavity.is_open(x) or not any(r0 > 0 for r0, _ in contact_set(cn.iface, x)[1])


def _sealed_ahead(cn, x, t, ds) -> bool:
    """Whether the pocket is still closed a step ds ahead on the tangent (a predictor
    check: a corrector that fails near the opening fails because V(x) jumps there)."""
    return not _opens(cn, x + ds * t[0])


def _sum(timers) -> Timer:
    """One Timer adding up the counts and times of several."""
    out = Timer()
    for tm in timers:
        for k, v in tm.as_dict().items():
            if isinstance(v, (int, float)) and not isinstance(v, bool):
                setattr(out, k, getattr(out, k) + v)
            elif v:
                setattr(out, k, v)
    return out


def _correct(cn, c, x0, d0, t, ds):
    """Equilibrium on the hyperplane t . (y - y0) = ds: (x, delta, K, r, iterations), as
    `arclength._Continuation.correct`, with each bordered Newton step refined once
    against the whole bordered system.  Near a fold or a bifurcation the free block of
    the tangent is nearly singular and block elimination loses the step's accuracy (the
    residual stalls at 1e-11 of P at the snap of t/R 0.02); one refinement restores it."""
    s, d = cn.s, cn.d
    tx, td = t
    x = x0 + ds * tx
    delta = d0 + ds * td
    x[c.rimz] = -delta
    history = []
    size = math.sqrt(cn.dot(x0, d0, x0, d0))
    weight = np.zeros(d.ndof)               # the continuation's metric on x
    weight[cn.metric] = 1.0
    tw = (tx * weight)[c.free]
    for it in range(s.max_iter + 1):
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            K, r = cn.linearise(x)
        if not (np.all(np.isfinite(r)) and np.all(np.isfinite(K.data))):
            raise ConvergenceError("non-finite residual")
        res = np.abs(r[c.free]).max()
        goal = s.tol * np.abs(r[c.fixed]).max() + s.atol * d.force_scale
        g = cn.dot(tx, td, x - x0, delta - d0) - ds
        history.append(res)
        if res <= goal and abs(g) <= 1e-10 * (abs(ds) + size):
            return x, delta, K, r, it
        if it == s.max_iter or (it > 2 and res > 1e3 * history[1]):
            break
        lu, dr_dd = cn.factor(K, c)
        cn.timer.newton_iterations += 1
        Kff = K[c.free][:, c.free]
        rhs_r, rhs_g = -r[c.free], -g
        dx, dd = _bordered(cn, lu, dr_dd, tw, td, rhs_r, rhs_g)
        # one refinement against [K_ff dr_dd; tw td]
        e_r = rhs_r - (Kff @ dx + dr_dd * dd)
        e_g = rhs_g - (tw @ dx + td * dd)
        ex, ed = _bordered(cn, lu, dr_dd, tw, td, e_r, e_g)
        x[c.free] += dx + ex
        delta += dd + ed
        x[c.rimz] = -delta
    raise ConvergenceError("corrector did not converge (residuals "
                           + ", ".join(f"{h:.3g}" for h in history[-3:]) + ")")


def _bordered(cn, lu, dr_dd, tw, td, rhs_r, rhs_g):
    """Solve [K_ff dr_dd; tw td] (dx, dd) = (rhs_r, rhs_g) by block elimination."""
    a = cn.solve(lu, rhs_r)
    b = cn.solve(lu, -dr_dd)
    dd = (rhs_g - tw @ a) / (tw @ b + td)
    return a + b * dd, dd


def _state(cn, x, delta, K, r, t, it, seconds, slope=None) -> SnapState:
    d = cn.d
    runs, radii = contact_set(cn.iface, x)
    apex = float(gaps(d, x, [0])[0])
    pocket = {}
    if _pocket_of(d) is not None:
        V, p, r_seal = d.cavity.measure(x)
        pocket = dict(V=V, p=p, r_seal=r_seal, E_gas=d.cavity.energy(x),
                      sealed=d.cavity.sealed)
    return SnapState(float(delta), rim_load(d, r), strain_energy(d, x),
                     cn.iface.energy(x, cn.anchors),
                     runs, radii, apex, it,
                     (float(t[1]), rim_load(d, K @ t[0])) if slope is None else slope,
                     seconds, x.copy(), **pocket)


def ring_arc(delta_max: float) -> float:
    """Arc length / R from the apex to be meshed evenly for a loading to delta_max / R:
    past the mirror-buckled ring, which sits near sqrt(2 delta) R (the inverted cap's
    edge), with a quarter and 0.05 R to spare."""
    return 1.25 * math.sqrt(2.0 * delta_max) + 0.05


T_MIN_SNAP = 0.005     # the thinnest shell whose loading alone is traced, t / R


def loading_cap(t: float, h: float) -> Cap:
    """The cap t / R, h / R for a loading alone: the supported domain's rules
    (geometry.check_cap), except that t / R may go down to T_MIN_SNAP (below the domain's
    T_MIN: the energy method is not validated there, the loading is)."""
    check_cap(max(t, T_MIN) if math.isfinite(t) else t, h)
    if t < T_MIN:
        if not t >= T_MIN_SNAP:
            raise InputError(f"t/R: {t:g} is outside the loading's domain t/R >= {T_MIN_SNAP:g}")
        if not h > t:
            raise InputError(f"h/R: {h:g} must be > t ({t:g})")
        cap = object.__new__(Cap)
        object.__setattr__(cap, "t", float(t))
        object.__setattr__(cap, "h", float(h))
        return cap
    return Cap(t, h)


def trace_shell(t: float, h: float, mesh: str, delta_max: float, uniform: float = None,
                settings: SnapSettings = SnapSettings(), progress=None,
                interface: str = "frictionless"):
    """(discretisation, SnapPath) of the shell t / R, h / R on the named mesh, evenly
    meshed out to `uniform` of arc / R (default `ring_arc(delta_max)`), loaded to
    delta_max / R (`trace_loading`, with `interface`).  A shell, delta_max or interface
    outside the supported domain raises InputError (a ValueError)."""
    _check_interface(interface)
    cap = loading_cap(t, h)
    check_delta_max(delta_max, h, t_over_R=t)
    uniform = ring_arc(delta_max) if uniform is None else uniform
    d = discretise(cap_mesh(cap, mesh_spec(mesh, uniform)))
    return d, trace_loading(d, delta_max, settings, progress, interface=interface)


def log_slope(path: SnapPath, lo: float, hi: float) -> tuple:
    """(slope, drift) of ln P against ln delta over lo <= delta <= hi (units of R) on the
    path's last branch (after the last fold at which delta turns from falling to rising:
    beyond the snap, the mirror-buckled branch from its lower fold on): the slope of
    the least-squares line, and the slope over the upper half of the range (in ln delta)
    minus that over the lower half.  Raises ValueError with fewer than 3 states per half."""
    D, P = path.array("delta"), path.array("P")
    turns = [i for i in range(1, len(D) - 1) if D[i] <= D[i - 1] and D[i] < D[i + 1]]
    start = turns[-1] if turns else 0
    D, P = D[start:], P[start:]
    m = (D >= lo) & (D <= hi)
    mid = 0.5 * (math.log(lo) + math.log(hi))
    lower, upper = m & (np.log(D) <= mid), m & (np.log(D) >= mid)
    if min(lower.sum(), upper.sum()) < 3:
        raise ValueError(f"log_slope: {int(m.sum())} states in delta/R {lo:g} to {hi:g} "
                         "on the last branch; need 3 in each half")
    fit = [np.polyfit(np.log(D[k]), np.log(P[k]), 1)[0] for k in (m, lower, upper)]
    return float(fit[0]), float(fit[2] - fit[1])
