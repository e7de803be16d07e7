"""One shell end to end, with units: `shell_adhesion.solve_case` and the `case` command.

Dimensional input (R, t, h and delta_max in mm, C10 in MPa, gamma in J/m^2) is checked by
the solver's rules (`solver.scaling`, `solver.geometry`, `solver.case.check_gamma`) before
any computation; the FE paths are solved once (`solver.case.solve_paths`) and serve every
gamma.  The result renders as JSON (what `shell-adhesion case --json` prints) or as an
xarray Dataset (`study.case_report`).  P > 0 compression, delta > 0 approach.
"""
from dataclasses import dataclass, field
import json
from numbers import Real
import sys
import time

from shell_adhesion.solver import __version__
from shell_adhesion.solver.case import GAMMA_MAX, PathSet, check_gamma, solve_paths
from shell_adhesion.solver.contact import INTERFACES
from shell_adhesion.solver.geometry import InputError, check_cap, check_delta_max
from shell_adhesion.solver.path import Settings
from shell_adhesion.solver.scaling import check_C10, check_finite, check_R, gamma_hat

from . import case_report

MESHES = ("coarse", "default", "fine")
GAMMA_HEADROOM = 1.25   # the paths serve up to 1.25 x the largest gamma asked for

# the name of each input in the Python API (the command line passes its flags instead)
API_NAMES = dict(R_mm="R_mm", t_mm="t_mm", h_mm="h_mm", C10_MPa="C10_MPa",
                 gamma_J_m2="gamma_J_m2", delta_max_mm="delta_max_mm",
                 interface="interface", mesh="mesh")


@dataclass(frozen=True)
class CaseInput:
    """Checked input of one shell: lengths in mm, C10 in MPa, gamma in J/m^2."""

    R_mm: float
    t_mm: float
    h_mm: float
    C10_MPa: float
    delta_max_mm: float
    gamma_J_m2: tuple = ()
    interface: str = "no_slip"
    mesh: str = "default"

    def as_dict(self) -> dict:
        return dict(R_mm=self.R_mm, t_mm=self.t_mm, h_mm=self.h_mm, C10_MPa=self.C10_MPa,
                    delta_max_mm=self.delta_max_mm, gamma_J_m2=list(self.gamma_J_m2),
                    interface=self.interface, mesh=self.mesh)


def case_input(R_mm, t_mm, h_mm, C10_MPa, gamma_J_m2=(), delta_max_mm=None,
               interface="no_slip", mesh="default", names=None) -> CaseInput:
    """Check the input of one shell; InputError names the field (as `names` calls it).

    `names` maps each argument to the caller's name for it (default API_NAMES; the
    command line gives its flags).  delta_max_mm defaults to R/4.
    """
    n = dict(API_NAMES, **(names or {}))
    R = check_finite(R_mm, n["R_mm"], "mm")
    t = check_finite(t_mm, n["t_mm"], "mm")
    h = check_finite(h_mm, n["h_mm"], "mm")
    C10 = check_finite(C10_MPa, n["C10_MPa"], "MPa")
    delta_max = R / 4 if delta_max_mm is None else check_finite(delta_max_mm,
                                                                 n["delta_max_mm"], "mm")
    if isinstance(gamma_J_m2, (str, Real)):
        gamma_J_m2 = [gamma_J_m2]
    gammas = tuple(check_finite(g, n["gamma_J_m2"], "J/m^2") for g in gamma_J_m2)
    check_R(R, n["R_mm"])
    check_C10(C10, n["C10_MPa"])
    check_cap(t / R, h / R, _ratio(n["t_mm"], "t", t, R), _ratio(n["h_mm"], "h", h, R))
    check_delta_max(delta_max / R, h / R, _ratio(n["delta_max_mm"], "delta_max", delta_max, R),
                    n["h_mm"])
    for g in gammas:
        check_gamma(gamma_hat(g, C10, R), GAMMA_MAX, n["gamma_J_m2"], f"{g:g} J/m^2",
                    f"with C10 = {C10:g} MPa and R = {R:g} mm")
    if interface not in INTERFACES:
        raise InputError(f"{n['interface']}: {interface!r} must be one of {', '.join(INTERFACES)}")
    if mesh not in MESHES:
        raise InputError(f"{n['mesh']}: {mesh!r} must be one of {', '.join(MESHES)}")
    return CaseInput(R, t, h, C10, delta_max, gammas, interface, mesh)


def _ratio(name, symbol, value_mm, R_mm):
    """How a length enters a dimensionless rule, e.g. '--t (t/R = 25/20)'."""
    return f"{name} ({symbol}/R = {value_mm:g}/{R_mm:g})"


@dataclass(frozen=True, eq=False)
class CaseResult:
    """The solution of one shell: its FE paths and the pull-off of each gamma.

    Attributes
    ----------
    input : CaseInput
        The checked input (mm, MPa, J/m^2).
    pathset : solver.case.PathSet
        The dimensionless FE paths (lengths / R, forces / (C10 R^2), energies /
        (C10 R^3)); they serve any gamma / (C10 R) up to ``pathset.gamma_max``.
    adhesion : tuple
        One ``(gamma_J_m2, Equilibrium, PullOff)`` per gamma, dimensionless.
    provenance : dict
        Package version, mesh, interface, dofs, Newton iterations, wall times [s] and
        solver tolerances.
    """

    input: CaseInput
    pathset: PathSet
    adhesion: tuple = ()
    provenance: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        """The result as plain JSON-able data (NaN as None): input, loading, relaxation,
        equilibrium and pull_off (with gamma), provenance."""
        return case_report.as_dict(self)

    def to_json(self) -> str:
        """The JSON text `shell-adhesion case --json` prints (without the final newline)."""
        return json.dumps(self.to_dict(), indent=1, allow_nan=False)

    def to_dataset(self):
        """The result as an xarray Dataset with named dimensions (``gamma``,
        ``loading_state``, ``relaxation``, ``relaxation_state``, ``point``); every variable
        and coordinate has ``units`` and ``long_name``."""
        return case_report.as_dataset(self)


def solve_case(R_mm, t_mm, h_mm, C10_MPa, gamma_J_m2=(), *, delta_max_mm=None,
               interface="no_slip", mesh="default", progress=True) -> CaseResult:
    """Solve one spherical-cap shell pressed on a rigid plane, and its pull-off.

    Parameters
    ----------
    R_mm : float
        Outer radius of curvature R [mm], from 0.001 to 10000.
    t_mm : float
        Shell thickness t [mm], 0 < t <= R (t = R: a solid cap).
    h_mm : float
        Depth h from the apex to the base plane [mm], t < h <= R.
    C10_MPa : float
        Neo-Hookean constant C10 [MPa] (shear modulus 2 C10), from 1e-6 to 1e4.
    gamma_J_m2 : float or sequence of float, optional
        Work(s) of adhesion gamma [J/m^2]; each gamma / (C10 R) at most
        ``solver.case.GAMMA_MAX``.  One set of FE paths serves them all.  Without any,
        only the loading curve is computed.
    delta_max_mm : float, optional
        Deepest rim approach delta [mm], 0 < delta_max < h and at most R/2; default R/4.
    interface : {"no_slip", "frictionless"}
        Interface model (default no_slip, the paper's cohesive contact).
    mesh : {"coarse", "default", "fine"}
        Mesh density.
    progress : bool
        Show a progress bar on stderr (when it is a terminal).

    Returns
    -------
    CaseResult
        ``.to_dataset()`` and ``.to_json()`` render it.

    Raises
    ------
    InputError
        (a ValueError) before any computation, with one line naming the argument, its
        value and the rule.
    solver.ConvergenceError
        If the FE solution cannot go on.
    """
    inp = case_input(R_mm, t_mm, h_mm, C10_MPa, gamma_J_m2, delta_max_mm, interface, mesh)
    return _solve(inp, progress)


def _solve(inp: CaseInput, progress: bool) -> CaseResult:
    from tqdm import tqdm

    R, C10 = inp.R_mm, inp.C10_MPa
    g_hats = [gamma_hat(g, C10, R) for g in inp.gamma_J_m2]
    gamma_max = max(g_hats) * GAMMA_HEADROOM if g_hats else GAMMA_MAX
    t0 = time.perf_counter()
    with tqdm(total=round(inp.delta_max_mm, 6), unit="mm", desc="loading", file=sys.stderr,
              disable=None if progress else True, leave=False) as bar:
        def on_state(delta):
            bar.update(round(delta * R, 6) - bar.n)

        def on_path(done, total):
            if done == 1:
                bar.set_description("relaxation paths")
                bar.unit = "path"
                bar.reset(total)
            bar.update(1)
        ps, d, loading = solve_paths(inp.t_mm / R, inp.h_mm / R, inp.interface, inp.mesh,
                                     inp.delta_max_mm / R, gamma_max, relax_paths=bool(g_hats),
                                     progress=on_state, path_progress=on_path)
    t1 = t0 + ps.stats["loading_s"]
    t2 = t1 + ps.stats["relaxation_s"]
    adhesion = ()
    if g_hats:
        surface = ps.surface()
        adhesion = tuple((g, *ps.pull_off(gh, surface)) for g, gh in zip(inp.gamma_J_m2, g_hats))
    t3 = time.perf_counter()
    settings = Settings()
    provenance = {
        "version": __version__, "mesh": inp.mesh, "interface": inp.interface,
        "dofs": int(d.ndof), "elements": int(d.capmesh.mesh.nelements),
        "newton_iterations": loading.timer.newton_iterations
        + sum(r.newton_iterations for r in ps.relaxations),
        "wall_s": round(t3 - t0, 3),
        "time_split_s": {"loading": round(t1 - t0, 3), "relaxation": round(t2 - t1, 3),
                         "energy_method": round(t3 - t2, 3)},
        "tolerances": {"newton_rtol": settings.tol, "newton_atol": settings.atol,
                       "gap_tol_over_R": settings.gap_tol},
        "relaxation_gamma_max_over_C10R": gamma_max}
    return CaseResult(inp, ps, adhesion, provenance)

