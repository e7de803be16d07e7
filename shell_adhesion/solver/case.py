"""One shell, start to finish, in dimensionless units (lengths / R, forces / (C10 R^2),
energies / (C10 R^3), gamma / (C10 R)): loading, one relaxation path per contact radius,
and the energy method for any number of gamma values.

A `PathSet` holds only arrays, so it can be stored, shipped to other processes and
post-processed for any C10, R and gamma (DESIGN.md section 3).
"""
from dataclasses import dataclass, field, replace
import time

import numpy as np

from .energy import EnergySurface, energy_surface, equilibrium, pull_off
from .forms import Discretisation, discretise
from .geometry import Cap, InputError
from .material import NEO_HOOKE, Material
from .mesh import CapMesh, cap_mesh, mesh_spec
from .path import LoadingPath, RelaxationPath, Settings, State, load, relax
from .postprocess import StressMap, profile, spread, stress_map

GAMMA_MAX = 0.03        # default largest gamma / (C10 R) the relaxation paths must serve
STEPS_PER_PATH = 8      # relaxation steps down to the stop criterion (about)
G_SAFETY = 3.0          # relax until the flat-punch estimate of G exceeds G_SAFETY * gamma_max


def check_gamma(gamma_hat: float, gamma_max: float = GAMMA_MAX, name: str = "gamma/(C10 R)",
                given: str = "", scales: str = ""):
    """Raise InputError unless 0 < gamma / (C10 R) <= gamma_max (what the paths serve).

    `name` is the caller's field, `given` the value as the user wrote it (e.g. "900 J/m^2")
    and `scales` what made it dimensionless (e.g. "with C10 = 0.3 MPa and R = 20 mm").
    """
    if not gamma_hat > 0:
        raise InputError(f"{name}: {given or format(gamma_hat, 'g')} must be > 0")
    if gamma_hat > gamma_max * (1 + 1e-12):
        shown = f"{gamma_hat:.4g}"
        if given:
            shown = " ".join(w for w in (given, scales) if w) + f" gives gamma/(C10 R) = {shown}"
        raise InputError(f"{name}: {shown}, which must be <= {gamma_max:g} (the range of the "
                         "relaxation paths)")


def flat_punch_G(start: State, s: State) -> float:
    """Estimate of G at state s of a relaxation path: (P1 - P)^2 / (4 pi a^2 k).

    Exact for a flat punch on a half space (k = dP/ddelta = 2 E* a); used only to decide
    how far to relax, never as a result.
    """
    k = s.dP_ddelta
    if not k > 0:
        return np.inf
    return (start.P - s.P) ** 2 / (4 * np.pi * start.a ** 2 * k)


def relaxation_starts(loading: LoadingPath, capmesh: CapMesh):
    """Loaded states to relax: one per contact radius, all ending on the same node type.

    A state ending on a midside node holds part of the next edge, so its energy does not
    line up with a corner-ended neighbour's (G would oscillate, DESIGN.md section 7).
    Where the contact front is not monotone (a node touches before the one inside it),
    the state with the gap is skipped and the one that closes it is used.  The states
    whose front is whole form two families, ending on corners or on midside nodes; the
    larger family is used, never a mix.
    """
    families = {True: [], False: []}
    for s in loading.events:
        m = max(s.held)
        if m > 0 and set(range(max(0, m - 3), m + 1)) <= set(s.held):
            families[bool(capmesh.outer_corner[m])].append(s)
    corner, midside = families[True], families[False]
    return corner if len(corner) >= len(midside) else midside


def has_hole(state: State) -> bool:
    """True if a node inside the contact zone is not held (the centre has lifted)."""
    return len(state.held) < max(state.held) + 1


def relax_from(d: Discretisation, interface: str, start: State, gamma_max: float = GAMMA_MAX,
               settings: Settings = Settings()) -> RelaxationPath:
    """Relax one loaded state until the estimated G exceeds G_SAFETY * gamma_max."""
    G_stop = G_SAFETY * gamma_max
    k0 = start.dP_ddelta
    dP_total = np.sqrt(G_stop * 4 * np.pi * start.a ** 2 * k0)
    step = min(dP_total / k0 / STEPS_PER_PATH, settings.step_max)
    return relax(d, interface, start, lambda s: flat_punch_G(start, s) >= G_stop, step, settings)


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
    centre_lifts: bool
    newton_iterations: int
    views: tuple = ()       # Profile and StressMap of the path, when asked for (figures)

    @property
    def usable(self) -> bool:
        """Used by the energy method: the centre stays down and no free node touches."""
        return not (self.centre_lifts or self.penetration)

    @classmethod
    def of(cls, path: RelaxationPath, d: Discretisation = None):
        """The path's arrays; with `d`, also its views (see `relaxation_views`)."""
        return cls(path.start.a, path.array("delta"), path.array("P"), path.array("U"),
                   path.array("dP_ddelta"), path.ended_by, path.penetration,
                   path.centre_lifts or has_hole(path.start), path.timer.newton_iterations,
                   relaxation_views(d, path) if d is not None else ())


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

    def surface(self) -> EnergySurface:
        usable = [r for r in self.relaxations if r.usable]
        return energy_surface([(r.a, r.delta, r.P, r.U) for r in sorted(usable, key=lambda r: r.a)])

    def pull_off(self, gamma: float, surface: EnergySurface = None):
        """Equilibrium curve and pull-off for gamma / (C10 R)."""
        check_gamma(gamma, self.gamma_max)
        eq = equilibrium(surface or self.surface(), gamma)
        return eq, pull_off(eq)


def solve_loading(t: float, h: float, interface: str, mesh: str, delta_max: float,
                  settings: Settings = Settings(), progress=None, material: Material = NEO_HOOKE):
    """Discretisation and loading path of one dimensionless shell."""
    cm = cap_mesh(Cap(t, h), mesh_spec(mesh))
    d = discretise(cm, material=material)
    return d, load(d, interface, delta_max, settings, progress)


def solve_paths(t: float, h: float, interface: str = "no_slip", mesh: str = "default",
                delta_max: float = 0.25, gamma_max: float = GAMMA_MAX,
                settings: Settings = Settings(), relax_paths: bool = True,
                progress=None, map=None, path_progress=None,
                material: Material = NEO_HOOKE) -> tuple:
    """Loading and relaxation paths of one shell: (PathSet, Discretisation, LoadingPath).

    `progress(delta)` is called after each loading state, `path_progress(done, total)`
    after each relaxation path; `map` (e.g. an executor's map) runs the independent
    relaxation paths in parallel.  `material` (solver.material.Material, ratios to C10)
    is the solid; neo-Hooke by default.
    """
    t0 = time.perf_counter()
    d, loading = solve_loading(t, h, interface, mesh, delta_max, settings, progress, material)
    t1 = time.perf_counter()
    relaxations = ()
    if relax_paths:
        starts = relaxation_starts(loading, d.capmesh)
        if map is None:
            relaxations = []
            for i, s in enumerate(starts):
                path = relax_from(d, interface, s, gamma_max, settings)
                relaxations.append(Relaxation.of(path, d if i == len(starts) - 1 else None))
                if path_progress is not None:
                    path_progress(len(relaxations), len(starts))
            relaxations = tuple(relaxations)
        else:
            n = len(starts)
            relaxations = tuple(map(relaxation_task, [t] * n, [h] * n, [interface] * n,
                                    [mesh] * n, starts, [gamma_max] * n, [settings] * n,
                                    [i == n - 1 for i in range(n)], [material] * n))
    t2 = time.perf_counter()
    stats = dict(dofs=int(d.ndof), elements=int(d.capmesh.mesh.nelements),
                 loading_states=len(loading.states),
                 loading_newton_iterations=loading.timer.newton_iterations,
                 relaxation_newton_iterations=sum(r.newton_iterations for r in relaxations),
                 assembly_s=loading.timer.assembly, linear_solve_s=loading.timer.solve,
                 loading_s=t1 - t0, relaxation_s=t2 - t1)
    return pathset_of(t, h, interface, mesh, delta_max, gamma_max, loading, relaxations,
                      stats, loading_views(d, loading)), d, loading


def pathset_of(t, h, interface, mesh, delta_max, gamma_max, loading, relaxations, stats,
               views=()):
    """The PathSet of a loading path, its Relaxations and the loading views; the
    relaxations' views move to the set's (profiles, then stress maps, each in stage order)."""
    views = tuple(views) + tuple(v for r in relaxations for v in r.views)
    views = tuple(sorted(views, key=lambda v: isinstance(v, StressMap)))  # profiles first
    relaxations = tuple(replace(r, views=()) if r.views else r for r in relaxations)
    return PathSet(t, h, interface, mesh, delta_max, gamma_max,
                   loading.array("delta"), loading.array("P"), loading.array("a"),
                   loading.array("U"), loading.array("joined"), relaxations, stats, views)


def relaxation_task(t: float, h: float, interface: str, mesh: str, start: State,
                    gamma_max: float = GAMMA_MAX, settings: Settings = Settings(),
                    views: bool = False, material: Material = NEO_HOOKE) -> Relaxation:
    """One relaxation path as an independent task (rebuilds the discretisation); with
    `views`, it keeps the path's profiles and stress map."""
    d = discretise(cap_mesh(Cap(t, h), mesh_spec(mesh)), material=material)
    return Relaxation.of(relax_from(d, interface, start, gamma_max, settings),
                         d if views else None)
