"""One shell, start to finish, in dimensionless units (lengths / R, forces / (C10 R^2),
energies / (C10 R^3), gamma / (C10 R)): loading, one relaxation path per contact radius,
and the energy method for any number of gamma values.

A `PathSet` holds only arrays, so it can be stored, shipped to other processes and
post-processed for any C10, R and gamma (DESIGN.md section 3).
"""
from dataclasses import dataclass, field, replace
from functools import cached_property, lru_cache
import math
import time

import numpy as np

from .cavity import OPEN, Cavity, bind, first_touch, lifted
from shell_adhesion.energy import (Bridged, EnergySurface, InGradedZone, NotBracketed,
                                   OutOfRange, energy_surface, equilibrium, pull_off)
from .forms import Discretisation, discretise
from .contact import check_interface
from .geometry import DEPTH_SHARE, GAMMA_MAX, Cap, check_delta_max, check_gamma, shown
from shell_adhesion.errors import InputError
from .material import NEO_HOOKE, Material
from .mesh import CapMesh, cap_mesh, mesh_spec, uniform_radius
from .path import LoadingPath, RelaxationPath, Settings, State, load, relax
from .postprocess import StressMap, profile, spread, stress_map

G_SAFETY = 3.0          # relax until the flat-punch estimate of G exceeds G_SAFETY * gamma_max
UNIFORM_SHARE = 0.9     # pull-off radii must lie within this share of the evenly meshed radius
EDGE_GROWTH_MAX = 0.25  # frictionless: the adhesive edge force may grow the covered area at
#                         a* by at most this share (the energy method takes it to second
#                         order in gamma; at 0.052 the third order moved P* by 0.038 %;
#                         the largest growth measured in the domain is 0.12)


def flat_punch_G(start: State, s: State) -> float:
    """Estimate of G at state s of a relaxation path: (P1 - P)^2 / (4 pi a^2 k).

    Exact for a flat punch on a half space (k = dP/ddelta = 2 E* a); used only to decide
    how far to relax, never as a result.
    """
    k = s.dP_ddelta
    if not k > 0:
        return np.inf
    return (start.P - s.P) ** 2 / (4 * np.pi * start.a ** 2 * k)


FAMILIES = ("corner", "midside")
CORNER_SHARE = 0.8      # frictionless: the corner family if it has this share of the starts


def relaxation_starts(loading: LoadingPath, capmesh: CapMesh, family: str = None):
    """Loaded states to relax: one per contact radius, all ending on the same node type.

    A state ending on a midside node holds part of the next edge, so its energy does not
    line up with a corner-ended neighbour's (G would oscillate, DESIGN.md section 7).
    Where the contact front is not monotone (a node touches before the one inside it),
    the state with the gap is skipped and the one that closes it is used.  The states
    whose front is whole form two families, ending on corners or on midside nodes; the
    larger family is used (`family`: that one, "corner" or "midside"), never a mix.
    The two converge to one value from different sides on coarse meshes (thin shell t/R
    0.1: P* 0.7 % apart on the coarse mesh), so an error bar's coarser meshes use the
    answer's family (`start_family`; study.case).  Frictionless, the corner family is used
    unless it has fewer than CORNER_SHARE of the midside one's starts: the adhesive edge
    force sits on the edge node, and on corners it converges with the mesh several times
    faster (base shell P*, coarse -> default -> fine: steps 0.05 %, 0.02 % against 0.37 %,
    0.22 % on midside nodes; docs/adhesion-range.md).
    """
    families = {True: [], False: []}
    for s in loading.events:
        m = max(s.held)
        if m > 0 and set(range(max(0, m - 3), m + 1)) <= set(s.held):
            families[bool(capmesh.outer_corner[m])].append(s)
    corner, midside = families[True], families[False]
    if family is not None:
        if family not in FAMILIES:
            raise InputError(f"family: {family!r} must be one of {', '.join(FAMILIES)}")
        return corner if family == "corner" else midside
    if loading.interface == "frictionless" and len(corner) >= CORNER_SHARE * len(midside):
        return corner
    return corner if len(corner) >= len(midside) else midside


def start_family(starts, capmesh: CapMesh):
    """The node type the relaxation starts' contact fronts end on, "corner" or "midside"
    (`relaxation_starts`; None without starts)."""
    if not starts:
        return None
    return "corner" if capmesh.outer_corner[max(starts[0].held)] else "midside"


def has_hole(state: State) -> bool:
    """True if a node inside the contact zone is not held (the centre has lifted)."""
    return len(state.held) < max(state.held) + 1


def relax_from(d: Discretisation, interface: str, start: State, gamma_max: float = GAMMA_MAX,
               settings: Settings = Settings(), progress=None,
               reach: float = 1.0, gamma_edge: float = 0.0,
               edge_width: float = 0.0) -> RelaxationPath:
    """Relax one loaded state until the estimated G exceeds G_SAFETY * reach * gamma_max
    (`reach` > 1 takes a path further, where its pair's G fell short: solver.request).

    The step is 1 / settings.relaxation_steps of the flat-punch estimate of the way down,
    at most settings.relaxation_step_max; the estimate needs a positive start stiffness,
    and a start that softens (dP/ddelta <= 0: the shell is buckling under its contact) is
    relaxed in steps of relaxation_step_max / relaxation_steps instead.  `progress(delta)` is
    called after each state (it may raise to end the path, e.g. on a wall-time limit).
    `gamma_edge`, `edge_width`: the adhesive edge force it carries (path.relax).
    """
    G_stop = G_SAFETY * reach * gamma_max
    k0 = start.dP_ddelta
    if k0 > 0 and math.isfinite(k0):
        dP_total = np.sqrt(G_stop * 4 * np.pi * start.a ** 2 * k0)
        step = min(dP_total / k0 / settings.relaxation_steps, settings.relaxation_step_max)
    else:
        step = settings.relaxation_step_max / settings.relaxation_steps
    def stop(s):
        if progress is not None:
            progress(s.delta)
        return flat_punch_G(start, s) >= G_stop

    return relax(d, interface, start, stop, step, settings, gamma_edge, edge_width)


@dataclass(frozen=True, eq=False)
class Relaxation:
    """One relaxation path as arrays (delta decreasing from the loaded state)."""

    a: float
    delta: np.ndarray
    P: np.ndarray
    U: np.ndarray
    dP_ddelta: np.ndarray
    ended_by: str
    penetration: bool
    centre_lifts: bool      # the contact zone inverted: its centre left the plane
    newton_iterations: int
    views: tuple = ()       # Profile and StressMap of the path, when asked for (figures)
    inversion_delta: float = np.nan  # delta / R where the centre left the plane (NaN: never)
    J_min: float = 1.0      # worst pointwise J and in-plane det F over the path
    J_max: float = 1.0
    detF_min: float = 1.0
    timing: dict = field(default_factory=dict, compare=False)  # the path's Timer (not stored)
    V: np.ndarray = None    # cavity: enclosed volume / R^3 along the path (NaN if open)
    p: np.ndarray = None    # cavity: gauge pressure / C10 along the path (NaN if open)
    reach: float = 1.0      # its stop rule's G_SAFETY * reach * gamma_max (relax_from)
    a_edge: np.ndarray = None     # deformed radius / R of the held edge along the path (the
    #                               covered radius r_k(delta); a where the edge cannot slide)
    da_ddelta: np.ndarray = None  # its slope d a_edge / d delta along the path
    gamma_edge: float = 0.0       # gamma / (C10 R) of the edge force it was relaxed with
    #                               (solver.edge; its U is then U_E - gamma_edge pi a_edge^2)
    dA_dgamma: np.ndarray = None  # d(covered area / R^2) / d(gamma / (C10 R)) at fixed
    #                               delta along the path (solver.edge; 0 where the edge
    #                               cannot slide): the energy method's second order

    def __post_init__(self):
        for name, fill in (("V", np.nan), ("p", np.nan), ("a_edge", self.a),
                           ("da_ddelta", 0.0), ("dA_dgamma", 0.0)):
            if getattr(self, name) is None:
                object.__setattr__(self, name, np.full(len(self.delta), fill))

    @property
    def usable(self) -> bool:
        """Used by the energy method, up to where its contact zone inverted (`upright`): no
        free node touched the plane, and at least two states came before the centre lifted."""
        return not self.penetration and int(np.sum(self._upright)) >= 2

    @property
    def _upright(self) -> np.ndarray:
        """Mask of the states before the contact zone inverted (all if it never did)."""
        if not self.centre_lifts:
            return np.ones(len(self.delta), dtype=bool)
        return self.delta > self.inversion_delta

    def upright(self) -> "Relaxation":
        """The path up to where its contact zone inverted (the centre left the plane): the
        states before are a disc of contact on the plane, which the energy method needs."""
        if not self.centre_lifts:
            return self
        keep = self._upright
        return replace(self, **{k: getattr(self, k)[keep]
                                for k in _PER_STATE})

    @classmethod
    def of(cls, path: RelaxationPath, d: Discretisation = None, reach: float = 1.0,
           gamma_edge: float = 0.0):
        """The path's arrays; with `d`, also its views (see `relaxation_views`); `reach` as
        the path was relaxed (relax_from)."""
        start_off = has_hole(path.start) or path.start.centre_off
        inversion = path.start.delta if start_off else path.inversion_delta
        q = path.quality
        return cls(path.start.a, path.array("delta"), path.array("P"), path.array("U"),
                   path.array("dP_ddelta"), path.ended_by, path.penetration,
                   path.centre_lifts or start_off, path.timer.newton_iterations,
                   relaxation_views(d, path) if d is not None else (),
                   float(inversion), q.J_min, q.J_max, q.detF_min, path.timer.as_dict(),
                   path.array("V"), path.array("p"), float(reach), path.array("a"),
                   path.array("da_ddelta"), float(gamma_edge), path.array("dA_dgamma"))

    def energy_path(self) -> tuple:
        """(a, delta, P, U, dP/ddelta, a_edge, da_edge/ddelta, gamma_edge, dA/dgamma) as
        energy_surface takes it."""
        return (self.a, self.delta, self.P, self.U, self.dP_ddelta, self.a_edge,
                self.da_ddelta, self.gamma_edge, self.dA_dgamma)


_PER_STATE = ("delta", "P", "U", "dP_ddelta", "V", "p", "a_edge", "da_ddelta", "dA_dgamma")


def loading_views(d: Discretisation, loading: LoadingPath) -> tuple:
    """Profiles of loading states evenly spaced in delta (from the undeformed cap at
    delta = 0), and the stress map at the end of loading."""
    return (*(profile(d, s, "loading") for s in spread(loading.states)),
            stress_map(d, loading.states[-1], "loading"))


def relaxation_views(d: Discretisation, path: RelaxationPath) -> tuple:
    """Profiles evenly spaced in delta along the path, and the stress map where delta is
    nearest 0 (the paper's Fig. 2b), or at its end if it stays above 0."""
    states = path.states
    deltas = np.array([s.delta for s in states])
    at = int(np.argmin(np.abs(deltas))) if deltas.min() <= 0 else len(states) - 1
    return (*(profile(d, s, "relaxation") for s in spread(states)),
            stress_map(d, states[at], "relaxation"))


@dataclass(frozen=True, eq=False)
class PathSet:
    """Everything the FE computes for one dimensionless shell (no C10, R or gamma)."""

    t: float
    h: float
    interface: str
    mesh: str
    delta_max: float
    gamma_max: float
    loading_delta: np.ndarray
    loading_P: np.ndarray
    loading_a: np.ndarray
    loading_U: np.ndarray
    loading_joined: np.ndarray      # outer node joining at each state (-1: plain step)
    relaxations: tuple
    stats: dict = field(default_factory=dict)
    views: tuple = ()               # Profile and StressMap states kept for figures
    loading_V: np.ndarray = None    # cavity: enclosed volume / R^3 (NaN if open)
    loading_p: np.ndarray = None    # cavity: gauge pressure / C10 (NaN if open)
    cavity: Cavity = OPEN           # what fills the cavity (solver.cavity)
    uniform: float = None           # arc / R meshed evenly from the apex (None: the family's)

    def __post_init__(self):
        for name in ("loading_V", "loading_p"):
            if getattr(self, name) is None:
                object.__setattr__(self, name, np.full(len(self.loading_delta), np.nan))

    @property
    def gamma_edge(self) -> float:
        """gamma / (C10 R) of the edge force its paths were relaxed with (solver.edge; 0:
        none, the energy method's first order)."""
        return max((r.gamma_edge for r in self.relaxations), default=0.0)

    def surface(self) -> EnergySurface:
        """U_E(a, delta) and G of the usable paths (built once: the set is immutable)."""
        return self._surface

    @cached_property
    def _surface(self) -> EnergySurface:
        return energy_surface([r.energy_path() for r in self.usable()])

    def usable(self) -> tuple:
        """Relaxation paths the energy method uses (by increasing a), each up to where its
        contact zone inverted (`Relaxation.upright`): the states in which the contact zone
        is a disc on the plane and no free node touches it."""
        return tuple(sorted((r.upright() for r in self.relaxations if r.usable),
                            key=lambda r: r.a))

    def G_reached(self):
        """(a_pair, G_max): for each pair of neighbouring usable paths, the radius of its
        midpoint and the largest G / (C10 R) its relaxations reached (the largest gamma
        that pair can put in equilibrium)."""
        return self._G_reached

    @cached_property
    def _G_reached(self):
        return G_reached(self.relaxations, self.surface)

    def unreached(self, gamma: float) -> np.ndarray:
        """Pair radii a / R whose relaxations stopped before G reached gamma / (C10 R):
        the equilibrium curve for gamma has no point there (it is bridged)."""
        a, G = self.G_reached()
        return a[~(G >= gamma)]

    def inverted(self, a) -> np.ndarray:
        """True where an equilibrium point at contact radius a / R is affected by a
        contact-zone inversion: it lies between two usable paths that bridge a path that
        inverted before two states (so is left out), or at or beyond the radius where the
        loading inverted.  (A path that inverts later serves up to its inversion.)"""
        a = np.atleast_1d(np.asarray(a, dtype=float))
        out = np.zeros(a.shape, dtype=bool)
        a_use = np.array([r.a for r in self.usable()])
        for r in self.relaxations:
            if not r.centre_lifts or r.usable:
                continue
            below = a_use[a_use < r.a]
            above = a_use[a_use > r.a]
            lo = below.max() if len(below) else -np.inf
            hi = above.min() if len(above) else np.inf
            out |= (a > lo) & (a < hi)
        a_inv = self.stats.get("inversion_a_loading")
        if a_inv is not None:
            out |= a >= a_inv
        return out

    def pull_off(self, gamma: float, surface: EnergySurface = None, strict: bool = False):
        """Equilibrium curve and pull-off for gamma / (C10 R).

        Raises OutOfRange (a ValueError) where the paths cannot vouch for the pull-off:
        its curve is not bracketed (shell_adhesion.energy.pull_off); the adhesive edge force
        of a frictionless set grows the covered area at a* by more than EDGE_GROWTH_MAX (its
        second order would not do); a pull-off radius lies beyond
        UNIFORM_SHARE of the mesh's evenly meshed radius (`mesh.uniform_radius`); or a pair
        of paths near a pull-off radius stopped before G reached gamma, so the curve is
        bridged there (`unreached`).  Bridged near a_dagger only, the fixed-load pull-off is
        given with the fixed-grips values NaN and `PullOff.note` saying why (`strict`:
        raise instead).
        """
        check_gamma(gamma, self.gamma_max)
        eq = None
        try:
            eq = equilibrium(surface or self.surface(), gamma)
            po = pull_off(eq)
        except NotBracketed as e:
            if e.side == "large":
                end = None if eq is None else float(np.max(eq.a))
                e.args = (f"{e}{self._why_the_curve_ends(end)}",)
            raise
        if not po.edge_growth <= EDGE_GROWTH_MAX:       # NaN too: a failed compliance
            raise OutOfRange(
                f"gamma/(C10 R) = {gamma:g}: the adhesive edge force grows the covered area "
                f"at a* by {100 * po.edge_growth:.3g} %, more than {100 * EDGE_GROWTH_MAX:g} %: "
                f"the energy method takes it to second order in gamma and cannot vouch for "
                f"the pull-off there")
        limit = UNIFORM_SHARE * self.uniform_radius
        for name, a in (("a*", po.a_star), ("a_dagger", po.a_dagger)):
            if a > limit:
                raise InGradedZone(
                    f"gamma/(C10 R) = {gamma:g}: the pull-off radius {name} = {a:.4g} R lies "
                    f"beyond {limit:.3g} R, where the {self.mesh} mesh's elements grow; the "
                    f"energy method is biased there by the grading (1.3 % on P* measured for "
                    f"t/R = 0.1), which the error bar cannot see, so the value is not given",
                    a, limit)
            near = eq.a[np.argsort(np.abs(eq.a - a))[:4]]     # the spline's support
            gap = self.unreached(gamma)
            gap = gap[(gap > near.min()) & (gap < near.max())]
            if len(gap):
                error = self._bridged(gamma, name, a, gap)
                if name == "a*" or strict:
                    raise error
                # the fixed-load pull-off stands on its own: give it, say why not the other
                po = replace(po, P_dagger=np.nan, delta_dagger=np.nan, a_dagger=np.nan,
                             note=f"fixed grips not given: {error}")
        return eq, po

    def _why_the_curve_ends(self, a_end: float = None) -> str:
        """What ends an equilibrium curve (at a_end / R, if known) on its large-a side:
        relaxation paths held beyond it whose contact zone inverted (the energy method of
        a contact disc ends at the inversion), and a loading that stopped before the
        contact radius the request aimed at."""
        why = ""
        flipped = sorted(r.a for r in self.relaxations
                         if r.centre_lifts and (a_end is None or r.a > a_end))
        if flipped:
            why += (f"; the {len(flipped)} relaxation paths held beyond it (a = "
                    f"{flipped[0]:.4g} to {flipped[-1]:.4g} R) invert (the centre of their "
                    f"contact zone leaves the plane: the paper's buckling) before G reaches "
                    f"gamma, and the energy method of a contact disc ends at an inversion")
        if not self.stats.get("loading_reached_a", False):
            stop = self.stats.get("loading_stopped_by") or "its depth bound delta_max"
            at_depth = self.delta_max >= DEPTH_SHARE * self.h * (1 - 1e-9)
            if stop.startswith("its depth") and at_depth:
                stop += f" ({DEPTH_SHARE:g} of the cap's depth h: the rim nears the plane)"
            why += (f"; the loading (no adhesion) ended at delta = "
                    f"{self.stats.get('delta_reached', self.loading_delta[-1]):.4g} R "
                    f"with the contact radius a = {self.loading_a[-1]:.4g} R "
                    f"(largest: {self.loading_a.max():.4g} R), stopped by {stop}")
        return why

    def _bridged(self, gamma, name, a, gap) -> Bridged:
        """Why the curve for gamma is bridged at the pair radii `gap` near the pull-off
        radius `a` (`name`): the G the pairs reached, or their paths' inversion."""
        a_pair, G = self.G_reached()
        G_gap = G[np.isin(a_pair, gap)]
        reached = (f"reached only G/(C10 R) = {np.nanmax(G_gap):.4g}"
                   if np.isfinite(G_gap).any() else "do not overlap in delta")
        a_use = np.array([r.a for r in self.usable()])
        k = np.searchsorted(a_use, gap[0])
        pair = [r for r in self.relaxations if r.a in a_use[max(k - 1, 0):k + 1]]
        flipped = [r for r in pair if r.centre_lifts]
        why = (f"; the contact zone of the path at a = {flipped[0].a:.4g} R inverted (its "
               f"centre left the plane) at delta = {flipped[0].inversion_delta:.4g} R, so the "
               f"energy method of a contact disc ends there" if flipped else "")
        return Bridged(
            f"gamma/(C10 R) = {gamma:g}: near the pull-off radius {name} = {a:.4g} R the "
            f"relaxation paths {reached} (at a = {gap[0]:.4g} R), below gamma{why}: the "
            f"equilibrium curve is bridged there, so the value is not given", gap)

    @property
    def uniform_radius(self) -> float:
        """Reference radius / R out to which the set's mesh is even (solver.mesh)."""
        return uniform_radius(Cap(self.t, self.h), mesh_spec(self.mesh, self.uniform))


def solve_loading(t: float, h: float, interface: str, mesh: str, delta_max: float,
                  settings: Settings = Settings(), progress=None, material: Material = NEO_HOOKE,
                  cavity: Cavity = OPEN, stop_at_limit: bool = False, uniform: float = None,
                  a_stop: float = None):
    """Discretisation and loading path of one dimensionless shell; a shell or delta_max
    outside the supported domain (solver.geometry) raises InputError (a ValueError).
    With `stop_at_limit`, a loading refused by the element-quality check or stalled keeps
    its states so far and says why (`LoadingPath.stopped_by`); else it raises.  The mesh is
    even out to `uniform` of arc (solver.mesh.mesh_spec); with `a_stop` the loading ends at
    the first contact event reaching that contact radius / R (solver.path.load).

    A closed `cavity` (solver.cavity) is pressurised first with the shell free; delta is
    then measured from the first touch of the pressurised shell, whose apex displacement
    is `cavity_lift(d)` (CavitySnap if the free shell snaps before).
    """
    cap = Cap(t, h)
    check_delta_max(delta_max, h, t_over_R=t)
    check_interface(interface)
    cm = cap_mesh(cap, mesh_spec(mesh, uniform))
    d = discretise(cm, material=material)
    x0 = None
    if cavity.closed:
        d, x0, _ = first_touch(bind(d, cavity), settings)
    return d, load(d, interface, delta_max, settings, progress, x0=x0,
                   stop_at_limit=stop_at_limit, a_stop=a_stop)


def cavity_lift(d: Discretisation) -> float:
    """The height / R by which the mesh of `d` is lifted so that the pressurised free shell
    touches at delta = 0: minus its apex displacement u_z (> 0: the apex bulged toward the
    plane, < 0: it was drawn up).  0 if open."""
    return float(d.capmesh.nodes[1, d.capmesh.outer[0]])


def solve_paths(t: float, h: float, interface: str = "no_slip", mesh: str = "default",
                delta_max: float = 0.25, gamma_max: float = GAMMA_MAX,
                settings: Settings = Settings(), relax_paths: bool = True,
                progress=None, map=None, path_progress=None,
                material: Material = NEO_HOOKE, cavity: Cavity = OPEN, uniform: float = None,
                a_stop: float = None, reach=None, known=None, gamma_edge: float = 0.0,
                family: str = None, a_window: tuple = None) -> tuple:
    """Loading and relaxation paths of one shell: (PathSet, Discretisation, LoadingPath).

    A loading that reaches the element-quality limit (or stalls) before delta_max stops
    there and keeps its states; the set's stats say how far it got (`delta_reached`) and
    why (`loading_stopped_by`), and the pull-offs are computed from the states it has.

    `progress(delta)` is called after each loading state, `path_progress(done, total)`
    after each relaxation path; `map` (e.g. an executor's map) runs the independent
    relaxation paths in parallel.  `material` (solver.material.Material, ratios to C10)
    is the solid; neo-Hooke by default; `cavity` (solver.cavity) what fills the cavity.
    `uniform` (arc / R meshed evenly) and `a_stop` (the contact radius / R at which the
    loading ends, before delta_max) fit the paths to a request (solver.request);
    `reach(start)` gives a start's relax_from reach (default 1), and `known` maps
    `start_key(start, reach)` to a Relaxation already computed (it is not solved again;
    the paths this call relaxes are added to it).  `gamma_edge` > 0 (gamma / (C10 R),
    frictionless): every path is relaxed with the adhesive edge force of that gamma
    (solver.edge), so the set answers that gamma exactly and others to first order in the
    difference (shell_adhesion.energy).  `family` ("corner" or "midside") picks the
    node type the relaxed contact fronts end on (`relaxation_starts`; None: the larger);
    the set's stats say which (`relaxation_family`).  `a_window` (lo, hi): only the
    starts whose contact radius / R lies in [lo, hi] are relaxed (a reference near a
    known pull-off radius: the equilibrium curve is then known only there).
    """
    if not (isinstance(gamma_max, (int, float)) and math.isfinite(gamma_max) and gamma_max > 0):
        raise InputError(f"gamma_max: {shown(gamma_max)} must be a finite number > 0 (gamma/(C10 R))")
    t0 = time.perf_counter()
    d, loading = solve_loading(t, h, interface, mesh, delta_max, settings, progress, material,
                               cavity, stop_at_limit=True, uniform=uniform, a_stop=a_stop)
    t1 = time.perf_counter()
    relaxations, used = (), None
    if relax_paths:
        starts = relaxation_starts(loading, d.capmesh, family)
        used = start_family(starts, d.capmesh)
        if a_window is not None:
            starts = [s for s in starts if a_window[0] <= s.a <= a_window[1]]
        reaches = [1.0 if reach is None else float(reach(s)) for s in starts]
        last = len(starts) - 1
        done = {}               # the paths `known` already holds (views: the last one's)
        for i, (s, k) in enumerate(zip(starts, reaches)):
            r = (known or {}).get(start_key(s, k))
            if r is not None and (i < last or r.views):
                done[i] = replace(r, views=()) if i < last and r.views else r
        todo = [i for i in range(len(starts)) if i not in done]
        if map is None:
            for n, i in enumerate(todo):
                path = relax_from(d, interface, starts[i], gamma_max, settings, reach=reaches[i],
                                  gamma_edge=gamma_edge)
                done[i] = Relaxation.of(path, d if i == last else None, reaches[i], gamma_edge)
                if path_progress is not None:
                    path_progress(n + 1, len(todo))
        else:
            n = len(todo)
            out = map(relaxation_task, [t] * n, [h] * n, [interface] * n, [mesh] * n,
                      [starts[i] for i in todo], [gamma_max] * n, [settings] * n,
                      [i == last for i in todo], [material] * n, [cavity] * n,
                      [cavity_lift(d)] * n, [None] * n, [uniform] * n,
                      [reaches[i] for i in todo], [gamma_edge] * n)
            done.update(zip(todo, out))
        relaxations = tuple(done[i] for i in range(len(starts)))
        if known is not None:
            known.update((start_key(starts[i], reaches[i]), done[i]) for i in todo)
    t2 = time.perf_counter()
    stats = dict(dofs=int(d.ndof), elements=int(d.capmesh.mesh.nelements),
                 loading_states=len(loading.states),
                 loading_newton_iterations=loading.timer.newton_iterations,
                 relaxation_newton_iterations=sum(r.newton_iterations for r in relaxations),
                 assembly_s=loading.timer.assembly,
                 linear_solve_s=loading.timer.factor + loading.timer.solve,
                 loading_s=t1 - t0, relaxation_s=t2 - t1,
                 timing=timing_stats(loading.timer, relaxations), relaxation_family=used)
    return pathset_of(t, h, interface, mesh, delta_max, gamma_max, loading, relaxations,
                      stats, loading_views(d, loading), cavity, cavity_lift(d),
                      uniform), d, loading


def start_key(start: State, reach: float = 1.0) -> tuple:
    """What identifies the relaxation path of a loaded state (within one loading): where it
    starts (delta, a / R) and how far it goes (`reach`).  A Relaxation's own is
    (r.delta[0], r.a, r.reach)."""
    return (float(start.delta), float(start.a), float(reach))


def timing_stats(loading_timer, relaxations) -> dict:
    """Where the FE time went, loading and relaxation paths together (seconds of one
    process each, so with parallel paths their sum exceeds the wall time), the counts, and
    the linear solver used (solver.linear; `solver_fallbacks`: QDLDL factorisations redone
    by SuperLU)."""
    timers = [loading_timer.as_dict()] + [r.timing for r in relaxations if r.timing]
    total = lambda k: sum(t[k] for t in timers)
    backends = sorted({t["backend"] for t in timers if t["backend"]})
    return {"assembly_s": round(total("assembly"), 4),
            "factorisation_s": round(total("factor"), 4),
            "solve_s": round(total("solve"), 4),
            "event_location_s": round(total("event"), 4),
            "newton_iterations": int(total("newton_iterations")),
            "chord_iterations": int(total("chord_iterations")),
            "factorisations": int(total("factorisations")),
            "symbolic_analyses": int(total("symbolic")),
            "linear_solver": "+".join(backends),
            "solver_fallbacks": int(total("fallbacks"))}


def pathset_of(t, h, interface, mesh, delta_max, gamma_max, loading, relaxations, stats,
               views=(), cavity: Cavity = OPEN, lift: float = 0.0, uniform: float = None):
    """The PathSet of a loading path, its Relaxations and the loading views; the
    relaxations' views move to the set's (profiles, then stress maps, each in stage order).
    The set's stats gain the element quality and the contact-zone inversion
    (`provenance_stats`), and a closed cavity's `cavity_lift` (lift: the apex displacement /
    R of the free pressurised shell, downward > 0) and touch state."""
    views = tuple(views) + tuple(v for r in relaxations for v in r.views)
    views = tuple(sorted(views, key=lambda v: isinstance(v, StressMap)))  # profiles first
    # each path's timing lives on in the set's stats (timing_stats), not in the set
    relaxations = tuple(replace(r, views=(), timing={}) if r.views or r.timing else r
                        for r in relaxations)
    stats = {**provenance_stats(loading, relaxations), **stats,
             "loading_reached_a": bool(loading.reached_a)}
    if cavity.closed:
        s0 = loading.states[0]
        stats.update(cavity_lift=float(lift), cavity_V_touch=float(s0.V),
                     cavity_p_touch=float(s0.p), cavity_U_touch=float(s0.U))
    return PathSet(t, h, interface, mesh, delta_max, gamma_max,
                   loading.array("delta"), loading.array("P"), loading.array("a"),
                   loading.array("U"), loading.array("joined"), relaxations, stats, views,
                   loading.array("V"), loading.array("p"), cavity,
                   None if uniform is None else float(uniform))


def G_reached(relaxations, surface=None):
    """(a_pair, G_max) of the usable relaxation paths (see PathSet.G_reached); `surface()`
    gives their energy surface if it is already built."""
    usable = sorted((r.upright() for r in relaxations if r.usable), key=lambda r: r.a)
    if len(usable) < 2:
        return np.zeros(0), np.zeros(0)
    surf = surface() if surface is not None else energy_surface(
        [r.energy_path() for r in usable])
    with np.errstate(invalid="ignore"):
        G = np.array([np.nanmax(g) if np.isfinite(g).any() else np.nan for g in surf.G])
    return surf.a_pair, G


def provenance_stats(loading: LoadingPath, relaxations) -> dict:
    """Worst element quality and where the contact zone inverted (dimensionless; None
    where there is no inversion).

    J_min, J_max, detF_min, distortion_min: over the loading states (refused beyond
    solver.quality's thresholds); relaxation_J_min, relaxation_J_max, relaxation_detF_min:
    over the relaxation paths (their held zone's edge is a crack tip, so J there is
    reported, not refused).  delta_reached: the deepest delta loaded; loading_stopped_by:
    why the loading ended before delta_max ("" if it did not).  inversion_delta, inversion_a: the first inversion, on loading
    if the loading inverts, else on the relaxation path of smallest a that does
    (inversion_stage says which); inversion_delta_loading, inversion_a_loading: the
    loading's own; inverted_paths: how many relaxation paths inverted.
    """
    q = loading.quality
    out = dict(q.as_dict())
    out.update(delta_reached=loading.delta_reached, loading_stopped_by=loading.stopped_by)
    if relaxations:
        out.update(relaxation_J_min=min(r.J_min for r in relaxations),
                   relaxation_J_max=max(r.J_max for r in relaxations),
                   relaxation_detF_min=min(r.detF_min for r in relaxations))
    inv = loading.inversion
    out.update(inversion_delta_loading=None if inv is None else float(inv.delta),
               inversion_a_loading=None if inv is None else float(inv.a),
               inverted_paths=sum(bool(r.centre_lifts) for r in relaxations))
    flipped = sorted((r for r in relaxations if r.centre_lifts), key=lambda r: r.a)
    if inv is not None:
        stage, where = "loading", (float(inv.delta), float(inv.a))
    elif flipped:
        stage, where = "relaxation", (float(flipped[0].inversion_delta), float(flipped[0].a))
    else:
        stage, where = None, (None, None)
    out.update(inversion_stage=stage, inversion_delta=where[0], inversion_a=where[1])
    _, G = G_reached(relaxations)
    out["G_max_reached"] = float(np.nanmin(G)) if np.isfinite(G).any() else None
    return out


def relaxation_task(t: float, h: float, interface: str, mesh: str, start: State,
                    gamma_max: float = GAMMA_MAX, settings: Settings = Settings(),
                    views: bool = False, material: Material = NEO_HOOKE,
                    cavity: Cavity = OPEN, lift: float = 0.0, progress=None,
                    uniform: float = None, reach: float = 1.0,
                    gamma_edge: float = 0.0) -> Relaxation:
    """One relaxation path as an independent task (the discretisation is built once per
    process: `task_discretisation`); with `views`, it keeps the path's profiles and stress
    map; `progress` and `reach` as in `relax_from`.  A closed `cavity` needs the loading's
    `lift` (`cavity_lift`); `uniform` is the mesh's even arc (solver.mesh.mesh_spec);
    `gamma_edge` the edge force's gamma / (C10 R) (solve_paths)."""
    d = task_discretisation(t, h, mesh, material, cavity, lift, uniform)
    return Relaxation.of(relax_from(d, interface, start, gamma_max, settings, progress, reach,
                                    gamma_edge),
                         d if views else None, reach, gamma_edge)


@lru_cache(maxsize=2)
def task_discretisation(t: float, h: float, mesh: str, material: Material = NEO_HOOKE,
                        cavity: Cavity = OPEN, lift: float = 0.0,
                        uniform: float = None) -> Discretisation:
    """The discretisation of a shell (lifted by `lift` / R if its cavity is closed), kept
    for the process's next relaxation task of the same shell: a worker relaxes many paths
    of one shell, and the build takes 60 ms (base shell) to 220 ms (solid cap) on the
    default mesh.  Immutable, so sharing it changes no result."""
    d = discretise(cap_mesh(Cap(t, h), mesh_spec(mesh, uniform)), material=material)
    return lifted(bind(d, cavity), lift) if cavity.closed else d
