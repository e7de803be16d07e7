"""C10 and gamma of one shell from a measured force-displacement curve:
`shell_adhesion.fit_curve` and the `fit` command.

Input with units: R, t, h in mm; the curve in time order (approach, then retraction), as a
CSV file whose header names its columns with their units (`read_curve`: delta_mm, delta_um,
P_N, P_mN, P_uN, t_s, index, segment, and rheometer and testing-machine exports; sorted by
time or index when given) or as arrays (mm, N); optionally a measured pull-off force in N.
One set of FE paths of the shell (t/R, h/R) serves every C10 and gamma (DESIGN.md section
3); `solver.fit` removes the baseline, finds the jump-off, and fits C10, gamma and the
contact offset delta0 (measured delta = model delta + delta0) by least squares, and also
what the half-space tools give (Hertz loading, JKR pull-off).  The fit repeated on the next
coarser mesh gives the model's error: the 95 % intervals (C10 and delta0 profile likelihood
on the loading, gamma linearised) are widened by it, and a residual beyond
solver.fit.MISFIT_FACTOR x hypot(noise, model error) is a misfit (solver.fit.Misfit, exit 1).
P > 0 compression, delta > 0 approach.
"""
import csv
from dataclasses import dataclass, field
import functools
import json
import math
from pathlib import Path
import time

import numpy as np

from shell_adhesion import __version__
from shell_adhesion.solver import fit as solver_fit
from shell_adhesion.solver.geometry import (GAMMA_MAX, Cap, check_cap, check_delta_max,
                                            delta_bound)
from shell_adhesion.errors import InputError
from shell_adhesion.solver.contact import INTERFACES
from shell_adhesion.solver.mesh import coarser_mesh
from shell_adhesion.solver.request import Request, gamma_bucket, solve_request
from shell_adhesion.solver.scaling import check_finite, check_R
from shell_adhesion.theory import youngs_modulus_MPa

MESHES = ("coarse", "default", "fine")
HEADER = ("delta_mm", "P_N")
API_NAMES = dict(R_mm="R_mm", t_mm="t_mm", h_mm="h_mm", curve="curve",
                 pull_off_N="pull_off_N", interface="interface", mesh="mesh")
DEPTH_MARGIN = 1.25     # the paths are loaded this much deeper than the curve seems to go
GAMMA_MARGIN = 3.0      # and relaxed for gamma / (C10 R) up to this times the JKR estimate
MAX_SOLVES = 3
SOFT_C10_MPA = (1e-3, 50.0)     # a fitted C10 outside is not a soft solid's: a unit is off
PATH_CACHE = 16                 # path sets kept in memory (a second fit of a shell reuses them)

# column names: (quantity, factor to mm, N or s); "gap" falls as the shell is pressed
COLUMNS = {
    "delta_mm": ("delta", 1.0), "delta_um": ("delta", 1e-3),
    "P_N": ("P", 1.0), "P_mN": ("P", 1e-3), "P_uN": ("P", 1e-6),
    "t_s": ("time", 1.0), "index": ("index", 1.0), "segment": ("segment", 1.0),
    "Gap [mm]": ("gap", 1.0), "Gap [um]": ("gap", 1e-3), "Normal Force [N]": ("P", 1.0),
    "Normal Force [mN]": ("P", 1e-3), "Time [s]": ("time", 1.0), "Point No.": ("index", 1.0),
    "Extension (mm)": ("delta", 1.0), "Load (N)": ("P", 1.0), "Load (mN)": ("P", 1e-3),
    "Time (s)": ("time", 1.0),
}
SEGMENTS = ("approach", "retract")


def read_curve(path) -> tuple:
    """(delta_mm, P_N, how) of a CSV curve file, rows in time order: sorted by its time
    column, else its index column, else as in the file (approach rows before retract rows
    when it has a `segment` column); `how` says which, and how many rows were read.
    Accepted columns (any order, `COLUMNS`): delta_mm or delta_um (approach), or a
    rheometer's gap (delta = first gap - gap), P_N, P_mN or P_uN (compression > 0), t_s,
    index, segment (approach or retract), and the instrument headers ``Point No.,Normal
    Force [N],Gap [mm],Time [s]`` and ``Time (s),Extension (mm),Load (N)``.  Lines starting
    with # are comments; a UTF-8 BOM is accepted.  InputError names the file, the row and
    the field of anything else."""
    name = str(path)
    try:
        with open(path, newline="", encoding="utf-8-sig") as f:
            rows = [r for r in csv.reader(f) if not (r and r[0].lstrip().startswith("#"))]
    except OSError as e:
        raise InputError(f"{name}: cannot be read ({e.strerror or e})") from None
    except UnicodeDecodeError:
        raise InputError(f"{name}: not a text (UTF-8) CSV file") from None
    if not rows:
        raise InputError(f"{name}: row 1: an empty file; the header must name the columns "
                         f"(accepted: {', '.join(COLUMNS)})")
    header = [c.strip() for c in rows[0]]
    kinds = {}
    for column in header:
        if column not in COLUMNS:
            raise InputError(f"{name}: header: unknown column {column!r}; accepted: "
                             f"{', '.join(COLUMNS)}")
        kind = COLUMNS[column][0]
        if kind in kinds or (kind in ("delta", "gap") and {"delta", "gap"} & set(kinds)):
            raise InputError(f"{name}: header: {column!r} gives the {kind} a second time")
        kinds[kind] = column
    for need, names in (("P", "P_N, P_mN, P_uN, Normal Force [N] or Load (N)"),
                        ("delta", "delta_mm, delta_um, Gap [mm] or Extension (mm)")):
        if need not in kinds and not (need == "delta" and "gap" in kinds):
            raise InputError(f"{name}: header: no {need} column (one of {names})")
    values, segments, blank = [], [], 0
    for i, row in enumerate(rows[1:], start=2):
        if not row or all(not c.strip() for c in row):
            blank += 1
            continue
        if len(row) != len(header):
            raise InputError(f"{name}: row {i}: {len(row)} fields, expected {len(header)} "
                             f"({','.join(header)})")
        cells = dict(zip(header, row))
        if "segment" in kinds:
            seg = cells.pop(kinds["segment"]).strip().lower()
            if seg not in SEGMENTS:
                raise InputError(f"{name}: row {i}: segment: {seg!r} must be one of "
                                 f"{', '.join(SEGMENTS)}")
            segments.append(SEGMENTS.index(seg))
        values.append({c: _cell(name, i, c, t) * COLUMNS[c][1] for c, t in cells.items()})
    delta, P, how = _ordered(name, kinds, values, segments)
    return delta, P, how + (f" ({blank} empty rows skipped)" if blank else "")


def _ordered(name, kinds, values, segments) -> tuple:
    """(delta_mm, P_N, how) of the parsed rows in time order (`read_curve`)."""
    col = {k: np.array([v[c] for v in values], dtype=float) for k, c in kinds.items()
           if k != "segment"}
    n = len(values)
    keys, how = [], "in the file's order"
    for kind in ("time", "index"):
        if kind in col:
            keys.append(col[kind])
            how = f"ordered by {kinds[kind]}"
            break
    if segments:
        keys.append(np.array(segments))
        how = "ordered by segment (approach, retract), then " + how.replace("ordered ", "")
    order = np.lexsort(keys) if keys else np.arange(n)    # the last key sorts first
    if "gap" in col:
        gap = col["gap"][order]
        delta = gap[0] - gap if n else gap
        how += f"; delta = first gap - {kinds['gap']}"
    else:
        delta = col["delta"][order]
    return delta, col["P"][order], f"{n} rows, {how}"


def _cell(name, row, field, text):
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"{name}: row {row}: {field}: {text.strip()!r} is not a number") from None
    if not math.isfinite(value):
        raise InputError(f"{name}: row {row}: {field}: {text.strip()} must be a finite number")
    return value


def check_curve(delta_mm, P_N, name="curve"):
    """The curve as float arrays; InputError unless it is finite, in time order (delta
    rises to its deepest point and falls after it, solver.fit.MAX_BACKTRACK), has at least
    MIN_LOADING_POINTS points up to its deepest delta and compresses the shell (P > 0).
    Rows are numbered as in the CSV file (the header is row 1)."""
    try:
        d = np.asarray(delta_mm, dtype=float).ravel()
        P = np.asarray(P_N, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"{name}: delta_mm and P_N must be sequences of numbers") from None
    if len(d) != len(P):
        raise InputError(f"{name}: {len(d)} delta_mm values but {len(P)} P_N values")
    for column, v in zip(HEADER, (d, P)):
        bad = np.flatnonzero(~np.isfinite(v))
        if len(bad):
            raise InputError(f"{name}: row {bad[0] + 2}: {column}: {v[bad[0]]} must be a "
                             "finite number")
    back = solver_fit.backtrack_share(d)
    if back > solver_fit.MAX_BACKTRACK:
        raise InputError(f"{name}: the rows are not in time order: delta_mm goes back "
                         f"{100 * back:.0f} % of its travel against the approach before its "
                         f"deepest point and the retraction after it (at most "
                         f"{100 * solver_fit.MAX_BACKTRACK:g} %); sort the file or give a time "
                         "or index column (t_s, index)")
    n_load = int(np.argmax(d)) + 1 if len(d) else 0
    if n_load < solver_fit.MIN_LOADING_POINTS:
        raise InputError(f"{name}: {n_load} loading points (rows up to the deepest delta_mm); "
                         f"at least {solver_fit.MIN_LOADING_POINTS} needed")
    if not np.any(P[:n_load] > 0):
        raise InputError(f"{name}: P_N is never > 0 while loading: the curve never compresses "
                         "the shell (P > 0 is compression)")
    return d, P


@dataclass(frozen=True)
class FitInput:
    """Checked input: lengths in mm, the curve (mm, N), the pull-off force (N) or None."""

    R_mm: float
    t_mm: float
    h_mm: float
    delta_mm: np.ndarray = field(repr=False)
    P_N: np.ndarray = field(repr=False)
    pull_off_N: float = None
    interface: str = "no_slip"
    mesh: str = "default"
    source: str = "curve"
    rows: str = ""              # how many rows were read and how they were ordered


def fit_input(R_mm, t_mm, h_mm, curve, pull_off_N=None, interface="no_slip",
              mesh="default", names=None) -> FitInput:
    """Check the input of a fit; InputError names the field (as `names` calls it)."""
    n = dict(API_NAMES, **(names or {}))
    R = check_finite(R_mm, n["R_mm"], "mm")
    t = check_finite(t_mm, n["t_mm"], "mm")
    h = check_finite(h_mm, n["h_mm"], "mm")
    check_R(R, n["R_mm"])
    check_cap(t / R, h / R, f"{n['t_mm']} (t/R = {t:g}/{R:g})", f"{n['h_mm']} (h/R = {h:g}/{R:g})")
    if isinstance(curve, (str, Path)):
        source = str(curve)
        d, P, rows = read_curve(curve)
    else:
        source = n["curve"]
        d, P = curve
        rows = f"{len(d)} rows, in the order given"
    d, P = check_curve(d, P, source)
    if pull_off_N is not None:
        pull_off_N = check_finite(pull_off_N, n["pull_off_N"], "N")
        if pull_off_N == 0:
            raise InputError(f"{n['pull_off_N']}: 0 must be a non-zero force (N)")
    if interface not in INTERFACES:
        raise InputError(f"{n['interface']}: {interface!r} must be one of {', '.join(INTERFACES)}")
    if mesh not in MESHES:
        raise InputError(f"{n['mesh']}: {mesh!r} must be one of {', '.join(MESHES)}")
    return FitInput(R, t, h, d, P, pull_off_N, interface, mesh, source, rows)


@dataclass(frozen=True, eq=False)
class FitResult:
    """A fitted curve: C10 [MPa], gamma [J/m^2] and delta0 [mm] (the contact point) with
    95 % intervals (the data's scatter, and the model's discretisation
    error from the same fit on the next coarser mesh, in quadrature), the baseline removed,
    the goodness of fit (`verdict`), the half-space answer (`jkr`), and the paths and
    estimates behind them (dimensionless, `solver.fit`)."""

    input: FitInput
    estimate: solver_fit.Estimate
    jkr: tuple                  # (C10, x0, gamma_hat) of the half-space fit, dimensionless
    pathset: object
    provenance: dict = field(default_factory=dict)
    other: solver_fit.Estimate = None       # the same fit on the next coarser mesh
    other_pathset: object = None
    baseline: solver_fit.Baseline = solver_fit.Baseline()   # found before the fit
    shifted: solver_fit.Estimate = None     # the coarser mesh's fit of this fit's curve

    @property
    def C10_MPa(self):
        return self.estimate.C10

    @property
    def gamma_J_m2(self):
        return self.estimate.gamma_hat * self.estimate.C10 * self.input.R_mm * 1e3

    @property
    def delta0_mm(self):
        return self.estimate.x0 * self.input.R_mm

    def intervals(self) -> dict:
        """95 % intervals of C10 [MPa], gamma [J/m^2], delta0 [mm]: the data's widened by the
        model's error (`solver.fit.with_model_error`: the shift of the parameters when the
        next coarser mesh fits this fit's curve) where it is known."""
        e, o, R = self.estimate, self.shifted, self.input.R_mm
        values = {"C10_MPa": (e.C10, e.C10_ci, o and o.C10, 1.0),
                  "gamma_J_m2": (e.gamma_hat * e.C10, e.gamma_ci,
                                 o and o.gamma_hat * o.C10, R * 1e3),
                  "delta0_mm": (e.x0, e.x0_ci, o and o.x0, R)}
        out = {}
        for name, (v, ci, other, scale) in values.items():
            both = ci if other is None else solver_fit.with_model_error(v, ci, other)
            out[name] = [float(c * scale) for c in both]
        return out

    def model_errors(self) -> dict:
        """|this fit - the coarser mesh's fit of its curve| of C10 [MPa], gamma [J/m^2],
        delta0 [mm]."""
        e, o, R = self.estimate, self.shifted, self.input.R_mm
        if o is None:
            return {}
        return {"C10_MPa": abs(e.C10 - o.C10),
                "gamma_J_m2": abs(e.gamma_hat * e.C10 - o.gamma_hat * o.C10) * R * 1e3,
                "delta0_mm": abs(e.x0 - o.x0) * R}

    def _model_p(self, ps, est, split=None):
        """An estimate's model p at the curve's points (baseline removed; NaN where unused)."""
        x = self.input.delta_mm / self.input.R_mm
        out = solver_fit.model(ps, est.C10, est.gamma_hat, est.x0, x, split or est.split)
        if est.baseline:
            out = out + est.baseline[0] + (est.baseline[1] * x if len(est.baseline) > 1 else 0.0)
        return out

    @property
    def verdict(self) -> solver_fit.Verdict:
        """Goodness of fit (solver.fit.verdict) of the points used."""
        e = self.estimate
        used = np.concatenate([e.split.loading, e.split.retraction]).astype(int)
        x = self.input.delta_mm / self.input.R_mm
        p = self.input.P_N / self.input.R_mm ** 2 - self.baseline(x)
        here = self._model_p(self.pathset, e)[used]
        there = self._model_p(self.other_pathset, self.other, e.split)[used] \
            if self.other is not None else here
        return solver_fit.verdict(e.residuals, p, here, there)

    def model_P_N(self):
        """The fitted model's P [N] at the measured points, baseline included (NaN from the
        jump-off on)."""
        x = self.input.delta_mm / self.input.R_mm
        return (self._model_p(self.pathset, self.estimate) + self.baseline(x)) * self.input.R_mm ** 2

    def to_dict(self) -> dict:
        """The result as plain JSON-able data."""
        R, e, inp = self.input.R_mm, self.estimate, self.input
        C10_j, x0_j, gh_j = self.jkr
        ci = self.intervals()
        v = self.verdict
        b_off, b_slope = (tuple(e.baseline) + (0.0, 0.0))[:2]
        R2 = R ** 2
        return {
            "input": dict(R_mm=R, t_mm=inp.t_mm, h_mm=inp.h_mm, curve=inp.source,
                          points=len(inp.delta_mm), rows=inp.rows, pull_off_N=inp.pull_off_N,
                          interface=inp.interface, mesh=inp.mesh),
            "C10_MPa": float(e.C10), "C10_MPa_ci95": ci["C10_MPa"],
            "gamma_J_m2": float(self.gamma_J_m2), "gamma_J_m2_ci95": ci["gamma_J_m2"],
            "gamma_from": e.gamma_from,
            "delta0_mm": float(self.delta0_mm), "delta0_mm_ci95": ci["delta0_mm"],
            "baseline": {"offset_N": float((self.baseline.offset + b_off) * R2),
                         "drift_N_per_mm": float((self.baseline.slope + b_slope) * R),
                         "non_contact_points": self.baseline.points,
                         "drift_fitted": self.baseline.drift,
                         "removed": self.baseline.points > 0},
            "residual_rms_N": float(v.rms * R2),
            "noise_sd_N": float(v.noise * R2),
            "model_error_rms_N": float(v.model * R2),
            "verdict": {"misfit": bool(v.misfit), "ratio": float(v.ratio),
                        "factor": v.factor,
                        "rule": "misfit when the residual rms exceeds the factor times "
                                "hypot(noise sd, model error rms)"},
            "model_error": {k: float(val) for k, val in self.model_errors().items()},
            "points_used": dict(e.used),
            "intervals": (("95 %: C10 and delta0 profile likelihood on the loading (F(1, m - n) "
                           "on its residual sum of squares, baseline and the other refitted), "
                           "gamma linearised on the retraction with their uncertainty carried "
                           "through")
                          if e.intervals else "95 %, linearised: s^2 (J^T J)^-1, Student t"
                          + ("; gamma's from C10's only (the pull-off force taken as exact)"
                             if e.gamma_from == "pull_off" else ""))
                         + (f"; widened in quadrature by the model's error (the shift of the "
                            f"values when the {self.provenance.get('model_error_mesh')} mesh "
                            f"fits this fit's curve)"
                            if self.other is not None else "; without the model's error"),
            "jkr": {"E_MPa": float(youngs_modulus_MPa(C10_j)), "C10_MPa": float(C10_j),
                    "gamma_J_m2": float(gh_j * C10_j * R * 1e3), "delta0_mm": float(x0_j * R),
                    "method": "Hertz fit of the loading (E* = 8 C10 = 4 E / 3), gamma from "
                              "JKR's P* = -(3/2) pi R gamma with P* the most tensile force"
                              + (" (the pull-off force given)" if inp.pull_off_N is not None
                                 else "")},
            "provenance": self.provenance,
        }

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), indent=1, allow_nan=False)


def fit_curve(R_mm, t_mm, h_mm, curve, *, pull_off_N=None, interface="no_slip",
              mesh="default") -> FitResult:
    """Fit C10 and gamma of one shell to a measured force-displacement curve.

    Parameters
    ----------
    R_mm, t_mm, h_mm : float
        The shell: outer radius R, thickness t and depth h [mm] (as `solve_case`).
    curve : str or Path or (delta_mm, P_N)
        A CSV file whose header names its columns (`read_curve`: delta_mm or delta_um,
        P_N, P_mN or P_uN, t_s, index, segment, or an instrument's export), or two
        sequences: the rim approach delta [mm] and the force P [N] (P > 0 compression), in
        time order: approach to the deepest point, then retraction (up to and beyond the
        jump-off, whose points are left out and counted).
    pull_off_N : float, optional
        A measured pull-off force [N] (its magnitude is used): gamma then comes from the
        fixed-load pull-off P* alone, and C10 and delta0 from the loading.
    interface : {"no_slip", "frictionless"}
    mesh : {"coarse", "default", "fine"}

    Returns
    -------
    FitResult
        ``.to_dict()``: C10_MPa, gamma_J_m2 and delta0_mm (the contact point) with 95 %
        intervals (the data's scatter, widened by the model's error from the next coarser
        mesh), the baseline removed, residual_rms_N against noise_sd_N and
        model_error_rms_N (the verdict), the rows used from each part and the half-space
        (Hertz + JKR) answer ``jkr``.

    Raises
    ------
    InputError
        (a ValueError) before any computation, naming the field, row or file.
    solver.fit.Misfit
        If the residual is more than MISFIT_FACTOR times the noise and model error, or C10
        is not a soft solid's; ``.result`` holds the fit.
    solver.fit.FitError
        If the curve cannot be fitted with the shell's paths.
    """
    inp = fit_input(R_mm, t_mm, h_mm, curve, pull_off_N, interface, mesh)
    return fit_checked(inp)


def fit_checked(inp: FitInput) -> FitResult:
    """Solve the shell's paths as the curve needs and fit it (`fit_curve` after checks):
    the baseline (offset and drift of the non-contact part) first; then the loading alone
    (C10 and delta0, so the gamma range of the paths can be chosen), then loading and
    relaxation paths, again deeper or for larger gammas if the fit needs it (at most
    MAX_SOLVES); the next coarser mesh's fit of the fitted curve gives the model's error,
    which widens the intervals and enters the verdict.  Raises solver.fit.Misfit (with the
    result) when the residual is MISFIT_FACTOR times the noise and model error, or C10 is
    not a soft solid's."""
    R = inp.R_mm
    x, p_raw = inp.delta_mm / R, inp.P_N / R ** 2
    base = solver_fit.baseline(x, p_raw)
    p = p_raw - base(x)
    p_pull = None if inp.pull_off_N is None else -abs(inp.pull_off_N) / R ** 2
    jkr = solver_fit.fit_jkr(x, p, p_pull)
    cap = Cap(inp.t_mm / R, inp.h_mm / R)
    depth = _depth(x, p, cap, inp.source)
    t0 = time.perf_counter()
    first = _paths(cap.t, cap.h, Request.serving(None, depth), GAMMA_MAX, inp.interface, inp.mesh)
    start = solver_fit.fit_loading(first, x, p, jkr[:2])
    _check_reach(x.max() - start[1], cap, inp)
    gamma_max = _gamma_max(jkr, start[0])
    solves = [dict(delta_max_over_R=float(first.delta_max), loading_only=True,
                   solve_s=round(time.perf_counter() - t0, 3))]
    for _ in range(MAX_SOLVES):
        t1 = time.perf_counter()
        request = Request.serving(gamma_max, depth)
        ps = _paths(cap.t, cap.h, request, gamma_max, inp.interface, inp.mesh)
        t2 = time.perf_counter()
        try:
            est = solver_fit.fit_curve(ps, x, p, p_pull, hertz=start,
                                       baseline_parameters=base.parameters)
        except solver_fit.TooDeep as e:
            _check_reach(e.x_turn, cap, inp)
            depth = _depth_bucket(min(delta_bound(cap), max(depth, e.x_turn) * DEPTH_MARGIN))
            solves.append(dict(delta_max_over_R=float(ps.delta_max), solve_s=round(t2 - t1, 3)))
            continue
        solves.append(dict(delta_max_over_R=float(ps.delta_max), gamma_max_over_C10R=ps.gamma_max,
                           solve_s=round(t2 - t1, 3), fit_s=round(time.perf_counter() - t2, 3)))
        if est.gamma_hat < 0.999 * est.gamma_span[1]:
            break
        if ps.gamma_max >= GAMMA_MAX:
            raise solver_fit.FitError(
                f"gamma/(C10 R) reaches {est.gamma_span[1]:.4g}, the largest the paths give "
                f"(loaded to delta/R = {ps.loading_delta[-1]:.4g})")
        gamma_max = gamma_bucket(min(GAMMA_MAX, GAMMA_MARGIN * est.gamma_hat))
    else:
        raise solver_fit.FitError(f"no fit within {MAX_SOLVES} solves of the paths")
    t3 = time.perf_counter()
    other_mesh = coarser_mesh(inp.mesh)
    other, est_c, est_m = _companion(inp, cap, x, p, p_pull, est, base, gamma_max, depth)
    provenance = {"version": __version__, "mesh": inp.mesh, "interface": inp.interface,
                  "model_error_mesh": other_mesh, "solves": solves,
                  "model_error_s": round(time.perf_counter() - t3, 3),
                  "wall_s": round(time.perf_counter() - t0, 3), "dofs": ps.stats.get("dofs")}
    result = FitResult(inp, est, jkr, ps, provenance, est_c, other, base, est_m)
    _judge(result)
    return result


def _companion(inp, cap, x, p, p_pull, est, base, gamma_max, depth):
    """(paths, fit of the data, fit of this fit's curve) on the next coarser mesh: the
    first's curve against this fit's is the verdict's model error; the second is
    noise-free, so the parameters' shift between the meshes is the model's, not the
    noise's: the intervals' model error.  Solved deeper once if the coarser fit needs it."""
    other_mesh = coarser_mesh(inp.mesh)
    used = np.concatenate([est.split.loading, est.split.retraction]).astype(int)
    used = used[:len(est.residuals)]            # the loading alone with a pull-off force
    p_model = p.copy()
    p_model[used] = p[used] + est.residuals
    for _ in range(2):
        other = _paths(cap.t, cap.h, Request.serving(gamma_max, depth), gamma_max,
                       inp.interface, other_mesh)
        try:
            fits = [solver_fit.fit_curve(other, x, q, p_pull, hertz=(est.C10, est.x0),
                                         split=est.split, intervals=False,
                                         baseline_parameters=base.parameters)
                    for q in (p, p_model)]
            return (other, *fits)
        except solver_fit.TooDeep as e:
            depth = min(delta_bound(cap), _depth_bucket(max(depth, e.x_turn) * DEPTH_MARGIN))
            error = e
        except (solver_fit.FitError, ValueError) as e:
            error = e
            break
    raise solver_fit.FitError(f"the model's error cannot be estimated: the fit on the "
                              f"{other_mesh} mesh fails ({error})")


def _judge(result):
    """Raise solver.fit.Misfit (one line, with the result) for a misfit or a C10 that is
    not a soft solid's."""
    v = result.verdict
    if v.misfit:
        raise solver_fit.Misfit(
            f"misfit: the residual rms {v.rms * result.input.R_mm ** 2:.3g} N is "
            f"{v.ratio:.1f} x the noise and model error ({_N(v.noise, result)} N noise, "
            f"{_N(v.model, result)} N model; above {v.factor:g} x is a misfit): this shell's "
            f"model does not describe {result.input.source} (another shell, or a unit off?)",
            result)
    lo, hi = SOFT_C10_MPA
    if not lo <= result.C10_MPa <= hi:
        raise solver_fit.Misfit(
            f"misfit: C10 = {result.C10_MPa:.4g} MPa is not a soft solid's ({lo:g} to "
            f"{hi:g} MPa): is a unit off (a force in mN read as N is 1000 x; name it in the "
            f"header, e.g. P_mN)?", result)


def _N(value, result):
    return f"{value * result.input.R_mm ** 2:.3g}"


@functools.lru_cache(maxsize=PATH_CACHE)
def _paths(t, h, request, gamma_max, interface, mesh):
    """The shell's paths for `request` (solver.request.solve_request), kept in memory."""
    return solve_request(t, h, request, gamma_max, interface, mesh)[0]


def _depth_bucket(depth: float) -> float:
    """depth / R rounded up to the ladder 2^(k/8), so that curves of one shell reach the
    same paths."""
    return float(2.0 ** (math.ceil(8.0 * math.log2(depth) - 1e-9) / 8.0))


def _depth(x, p, cap: Cap, source) -> float:
    """delta_max / R of the paths: the curve's depth from where P first exceeds 5 % of
    its largest value, with DEPTH_MARGIN, within the shell's bound."""
    split = solver_fit.split_curve(x, p)
    xl, pl = x[split.loading], p[split.loading]
    touch = xl[np.argmax(pl > 0.05 * pl.max())]
    depth = DEPTH_MARGIN * (x.max() - touch)
    bound = delta_bound(cap)
    depth = min(_depth_bucket(max(depth, 1e-3)), bound)
    check_delta_max(depth, cap.h, f"{source}: the depth delta/R", t_over_R=cap.t)
    return depth


def _check_reach(x_turn, cap: Cap, inp: FitInput):
    """InputError if the curve goes deeper from contact than the shell's supported depth."""
    bound = delta_bound(cap)
    if x_turn > bound * (1 + 1e-9):
        R = inp.R_mm
        raise InputError(f"{inp.source}: the curve goes {x_turn * R:.4g} mm deep from contact "
                         f"(delta0 = {(inp.delta_mm.max() / R - x_turn) * R:.4g} mm from its "
                         f"loading), beyond the supported {bound * R:.4g} mm for this shell "
                         f"(delta/R <= {bound:g})")


def _gamma_max(jkr, C10) -> float:
    """gamma / (C10 R) the paths serve: GAMMA_MARGIN x JKR's gamma over the loading's C10
    (a shell pulls off at a smaller force than JKR's, so its gamma is larger), on the
    ladder."""
    gR = jkr[2] * jkr[0]            # gamma / R of the half-space fit
    gh = gR / C10 if np.isfinite(gR) and gR > 0 and C10 > 0 else 1e-3
    return gamma_bucket(min(GAMMA_MAX, GAMMA_MARGIN * gh))


def plot_fit(result: FitResult, path) -> Path:
    """A figure of the data, the fitted curves (this fit and the half-space one) and the
    residuals, written to `path` (its suffix picks the format)."""
    from matplotlib.figure import Figure

    inp, R = result.input, result.input.R_mm
    model = result.model_P_N()
    C10_j, x0_j, _ = result.jkr
    fig = Figure(figsize=(7, 6.5), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True, height_ratios=(3, 1))
    top.plot(inp.delta_mm, inp.P_N, ".", color="0.5", label="data")
    top.plot(inp.delta_mm, model, "-", color="C0",
             label=f"shell fit: C10 = {result.C10_MPa:.4g} MPa, "
                   f"gamma = {result.gamma_J_m2:.4g} J/m$^2$")
    dl = inp.delta_mm[result.estimate.split.loading]
    top.plot(dl, solver_fit.hertz_p(C10_j, dl / R - x0_j) * R ** 2, "--", color="C3",
             label=f"half-space Hertz loading: E = {youngs_modulus_MPa(C10_j):.4g} MPa")
    top.axhline(0.0, color="k", lw=0.5)
    top.set_ylabel("P [N] (> 0 compression)")
    top.legend(fontsize=8)
    bottom.plot(inp.delta_mm, inp.P_N - model, ".", color="C0")
    bottom.axhline(0.0, color="k", lw=0.5)
    bottom.set_xlabel("delta [mm] (> 0 approach)")
    bottom.set_ylabel("residual [N]")
    path = Path(path)
    fig.savefig(path, dpi=150)
    return path
