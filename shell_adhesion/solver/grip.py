"""The sealed gripper in its working order: pressed, sealed, depressurised, pulled.

A thin shell whose own cavity is closed at the rim by a rigid lid (solver.cavity) is
pressed frictionless onto the plane by arc length (solver.snap.trace_loading) to
delta_max with the cavity at ambient pressure and the pocket under its dimple vented;
there the pocket's gas is sealed (ambient pressure, p_abs V^n constant: solver.pocket),
the cavity's gauge pressure is lowered at fixed delta to p_c (< 0: the suction draws the
dimple up against the sealed gas, whose pressure falls), and the rim is raised by the
same continuation until the pocket opens or unload_to.  Without adhesion, or with a
finite-range law (solver.cohesive) switched on at fixed delta where the pull starts.

Dimensionless as the solver: lengths / R, forces / (C10 R^2), pressures / C10.  P > 0
compresses; the pull-off is the most tensile P along the pull (0 if none; a bound where
the pull stops at a fold it cannot jump from: `Grip.bound`).
"""
from dataclasses import dataclass, replace
import math

import numpy as np

from shell_adhesion.errors import ConvergenceError, InputError

from .arclength import ArcSettings, _Continuation
from .cavity import Cavity
from .cohesive import Interface
from .contact import constraints, rim_load
from .pocket import MODES, Pocket, bind_depressurised, seal
from .snap import (PenaltyContact, SnapPath, SnapSettings, _append, _state, _sum,
                   trace_loading)


PULL_DS_MAX = 0.002     # the pull's largest arc step / R: with the loading's 0.01 the
#                         pull's energy balance missed by up to 2.5e-4 of max |dU| (t/R 0.02,
#                         0.75 p_cl, coarser mesh; the ring's edges crossing elements), with
#                         0.002 by less than 7e-6 at the same P* (to 1e-5)


@dataclass(frozen=True)
class RampStep:
    """An equilibrium of the ramp of the cavity's pressure at fixed delta."""

    p_c: float          # the cavity's gauge pressure / C10
    P: float            # rim load / (C10 R^2)
    p: float            # the pocket's gauge pressure / C10
    V: float            # the pocket's volume / R^3
    r_seal: float       # the seal's radius / R


@dataclass(frozen=True, eq=False)
class Grip:
    """The three stages: `press` (SnapPath), `ramp` (RampStep, ...), `pull` (SnapPath,
    from the depressurised state; None if the ramp did not get there), and `ended_by`
    ("" if the pull reached where the pocket opens or unload_to)."""

    press: SnapPath
    ramp: tuple
    pull: SnapPath
    ended_by: str

    def pull_off(self) -> tuple:
        """(P*, state): the most tensile rim load / (C10 R^2) along the pull, from the
        ramp's end on (a sealed pull ends where the pocket opens), 0 and None if P stays
        compressive, with the SnapState where it is reached."""
        states = self.pull.states if self.pull else ()
        if not states:
            return 0.0, None
        k = int(np.argmin([s.P for s in states]))
        return min(states[k].P, 0.0), (states[k] if states[k].P < 0 else None)

    @property
    def bound(self) -> bool:
        """The pull stopped at a fold of delta it could not jump from (the jump's damped
        descent found no equilibrium and did not open the pocket), so P* is the least P
        up to there: the pull-off is at least that tensile.  (With adhesion the measured
        folds all open the pocket in the jump: the pull ends there, P* exact.)"""
        return self.pull is not None and self.ended_by.startswith(
            "the pull stopped: the unloading passed a fold")

    def path(self) -> SnapPath:
        """The press and the pull as one SnapPath (turn: the pull's turn): the ramp is a
        step at fixed delta, the energy it adds (U + Pi + E_gas after minus before, the
        cavity's load now counted in E_gas) the press's last state's anchor_jump, so
        that SnapPath.energy_miss balances across it.  Without a pull, the press."""
        if self.pull is None:
            return replace(self.press, ended_by=self.ended_by)
        states = list(self.press.states)
        _append(states, self.pull.states[0], jumped=True)
        states += self.pull.states[1:]
        return SnapPath(tuple(states), self.pull.ended_by,
                        _sum([self.press.timer, self.pull.timer]),
                        len(self.press.states) + self.pull.turn)

    def ideal_suction(self, p_atm: float) -> float:
        """p_a pi r_seal^2 at the largest seal radius while sealed (C10 R^2)."""
        radii = [s.r_seal for s in self.pull.states if s.sealed] if self.pull else []
        radii += [s.r_seal for s in self.ramp]
        return p_atm * math.pi * max(radii, default=math.nan) ** 2


@dataclass(frozen=True, eq=False)
class Pressed:
    """The press of `grip`, which depends on none of the suction, the pocket, the gas,
    the pull or the adhesion: one press serves a sweep over them (`grip(pressed=)`).
    `shell` the discretisation pressed (no cavity bound), `d` it bound to the cavity at
    ambient pressure and the pocket vented, `path` the press (its last state exactly at
    delta_max where it got there), `ended_by` "" or why a grip ends after the press."""

    shell: object
    d: object
    delta_max: float
    p_atm: float
    settings: SnapSettings
    path: SnapPath
    ended_by: str

    def serves(self, d, delta_max: float, p_atm: float, settings: SnapSettings) -> bool:
        """True if this is the press of `d` (the same object) to delta_max at p_atm with
        `settings`."""
        return (self.shell is d and self.delta_max == delta_max and self.p_atm == p_atm
                and self.settings == settings)


def press(d, delta_max: float, p_atm: float, settings: SnapSettings = SnapSettings(),
          progress=None) -> Pressed:
    """Press the shell `d` (a forms.Discretisation, no cavity bound; its cavity at ambient
    pressure p_atm / C10, the pocket vented) frictionless to delta_max / R by arc length
    and land on delta_max exactly; `progress(state)` after each state.  Its contact there
    must be a ring around an apex lifted by SnapSettings.seal_lift t, else `ended_by`
    says "no ring around a dimple"."""
    shell = d
    d, x0, _ = bind_depressurised(d, Pocket("vented"), Cavity("pressure", p=0.0, p_atm=p_atm))
    path = trace_loading(d, delta_max, replace(settings, seal_at_turn=False), progress, x0=x0)

    def pressed(path, ended_by=""):
        return Pressed(shell, d, delta_max, p_atm, settings, path, ended_by)
    if path.ended_by:
        return pressed(path, f"the press stopped: {path.ended_by}")
    arc = ArcSettings(tol=settings.tol, max_iter=settings.max_iter)
    try:
        landed = _landed(path, d, delta_max, PenaltyContact(settings.stiffness, settings.onset),
                         arc)
    except ConvergenceError as err:
        return pressed(path, f"the press found no state at delta_max: {err}")
    last, t_over_R = landed.states[-1], shell.capmesh.cap.t
    if not (last.ring and last.apex_gap > settings.seal_lift * t_over_R):
        return pressed(landed, f"no ring around a dimple to seal at delta_max (contact "
                       f"{last.contact}, apex {last.apex_gap / t_over_R:.3g} t above the "
                       "plane; R = 1): press further")
    return pressed(landed)


def grip(d, delta_max: float, p_c: float, p_atm: float, n: float = 1.0,
         unload_to: float = None, settings: SnapSettings = SnapSettings(),
         ramp_steps: int = 4, max_steps: int = 100, progress=None,
         pocket: str = "sealed", adhesion=None, pressed: Pressed = None) -> Grip:
    """Press the shell `d` (a forms.Discretisation, no cavity bound) to delta_max / R
    (`press`; where its contact is not a ring around a dimple the Grip ends there), seal
    the pocket (`pocket` "vented": leave it open, the comparison), lower the cavity's
    gauge pressure to p_c / C10 (<= 0) at fixed delta in about `ramp_steps` steps (a step
    that fails is halved; at most `max_steps` tries), and pull to unload_to / R (default
    -delta_max).  Raises InputError for p_c > 0 or p_c + p_atm < 0; a stage that fails
    ends the Grip early with `ended_by` saying where.  `progress(state)` after each state
    of the press and of the pull.  `adhesion` (a cohesive.CohesiveLaw): switched on at
    fixed delta where the pull starts (after the ramp), the pull then by the law
    (snap.trace_loading's adhesion).  `pressed`: `press(d, delta_max, p_atm, settings)`
    done before (a sweep over p_c, the pocket, n or the adhesion presses once; ValueError
    if it is another shell's or press's)."""
    if not (math.isfinite(p_c) and -p_atm <= p_c <= 0):
        raise InputError(f"p_c: {p_c!r} must be a gauge pressure in [-p_atm, 0] "
                         f"(p_atm = {p_atm:g} C10)")
    if pocket not in MODES:
        raise InputError(f"pocket: {pocket!r} must be one of sealed, vented")
    unload_to = -delta_max if unload_to is None else unload_to
    if pressed is None:
        pressed = press(d, delta_max, p_atm, settings, progress)
    elif not pressed.serves(d, delta_max, p_atm, settings):
        raise ValueError("pressed: not the press of this shell to this delta_max at this "
                         "p_atm with these settings (press(d, delta_max, p_atm, settings))")
    d, press_path = pressed.d, pressed.path
    if pressed.ended_by:
        return Grip(press_path, (), None, pressed.ended_by)
    fixed = (np.zeros(d.ndof), 1.0)
    arc = ArcSettings(tol=settings.tol, max_iter=settings.max_iter)
    law = PenaltyContact(settings.stiffness, settings.onset)
    x, delta = press_path.states[-1].x.copy(), press_path.states[-1].delta
    load = d.cavity
    if pocket == "sealed":
        try:
            d = seal(replace(d, cavity=replace(load, pocket=Pocket("sealed", p_atm, n))), x)
        except ValueError as err:
            return Grip(press_path, (), None, f"nothing to seal at delta_max: {err}")

    def at(p):          # d with its cavity's gauge pressure p / C10
        return replace(d, cavity=replace(d.cavity, shell=replace(
            d.cavity.shell, cavity=Cavity("pressure", p=p, p_atm=p_atm))))

    ramp, f, h = [], 0.0, 1.0 / ramp_steps
    for _ in range(max_steps):
        if f >= 1.0 - 1e-12 or p_c == 0:
            break
        h = min(h, 1.0 - f)
        dp = at((f + h) * p_c)
        cn = _Continuation(Interface(dp, law, None), "frictionless", arc)
        c = constraints(dp, "frictionless", [])
        try:
            z, _, _, r, _ = cn.correct(c, x.copy(), delta, fixed, 0.0)
        except ConvergenceError:
            h /= 2
            if h < 1e-3:
                break
            continue
        if pocket == "sealed" and dp.cavity.is_open(z):
            return Grip(press_path, tuple(ramp), None,
                        f"the pocket opened at p_c = {(f + h) * p_c:.4g} C10 on the ramp")
        f, x = f + h, z
        V, p, r_seal = dp.cavity.measure(x)
        ramp.append(RampStep(f * p_c, rim_load(dp, r), p, V, r_seal))
        h = min(2 * h, 1.0 / ramp_steps)
    if p_c != 0 and f < 1.0 - 1e-12:
        P_now = ramp[-1].P if ramp else press_path.states[-1].P
        return Grip(press_path, tuple(ramp), None,
                    f"the ramp stopped at p_c = {f * p_c:.4g} C10 of {p_c:.4g} (a step of "
                    f"1e-3 of it failed, or {max_steps} tries), P {P_now:.3g} C10 R^2 "
                    f"against {press_path.states[-1].P:.3g} at the press's end")
    pull = trace_loading(at(p_c), delta, replace(settings, seal_at_turn=False,
                                                 ds_max=min(settings.ds_max, PULL_DS_MAX)),
                         progress,
                         unload_to=unload_to, x0=x, delta0=delta, adhesion=adhesion)
    ends = pull.ended_by.startswith("pocket opened") or not pull.ended_by
    return Grip(press_path, tuple(ramp), pull,
                "" if ends else f"the pull stopped: {pull.ended_by}")


def _landed(press: SnapPath, d, delta_max: float, law, arc) -> SnapPath:
    """The press with one more state exactly at delta_max (Newton at fixed delta from its
    last state, which the arc step put past it), so that the seal's depth does not depend
    on the step; the press itself if it ended there."""
    last = press.states[-1]
    if last.delta == delta_max:
        return press
    cn = _Continuation(Interface(d, law, None), "frictionless", arc)
    c = constraints(d, "frictionless", [])
    x, _, K, r, it = cn.correct(c, last.x.copy(), delta_max, (np.zeros(d.ndof), 1.0), 0.0)
    state = _state(cn, x, delta_max, K, r, cn.tangent_at(K, c), it, 0.0)
    return replace(press, states=press.states + (state,))
