"""`shell_adhesion.design` and the `design` command: the shell that sticks best for a
material and a size, searched on a pull-off map and confirmed by one FE case.

Units at the edges: C10 in MPa, gamma in J/m^2, R, b, t, h in mm, forces in N.  The
search is `analysis.design_search`; the confirmation solves the optimum with `solve_case`
on the map's own mesh and interface, so that map and case differ only by the map's
interpolation and by their meshes (each shell is meshed for itself).
"""
from dataclasses import asdict, dataclass
import math
import sys

from shell_adhesion.analysis.design_search import OBJECTIVES, Design, search
from shell_adhesion.study.progress import bar as progress_bar, logged
from shell_adhesion.study.pull_off_map import DEFAULT_MAP, pull_off_map

NAMES = ("P_star", "delta_star", "a_star")


@dataclass(frozen=True)
class DesignResult:
    """The map's optimum (`design`) and, unless skipped, its FE confirmation: name_unit ->
    (value, error) of the case, and whether map and case agree within their error bars
    (`agrees`: ``|P*_map - P*_case|`` at most the two error bars in quadrature)."""
    design: Design
    material: dict
    confirmation: dict = None
    agrees: bool = None

    def to_dict(self) -> dict:
        d = asdict(self.design)
        d["answers"] = {k: list(v) for k, v in d["answers"].items()}
        return dict(design=d, material=self.material, confirmation=self.confirmation,
                    agrees=self.agrees)

    def to_text(self) -> str:
        d, m = self.design, self.material
        lines = [f"design for C10 {m['C10_MPa']:g} MPa, gamma {m['gamma_J_m2']:g} J/m^2, "
                 f"objective {d.objective} = {OBJECTIVES[d.objective]}",
                 f"optimum: R {d.R_mm:.4g} mm, t {d.t_mm:.4g} mm (t/R {d.t_mm / d.R_mm:.4g}), "
                 f"h {d.h_mm:.4g} mm (h/R {d.h_mm / d.R_mm:.4g}); objective "
                 f"{d.objective_value:.5g} ({d.evaluated} map evaluations)",
                 "on a bound: " + ("; ".join(d.on_bounds) if d.on_bounds else
                                   "no (an inner optimum)")]
        rows = [("", "map", "FE case" if self.confirmation else "")]
        for q in NAMES:
            key = "P_star_N" if q == "P_star" else f"{q}_mm"
            v, e = d.answers[key]
            fe = self.confirmation.get(key) if self.confirmation else None
            rows.append((key, f"{v:.5g} +- {e:.2g}",
                         "" if fe is None else f"{fe[0]:.5g} +- {_num(fe[1]):.2g}"))
        width = max(len(r[0]) for r in rows)
        lines += [f"  {a:<{width}}  {b:<22} {c}" for a, b, c in rows]
        if self.confirmation is not None:
            lines.append("map and FE case agree within their error bars" if self.agrees
                         else "map and FE case DIFFER by more than their error bars")
        return "\n".join(lines)


def _say(progress, text):
    """A stage's line on stderr (a terminal, a notebook or a log) when `progress`."""
    if progress:
        print(text, file=sys.stderr, flush=True)


def _num(v):
    return math.nan if v is None else v


def design(C10_MPa, gamma_J_m2, objective="pull_off", *, R_mm=None, b_mm=None,
           t_mm=(0.0, math.inf), h_mm=(0.0, math.inf), map=DEFAULT_MAP, confirm=True,
           progress=False) -> DesignResult:
    """The spherical-cap shell that maximises `objective` for a material and a size.

    Parameters
    ----------
    C10_MPa : float
        Neo-Hookean C10 [MPa] (shear modulus 2 C10).
    gamma_J_m2 : float
        Work of adhesion [J/m^2].
    objective : {"pull_off", "per_preload", "per_volume"}
        ``|P*|`` [N], ``|P*|`` / preload (the rim force at the contact radius a* on loading),
        or ``|P*|`` per material volume [N/mm^3].
    R_mm, b_mm : float
        The size: the outer radius of curvature R [mm], or the rim radius b [mm] of the
        cap's base (then R follows from h); exactly one.
    t_mm, h_mm : (float, float)
        Bounds of the thickness and the depth [mm] (default: the map's).
    map : str or path
        The shipped map (``coarse``, the default) or a map file built by `map build`.
    confirm : bool
        Solve the optimum with one FE case on the map's mesh and interface.
    progress : bool
        Show what runs on stderr: a bar (done/total, ETA) of the map search and of the FE
        case's stages on a terminal or in a notebook, and the FE case's line; in a log file
        each stage's line at its start, at most every 10 s and when complete.
    """
    with logged():          # in a log file too, its stages' lines (study.progress)
        return _design(C10_MPa, gamma_J_m2, objective, R_mm, b_mm, t_mm, h_mm, map, confirm,
                       progress)


def _design(C10_MPa, gamma_J_m2, objective, R_mm, b_mm, t_mm, h_mm, map, confirm,
            progress) -> DesignResult:
    pm = pull_off_map(map)
    material = dict(C10_MPa=C10_MPa, gamma_J_m2=gamma_J_m2, model="neo-hookean",
                    interface=pm.ds.attrs.get("interface", "no_slip"),
                    mesh=pm.ds.attrs.get("mesh", "default"))
    stages = 2 if confirm else 1
    with progress_bar(None, f"design 1/{stages}: map search", "shell", progress) as bar:
        def on_grid(done, total):
            if bar.total is None:
                bar.reset(total)
            bar.update(done - bar.n)
        found = search(pm, C10_MPa, gamma_J_m2, objective, R_mm=R_mm, b_mm=b_mm,
                       t_mm=tuple(t_mm), h_mm=tuple(h_mm), on_grid=on_grid)
    if not confirm:
        return DesignResult(found, material)
    from shell_adhesion.study.case import solve_case
    _say(progress, f"design 2/2: one FE case (R {found.R_mm:.4g} mm, t {found.t_mm:.4g} mm, "
                   f"h {found.h_mm:.4g} mm) on the {material['mesh']} mesh, then "
                   "two coarser meshes for its error bars")
    case = solve_case(found.R_mm, found.t_mm, found.h_mm, C10_MPa, [gamma_J_m2],
                      interface=material["interface"], mesh=material["mesh"],
                      progress=progress).to_dict()["pull_off"][0]
    if case["status"] != "ok":
        return DesignResult(found, material, dict(status=case["status"],
                                                  reason=case.get("reason")), False)
    fl = case["fixed_load"]
    confirmation = {"P_star_N": (fl["P_N"], fl.get("P_N_error")),
                    "delta_star_mm": (fl["delta_mm"], fl.get("delta_mm_error")),
                    "a_star_mm": (fl["a_mm"], fl.get("a_mm_error"))}
    v, e = found.answers["P_star_N"]
    fe, fe_error = confirmation["P_star_N"]
    # each shell has a mesh of its own: the map's error (interpolation and FE) and the
    # case's FE error bar both separate them
    agrees = abs(fe - v) <= math.hypot(e, _num(fe_error) if fe_error is not None else 0.0)
    return DesignResult(found, material, confirmation, bool(agrees))
