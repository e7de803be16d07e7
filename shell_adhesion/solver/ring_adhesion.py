"""Adhesion at a ring contact: does a mirror-buckled shell keep its ring when
finite-range adhesion acts?

A thin deep shell pressed past its snap touches the plane in a ring around a dimple
(solver.snap).  Finite-range adhesion (a `cohesive.CohesiveLaw`) switched on at that
delta, as `snap.trace_loading` switches it on at the turn (the law ramped in at fixed
delta, `arclength._switch_on`), widens the ring.  Above a limit gamma_c no equilibrium is
left near the ring: the ring's inner edge zips inward and the dimple closes (the damped
descent of the switch settles on a flat contact disc, `arclength.ESCAPE_STEPS`).
`ring_holds` answers one law, `adhesion_limit` brackets gamma_c by bisection.

Dimensionless as the solver (lengths / R, gamma / (C10 R), forces / (C10 R^2)).
"""
from dataclasses import dataclass
import math

from shell_adhesion.errors import ConvergenceError
from shell_adhesion.solver.arclength import ArcSettings
from shell_adhesion.solver.cohesive import CohesiveLaw
from shell_adhesion.solver.contact import constraints
from shell_adhesion.solver.snap import SnapSettings, SnapState, _adhere, _state


WIDEN_MAX = 4       # `adhesion_limit`: moves of a bracket whose ends are on one side
# gamma_c / (C10 R) is about LIMIT_SCALE (t/R) (delta/R)^2, measured (h = R, lambda 0.3,
# coarse mesh): t/R 0.02 at 5 t and 10 t, 4.2e-5 and 1.79e-4 (0.21, 0.22); t/R 0.01 at
# 5 t, 5.4e-6 (0.22); the rule a search starts from
LIMIT_SCALE = 0.21


@dataclass(frozen=True)
class RingAdhesion:
    """One law switched on at a ring state: `holds` if the equilibrium found keeps a ring
    around an apex lifted by more than SnapSettings.seal_lift t; `state` that equilibrium
    (None where none was found); `why` the reason it does not hold ("" where it does)."""

    gamma: float
    holds: bool
    state: SnapState = None
    why: str = ""


def around_dimple(state: SnapState, t: float, settings: SnapSettings = SnapSettings()) -> bool:
    """Whether the state's contact is a ring around an apex lifted by more than
    settings.seal_lift thicknesses (t / R): the ring `ring_holds` asks to keep."""
    return state.ring and state.apex_gap > settings.seal_lift * t


def ring_holds(d, ring: SnapState, law: CohesiveLaw,
               settings: SnapSettings = SnapSettings()) -> RingAdhesion:
    """Switch `law` on at the ring state `ring` (a state of a frictionless loading without
    adhesion on the discretisation d, with its x) at its delta, and say whether the
    shell keeps its ring there (RingAdhesion)."""
    if not ring.ring:
        raise ValueError(f"ring_holds: the state's contact is {ring.contact}, not a ring")
    arc = ArcSettings(tol=settings.tol, max_iter=settings.max_iter)
    c = constraints(d, "frictionless", [])
    try:
        cn, x, K, r, c, t, n = _adhere(d, law, c, ring.x, ring.delta, arc)
    except ConvergenceError as err:
        return RingAdhesion(law.gamma, False, None, f"no equilibrium found ({err})")
    state = _state(cn, x, ring.delta, K, r, t, n, 0.0)
    if around_dimple(state, d.capmesh.cap.t, settings):
        return RingAdhesion(law.gamma, True, state)
    return RingAdhesion(law.gamma, False, state, f"the contact became {state.contact}")


def adhesion_limit(d, ring: SnapState, law_of, gamma_lo: float, gamma_hi: float,
                   rel: float = 0.05, max_solves: int = 20,
                   settings: SnapSettings = SnapSettings(), progress=None,
                   widen: float = None) -> tuple:
    """Bracket gamma_c, the largest gamma / (C10 R) at which the ring state keeps its
    ring (`ring_holds`), by bisection in ln gamma between gamma_lo (must hold) and
    gamma_hi (must not) until gamma_hi / gamma_lo <= 1 + rel.  `law_of(gamma)` gives the
    law of a gamma (e.g. at a fixed Tabor parameter).  `widen` (> 1): where an end is on
    the wrong side, the bracket moves by that factor (at most WIDEN_MAX times) instead.
    Returns (lo, hi) as RingAdhesion results; ValueError where the ends do not bracket,
    or after max_solves switches; `progress(result)` after each."""
    if not (0 < gamma_lo < gamma_hi and rel > 0 and (widen is None or widen > 1)):
        raise ValueError(f"adhesion_limit: need 0 < gamma_lo ({gamma_lo!r}) < gamma_hi "
                         f"({gamma_hi!r}), rel ({rel!r}) > 0 and widen ({widen!r}) > 1")
    solves = 0

    def attempt(gamma):
        nonlocal solves
        solves += 1
        out = ring_holds(d, ring, law_of(gamma), settings)
        if progress is not None:
            progress(out)
        return out

    lo, hi = attempt(gamma_lo), attempt(gamma_hi)
    for _ in range(WIDEN_MAX if widen else 0):
        if not lo.holds and not hi.holds:
            lo, hi = attempt(lo.gamma / widen), lo
        elif lo.holds and hi.holds:
            lo, hi = hi, attempt(hi.gamma * widen)
    if not lo.holds:
        raise ValueError(f"adhesion_limit: the ring does not hold at gamma_lo = {lo.gamma:g} "
                         f"({lo.why})")
    if hi.holds:
        raise ValueError(f"adhesion_limit: the ring still holds at gamma_hi = {hi.gamma:g}")
    while hi.gamma / lo.gamma > 1 + rel:
        if solves >= max_solves:
            raise ValueError(f"adhesion_limit: {max_solves} switches and the bracket is "
                             f"still {lo.gamma:g} to {hi.gamma:g}")
        mid = attempt(math.sqrt(lo.gamma * hi.gamma))
        lo, hi = (mid, hi) if mid.holds else (lo, mid)
    return lo, hi
