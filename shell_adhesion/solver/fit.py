"""Fitting C10, gamma and the contact offset of one shell to a measured force-displacement
curve (approach, then retraction, under displacement control).

Dimensionless (DESIGN.md section 3): x = delta / R, p = P / R^2, so that p = C10 F(x) and C10
comes out in the unit of P / R^2 (MPa for N and mm); gamma_hat = gamma / (C10 R); x0 =
delta0 / R, the contact offset (measured delta = model delta + delta0).  P > 0 compression,
delta > 0 approach.

The model of the test, from one PathSet (any C10 and gamma):
- loading: p = C10 F_load(x - x0), the FE loading curve (no adhesion while the contact grows,
  as in Maugis' method); 0 before contact;
- retraction from the turning point: no node joins after the turn, so the contact held is the
  one of the deepest state; P goes back down the loading curve to where that contact radius
  was reached, then along its relaxation path (cubic Hermite in delta) down to where the
  path meets the fixed-grips equilibrium curve G = gamma; then along that curve (the contact
  shrinking) to the fixed-grips pull-off delta_dagger, where the shell jumps off.  Points
  after the jump (detached) are not used.

Confidence intervals are linearised at the optimum: cov = s^2 (J^T J)^-1 from the
least-squares Jacobian J and s^2 = sum(r^2) / (m - n), with Student's t at 97.5 %.  They hold
for independent noise of one variance and do not include the model's own (mesh) error.
Pure functions (no files, no printing).
"""
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import CubicHermiteSpline
from scipy.optimize import brentq, least_squares
from scipy.stats import t as student_t

from .case import PathSet, Relaxation
from shell_adhesion.energy import OutOfRange, equilibrium, pull_off
from shell_adhesion.errors import InputError
from shell_adhesion.theory import hertz_P_N, jkr_P_star_N

MIN_LOADING_POINTS = 5
JUMP_SHARE = 0.5        # a rise of P by this share of |min P| between two retraction points is the jump-off


class FitError(ValueError):
    """The data cannot be fitted by these paths (e.g. deeper than the paths were loaded)."""


class TooDeep(FitError):
    """The curve goes deeper (from contact) than the paths were loaded."""

    def __init__(self, text, x_turn):
        super().__init__(text)
        self.x_turn = x_turn


@dataclass(frozen=True)
class Split:
    """The measured curve cut into its parts: indices of the loading points (to the deepest
    delta), of the retraction points used (before the jump-off) and of the points after it."""

    loading: np.ndarray
    retraction: np.ndarray
    detached: np.ndarray


def split_curve(x, p) -> Split:
    """Loading up to the (first) deepest point; retraction after it, up to the largest rise
    of P if that rise is a jump-off (at least JUMP_SHARE of |min P| from a tensile P)."""
    x, p = np.asarray(x, float), np.asarray(p, float)
    turn = int(np.argmax(x))
    idx = np.arange(len(x))
    ret = idx[turn + 1:]
    detached = idx[:0]
    if len(ret) >= 2:
        rise = np.diff(p[turn:])
        j = int(np.argmax(rise))
        low = float(np.min(p[turn:]))
        if low < 0 and rise[j] >= JUMP_SHARE * abs(low):
            detached = ret[j:]
            ret = ret[:j]
    return Split(idx[:turn + 1], ret, detached)


def loading_F(ps: PathSet, x):
    """F_load(x) = P / (C10 R^2) on the loading curve; 0 before contact, linear beyond the
    paths' deepest state (a FitError is raised later if the data needs it)."""
    d, P = ps.loading_delta, ps.loading_P
    x = np.asarray(x, float)
    out = np.interp(x, d, P, left=0.0)
    slope = (P[-1] - P[-2]) / (d[-1] - d[-2])
    deep = x > d[-1]
    out[deep] = P[-1] + slope * (x[deep] - d[-1])
    return out


def turn_path(ps: PathSet, x_turn: float) -> Relaxation:
    """The relaxation path of the contact held at the turn x_turn = delta / R: the last
    usable path whose loaded state lies at or before the turn."""
    paths = [r for r in ps.usable() if r.delta[0] <= x_turn * (1 + 1e-12)]
    if not paths:
        raise FitError(f"the turn at delta/R = {x_turn:.4g} lies before the first contact "
                       "radius of the paths")
    return paths[-1]


def gamma_range(ps: PathSet) -> tuple:
    """(lowest, highest) gamma / (C10 R) of the ladder gamma_max x 10^(-k/4), k = 0..12,
    whose pull-off the paths give (smaller gammas pull off between the first nodes, larger
    ones may need paths beyond the loading's end)."""
    ok = []
    for k in range(13):
        g = ps.gamma_max * 10 ** (-k / 4)
        try:
            gamma_curve(ps, g)
            ok.append(g)
        except OutOfRange:
            continue
    if not ok:
        raise FitError(f"the paths give no pull-off up to gamma/(C10 R) = {ps.gamma_max:g}")
    return min(ok), max(ok)


def gamma_curve(ps: PathSet, gamma_hat: float):
    """(Equilibrium, PullOff) for gamma / (C10 R); where the set cannot vouch for the
    pull-off (solver.case.PathSet.pull_off) the plain energy method's curve is used."""
    try:
        return ps.pull_off(gamma_hat)
    except OutOfRange:
        eq = equilibrium(ps.surface(), gamma_hat)
        return eq, pull_off(eq)


@dataclass(frozen=True, eq=False)
class Retraction:
    """F(x) = P / (C10 R^2) of a displacement-controlled retraction for one gamma and turn
    path: loading above x_rel, the relaxation down to x_eq, the equilibrium curve below."""

    x_rel: float               # where the held contact radius was reached on loading
    x_eq: float                # where the relaxation meets the equilibrium curve
    relaxation: CubicHermiteSpline
    eq_x: np.ndarray           # the equilibrium curve below x_eq, increasing delta
    eq_F: np.ndarray
    x_dagger: float
    F_dagger: float
    loading: PathSet = field(repr=False)

    def __call__(self, x):
        x = np.asarray(x, float)
        out = np.interp(x, self.eq_x, self.eq_F)
        held = x >= self.x_eq
        out[held] = self.relaxation(np.maximum(x[held], self.relaxation.x[0]))
        back = x >= self.x_rel
        out[back] = loading_F(self.loading, x[back])
        return out


def retraction(ps: PathSet, path: Relaxation, gamma_hat: float) -> Retraction:
    """The retraction model (see the module docstring) for gamma / (C10 R) and the held
    contact of `path`."""
    eq, po = gamma_curve(ps, gamma_hat)
    below = np.flatnonzero(eq.a < path.a)
    if not len(below):
        raise FitError(f"gamma/(C10 R) = {gamma_hat:.4g}: no equilibrium point below the held "
                       f"contact radius a/R = {path.a:.4g}")
    top = below[np.argmax(eq.a[below])]
    a_end = po.a_dagger if np.isfinite(po.a_dagger) else po.a_star
    keep = (eq.a <= eq.a[top]) & (eq.a >= a_end)
    ex, eF = list(eq.delta[keep]), list(eq.P[keep])
    if np.isfinite(po.delta_dagger):
        ex.append(po.delta_dagger)
        eF.append(po.P_dagger)
    order = np.argsort(ex)
    ex, eF = np.asarray(ex)[order], np.asarray(eF)[order]
    spline = CubicHermiteSpline(path.delta[::-1], path.P[::-1], path.dP_ddelta[::-1])
    x_eq = float(eq.delta[top])
    return Retraction(float(path.delta[0]), x_eq, spline, ex, eF,
                      float(po.delta_dagger if np.isfinite(po.delta_dagger) else ex[0]),
                      float(po.P_dagger if np.isfinite(po.P_dagger) else eF[0]), ps)


@dataclass(frozen=True)
class Estimate:
    """A least-squares estimate: the values, their 95 % intervals, the residuals (in p)."""

    C10: float
    C10_ci: tuple
    gamma_hat: float
    gamma_ci: tuple            # of gamma_hat * C10 (gamma / R, in the unit of p times R)
    x0: float
    x0_ci: tuple
    residuals: np.ndarray
    used: dict                 # points used from each part
    gamma_from: str            # "retraction" or "pull_off"
    gamma_span: tuple = ()     # the gamma / (C10 R) the paths give (`gamma_range`)


def _ci(value, sd, dof):
    half = float(student_t.ppf(0.975, max(dof, 1)) * sd)
    return (value - half, value + half)


def _covariance(res) -> np.ndarray:
    """s^2 (J^T J)^-1 at a least-squares optimum (pseudo-inverse if singular)."""
    J, r = res.jac, res.fun
    dof = max(len(r) - J.shape[1], 1)
    return float(r @ r) / dof * np.linalg.pinv(J.T @ J)


def fit_loading(ps: PathSet, x, p, start) -> tuple:
    """(C10, x0) of the loading part of a curve alone (x = delta / R, p = P / R^2, time
    order), the search starting at start = (C10, x0)."""
    x, p = np.asarray(x, float), np.asarray(p, float)
    keep = split_curve(x, p).loading
    return tuple(_fit_loading(ps, x[keep], p[keep], *start).x)


def _fit_loading(ps: PathSet, x, p, C10_0, x0_0):
    """The least-squares fit of (C10, x0) to loading points."""
    def resid(v):
        return v[0] * loading_F(ps, x - v[1]) - p
    return least_squares(resid, [C10_0, x0_0], x_scale="jac",
                         bounds=([0.0, -np.inf], [np.inf, np.inf]))


def gamma_of_P_star(ps: PathSet, C10: float, p_star: float, span: tuple = None) -> float:
    """gamma / (C10 R) whose fixed-load pull-off C10 P* equals -|p_star| (in p), searched
    within `span` (default `gamma_range`)."""
    target = -abs(p_star) / C10

    def gap(g):
        return gamma_curve(ps, g)[1].P_star - target
    lo, hi = span or gamma_range(ps)
    if gap(hi) > 0:
        raise FitError(f"the pull-off force needs gamma/(C10 R) > {hi:g}, beyond the paths")
    if gap(lo) < 0:
        raise FitError(f"the pull-off force is weaker than the smallest gamma/(C10 R) the "
                       f"paths resolve ({lo:.3g})")
    return brentq(gap, lo, hi, xtol=1e-10, rtol=1e-10)


def fit_curve(ps: PathSet, x, p, p_pull_off=None, hertz=None) -> Estimate:
    """Fit C10, gamma / (C10 R) and x0 of one measured curve (x = delta / R, p = P / R^2,
    in time order) with the paths `ps`; `p_pull_off` (P* / R^2, a measured pull-off force)
    gives gamma through P* instead of the retraction.  `hertz` = (C10, x0) starts the search
    (default: the half-space fit, `fit_jkr`)."""
    x, p = np.asarray(x, float), np.asarray(p, float)
    parts = split_curve(x, p)
    xl, pl = x[parts.loading], p[parts.loading]
    xr, pr = x[parts.retraction], p[parts.retraction]
    if p_pull_off is None and not len(xr):
        raise FitError("no retraction points before the jump-off and no pull-off force: "
                       "gamma cannot be fitted")
    C10_0, x0_0 = hertz if hertz is not None else fit_jkr(x, p)[:2]
    load = _fit_loading(ps, xl, pl, C10_0, x0_0)
    used = dict(loading=len(xl), retraction=len(xr), after_pull_off=len(parts.detached))
    if p_pull_off is not None:
        _check_depth(ps, x.max() - load.x[1])
        return _pull_off_estimate(ps, load, p_pull_off, used)
    C10, x0 = load.x
    span = gamma_range(ps)
    g = _start_gamma(ps, C10, pr, span)
    for _ in range(3):              # the turn path follows x0; refit if it changes
        path = turn_path(ps, x.max() - x0)
        full = _fit_all(ps, path, xl, pl, xr, pr, (C10, g, x0), span)
        C10, g, x0 = full.x
        if turn_path(ps, x.max() - x0).a == path.a:
            break
    _check_depth(ps, x.max() - x0)
    cov = _covariance(full)
    dof = len(full.fun) - 3
    sd = np.sqrt(np.diag(cov))
    # gamma / R = gamma_hat C10: its variance by the delta method
    grad = np.array([g, C10, 0.0])
    sd_gR = float(np.sqrt(grad @ cov @ grad))
    return Estimate(C10, _ci(C10, sd[0], dof), g, _ci(g * C10, sd_gR, dof), x0,
                    _ci(x0, sd[2], dof), full.fun, used, "retraction", span)


def _start_gamma(ps: PathSet, C10, pr, span) -> float:
    """gamma / (C10 R) whose P* is the most tensile measured force (the search's start)."""
    low = float(np.min(pr))
    if low >= 0:
        return span[0]
    try:
        return gamma_of_P_star(ps, C10, low, span)
    except FitError:
        return float(np.sqrt(span[0] * span[1]))


def _fit_all(ps: PathSet, path: Relaxation, xl, pl, xr, pr, start, span):
    def resid(v):
        C10, g, x0 = v
        F_ret = retraction(ps, path, g)
        return np.concatenate([C10 * loading_F(ps, xl - x0) - pl, C10 * F_ret(xr - x0) - pr])
    lo = [0.0, span[0], -np.inf]
    hi = [np.inf, span[1], np.inf]
    start = np.clip(start, [1e-300, span[0], -np.inf], hi)
    return least_squares(resid, start, x_scale="jac", bounds=(lo, hi), diff_step=1e-6)


def _pull_off_estimate(ps: PathSet, load, p_star, used) -> Estimate:
    """C10 and x0 from the loading, gamma through P*; gamma's interval from C10's."""
    C10, x0 = load.x
    cov = _covariance(load)
    dof = len(load.fun) - 2
    sd = np.sqrt(np.diag(cov))
    C10_ci = _ci(C10, sd[0], dof)
    span = gamma_range(ps)
    g = gamma_of_P_star(ps, C10, p_star, span)
    ends = [gamma_of_P_star(ps, c, p_star, span) * c for c in C10_ci if c > 0]
    gR = g * C10
    gamma_ci = (min(ends + [gR]), max(ends + [gR]))
    return Estimate(C10, C10_ci, g, gamma_ci, x0, _ci(x0, sd[1], dof), load.fun,
                    dict(used, retraction=0), "pull_off", span)


def _check_depth(ps: PathSet, x_turn):
    if x_turn > ps.loading_delta[-1] * (1 + 1e-9):
        raise TooDeep(f"the curve is loaded to delta/R = {x_turn:.4g} from contact, deeper "
                      f"than the paths ({ps.loading_delta[-1]:.4g})", x_turn)


def model(ps: PathSet, C10, gamma_hat, x0, x, split: Split):
    """The fitted model at the measured points: p on the loading and on the retraction
    points used, NaN after the jump-off."""
    x = np.asarray(x, float)
    out = np.full(len(x), np.nan)
    out[split.loading] = C10 * loading_F(ps, x[split.loading] - x0)
    if len(split.retraction):
        F = retraction(ps, turn_path(ps, x.max() - x0), gamma_hat)
        out[split.retraction] = C10 * F(x[split.retraction] - x0)
    return out


def simulated_curve(ps: PathSet, C10, gamma_hat, x_turn, n_loading=40, n_retraction=40,
                    n_detached=5):
    """A displacement-controlled test as the model sees it (x = delta / R from contact, p =
    P / R^2, time order): loading to x_turn, retraction to the fixed-grips pull-off, then
    `n_detached` points of the detached shell (p = 0) below it.  For examples and tests."""
    _check_depth(ps, x_turn)
    F = retraction(ps, turn_path(ps, x_turn), gamma_hat)
    xl = np.linspace(0.0, x_turn, n_loading)
    xr = np.linspace(x_turn, F.x_dagger, n_retraction + 1)[1:]
    step = (x_turn - F.x_dagger) / n_retraction
    xd = F.x_dagger - step * np.arange(1, n_detached + 1)
    p = np.concatenate([C10 * loading_F(ps, xl), C10 * F(xr), np.zeros(n_detached)])
    return np.concatenate([xl, xr, xd]), p


def hertz_p(C10, x):
    """Hertz P / R^2 of a half-space at approach x = delta / R (theory.hertz_P_N with R = 1,
    the dimensionless form)."""
    return hertz_P_N(np.maximum(np.asarray(x, float), 0.0), 1.0, C10)


def fit_jkr(x, p, p_pull_off=None):
    """What the half-space tools give: (C10, x0, gamma_hat) with C10 and x0 from a Hertz fit
    of the loading (E* = 8 C10) and gamma from JKR's fixed-load pull-off P* = -(3/2) pi R
    gamma, P* the most tensile measured force (or `p_pull_off`)."""
    x, p = np.asarray(x, float), np.asarray(p, float)
    parts = split_curve(x, p)
    xl, pl = x[parts.loading], p[parts.loading]
    if not np.any(pl > 0):
        raise InputError("the loading never compresses the shell (P > 0 is compression)")
    top = xl[np.argmax(pl)]
    start = [max(pl.max(), 1e-300) / hertz_p(1.0, top - xl[0]) if top > xl[0] else 1.0, xl[0]]

    def resid(v):
        return hertz_p(v[0], xl - v[1]) - pl
    C10, x0 = least_squares(resid, start, x_scale="jac",
                            bounds=([0.0, -np.inf], [np.inf, top])).x
    p_star = -abs(p_pull_off) if p_pull_off is not None else min(float(np.min(p)), 0.0)
    gR = p_star / jkr_P_star_N(1.0, 1e3)       # gamma / R from P* / R^2 = -(3/2) pi gamma / R
    return C10, x0, (gR / C10 if C10 > 0 else np.nan)
