"""One shell end to end, with units: `shell_adhesion.solve_case` and the `case` command.

Dimensional input (R, t, h and delta_max in mm, C10 and the other coefficients of the
material in MPa, D1 in 1/MPa, gamma in J/m^2) is checked by the solver's rules
(`solver.scaling`, `solver.geometry`, `solver.material`, `solver.geometry.check_gamma`) before
any computation; the FE paths are solved once (`solver.case.solve_paths`) and serve every
gamma.  The result renders as JSON (what `shell-adhesion case --json` prints) or as an
xarray Dataset (`study.case_report`); the input is checked by `study.case_input`.  P > 0 compression, delta > 0 approach.
"""
from dataclasses import dataclass, field
import json
import time

from shell_adhesion.errors import InputError, MaterialLimitError
from shell_adhesion import __version__
from shell_adhesion.solver.case import PathSet
from shell_adhesion.solver.cavity import CavitySnap
from shell_adhesion.solver.error_bars import estimate as error_estimate
from shell_adhesion.solver.geometry import GAMMA_MAX, Cap
from shell_adhesion.solver.mesh import coarser_mesh
from shell_adhesion.solver.path import Settings
from shell_adhesion.solver.request import (Request, answers, gamma_bucket, initial_fit,
                                           solve_request)
from shell_adhesion.solver.scaling import gamma_hat

from . import case_report
from .case_input import CaseInput, case_input
from .progress import bar as progress_bar

COMPANIONS = 2      # coarser meshes of the family solved for a case's error bars


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
        One ``(gamma_J_m2, Equilibrium, PullOff)`` per gamma answered, dimensionless.
    provenance : dict
        Package version, mesh, interface, dofs, Newton iterations, wall times [s] and
        solver tolerances.
    coarser : solver.case.PathSet or None
        The same shell on the next coarser mesh of the family, whose values give the
        error bars (`solver.error_bars`); None with ``error_bars=False``.
    coarser_pull_off : tuple
        Its PullOff per answered gamma (None where its paths do not reach the pull-off).
    coarsest, coarsest_pull_off :
        The same on the mesh after it: with three meshes converging monotonically the
        error bars use the observed order (solver.error_bars).
    refused : tuple
        ``(gamma_J_m2, reason)`` of each gamma whose pull-off the paths cannot vouch for
        (the command exits 1 if there is any).
    """

    input: CaseInput
    pathset: PathSet
    adhesion: tuple = ()
    provenance: dict = field(default_factory=dict)
    coarser: PathSet = None         # the same shell on the next coarser mesh (error bars)
    coarser_pull_off: tuple = ()    # its PullOff per answered gamma (None: out of its range)
    coarsest: PathSet = None        # and on the one after it (Richardson error bars)
    coarsest_pull_off: tuple = ()
    refused: tuple = ()             # (gamma_J_m2, reason) of each gamma not answered

    def to_dict(self, curves: bool = False) -> dict:
        """The result as plain JSON-able data (NaN as None): input, material, pull_off (with
        gamma, units and error bars) and provenance; with `curves` also the loading,
        relaxation and equilibrium curves."""
        return case_report.as_dict(self, curves)

    def to_json(self, curves: bool = False) -> str:
        """The JSON text `shell-adhesion case --json` prints (`--curves`: with the curves),
        without the final newline: the summary of `to_dict`, or everything with `curves`."""
        return json.dumps(self.to_dict(curves), indent=1, allow_nan=False)

    def to_dataset(self):
        """The result as an xarray Dataset with named dimensions (``gamma``,
        ``loading_state``, ``relaxation``, ``relaxation_state``, ``point``); every variable
        and coordinate has ``units`` and ``long_name``."""
        return case_report.as_dataset(self)


def solve_case(R_mm, t_mm, h_mm, C10_MPa, gamma_J_m2=(), *, delta_max_mm=None,
               interface="no_slip", mesh="default", material="neo_hooke", C01_MPa=0.0,
               C20_MPa=0.0, C30_MPa=0.0, Jm=None, D1_per_MPa=0.0, cavity="open",
               p_kPa=None, p0_kPa=None, p_atm_kPa=None, gas_exponent=None,
               progress=True, error_bars=True) -> CaseResult:
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
        Constant C10 [MPa] of the material (the scaling modulus; neo-Hookean shear modulus
        2 C10), from 1e-6 to 1e4.
    gamma_J_m2 : float or sequence of float, optional
        Work(s) of adhesion gamma [J/m^2]; each gamma / (C10 R) at most
        ``solver.case.GAMMA_MAX``.  One set of FE paths serves them all.  Without any,
        only the loading curve is computed.
    delta_max_mm : float, optional
        Deepest rim approach delta [mm], 0 < delta_max < h and at most R/4 (R/2 for a
        thin shell, t < 0.15 R: the supported domain).  Default: as deep as the requested
        pull-offs need (their equilibrium curves turned with a margin; solver.request),
        at most that bound and 0.9 h; without gamma, to that bound.
    interface : {"no_slip", "frictionless"}
        Interface model (default no_slip, the paper's cohesive contact).
    mesh : {"coarse", "default", "fine"}
        Mesh density.
    material : {"neo-hookean", "mooney-rivlin", "yeoh", "gent"}
        Strain energy, ABAQUS's forms (the solver's names neo_hooke, mooney_rivlin also
        do); default neo-Hookean.
    C01_MPa, C20_MPa, C30_MPa : float
        Mooney-Rivlin C01, Yeoh C20 and C30 [MPa]; only for their model.
    Jm : float
        Gent's limit of I1bar - 3 (required by and only for gent).
    D1_per_MPa : float
        Compressibility D1 [1/MPa], U = (J - 1)^2 / D1, any model; 0 (default) is
        incompressible.
    cavity : {"open", "pressure", "sealed"}
        What closes the shell (a rigid lid on the rim): nothing (default), a prescribed
        gauge pressure, or trapped gas.  P is then the force on rim and lid together.
    p_kPa : float
        Prescribed gauge pressure [kPa] (cavity "pressure" only, required there); > 0
        inflates.  delta is measured from the first touch of the pressurised shell.
    p0_kPa : float
        Gauge pressure of the trapped gas in the undeformed shell [kPa] (sealed; default 0).
    p_atm_kPa : float
        Ambient pressure [kPa] (closed cavities; default 101.325); absolute pressures must
        stay >= 0.
    gas_exponent : float
        Polytropic exponent n of p V^n = const (sealed; >= 1, default 1 isothermal).
    progress : bool
        Show a progress bar on stderr (when it is a terminal).
    error_bars : bool
        Also solve the next coarser mesh of the family and give every headline number
        and the loading P an error bar (``P_N_error`` beside ``P_N`` in the JSON); about
        a quarter more time.  False skips it.

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
    inp = case_input(R_mm, t_mm, h_mm, C10_MPa, gamma_J_m2, delta_max_mm, interface, mesh,
                     material=material, C01_MPa=C01_MPa, C20_MPa=C20_MPa, C30_MPa=C30_MPa,
                     Jm=Jm, D1_per_MPa=D1_per_MPa, cavity=cavity, p_kPa=p_kPa, p0_kPa=p0_kPa,
                     p_atm_kPa=p_atm_kPa, gas_exponent=gas_exponent)
    return _solve(inp, progress, error_bars)


def _request(inp: CaseInput, gamma_max) -> Request:
    """What the FE paths of `inp` must answer (solver.request): the ladder of gammas up to
    `gamma_max` (None: the loading only), as a study's set of the same shell."""
    return Request.serving(gamma_max, None if inp.delta_max_mm is None
                           else inp.delta_max_mm / inp.R_mm)


def _companions(inp: CaseInput, gamma_max: float, g_hats, on_mesh=None, family=None):
    """The shell on the next COMPANIONS coarser meshes of the family, each fitted to the
    same request and relaxed from contact fronts ending on the answer's node type
    (`family`, solver.case.relaxation_starts: the two types converge from different sides,
    so a mix measures no order), with its pull-off per gamma (None where its paths do not
    give one); ``on_mesh()`` after each (progress)."""
    out = []
    mesh = inp.mesh
    for _ in range(COMPANIONS):
        mesh = coarser_mesh(mesh)
        ps, _, _ = solve_request(inp.t_mm / inp.R_mm, inp.h_mm / inp.R_mm,
                                 _request(inp, gamma_max if g_hats else None), gamma_max,
                                 inp.interface, mesh,
                                 material=inp.material, cavity=inp.cavity, family=family)
        got = answers(ps, g_hats) if g_hats else {}
        out.append((ps, tuple(None if isinstance(got[g], Exception) else got[g][1]
                              for g in g_hats),
                    {g: f"the {mesh} mesh: {got[g]}" for g in g_hats
                     if isinstance(got[g], Exception)}))
        if on_mesh is not None:
            on_mesh()
    return out


def _solve(inp: CaseInput, progress: bool, error_bars: bool = True) -> CaseResult:
    R, C10 = inp.R_mm, inp.C10_MPa
    g_hats = [gamma_hat(g, C10, R) for g in inp.gamma_J_m2]
    gamma_max = gamma_bucket(max(g_hats)) if g_hats else GAMMA_MAX
    request = _request(inp, gamma_max if g_hats else None)
    depth = initial_fit(Cap(inp.t_mm / R, inp.h_mm / R), request).delta_max * R
    t0 = time.perf_counter()
    with progress_bar(round(depth, 6), "loading", "mm", progress) as bar:
        stage = ["loading"]

        def on_state(delta):
            if stage[0] != "loading":   # a further solve of the fit loads again
                stage[0] = "loading"
                bar.set_description("loading")
                bar.unit = "mm"
                bar.reset(round(depth, 6))
            bar.update(round(delta * R, 6) - bar.n)

        def on_path(done, total):
            if done == 1:
                stage[0] = "relaxation"
                bar.set_description("relaxation paths")
                bar.unit = "path"
                bar.reset(total)
            bar.update(1)
        try:
            ps, d, loading = solve_request(inp.t_mm / R, inp.h_mm / R, request, gamma_max,
                                           inp.interface, inp.mesh, progress=on_state,
                                           path_progress=on_path, material=inp.material,
                                           cavity=inp.cavity)
        except CavitySnap as err:
            kPa = C10 * 1e3
            raise InputError(f"cavity pressure: {err.p_target * kPa:g} kPa makes the free shell "
                             f"snap (limit point) before contact; it holds "
                             f"{err.p_reached * kPa:.4g} kPa") from None
        except MaterialLimitError as e:     # the same reason, in mm
            e.args = (e.text(R, "mm", "delta_max_mm"),)
            raise
        t_fe = time.perf_counter()
        adhesion, refused = [], []
        if g_hats:
            got = answers(ps, g_hats)
            for g, gh in zip(inp.gamma_J_m2, g_hats):
                if isinstance(got[gh], Exception):
                    refused.append((g, str(got[gh])))
                else:
                    adhesion.append((g, *got[gh]))
        t_energy = time.perf_counter()
        if error_bars:
            bar.set_description("error bars: coarser meshes")
            bar.unit = "mesh"
            bar.reset(COMPANIONS)
        companions = (_companions(inp, gamma_max, g_hats, bar.update,
                                  ps.stats.get("relaxation_family")) if error_bars else [])
    t3 = time.perf_counter()
    answered = [gh for g, gh in zip(inp.gamma_J_m2, g_hats) if g in {a[0] for a in adhesion}]
    pick = lambda pos: tuple(pos[g_hats.index(gh)] for gh in answered)
    settings = Settings()
    provenance = {
        "version": __version__, "mesh": inp.mesh, "interface": inp.interface,
        "material": inp.material.as_dict(),
        "dofs": int(d.ndof), "elements": int(d.capmesh.mesh.nelements),
        "newton_iterations": ps.stats["loading_newton_iterations"]
        + ps.stats["relaxation_newton_iterations"],
        "wall_s": round(t3 - t0, 3),
        "time_split_s": {"finite_elements": round(t_fe - t0, 3),
                         "energy_method": round(t_energy - t_fe, 3),
                         "coarser_meshes": round(t3 - t_energy, 3)},
        "timing": {**ps.stats.get("timing", {}), "energy_method_s": round(t_energy - t_fe, 4)},
        "tolerances": {"newton_rtol": settings.tol, "newton_atol": settings.atol,
                       "gap_tol_over_R": settings.gap_tol},
        "relaxation_gamma_max_over_C10R": gamma_max,
        "fit": fit_dict(ps.stats.get("fit", {}), R),
        "error_bars": ({"coarser_meshes": [c.mesh for c, _, _ in companions],
                        **error_estimate(), "not_given": _missing(companions, inp, g_hats,
                                                                  answered)}
                       if error_bars else None),
        **checks_dict(ps.stats, R, C10), **cavity_dict(ps.stats, R, C10)}
    (c1, p1, _), (c2, p2, _) = companions if companions else ((None, (), {}),) * 2
    return CaseResult(inp, ps, tuple(adhesion), provenance, c1, pick(p1) if c1 else (),
                      c2, pick(p2) if c2 else (), tuple(refused))


def _missing(companions, inp: CaseInput, g_hats, answered) -> dict:
    """Why an answered gamma [J/m^2] has no error bar, or an order-1 one only: which
    coarser mesh gives no pull-off for it, and why (empty if none)."""
    out = {}
    for g, gh in zip(inp.gamma_J_m2, g_hats):
        if gh in answered:
            why = [reasons[gh] for _, _, reasons in companions if gh in reasons]
            if why:
                out[f"{g:g}"] = "; ".join(why)
    return out


def fit_dict(fit: dict, R_mm: float) -> dict:
    """How the paths were fitted to the request (solver.request), with units: the evenly
    meshed radius and arc, the contact radius the loading went to (None: to delta_max),
    the depth bound (mm), the solves, re-meshings and paths relaxed further."""
    if not fit:
        return {}
    mm = lambda v: None if v is None else round(v * R_mm, 10)
    return {"even_arc_mm": mm(fit["uniform_arc"]),
            "loading_target_a_mm": mm(fit["a_stop"]) if fit["a_stop"] is not None
            and fit["a_stop"] < 1 else None,
            "delta_bound_mm": mm(fit["delta_bound"]), "solves": fit["solves"],
            "remeshed": fit["remeshed"], "paths_taken_further": fit["paths_taken_further"]}


def cavity_dict(stats: dict, R_mm: float, C10_MPa: float) -> dict:
    """A closed cavity's state at the first touch: the apex displacement of the free
    pressurised shell before contact (mm, z up: < 0 it bulged toward the plane), the volume
    (mm^3), the gauge pressure (kPa) and U_E there (mJ, strain minus pressure work); {} if
    open."""
    if "cavity_lift" not in stats:
        return {}
    return {"cavity_touch": {
        "apex_uz_mm": -stats["cavity_lift"] * R_mm,
        "V_mm3": stats["cavity_V_touch"] * R_mm ** 3,
        "p_kPa": stats["cavity_p_touch"] * C10_MPa * 1e3,
        "U_E_mJ": stats["cavity_U_touch"] * C10_MPa * R_mm ** 3}}


def checks_dict(stats: dict, R_mm: float, C10_MPa: float) -> dict:
    """What the solver checked, with units: the worst element quality (pointwise J and
    in-plane det F, dimensionless), how deep the loading got (mm) and why it stopped short
    of delta_max (None: it did not), where the contact zone inverted (mm; None: never) and
    the largest gamma every pair of relaxation paths reached (J/m^2; None: no pair)."""
    quality = {k: stats.get(k) for k in ("J_min", "J_max", "detF_min", "distortion_min",
                                         "relaxation_J_min", "relaxation_J_max",
                                         "relaxation_detF_min") if k in stats}
    mm = lambda v: None if v is None else round(v * R_mm, 10)
    G = stats.get("G_max_reached")
    return {"loading_reached": {"delta_reached_mm": mm(stats.get("delta_reached")),
                                "stopped_by": stats.get("loading_stopped_by") or None},
            "element_quality": quality,
            "inversion": {"stage": stats.get("inversion_stage"),
                          "inversion_delta_mm": mm(stats.get("inversion_delta")),
                          "inversion_a_mm": mm(stats.get("inversion_a")),
                          "inverted_relaxation_paths": stats.get("inverted_paths", 0)},
            "G_max_reached_J_m2": None if G is None else round(G * C10_MPa * R_mm * 1e3, 10)}

