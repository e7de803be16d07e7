"""Analysis of a results cube: values along the sweeps, the eta fit of eq. 3, the slope in
gamma, the JKR ratio, trend verdicts and the comparison with the paper (DESIGN.md section 4).

Reads a Dataset written by `study.dataset` and never runs the finite-element solver.
Units as in the cube: lengths mm, forces N, C10 MPa, gamma J/m^2; slopes d|P*|/dgamma in
m (N per J/m^2).  P < 0 is tension, so pull-off forces are compared by magnitude |P*|.
Intervals are 95 % (two-sided, Student t).
"""
from dataclasses import dataclass
import math
from pathlib import Path

import numpy as np
import xarray as xr
from scipy import stats
from scipy.interpolate import CubicHermiteSpline, CubicSpline

from shell_adhesion.errors import InputError
from shell_adhesion.solver.theory import jkr_P_star_N, shell_law_scale_N

from .dataset import DIMS, base_attr, study_of


# relative uncertainty of P* from the mesh: the measured change of P* is 0.32 % from coarse
# to default and 0.18 % from default to fine (README; test_convergence.py's limit is 0.5 %);
# each value is about three times the measured change to the next finer mesh
MESH_UNCERTAINTY = {"coarse": 0.01, "default": 0.005, "fine": 0.0025, "finer": 0.0025}

# the paper's statements about Fig. 6 (DESIGN.md section 4): |P*| grows with C10 and t/R,
# is roughly independent of h/R and linear in gamma
PAPER_TRENDS = {"C10": "increasing", "t_over_R": "increasing", "h_over_R": "flat",
                "gamma": "increasing"}

# exponents of eq. 3: |P*| = eta gamma^(4/3) R^(4/3) (1 - nu^2)^(1/3) E^(-1/3) t^(-2/3)
EQ3_EXPONENTS = {"gamma": 4 / 3, "C10": -1 / 3, "t_mm": -2 / 3, "h_mm": 0.0}

# the paper's base shell and its numbers (DESIGN.md section 4)
PAPER_SHELL = {"R_mm": 20.0, "C10": 0.3, "t_over_R": 0.15, "h_over_R": 1.0, "gamma": 30.0}

_REQUIRED = ("P_star", "status", "eta")
_UNITS_TEXT = {"1": ""}


class NotACube(InputError):
    """A file that cannot be read as a shell-adhesion results cube (bad input: exit 2)."""


def open_results(path) -> xr.Dataset:
    """The results cube at `path`, loaded into memory; NotACube names the file otherwise."""
    path = Path(path)
    if not path.is_file():
        raise NotACube(f"{path}: " + ("not a file" if path.exists() else "no such file"))
    try:
        with xr.open_dataset(path) as ds:
            ds = ds.load()
    except Exception as e:        # netCDF4, h5netcdf and the engine guess raise many kinds
        raise NotACube(f"{path}: cannot be read as netCDF ({type(e).__name__})") from None
    try:
        check_cube(ds)
    except NotACube as e:
        raise NotACube(f"{path}: {e}") from None
    return ds


def check_cube(ds: xr.Dataset) -> None:
    """Raise NotACube unless `ds` has the cube's dimensions, variables and study record
    (R_mm and the base values as numbers)."""
    missing = [d for d in DIMS if d not in ds.dims] + [v for v in _REQUIRED if v not in ds]
    if missing:
        raise NotACube("not a shell-adhesion results cube (missing " + ", ".join(missing) + ")")
    try:
        [float(ds.attrs[a]) for a in ("R_mm", *(base_attr(d) for d in DIMS
                                               if base_attr(d) in ds.attrs))]
    except (KeyError, TypeError, ValueError):
        raise NotACube("not a shell-adhesion results cube (no study record: R_mm and "
                       "base_* attributes)") from None


def base_point(ds: xr.Dataset) -> dict:
    """The study's base values by dimension name: C10 [MPa], t_over_R, h_over_R, gamma [J/m^2].

    A factor the study's base leaves out (a grid-only factor) takes the middle value of
    its axis."""
    return {d: float(ds.attrs[base_attr(d)]) if base_attr(d) in ds.attrs
            else float(ds[d].values[(ds.sizes[d] - 1) // 2]) for d in DIMS}


def R_mm(ds: xr.Dataset) -> float:
    """Outer radius of curvature R of the study, mm."""
    return float(ds["R"]) if "R" in ds.coords else float(ds.attrs["R_mm"])


def mesh_uncertainty(ds: xr.Dataset) -> float:
    """Relative mesh uncertainty of P* for the cube's mesh (the coarse value if unknown)."""
    return MESH_UNCERTAINTY.get(ds.attrs.get("mesh"), max(MESH_UNCERTAINTY.values()))


def _select(x, **at):
    """`x` at the given coordinate values (nearest within a relative 1e-9)."""
    for d, v in at.items():
        x = x.sel({d: v}, method="nearest", tolerance=1e-9 * max(1.0, abs(v)))
    return x


def along(ds: xr.Dataset, var: str, dim: str, **at) -> xr.DataArray:
    """`var` along `dim` with the other dimensions at the base point (or at `at`), keeping
    only points with status "ok" and a finite value."""
    point = {**base_point(ds), **at}
    point.pop(dim)
    sel = {d: v for d, v in point.items() if d in ds[var].dims}
    x = _select(ds[var].where(ds["status"] == "ok"), **sel)
    return x.dropna(dim)


def ok_cases(ds: xr.Dataset, where=None) -> xr.Dataset:
    """The points with status "ok" (and `where`, a boolean DataArray over the cube's
    dimensions, if given) as one Dataset along ``case``, labelled by C10, t_over_R,
    h_over_R, gamma, t_mm and h_mm; only variables on exactly the cube's dimensions."""
    dims = ds["status"].dims        # DIMS, and any swept material ratio (C01_over_C10, ...)
    names = [v for v in ds.data_vars if set(ds[v].dims) == set(dims)]
    mask = ds["status"] == "ok"
    if where is not None:
        mask = mask & where
    flat = ds[names].stack(case=dims)
    keep = np.flatnonzero(mask.broadcast_like(ds["status"]).stack(case=dims).values)
    return flat.isel(case=keep).reset_index("case")


# ---------------------------------------------------------------------------------------
# eta of eq. 3

@dataclass(frozen=True)
class EtaFit:
    """Least-squares eta of eq. 3 (exponents fixed) in log space.

    eta [1], ci (low, high) its 95 % interval, n the number of cases, residuals
    log|P*| - log(eta S) per case, rms their root mean square (about the relative scatter).
    """
    eta: float
    ci: tuple
    n: int
    residuals: xr.DataArray
    rms: float


def fit_log_constant(y):
    """Mean of `y` with its 95 % interval (NaN for fewer than two values)."""
    y = np.asarray(y, dtype=float)
    n = len(y)
    if n == 0:
        raise ValueError("no cases to fit")
    m = float(y.mean())
    if n < 2:
        return m, (math.nan, math.nan)
    half = stats.t.ppf(0.975, n - 1) * y.std(ddof=1) / math.sqrt(n)
    return m, (m - half, m + half)


def eta_fit(ds: xr.Dataset, where=None) -> EtaFit:
    """Fit log|P*| = log eta + log S over the ok points (and `where`), with S the scale
    [gamma^4 R^4 (1 - nu^2) / (E t^2)]^(1/3) of eq. 3 in N."""
    c = ok_cases(ds, where)
    S = shell_law_scale_N(R_mm(ds), c["t_mm"].values, c["C10"].values, c["gamma"].values)
    y = np.log(np.abs(c["P_star"].values)) - np.log(S)
    log_eta, (lo, hi) = fit_log_constant(y)
    r = y - log_eta
    residuals = xr.DataArray(r, dims="case", coords=c["P_star"].coords, name="log_residual",
                             attrs=dict(units="1", long_name="log|P*| - log(eta S) of eq. 3"))
    return EtaFit(math.exp(log_eta), (math.exp(lo), math.exp(hi)), len(r), residuals,
                  float(np.sqrt(np.mean(r ** 2))))


@dataclass(frozen=True)
class PowerLaw:
    """Free power law log|P*| = c + sum_k p_k log x_k over the factors that vary.

    exponents: factor -> (p, (low, high)); expected: factor -> exponent of eq. 3;
    disagrees: factors whose eq. 3 exponent lies outside the interval; n cases, rms of
    the log residuals.  Factors: gamma [J/m^2], C10 [MPa], t_mm, h_mm (eq. 3: 0).
    """
    exponents: dict
    expected: dict
    disagrees: tuple
    n: int
    rms: float


def power_law_fit(ds: xr.Dataset, where=None) -> PowerLaw:
    """Least squares of log|P*| against log gamma, log C10, log t and log h, each factor
    included only if the cases span at least two of its values."""
    c = ok_cases(ds, where)
    factors = [f for f in EQ3_EXPONENTS if len(np.unique(c[f].values)) >= 2]
    y = np.log(np.abs(c["P_star"].values))
    X = np.column_stack([np.ones_like(y)] + [np.log(c[f].values) for f in factors])
    n, p = X.shape
    coef, *_ = np.linalg.lstsq(X, y, rcond=None)
    r = y - X @ coef
    dof = n - p
    if dof > 0 and np.linalg.matrix_rank(X) == p:
        cov = (r @ r / dof) * np.linalg.inv(X.T @ X)
        half = stats.t.ppf(0.975, dof) * np.sqrt(np.diag(cov))
    else:
        half = np.full(p, np.nan)
    exps = {f: (float(coef[k + 1]), (float(coef[k + 1] - half[k + 1]),
                                     float(coef[k + 1] + half[k + 1])))
            for k, f in enumerate(factors)}
    # NaN interval: never "disagrees"; 1e-9: round-off of an exact power law
    bad = tuple(f for f, (_, (lo, hi)) in exps.items()
                if not lo - 1e-9 <= EQ3_EXPONENTS[f] <= hi + 1e-9)
    return PowerLaw(exps, {f: EQ3_EXPONENTS[f] for f in factors}, bad, n,
                    float(np.sqrt(np.mean(r ** 2))))


# ---------------------------------------------------------------------------------------
# slope in gamma and the JKR ratio

@dataclass(frozen=True)
class GammaSlope:
    """Slope of |P*| against gamma by linear regression, in m (N per J/m^2).

    slope with its 95 % interval ci (NaN for two points), intercept [N], n points,
    jkr = 1.5 pi R the JKR slope [m], gamma [J/m^2] and abs_P [N] the data, local the
    slopes between neighbours [m] (constant if |P*| is linear in gamma).
    """
    slope: float
    ci: tuple
    intercept: float
    n: int
    jkr: float
    gamma: np.ndarray
    abs_P: np.ndarray
    local: np.ndarray

    @property
    def ratio_to_jkr(self) -> float:
        return self.slope / self.jkr


def fit_line(x, y):
    """Slope, its 95 % interval and intercept of y against x (interval NaN for n = 2)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    if len(x) < 2:
        raise ValueError("a slope needs at least two points")
    fit = stats.linregress(x, y)
    if len(x) > 2:
        half = stats.t.ppf(0.975, len(x) - 2) * fit.stderr
        ci = (float(fit.slope - half), float(fit.slope + half))
    else:
        ci = (math.nan, math.nan)
    return float(fit.slope), ci, float(fit.intercept)


def gamma_slope(ds: xr.Dataset, **at) -> GammaSlope:
    """d|P*|/dgamma along gamma at the base point (or at `at`, e.g. C10=0.5), in m."""
    P = along(ds, "P_star", "gamma", **at)
    g, absP = P["gamma"].values, np.abs(P.values)
    slope, ci, intercept = fit_line(g, absP)
    return GammaSlope(slope, ci, intercept, len(g), -jkr_P_star_N(R_mm(ds), 1.0), g, absP,
                      np.diff(absP) / np.diff(g))


def jkr_ratio(ds: xr.Dataset) -> xr.DataArray:
    """P* / (-1.5 pi R gamma), the pull-off force over that of JKR's solid sphere [1]."""
    ratio = ds["P_star"] / (-1.5 * math.pi * R_mm(ds) * ds["gamma"] * 1e-3)
    return ratio.rename("jkr_ratio").assign_attrs(
        units="1", long_name="P* / (-1.5 pi R gamma), pull-off over JKR")


# ---------------------------------------------------------------------------------------
# trends

def trend_of(values, uncertainty: float, errors=None) -> str:
    """Verdict on a series of magnitudes: "increasing", "decreasing", "non-monotonic" or
    "flat".  A step counts only if it exceeds the combined error of its two ends, the sum
    of their error bars (`errors`, absolute; where one is missing, uncertainty * |value|);
    if no step counts but the whole change first -> last does, its sign decides."""
    v = np.abs(np.asarray(values, dtype=float))
    if len(v) < 2:
        raise ValueError("a trend needs at least two values")
    e = uncertainty * v
    if errors is not None:
        given = np.abs(np.asarray(errors, dtype=float))
        e = np.where(np.isfinite(given), given, e)
    steps = np.diff(v)
    real = np.abs(steps) > e[1:] + e[:-1]
    signs = set(np.sign(steps[real]))
    if not signs:
        total = v[-1] - v[0]
        if abs(total) <= e[-1] + e[0]:
            return "flat"
        signs = {np.sign(total)}
    if len(signs) > 1:
        return "non-monotonic"
    return "increasing" if signs.pop() > 0 else "decreasing"


@dataclass(frozen=True)
class Trend:
    """Verdict on |var| along a swept dimension at the base point.

    coords the dimension's values, values |var| there, change (last - first) / first,
    uncertainty the relative mesh uncertainty used, claim the paper's verdict (None if it
    makes none), agrees whether ours matches it (None without a claim), sentence one line
    with numbers and units.
    """
    dim: str
    var: str
    verdict: str
    coords: np.ndarray
    values: np.ndarray
    change: float
    uncertainty: float
    claim: object
    agrees: object
    sentence: str


def _unit(x: xr.DataArray) -> str:
    u = x.attrs.get("units", "")
    return _UNITS_TEXT.get(u, u)


def _with_unit(value, unit):
    return f"{value:.4g} {unit}" if unit else f"{value:.4g}"


def trend(ds: xr.Dataset, dim: str, var: str = "P_star") -> Trend:
    """Verdict on abs(`var`) along `dim` (other dimensions at the base), with the mesh
    uncertainty of `mesh_uncertainty` on each value, and the paper's claim for P*."""
    x = along(ds, var, dim)
    u = mesh_uncertainty(ds)
    coords, values = x[dim].values, np.abs(x.values)
    errors = (along(ds, f"{var}_error", dim).reindex({dim: x[dim]}).values
              if f"{var}_error" in ds else None)
    verdict = trend_of(values, u, errors)
    change = float((values[-1] - values[0]) / values[0])
    claim = PAPER_TRENDS.get(dim) if var == "P_star" else None
    agrees = None if claim is None else verdict == claim
    name = {"P_star": "|P*|"}.get(var, f"|{var}|")
    vu, du = _unit(ds[var]), _unit(ds[dim])
    pts = ", ".join(f"{_with_unit(v, vu)} at {c:g}" for c, v in zip(coords, values))
    if errors is not None and np.isfinite(errors).all():
        pts = ", ".join(f"{_with_unit(v, vu)} +- {e:.2g} at {c:g}"
                        for c, v, e in zip(coords, values, errors))
        basis = "a step counts beyond the sum of its two error bars"
    else:
        basis = f"mesh uncertainty {u:.1%} per value"
    sentence = (f"{name} {verdict} along {dim}{f' [{du}]' if du else ''}: {pts} "
                f"({change:+.2%} in all; {basis})")
    if claim is not None:
        sentence += f"; paper: {claim} ({'agrees' if agrees else 'DISAGREES'})"
    return Trend(dim, var, verdict, coords, values, change, u, claim, agrees, sentence)


def trends(ds: xr.Dataset, var: str = "P_star") -> list:
    """`trend` along every dimension with at least two ok values at the base point."""
    return [trend(ds, d, var) for d in DIMS if along(ds, var, d).size >= 2]


# ---------------------------------------------------------------------------------------
# the paper's numbers

@dataclass(frozen=True)
class Row:
    """One line of the comparison with the paper; difference = ours / paper - 1 in %."""
    quantity: str
    paper: object
    ours: object
    unit: str
    difference_pct: object
    note: str = ""


@dataclass(frozen=True)
class Comparison:
    """Rows the cube can answer, and the quantities it cannot (with the reason)."""
    rows: tuple
    skipped: tuple


def is_paper_shell(ds: xr.Dataset) -> bool:
    """Whether the study's base is the paper's shell (R = 20 mm, t/R = 0.15, h/R = 1,
    C10 = 0.3 MPa, gamma = 30 J/m^2)."""
    base = base_point(ds)
    return (math.isclose(R_mm(ds), PAPER_SHELL["R_mm"])
            and all(math.isclose(base[d], PAPER_SHELL[d]) for d in DIMS))


def _pct(ours, paper):
    return 100.0 * (ours / paper - 1.0)


def _row(quantity, paper, ours, unit, note=""):
    return Row(quantity, paper, float(ours), unit, _pct(float(ours), paper), note)


def _value(ds, var, **at):
    """A pull-off value at a point (the base completed by `at`); NaN unless status ok."""
    point = {**base_point(ds), **at}
    try:
        x = _select(ds[var].where(ds["status"] == "ok"), **point)
    except KeyError:
        return math.nan
    return float(x)


def _curve(ds, point):
    """The base point's equilibrium curve as (a, delta, P) arrays, mm and N, or None."""
    if not all(v in ds for v in ("a_eq_mm", "delta_eq", "P_eq")):
        return None
    a, d, P = (_select(ds[v], **point).values for v in ("a_eq_mm", "delta_eq", "P_eq"))
    ok = np.isfinite(a) & np.isfinite(d) & np.isfinite(P)
    return (a[ok], d[ok], P[ok]) if ok.sum() >= 4 else None


def _loading_at(ds, point, delta_mm):
    """(P [N], a [mm], node spacing [mm]) at delta on the base shell's loading curve, or
    None if not reached; a is interpolated between the contact events around delta (where
    nodes join)."""
    if not all(v in ds for v in ("loading_delta_mm", "loading_a", "loading_P")):
        return None
    shell = {d: point[d] for d in ("t_over_R", "h_over_R")}
    d = _select(ds["loading_delta_mm"], **shell).values
    a = _select(ds["loading_a"], **shell).values
    P = _select(ds["loading_P"], C10=point["C10"], **shell).values
    ok = np.isfinite(d) & np.isfinite(P) & np.isfinite(a)
    d, a, P = d[ok], a[ok], P[ok]
    if len(d) < 2 or d.max() < delta_mm * (1 - 1e-9):
        return None
    # P: the states are dense, linear between them; a: between the contact events (the
    # states where a node joins), the contact radius grows between nodes; beyond the last
    # event, the outermost node in contact (the next touches further on)
    event = np.r_[True, np.diff(a) > 0]
    spacing = float(np.diff(a[event])[-1]) if event.sum() >= 2 else np.nan
    return (float(np.interp(delta_mm, d, P)), float(np.interp(delta_mm, d[event], a[event])),
            spacing)


def _held_P_at_zero(ds, point, a_mm):
    """(P [N], note) at delta = 0 with the contact radius a held (relaxation curves, Fig.
    2b), interpolated linearly in a between the two neighbouring paths (or extrapolated up
    to one path spacing beyond the widest, the note says so); else why not (str)."""
    if not all(v in ds for v in ("relaxation_a_mm", "relaxation_delta_mm", "relaxation_P")):
        return "no relaxation curves"
    shell = {d: point[d] for d in ("t_over_R", "h_over_R")}
    a = _select(ds["relaxation_a_mm"], **shell).values
    D = _select(ds["relaxation_delta_mm"], **shell).values
    P = _select(ds["relaxation_P"], C10=point["C10"], **shell).values
    K = (_select(ds["relaxation_dP_ddelta"], C10=point["C10"], **shell).values
         if "relaxation_dP_ddelta" in ds else np.full_like(P, np.nan))
    # paths the energy method left out (the centre lifts, a free node touches) hold no clean
    # contact zone
    used = (_select(ds["relaxation_used"], **shell).values == 1 if "relaxation_used" in ds
            else np.ones(len(a), bool))
    a0, P0 = [], []
    for k in range(len(a)):
        ok = np.isfinite(D[k]) & np.isfinite(P[k])
        d, p, s = D[k][ok], P[k][ok], K[k][ok]
        if not (used[k] and np.isfinite(a[k])) or len(d) < 2 or not d.min() <= 0 <= d.max():
            continue
        o = np.argsort(d)
        d, p, s = d[o], p[o], s[o]
        a0.append(a[k])
        if np.all(np.isfinite(s)):      # the states' stiffness: cubic Hermite in delta
            P0.append(float(CubicHermiteSpline(d, p, s)(0.0)))
        else:
            P0.append(float(CubicSpline(d, p)(0.0)) if len(d) >= 4 else float(np.interp(0, d, p)))
    o = np.argsort(a0)
    a0, P0 = np.array(a0)[o], np.array(P0)[o]
    # a held radius up to one path spacing beyond the widest path: the cubic through the
    # last four paths, extrapolated (P(delta = 0) is smooth in a)
    reach = a0[-1] + (a0[-1] - a0[-2]) if len(a0) >= 4 else (a0[-1] if len(a0) else np.nan)
    if len(a0) < 2 or not a0[0] <= a_mm <= reach:
        span = f"{a0[0]:.4g} to {a0[-1]:.4g} mm" if len(a0) else "none"
        return f"held radii of the paths reaching delta = 0: {span}"
    if a_mm > a0[-1]:
        return float(np.polyval(np.polyfit(a0[-4:], P0[-4:], 3), a_mm)), (
            f"extrapolated {a_mm - a0[-1]:.2g} mm beyond the widest path ({a0[-1]:.4g} mm) "
            "by the cubic through the last four")
    return float(np.interp(a_mm, a0, P0)), ""


def paper_comparison(ds: xr.Dataset) -> Comparison:
    """Our numbers beside the paper's (base shell, Fig. 6) for what the cube can answer.

    Only for a study whose base is the paper's shell; otherwise no rows.  The paper's a*,
    delta*, P_dagger and a_dagger are node values on a flat curve, so its (a, delta, P)
    points are checked on our equilibrium curve (cubic spline in a) and our extrema are
    reported beside them.
    """
    if not is_paper_shell(ds):
        return Comparison((), ("all: the study's base is not the paper's shell (R = 20 mm, "
                               "t/R = 0.15, h/R = 1, C10 = 0.3 MPa, gamma = 30 J/m^2)",))
    base = base_point(ds)
    rows, skipped = [], []
    P_star = _value(ds, "P_star")
    if not math.isfinite(P_star):
        return Comparison((), ("all: the base point has no ok result",))
    rows.append(_row("P* (fixed load), gamma = 30 J/m^2", -1.70, P_star, "N"))
    rows.append(_row("delta_dagger (fixed grips)", -0.685, _value(ds, "delta_dagger"), "mm"))

    curve = _curve(ds, base)
    if curve is None:
        skipped.append("paper's points on our equilibrium curve: no equilibrium curves")
    else:
        a, d, P = curve
        for a_p, d_p, P_p, which in ((2.13, -0.563, -1.70, "fixed-load point"),
                                     (1.598, -0.685, -1.640, "fixed-grips point")):
            if not a.min() <= a_p <= a.max():
                skipped.append(f"our curve at a = {a_p} mm: outside the curve")
                continue
            note = f"paper's {which} (a = {a_p} mm) on our curve"
            rows.append(_row(f"delta on our curve at a = {a_p} mm", d_p,
                             CubicSpline(a, d)(a_p), "mm", note))
            rows.append(_row(f"P on our curve at a = {a_p} mm", P_p,
                             CubicSpline(a, P)(a_p), "N", note))
    flat = "paper: a node value; the curve is flat there"
    rows.append(_row("a* (extremum of our curve)", 2.13, _value(ds, "a_star"), "mm", flat))
    rows.append(_row("delta* (extremum of our curve)", -0.563, _value(ds, "delta_star"), "mm", flat))
    rows.append(_row("P_dagger (extremum of our curve)", -1.640, _value(ds, "P_dagger"), "N", flat))
    rows.append(_row("a_dagger (extremum of our curve)", 1.598, _value(ds, "a_dagger"), "mm", flat))

    loaded = _loading_at(ds, base, 5.0)
    if loaded is None:
        skipped.append("P and a at delta = 5 mm (Fig. 2a): the loading curve stops before 5 mm"
                       if "loading_delta_mm" in ds else
                       "P and a at delta = 5 mm (Fig. 2a): no loading curves")
    else:
        rows.append(_row("P at delta = 5 mm, no adhesion", 14.67, loaded[0], "N",
                         "loading curve, linear between states"))
        rows.append(_row("a at delta = 5 mm, no adhesion", 10.0, loaded[1], "mm",
                         f"between contact events, else the outermost node in contact "
                         f"(nodes {loaded[2]:.2g} mm apart there)"))

    held = _held_P_at_zero(ds, base, 10.0)
    if isinstance(held, str):
        skipped.append(f"P at delta = 0 with a = 10 mm held (Fig. 2b): {held}")
    else:
        P10, how = held
        rows.append(_row("P at delta = 0, a = 10 mm held", -35.49, P10, "N",
                         "; ".join(w for w in ("steep in a: about 13 N per mm of a", how) if w)))

    a_thick = _value(ds, "a_star", t_over_R=0.225)
    if math.isfinite(a_thick):
        rows.append(_row("a* at t/R = 0.225 (t = 4.5 mm)", 2.265, a_thick, "mm", flat))
    else:
        skipped.append("a* at t/R = 0.225: not in the cube")

    if along(ds, "P_star", "gamma").size >= 2:
        s = gamma_slope(ds)
        ci = (f"95 % interval {s.ci[0]:.4g} to {s.ci[1]:.4g} m, " if math.isfinite(s.ci[0])
              else "")
        rows.append(_row("slope d|P*|/dgamma", 0.050, s.slope, "m",
                         f"{ci}{s.n} values of gamma; JKR 1.5 pi R = {s.jkr:.4g} m"))
    else:
        skipped.append("slope d|P*|/dgamma: fewer than two gammas at the base")

    shells = ds["t_over_R"] < 1
    if int(((ds["status"] == "ok") & shells).sum()) >= 1:
        fit = eta_fit(ds, where=shells)
        e = ok_cases(ds, shells)["eta"].values
        inside = 7 <= fit.eta <= 11
        rows.append(Row("eta of eq. 3 (fit over the shells)", "7 to 11", fit.eta, "1", None,
                        f"{fit.n} cases, range {e.min():.3g} to {e.max():.3g}; "
                        + ("inside" if inside else "outside") + " the paper's range"))

    solid = _value(ds, "P_star", t_over_R=1.0)
    if math.isfinite(solid):
        gamma = base["gamma"]
        rows.append(_row("P*, solid hemisphere t/R = 1", jkr_P_star_N(R_mm(ds), gamma), solid,
                         "N", "paper: JKR, -1.5 pi R gamma"))
    else:
        skipped.append("solid hemisphere t/R = 1 against JKR: not in the cube")
    return Comparison(tuple(rows), tuple(skipped))


# ---------------------------------------------------------------------------------------

def summary(ds: xr.Dataset) -> str:
    """A few lines: trends of abs(P*), the eta fit, the slope in gamma, the JKR ratio."""
    s = study_of(ds)
    base = base_point(ds)
    lines = [f"study {s.get('name', '?')}: R = {R_mm(ds):g} mm, mesh {ds.attrs.get('mesh', '?')}, "
             f"interface {ds.attrs.get('interface', '?')}; base C10 = {base['C10']:g} MPa, "
             f"t/R = {base['t_over_R']:g}, h/R = {base['h_over_R']:g}, "
             f"gamma = {base['gamma']:g} J/m^2; {int((ds['status'] == 'ok').sum())} ok points"]
    for t in trends(ds):
        lines.append("trend: " + t.sentence)
    shells = ds["t_over_R"] < 1
    if int(((ds["status"] == "ok") & shells).sum()):
        f = eta_fit(ds, where=shells)
        ci = f"(95 %: {f.ci[0]:.3g} to {f.ci[1]:.3g})" if math.isfinite(f.ci[0]) else ""
        lines.append(f"eta of eq. 3 over {f.n} shell cases: {f.eta:.3g} {ci}, rms of log "
                     f"residuals {f.rms:.3f}")
        pl = power_law_fit(ds, where=shells)
        if pl.exponents:
            parts = [f"{k} {p:+.3f}" + (f" [{lo:+.3f}, {hi:+.3f}]" if math.isfinite(lo) else "")
                     + f" (eq. 3: {pl.expected[k]:+.3f})" for k, (p, (lo, hi)) in pl.exponents.items()]
            lines.append("free power law of |P*|: " + "; ".join(parts)
                         + (f"; eq. 3 outside the interval for {', '.join(pl.disagrees)}"
                            if pl.disagrees else ""))
    if along(ds, "P_star", "gamma").size >= 2:
        g = gamma_slope(ds)
        ci = f" (95 %: {g.ci[0]:.4g} to {g.ci[1]:.4g})" if math.isfinite(g.ci[0]) else ""
        lines.append(f"slope d|P*|/dgamma at the base: {g.slope:.4g} m{ci}, "
                     f"{g.ratio_to_jkr:.3f} of JKR's 1.5 pi R = {g.jkr:.4g} m; local slopes "
                     + ", ".join(f"{x:.4g}" for x in g.local) + " m")
    r = jkr_ratio(ds).where(ds["status"] == "ok")
    if int(r.notnull().sum()):
        at_base = _value(ds, "P_star") / jkr_P_star_N(R_mm(ds), base["gamma"])
        lines.append(f"P* / JKR (-1.5 pi R gamma): {float(r.min()):.3f} to {float(r.max()):.3f}"
                     + (f", {at_base:.3f} at the base" if math.isfinite(at_base) else ""))
    return "\n".join(lines)
