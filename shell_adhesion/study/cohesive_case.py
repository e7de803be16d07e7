"""One shell with finite-range (Maugis-Dugdale) adhesion, with units:
`shell_adhesion.solve_cohesive_case` and `shell-adhesion case --adhesion dugdale`.

The interface pulls with sigma0 wherever the outer surface's gap is below delta_c =
gamma / sigma0 (`solver.cohesive`, Dugdale's law with a cubic smooth-step of half delta_c;
frictionless contact, or no_slip: a node that touches keeps its radius until its gap
opens past 0.01 delta_c); the whole path (approach, jump-in, pressed state, retraction,
jump-off) is traced by arc-length continuation (`solver.arclength`) and gives the
fixed-load pull-off (least P) and the fixed-grips one (the fold in delta), with the
contact radius a (gap 0) and the cohesive-zone radius c (gap delta_c).  The strength is
given as sigma0 [MPa] or as the Tabor-Maugis parameter lambda = 2 sigma0 (R / (pi gamma
K^2))^(1/3), K = 4 E* / 3, E* = 8 C10 (the solid sphere's; for a shell it is a measure of
the range against R).  The named mesh is refined at the contact where its apex elements
are too large for the cohesive zone Maugis expects (`zone_refinement`, `fitted_spec`);
a path that snaps from node to node without turning is traced again with twice the
elements.  With no_slip the law is mixed-mode (`beta`, default 1): the slip of a point
from where it last touched opens the same potential as the gap (toughness gamma in any
mode mix; beta = delta_c / delta_t; 0 is the normal-only law, mode-I-only toughness;
`solver.cohesive`), and the contact is formed as the energy method forms it (`history`
"loading", the default: pressed with the law switched off, switched on at the turn;
"adhesive": the law acts on the approach too, and points stick where adhesion pulls
them in).  A frictionless path does not depend on its history.  Error bars from the
next coarser mesh (`solver.error_bars`), refined by the same factor.

Units: R, t, h, delta, a, c in mm; C10 and sigma0 in MPa; gamma in J/m^2; P in N (> 0
compression; pull-off P < 0); delta > 0 approach.
"""
from dataclasses import dataclass, field, replace
import json
import math
import sys
import time

import numpy as np

from shell_adhesion import __version__
from shell_adhesion.errors import InputError
from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.solver.arclength import ArcPath, ArcSettings, CohesivePullOff, pull_off, trace
from shell_adhesion.solver.cohesive import TABOR_RANGE, CohesiveLaw, Interface
from shell_adhesion.solver.error_bars import error_bar
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import Cap, delta_bound
from shell_adhesion.solver.material import NEO_HOOKE
from shell_adhesion.solver.mesh import cap_mesh, coarser_mesh, mesh_spec
from shell_adhesion.solver.quality import Quality, quality, worst
from shell_adhesion.solver.request import TURN, a_star_estimate, even_arc
from shell_adhesion.solver.scaling import check_finite, force_N, gamma_hat, length_mm

from .case_input import API_NAMES, CaseInput, case_input

ADHESIONS = ("energy", "dugdale")
K_OVER_C10 = 32.0 / 3.0       # K = 4 E* / 3 with E* = 8 C10 (incompressible neo-Hookean)
APPROACH_MAX = 0.5   # deepest approach / R without an explicit delta_max (and at most the
#                      domain's, solver.geometry.delta_bound): it turns at the contact radius
#                      the pull-off needs well before; its step bound scales with it
ZONE_EDGES_MIN = 2.0          # fewer outer edges across the cohesive zone: a warning
# outer elements across the cohesive zone Maugis expects at the pull-off on the requested
# mesh (its next coarser mesh, the error bar's, has half as many): where the named mesh's
# apex elements are larger, its sizes at the contact are scaled down to this.  Eight are
# more accurate in fewer states (hemisphere, lambda 1: P* +0.57 -> +0.27 % of Maugis';
# base shell, lambda 3: 1690 -> 553 states), but the coarse companion then has four: at
# lambda 3 no_slip's stalls on a snap (no error bars), and the frictionless one's snapping
# makes a bar 50 times eight's distance from sixteen: `zone_elements` asks for them
ZONE_ELEMENTS = 4.0
# a path that does not turn round or does not leave the cohesive range (the contact edge
# snapping from node to node until the state bound) is traced once more with this many
# times the elements across the zone (base shell, lambda 3, no_slip: four, no turn in
# 3000 states; eight, answered in 520); once: each retry doubles the dofs at the contact
RETRY_FACTOR = 2.0
# on a mesh so refined the states are spent crossing the zone's elements, at 5-6 Newton
# iterations each: the step grows after up to 6 (base shell, lambda 3: with 4, no turn in
# 3000 states).  Where the named mesh is kept, 4 (lambda 0.3: growing after 6 sampled P
# coarsely near P*, its error bar 0.0016 -> 0.03 N)
REFINED_SETTINGS = ArcSettings(easy=6)
COHESIVE_NAMES = dict(sigma0_MPa="sigma0_MPa", tabor="tabor", adhesion="adhesion",
                      zone_elements="zone_elements", beta="beta", history="history")
# no_slip's contact history and law (one physical question, one answer: the energy
# method's no_slip peels a bonded annulus formed by an adhesion-free loading and charges
# gamma for opening and shear alike).  Base shell, lambda 3, P* [N] (docs/adhesion-range.md):
# beta 1 with the loading history -1.7656 (energy method -1.7146); with the adhesive
# history -2.0755; the normal-only law (beta 0), adhesive history -2.0684
HISTORIES = ("loading", "adhesive")
NO_SLIP_DEFAULTS = dict(beta=1.0, history="loading")
# with the loading history the law is switched on at the turn, where the contact jumps in
# to about 2.4 times the estimate of a* (base shell, lambda 2 and 3): the evenly meshed arc
# (refined to the zone) reaches this many times that estimate, or the retraction stalls
# where the zone spans about two outer edges
SWITCH_REACH = 2.5
HISTORY_WORDS = dict(loading="loading: pressed with the law switched off, switched on at the "
                             "turn (the energy method's contact)",
                     adhesive="adhesive: the law acts on the approach too")
# the elements a user may ask for: fewer than one is no resolution; 32 bounds the cost
# (the dofs at the contact grow with them: 8 at lambda 3 on the base shell, 21,066)
ZONE_ELEMENTS_RANGE = (1.0, 32.0)
# the pull-off values: name, dimensionless field of CohesivePullOff, unit
PULL_OFF_FIELDS = (("P_star_N", "P_star", "N"), ("delta_star_mm", "delta_star", "mm"),
                   ("a_star_mm", "a_star", "mm"), ("c_star_mm", "c_star", "mm"),
                   ("P_dagger_N", "P_dagger", "N"), ("delta_dagger_mm", "delta_dagger", "mm"),
                   ("a_dagger_mm", "a_dagger", "mm"), ("c_dagger_mm", "c_dagger", "mm"))


@dataclass(frozen=True)
class CohesiveInput:
    """Checked input of a cohesive case: the shell (`case`, one gamma) and the law's
    sigma0 [MPa] and lambda (both filled, from whichever was given), and the elements the
    mesh puts across the cohesive zone expected at the pull-off."""

    case: CaseInput
    sigma0_MPa: float
    tabor: float
    zone_elements: float = ZONE_ELEMENTS
    beta: float = None        # the mixed-mode law's delta_c / delta_t (None: normal-only)
    history: str = "adhesive"     # how the contact is formed (HISTORIES)

    @property
    def gamma_hat(self) -> float:
        c = self.case
        return gamma_hat(c.gamma_J_m2[0], c.C10_MPa, c.R_mm)

    @property
    def law(self) -> CohesiveLaw:
        """The dimensionless law (sigma0 / C10, gamma / (C10 R))."""
        return CohesiveLaw(self.sigma0_MPa / self.case.C10_MPa, self.gamma_hat)

    def as_dict(self) -> dict:
        out = dict(self.case.as_dict(), adhesion="dugdale", sigma0_MPa=self.sigma0_MPa,
                   tabor=self.tabor, zone_elements=self.zone_elements)
        if self.case.interface == "no_slip":
            out.update(beta=self.beta, history=self.history)
        return out


def cohesive_input(R_mm, t_mm, h_mm, C10_MPa, gamma_J_m2, sigma0_MPa=None, tabor=None,
                   delta_max_mm=None, interface="frictionless", mesh="default",
                   names=None, zone_elements=ZONE_ELEMENTS, beta=None, history=None,
                   **solid) -> CohesiveInput:
    """Check a cohesive case's input before any computation; InputError names the field
    as `names` calls it (API_NAMES and COHESIVE_NAMES by default).  `solid` holds the
    material and cavity arguments of `case_input`: only the open neo-Hookean shell is
    supported.  `interface` frictionless or no_slip, as the energy method's;
    `zone_elements` the elements across the cohesive zone (ZONE_ELEMENTS_RANGE); `beta`
    (a finite number >= 0) the mixed-mode law's and `history` (HISTORIES) how the contact
    is formed, both no_slip only (None: NO_SLIP_DEFAULTS)."""
    n = {**API_NAMES, **COHESIVE_NAMES, **(names or {})}
    inp = case_input(R_mm, t_mm, h_mm, C10_MPa, gamma_J_m2, delta_max_mm, interface, mesh,
                     n, **solid)
    if inp.material != NEO_HOOKE:
        raise InputError(f"{n['material']}: {inp.material.model} with {n['adhesion']} dugdale: "
                         f"the cohesive interface is for the incompressible neo-Hookean "
                         f"solid only")
    if inp.cavity.closed:
        raise InputError(f"{n['cavity']}: {inp.cavity.mode} with {n['adhesion']} dugdale: "
                         f"the cohesive interface is for the open shell only")
    if len(inp.gamma_J_m2) != 1:
        raise InputError(f"{n['gamma_J_m2']}: {len(inp.gamma_J_m2)} values given: "
                         f"{n['adhesion']} dugdale needs exactly one gamma [J/m^2]")
    if (sigma0_MPa is None) == (tabor is None):
        raise InputError(f"{n['sigma0_MPa']}/{n['tabor']}: give exactly one of them with "
                         f"{n['adhesion']} dugdale ("
                         + ("both given" if sigma0_MPa is not None else "neither given") + ")")
    g = gamma_hat(inp.gamma_J_m2[0], inp.C10_MPa, inp.R_mm)
    if sigma0_MPa is not None:
        sigma0 = check_finite(sigma0_MPa, n["sigma0_MPa"], "MPa")
        if not sigma0 > 0:
            raise InputError(f"{n['sigma0_MPa']}: {sigma0:g} MPa must be > 0")
        lam = md.tabor_parameter(sigma0 / inp.C10_MPa, g, 1.0, K_OVER_C10)
        given = f"{n['sigma0_MPa']} = {sigma0:g} MPa gives lambda = {lam:.4g}"
    else:
        lam = check_finite(tabor, n["tabor"], "1")
        if not lam > 0:
            raise InputError(f"{n['tabor']}: {lam:g} must be > 0")
        sigma0 = md.sigma0_of(lam, g, 1.0, K_OVER_C10) * inp.C10_MPa
        given = f"{n['tabor']}: {lam:g}"
    if not TABOR_RANGE[0] <= lam <= TABOR_RANGE[1]:
        raise InputError(f"{given}: outside the supported domain {TABOR_RANGE[0]:g} <= "
                         f"lambda <= {TABOR_RANGE[1]:g} (with gamma = "
                         f"{inp.gamma_J_m2[0]:g} J/m^2, C10 = {inp.C10_MPa:g} MPa, R = "
                         f"{inp.R_mm:g} mm)")
    ze = check_finite(zone_elements, n["zone_elements"], "1")
    lo, hi = ZONE_ELEMENTS_RANGE
    if not lo <= ze <= hi:
        raise InputError(f"{n['zone_elements']}: {ze:g} must be between {lo:g} and {hi:g} "
                         f"(elements across the cohesive zone)")
    if inp.interface != "no_slip":
        for name, value, why in (("beta", beta, "the mixed-mode law is for no_slip only"),
                                 ("history", history, "a frictionless path has the law "
                                                      "act from the first touch (the "
                                                      "choice is for no_slip only)")):
            if value is not None:
                shown = f"{value:g}" if isinstance(value, (int, float)) else value
                raise InputError(f"{n[name]}: {shown} given with {n['interface']} "
                                 f"{inp.interface}: {why}")
        return CohesiveInput(inp, float(sigma0), float(lam), float(ze))
    return CohesiveInput(inp, float(sigma0), float(lam), float(ze), _beta(beta, n),
                         _history(history, n))


def _beta(beta, n: dict) -> float:
    """The checked mixed-mode beta of a no_slip case (None: the default)."""
    if beta is None:
        return NO_SLIP_DEFAULTS["beta"]
    b = check_finite(beta, n["beta"], "1")
    if not b >= 0:
        raise InputError(f"{n['beta']}: {b:g} must be >= 0 (delta_c / delta_t of the "
                         f"mixed-mode law)")
    return float(b)


def _history(history, n: dict) -> str:
    """The checked contact history of a no_slip case (None: the default)."""
    if history is None:
        return NO_SLIP_DEFAULTS["history"]
    if history not in HISTORIES:
        raise InputError(f"{n['history']}: {history!r} must be one of {', '.join(HISTORIES)}")
    return history


@dataclass(frozen=True, eq=False)
class CohesiveSolve:
    """One traced path on one mesh (dimensionless), its pull-off (None: refused) and why."""

    mesh: str
    ndof: int
    path: ArcPath
    pull_off: CohesivePullOff = None
    refused: str = ""
    zone_edges: float = math.nan      # outer edges across the cohesive zone at P*
    wall_s: float = math.nan
    quality: Quality = None           # the worst element quality over the retraction

    @property
    def path_failed(self) -> bool:
        """Refused because the path did not turn round or did not leave the cohesive
        range (not for its pull-off or its elements)."""
        return bool(self.refused) and (self.path.turn < 0
                                       or self.path.ended_by != "left the cohesive range")


@dataclass(frozen=True, eq=False)
class CohesiveCaseResult:
    """The cohesive pull-off of one shell: the solve on the requested mesh, the one on the
    next coarser mesh (error bars; None without), and the notes on what the solver can
    vouch for."""

    input: CohesiveInput
    solve: CohesiveSolve
    coarser: CohesiveSolve = None
    notes: tuple = ()
    provenance: dict = field(default_factory=dict)

    @property
    def refused(self) -> str:
        """Why the pull-off is not answered ('' if it is)."""
        return self.solve.refused

    def to_dict(self, curves: bool = False) -> dict:
        """Plain JSON-able data (NaN as None): input, law, pull_off (values and error bars
        in N and mm), checks, provenance; `curves`: the traced path in mm and N."""
        inp = self.input.case
        R, C10 = inp.R_mm, inp.C10_MPa
        out = dict(input=self.input.as_dict(), law=self._law_dict(), refused=self.refused or None)
        if not self.refused:
            out["pull_off"] = self._pull_off_dict()
        s = self.solve
        out["checks"] = dict(path_ended_by=s.path.ended_by, states=len(s.path.states),
                             cohesive_zone_edges=_clean(s.zone_edges),
                             quality=None if s.quality is None else s.quality.as_dict(),
                             notes=list(self.notes))
        out["provenance"] = self.provenance
        if curves:
            out["curves"] = dict(
                delta_mm=[length_mm(q.delta, R) for q in s.path.states],
                P_N=[force_N(q.P, C10, R) for q in s.path.states],
                a_mm=[length_mm(q.a, R) for q in s.path.states],
                c_mm=[length_mm(q.c, R) for q in s.path.states],
                turn=s.path.turn)
        return out

    def to_json(self, curves: bool = False) -> str:
        return json.dumps(self.to_dict(curves), indent=1, allow_nan=False)

    def _law_dict(self):
        law, R = self.input.law, self.input.case.R_mm
        b = self.input.beta
        mixed = ({} if b is None else dict(mixed_mode=(
            "beta = 0: normal-only, toughness gamma in mode I only" if b == 0 else
            f"beta = {b:g} (delta_c / delta_t), toughness gamma in any mode mix"),
            history=HISTORY_WORDS[self.input.history]))
        return dict(name="Dugdale", **mixed, sigma0_MPa=self.input.sigma0_MPa,
                    tabor=self.input.tabor,
                    gamma_J_m2=self.input.case.gamma_J_m2[0],
                    delta_c_mm=length_mm(law.delta_c, R),
                    smooth_step=f"cubic, {law.ramp:g} delta_c wide")

    def _pull_off_dict(self):
        inp = self.input.case
        R, C10 = inp.R_mm, inp.C10_MPa
        po = self.solve.pull_off
        cpo = None if self.coarser is None else self.coarser.pull_off
        out = {}
        for name, key, unit in PULL_OFF_FIELDS:
            scale = (lambda v: force_N(v, C10, R)) if unit == "N" else (lambda v: length_mm(v, R))
            value = scale(getattr(po, key))
            err = math.nan if cpo is None else float(error_bar(value, scale(getattr(cpo, key))))
            out[name] = _clean(value)
            out[name + "_error"] = _clean(err)
        return out


def _clean(v):
    return None if v is None or not math.isfinite(v) else float(v)


def solve_cohesive_case(R_mm, t_mm, h_mm, C10_MPa, gamma_J_m2, *, sigma0_MPa=None, tabor=None,
                        delta_max_mm=None, interface="frictionless", mesh="default",
                        zone_elements=ZONE_ELEMENTS, beta=None, history=None,
                        error_bars=True, progress=False) -> CohesiveCaseResult:
    """The Maugis-Dugdale pull-off of one open neo-Hookean shell on a rigid plane.

    Give the interface's strength as `sigma0_MPa` (> 0) or as the Tabor-Maugis parameter
    `tabor` (one of them); `interface` frictionless or no_slip (a node that touches keeps
    its radius).  Without delta_max_mm the approach turns at TURN times the
    energy method's estimate of the pull-off radius (solver.request), within the domain's
    depth bound.  `zone_elements`: the mesh is refined at the contact to put this many
    elements across the cohesive zone Maugis expects (1 to 32; where the named mesh has
    more it is kept); a path that does not turn round or does not leave the cohesive
    range is traced once more with RETRY_FACTOR times as many (the notes and
    provenance["first_path"] say so).  `beta` (no_slip only; default 1): the mixed-mode
    law with delta_c / delta_t = beta (>= 0; 0 is the normal-only law, mode-I-only
    toughness); `history` (no_slip only): "loading" (default: the contact formed without
    adhesion, as the energy method's; the law switched on at the turn) or "adhesive" (the
    law acts on the approach too).  `error_bars`: the same path on the next coarser
    mesh (not when the requested mesh's path is refused or was retried).  `progress`: a
    line per 50 states on stderr.  The input is checked before any computation
    (InputError names the field).
    """
    inp = cohesive_input(R_mm, t_mm, h_mm, C10_MPa, gamma_J_m2, sigma0_MPa, tabor,
                         delta_max_mm, interface, mesh, zone_elements=zone_elements,
                         beta=beta, history=history)
    return solve_checked(inp, error_bars, progress)


def solve_checked(inp: CohesiveInput, error_bars=True, progress=False,
                  timeout_s=None) -> CohesiveCaseResult:
    """`solve_cohesive_case` of an input already checked by `cohesive_input`; `timeout_s`:
    a path still being traced after this many seconds raises TimeoutError."""
    c = inp.case
    cap = Cap(c.t_mm / c.R_mm, c.h_mm / c.R_mm)
    g = inp.gamma_hat
    a_need = a_star_estimate(cap, g)
    zone = zone_estimate(g, inp.tabor)
    adhesion_free_approach = inp.history == "loading"
    fit = dict(uniform=even_arc(cap, (SWITCH_REACH if adhesion_free_approach else 1.0) * a_need),
               delta_max=(min(delta_bound(cap), APPROACH_MAX) if c.delta_max_mm is None
                          else c.delta_max_mm / c.R_mm),
               a_turn=None if c.delta_max_mm is not None else TURN * a_need,
               refine=zone_refinement(zone, c.mesh, inp.zone_elements))
    units = (c.R_mm, c.C10_MPa) if progress else None
    notes = []

    def note(text):         # kept for the answer, and shown at once with progress
        notes.append(text)
        if progress:
            print(f"  note: {text}", file=sys.stderr, flush=True)

    if fit["refine"] < 1.0:
        h = fitted_spec(c.mesh, fit).h_apex
        note(f"the {c.mesh} mesh is refined at the contact to {h * c.R_mm:.3g} mm (x "
             f"{fit['refine']:.2g}): {inp.zone_elements:g} elements across the cohesive zone "
             f"expected at the pull-off (a sphere's, Maugis: {zone * c.R_mm:.3g} mm)")
    deadline = None if timeout_s is None else time.monotonic() + timeout_s
    solve = _solve(cap, inp.law, c.interface, c.mesh, fit, units, deadline, inp.beta,
                   adhesion_free_approach)
    elements, first = inp.zone_elements, None
    retry = dict(fit, refine=zone_refinement(zone, c.mesh, RETRY_FACTOR * elements))
    if (solve.path_failed and RETRY_FACTOR * elements <= ZONE_ELEMENTS_RANGE[1]
            and retry["refine"] < fit["refine"]):
        first, fit, elements = solve, retry, RETRY_FACTOR * elements
        note(f"with {inp.zone_elements:g} elements across the cohesive zone the path "
             f"{first.refused} after {len(first.path.states)} states ({first.wall_s:.0f} s): "
             f"traced again with {elements:g} (the {c.mesh} mesh x {fit['refine']:.2g} at "
             f"the contact)")
        solve = _solve(cap, inp.law, c.interface, c.mesh, fit, units, deadline, inp.beta,
                       adhesion_free_approach)
    # the next coarser mesh with the retried factor has the failed path's elements at
    # the contact: its path is not run
    coarser = (_solve(cap, inp.law, c.interface, coarser_mesh(c.mesh), fit, units, deadline,
                      inp.beta, adhesion_free_approach)
               if error_bars and not solve.refused and first is None else None)
    if not solve.refused and solve.zone_edges < ZONE_EDGES_MIN:
        notes.append(f"the cohesive zone at the pull-off spans {solve.zone_edges:.2g} outer "
                     f"edges (< {ZONE_EDGES_MIN:g}): not resolved by the {c.mesh} mesh; "
                     f"trust P* within its error bar, a* and c* less")
    if first is not None and error_bars and not solve.refused:
        notes.append(f"no error bars: the next coarser mesh would have "
                     f"{elements / 2:g} elements across the zone, as the path that failed")
    if coarser is not None and coarser.refused and not solve.refused:
        notes.append(f"no error bars: the {coarser.mesh} mesh's path {coarser.refused}")
        coarser = None
    prov = dict(version=__version__, mesh=c.mesh, dofs=solve.ndof,
                states=len(solve.path.states),
                newton_iterations=int(solve.path.timer.newton_iterations),
                chord_iterations=int(solve.path.timer.chord_iterations),
                factorisations=int(solve.path.timer.factorisations), wall_s=solve.wall_s,
                even_arc=fit["uniform"], zone_elements=elements,
                zone_refinement=fit["refine"],
                apex_element_mm=fitted_spec(c.mesh, fit).h_apex * c.R_mm,
                delta_max_mm=fit["delta_max"] * c.R_mm,
                a_turn_mm=None if fit["a_turn"] is None else fit["a_turn"] * c.R_mm)
    if first is not None:
        prov["first_path"] = dict(zone_elements=inp.zone_elements, dofs=first.ndof,
                                  states=len(first.path.states), wall_s=first.wall_s,
                                  refused=first.refused)
    if coarser is not None:
        prov.update(coarser_mesh=coarser.mesh, coarser_wall_s=coarser.wall_s)
    return CohesiveCaseResult(inp, solve, coarser, tuple(notes), prov)


def _solve(cap, law, interface, mesh, fit, units=None, deadline=None,
           beta=None, adhesion_free_approach=False) -> CohesiveSolve:
    """Trace the path with `interface` contact on `mesh` (fitted to the zone:
    `fitted_spec`) and read its pull-off; `units` (R_mm, C10_MPa): report progress in them;
    `deadline` (time.monotonic()): TimeoutError after it; `beta` the mixed-mode law's."""
    t0 = time.perf_counter()
    d = discretise(cap_mesh(cap, fitted_spec(mesh, fit)))
    iface = Interface(d, law, beta)
    report = None if units is None else _progress_line(mesh, *units)
    if deadline is not None:
        report = _with_deadline(report, deadline, mesh)
    settings = REFINED_SETTINGS if fit.get("refine", 1.0) < 1.0 else ArcSettings()
    path = trace(iface, fit["delta_max"], settings=settings, progress=report,
                 a_turn=fit["a_turn"], interface=interface,
                 adhesion_free_approach=adhesion_free_approach)
    wall = time.perf_counter() - t0
    if path.turn < 0 or path.ended_by != "left the cohesive range":
        what = "did not turn round" if path.turn < 0 else "ended before leaving the cohesive range"
        last = path.states[-1]
        edges = zone_edges(iface, last.a, last.c) if last.a > 0 else math.nan
        hint = (f"; at its last state the cohesive zone spans {edges:.2g} outer edges: the "
                f"mesh does not resolve it (a finer mesh may)" if edges < ZONE_EDGES_MIN else "")
        return CohesiveSolve(mesh, int(d.ndof), path, refused=f"{what} ({path.ended_by}){hint}",
                             wall_s=wall)
    try:
        po = pull_off(path)
    except ValueError as err:
        return CohesiveSolve(mesh, int(d.ndof), path, refused=str(err), wall_s=wall)
    if not all(math.isfinite(v) for v in (po.P_star, po.delta_star, po.a_star)):
        return CohesiveSolve(mesh, int(d.ndof), path, refused="pull-off not finite", wall_s=wall)
    # the elements along the retraction (folding, distortion, pointwise J): solver.quality
    q = worst(*(quality(d, state.x) for state in path.states[path.turn:]))
    if q.problem():
        return CohesiveSolve(mesh, int(d.ndof), path, refused=f"retraction: {q.problem()}",
                             wall_s=wall, quality=q)
    return CohesiveSolve(mesh, int(d.ndof), path, po, "", zone_edges(iface, po.a_star, po.c_star),
                         wall, q)


def zone_refinement(zone: float, mesh: str, elements: float = ZONE_ELEMENTS) -> float:
    """The factor (<= 1) on `mesh`'s element sizes at the contact that puts `elements`
    apex elements across a cohesive zone of `zone` / R."""
    return min(1.0, zone / (elements * mesh_spec(mesh).h_apex))


def fitted_spec(mesh: str, fit: dict):
    """The mesh `mesh` evenly meshed out to fit["uniform"] of arc / R (None: the family's
    0.15), its apex element and
    first layer scaled by fit["refine"] (the same factor on every mesh of the family, so
    the next coarser mesh keeps half the resolution)."""
    spec = mesh_spec(mesh, fit["uniform"])
    f = fit.get("refine", 1.0)
    return replace(spec, h_apex=spec.h_apex * f, layer0=spec.layer0 * f)


def zone_estimate(gamma_hat: float, tabor: float) -> float:
    """The cohesive zone c - a / R at a solid sphere's pull-off (Maugis-Dugdale:
    (m - 1) A in Maugis' length (pi gamma R^2 / K)^(1/3)); a shell's is of the same order."""
    star = md.pull_off(tabor)
    return (star.m - 1.0) * star.A * (math.pi * gamma_hat / K_OVER_C10) ** (1.0 / 3.0)


def zone_edges(iface: Interface, a: float, c: float) -> float:
    """How many outer edges (of their reference radial extent at a) the zone a < r < c
    spans (lengths / R)."""
    r = iface.d.capmesh.nodes[0]
    r0, r2 = r[iface.edges[0]], r[iface.edges[2]]
    k = int(np.clip(np.searchsorted(r2, a), 0, len(r2) - 1))
    return float((c - a) / (r2[k] - r0[k]))


def _with_deadline(report, deadline, mesh):
    """`report` (or nothing) per state, then TimeoutError once time.monotonic() passes
    `deadline`."""
    def check(state):
        if report is not None:
            report(state)
        if time.monotonic() > deadline:
            raise TimeoutError(f"the path on the {mesh} mesh was still being traced at the "
                               f"task's time limit")
    return check


def _progress_line(mesh, R_mm, C10_MPa):
    """A callback printing every 50th state of the path on stderr, in mm and N."""
    count = [0]
    print(f"  tracing the path on the {mesh} mesh", file=sys.stderr, flush=True)

    def report(state):
        count[0] += 1
        if count[0] % 50 == 0:
            print(f"  {mesh} mesh: {count[0]} states, delta {length_mm(state.delta, R_mm):+.4f} "
                  f"mm, P {force_N(state.P, C10_MPa, R_mm):+.4f} N, a "
                  f"{length_mm(state.a, R_mm):.4f} mm", file=sys.stderr, flush=True)
    return report
