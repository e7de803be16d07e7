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
  shrinking) to the fixed-grips pull-off delta_dagger, where the shell jumps off.

The parts of the curve: the jump-off from the retraction's least force and the drop after it
(`split_curve`, moved earlier by the fit: `refine_jump`); the points from it on are not used.
The baseline (`baseline`: offset and drift of the approach's non-contact part) is removed
first and corrected in the fit.  The noise sd comes from the data (`noise_sd`).

The fit has two stages: C10, x0 (and the baseline's correction) from the loading alone, then
gamma from the retraction with them held.  The loading model converges smoothly with the
mesh (0.1 % on the coarse mesh); the retraction's moves by one node's contact at a time as
the turn passes a loaded state, and fitted jointly it pulled x0 and C10 with it (C10 0.9 %
off on the coarse mesh, against 0.14 % from the loading alone).

Intervals (95 %): C10 and x0 profile likelihood on the loading (`profile_intervals`), gamma
linearised with their uncertainty carried through (`_gamma_interval`), each widened in
quadrature by the model's discretisation error (`with_model_error`); a fit whose residual
rms exceeds MISFIT_FACTOR x hypot(noise, model error) is a misfit (`verdict`, `Misfit`).
Pure functions (no files, no printing).
"""
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.interpolate import CubicHermiteSpline
from scipy.ndimage import median_filter
from scipy.optimize import brentq, least_squares, root_scalar
from scipy.stats import linregress, median_abs_deviation, t as student_t

from .case import PathSet, Relaxation
from shell_adhesion.energy import OutOfRange, equilibrium, pull_off
from shell_adhesion.errors import InputError
from shell_adhesion.theory import hertz_P_N, jkr_P_star_N

MIN_LOADING_POINTS = 5
MAX_BACKTRACK = 0.1     # rows whose delta travels back this share of its travel are not in time order
MIN_BASELINE_POINTS = 5 # non-contact approach points needed for a baseline
DRIFT_P = 0.01          # a baseline slope is fitted where its two-sided p-value is below
RISE = 0.1              # contact is sought before P has risen by this share of its loading range
BASELINE_MARGIN = 0.3   # the non-contact part ends this share of the loading before that rise
SMOOTH = 5              # running-median width (points) that finds the least retraction force
JUMP_LEVEL = 0.25       # the drop is first cut where the force is back above this share of P*
JUMP_RESIDUAL = 4.0     # a point this many noise sd above the fitted attached curve is on the drop
JUMP_REFITS = 3         # fits that move the jump-off's start (each cut only moves earlier)
MISFIT_FACTOR = 2.0     # residual rms above this x hypot(noise sd, model error) is a misfit
PROFILE_STEPS = 8       # secant steps of one end of a profile-likelihood interval


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
    delta), of the retraction points used (before the jump-off) and of the points from the
    jump-off on (`detached`: the drop and the detached shell); `drop` of these lie on the
    drop itself (between the attached force and zero), `least` is the index of the
    retraction's least force (-1: no retraction)."""

    loading: np.ndarray
    retraction: np.ndarray
    detached: np.ndarray
    drop: int = 0
    least: int = -1


def backtrack_share(x, samples=100) -> float:
    """The share of the travel of x (time order) against the direction of its part: up to
    the (first) deepest point x should rise, after it fall; 0 for a clean test, about 1/2
    for rows in random order.  Taken on about `samples` evenly spaced rows, so that the
    noise of a densely sampled displacement does not count as travel."""
    x = np.asarray(x, float)
    x = x[::max(1, len(x) // samples)]
    if len(x) < 3:
        return 0.0
    turn = int(np.argmax(x))
    steps = np.diff(x)
    against = np.concatenate([np.minimum(steps[:turn], 0.0), np.maximum(steps[turn:], 0.0)])
    total = float(np.sum(np.abs(steps)))
    return float(np.sum(np.abs(against))) / total if total > 0 else 0.0


def noise_sd(p) -> float:
    """The standard deviation of white noise on the samples p (time order), from their
    second differences (variance 6 sd^2 for white noise; a smooth curve sampled densely adds
    little): 1.4826 x their median absolute deviation / sqrt(6), robust to the few
    differences a jump or a kink makes."""
    p = np.asarray(p, float)
    if len(p) < 4:
        return 0.0
    return float(median_abs_deviation(np.diff(p, 2), scale="normal") / np.sqrt(6.0))


@dataclass(frozen=True)
class Baseline:
    """The force measured without contact, p = offset + slope x (in p = P / R^2 and
    x = delta / R), fitted to the approach's non-contact points (`points` of them; 0: none
    found, nothing removed)."""

    offset: float = 0.0
    slope: float = 0.0
    points: int = 0
    drift: bool = False        # the slope differs from 0 (two-sided p < DRIFT_P); else 0

    @property
    def parameters(self) -> int:
        """Baseline parameters fitted with the rest: 0 (none found), 1 (offset), 2 (drift)."""
        return 0 if not self.points else 2 if self.drift else 1

    def __call__(self, x):
        return self.offset + self.slope * np.asarray(x, float)


def baseline(x, p) -> Baseline:
    """The zero-force offset and linear drift of the approach's non-contact part: the
    loading points before x_r - BASELINE_MARGIN (x_turn - x_r), x_r where the running median
    of P (width SMOOTH) first rises above RISE of its loading range (contact lies within
    0.27 (x_turn - x_r) before x_r for a Hertz-like P ~ delta^1.5, at x_r for a linear one).
    A line through them (at least MIN_BASELINE_POINTS; its slope only where it differs
    from 0, p < DRIFT_P, else their mean), or none."""
    x, p = np.asarray(x, float), np.asarray(p, float)
    turn = int(np.argmax(x))
    xl = x[:turn + 1]
    pl = median_filter(p[:turn + 1], size=min(SMOOTH, turn + 1), mode="nearest")
    rise = pl - float(np.median(pl[:MIN_BASELINE_POINTS]))
    if rise.max() <= 0:
        return Baseline()
    k = int(np.argmax(rise > RISE * rise.max()))
    free = xl < xl[k] - BASELINE_MARGIN * (xl[-1] - xl[k])
    if np.sum(free) < MIN_BASELINE_POINTS:
        return Baseline()
    pf = p[:turn + 1][free]
    line = linregress(xl[free], pf) if np.ptp(pf) > 0 else None
    if line is None or not line.pvalue < DRIFT_P:
        return Baseline(float(np.mean(pf)), 0.0, int(np.sum(free)))
    return Baseline(float(line.intercept), float(line.slope), int(np.sum(free)), True)


def _least_and_crossing(p_ret, sd):
    """(i_least, i_cross) of the retraction forces p_ret (time order): the least force of
    the running median (width SMOOTH) and the first point after it where the median is back
    above JUMP_LEVEL of it (None: no drop, the curve ends before the jump-off, or the least
    force is not tensile beyond JUMP_RESIDUAL noise sd)."""
    if len(p_ret) < 3:
        return (int(np.argmin(p_ret)) if len(p_ret) else -1), None
    smooth = median_filter(p_ret, size=min(SMOOTH, len(p_ret)), mode="nearest")
    i = int(np.argmin(smooth))
    low = smooth[i]
    if low >= -JUMP_RESIDUAL * sd:
        return i, None
    back = np.flatnonzero(smooth[i + 1:] >= JUMP_LEVEL * low)
    return i, (i + 1 + int(back[0]) if len(back) else None)


def split_curve(x, p, start=None, sd=None) -> Split:
    """Loading up to the (first) deepest point; retraction after it up to the jump-off.
    The jump-off is found from the retraction's physics: its least force (P*, on a running
    median) and the drop after it back towards zero; the first cut is where the drop has
    come JUMP_LEVEL of the way back (above any attached force: JKR's fixed-grips P_dagger
    is 0.56 P*), `start` (an index, from `refine_jump`) moves it earlier.  p must be free
    of its baseline (`baseline`); sd is its noise (default `noise_sd`)."""
    x, p = np.asarray(x, float), np.asarray(p, float)
    sd = noise_sd(p) if sd is None else sd
    turn = int(np.argmax(x))
    idx = np.arange(len(x))
    ret = idx[turn + 1:]
    least, cross = _least_and_crossing(p[ret], sd)
    cut = len(ret) if cross is None else cross
    if start is not None:
        cut = min(cut, max(start - turn - 1, least + 1))
    detached = ret[cut:]
    drop = 0
    if len(detached) and least >= 0:
        level = JUMP_LEVEL * abs(float(np.min(p[ret])))
        near_zero = np.flatnonzero(np.abs(p[detached]) < level / 2)
        drop = int(near_zero[0]) if len(near_zero) else len(detached)
    return Split(idx[:turn + 1], ret[:cut], detached, drop, int(turn + 1 + least) if least >= 0 else -1)


def refine_jump(split: Split, p, p_model, sd) -> int:
    """The index where the drop starts, from a fit: going back from the first cut, the
    retraction points after the least force that lie more than JUMP_RESIDUAL x (the noise
    sd, or the robust sd of the residuals if larger) above the fitted model, in one run up
    to the cut.  `p_model` holds the model at every point (the attached curve extended)."""
    ret = split.retraction
    if not len(ret) or not len(split.detached) or split.least < 0:
        return int(split.detached[0]) if len(split.detached) else len(p)
    r = np.asarray(p, float) - np.asarray(p_model, float)
    used = np.concatenate([split.loading, ret])
    spread = max(sd, float(median_abs_deviation(r[used], scale="normal")))
    k = int(split.detached[0])
    while k - 1 > split.least and r[k - 1] > JUMP_RESIDUAL * spread:
        k -= 1
    return k


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
    """A least-squares estimate: the values, their 95 % intervals (of the data's scatter
    alone: `with_model_error` adds the mesh's), the residuals (in p) of the points used."""

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
    split: Split = None        # the parts of the curve as fitted
    intervals: str = ""        # how the intervals were made
    baseline: tuple = ()       # (offset[, slope]) fitted besides (in p; added to the model)


class Misfit(FitError):
    """The fitted model does not describe the curve (its residual is MISFIT_FACTOR times
    the noise and model error, or its C10 is not a soft solid's); `result` holds the fit."""

    def __init__(self, text, result=None):
        super().__init__(text)
        self.result = result


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
    return _fit_loading_baseline(ps, x, p, (C10_0, x0_0))


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


def fit_curve(ps: PathSet, x, p, p_pull_off=None, hertz=None, split: Split = None,
              intervals: bool = True, baseline_parameters: int = 0) -> Estimate:
    """Fit C10, gamma / (C10 R) and x0 of one measured curve (x = delta / R, p = P / R^2
    free of its baseline, in time order) with the paths `ps`; `p_pull_off` (P* / R^2, a
    measured pull-off force) gives gamma through P* instead of the retraction.  `hertz` =
    (C10, x0) starts the search (default: the half-space fit, `fit_jkr`).  The jump-off's
    start is moved by the fit (`refine_jump`, at most JUMP_REFITS fits) unless `split`
    fixes the parts.  C10 and x0 come from the loading points, gamma from the retraction
    points with them held (the module docstring says why).  Intervals: C10's and x0's
    profile likelihood on the loading, gamma's linearised with theirs carried through,
    unless not `intervals` (then the values alone, the intervals empty).
    `baseline_parameters` (1: offset, 2: and slope, `Baseline.parameters`): a correction of
    the baseline (`Estimate.baseline`) is fitted with the loading, so its uncertainty enters
    the intervals."""
    x, p = np.asarray(x, float), np.asarray(p, float)
    sd = noise_sd(p)
    parts = split if split is not None else split_curve(x, p, sd=sd)
    C10_0, x0_0 = hertz if hertz is not None else fit_jkr(x, p)[:2]
    span = None
    nb = baseline_parameters
    for refit in range(1 if split is not None else JUMP_REFITS):
        xl, pl = x[parts.loading], p[parts.loading]
        xr, pr = x[parts.retraction], p[parts.retraction]
        if p_pull_off is None and not len(xr):
            raise FitError("no retraction points before the jump-off and no pull-off force: "
                           "gamma cannot be fitted")
        load = _fit_loading(ps, xl, pl, C10_0, x0_0)
        used = dict(loading=len(xl), retraction=len(xr), after_pull_off=len(parts.detached),
                    on_the_drop=parts.drop)
        if p_pull_off is not None:
            _check_depth(ps, x.max() - load.x[1])
            return replace(_pull_off_estimate(ps, load, p_pull_off, used), split=parts)
        span = span or gamma_range(ps)
        stage1 = _fit_loading_baseline(ps, xl, pl, load.x, nb) if nb else load
        C10, x0 = stage1.x[:2]
        corr = _baseline_fn(stage1.x[2:])
        path = turn_path(ps, x.max() - x0)
        g_start = _start_gamma(ps, C10, pr - corr(xr), span)
        g, r_ret, J_ret = _fit_gamma(ps, path, C10, x0, xr, pr - corr(xr), g_start, span)
        if split is not None or refit == JUMP_REFITS - 1:
            break
        start = refine_jump(parts, p, attached_model(ps, C10, g, x0, x, parts) + corr(x), sd)
        if not len(parts.detached) or start >= parts.detached[0]:
            break
        parts = split_curve(x, p, start, sd)
    _check_depth(ps, x.max() - x0)
    est = Estimate(C10, (), g, (), x0, (), np.concatenate([stage1.fun, r_ret]), used,
                   "retraction", span, parts, baseline=tuple(float(v) for v in stage1.x[2:]))
    if not intervals:
        return est
    C10_ci, x0_ci = profile_intervals(_loading_residuals(ps, xl, pl, nb), stage1)
    gamma_ci = _gamma_interval(ps, path, stage1, g, r_ret, J_ret, xr, pr, span)
    return replace(est, C10_ci=C10_ci, gamma_ci=gamma_ci, x0_ci=x0_ci,
                   intervals="profile likelihood")


def _baseline_fn(b):
    """The baseline correction b[0] + b[1] x (of the parameters fitted, none: 0)."""
    b = [float(v) for v in b]
    return lambda x: (b[0] if b else 0.0) + (b[1] * np.asarray(x, float) if len(b) > 1 else 0.0)


def _loading_residuals(ps: PathSet, xl, pl, nb=0):
    """The loading's residuals as a function of (C10, x0[, baseline])."""
    def resid(v):
        return v[0] * loading_F(ps, xl - v[1]) + _baseline_fn(v[2:2 + nb])(xl) - pl
    return resid


def _fit_loading_baseline(ps: PathSet, xl, pl, start, nb=0):
    """The least-squares fit of (C10, x0[, baseline]) to the loading points."""
    v0 = np.concatenate([start[:2], np.zeros(nb)])
    return least_squares(_loading_residuals(ps, xl, pl, nb), v0, x_scale="jac",
                         bounds=([0.0] + [-np.inf] * (1 + nb), [np.inf] * (2 + nb)),
                         diff_step=1e-6)


def _fit_gamma(ps: PathSet, path: Relaxation, C10, x0, xr, pr, start, span) -> tuple:
    """(gamma / (C10 R), residuals, d residuals / d gamma_hat): gamma fitted to the
    retraction points (their baseline removed) with C10 and x0 held.  FitError if the
    points do not depend on gamma (all on the held contact's relaxation, above where it
    meets the equilibrium curve G = gamma)."""
    def resid(v):
        return C10 * retraction(ps, path, v[0])(xr - x0) - pr
    sol = least_squares(resid, [float(np.clip(start, *span))], x_scale="jac",
                        bounds=([span[0]], [span[1]]), diff_step=1e-6, xtol=1e-12,
                        ftol=1e-12, gtol=1e-12)
    J = sol.jac[:, 0]
    if not np.any(J):
        raise FitError(f"the {len(xr)} retraction points used do not depend on gamma: they "
                       "lie on the held contact's relaxation, before the contact recedes; "
                       "record the retraction through the jump-off, or give --pull-off-N")
    return float(sol.x[0]), sol.fun, J


def _gamma_interval(ps: PathSet, path: Relaxation, stage1, g, r_ret, J, xr, pr,
                    span) -> tuple:
    """95 % interval of gamma / R = g C10, linearised: the retraction's scatter with C10, x0
    and the baseline held (s^2 / (J^T J), J = `J` / C10 the residuals' slope in gamma / R,
    Student t), plus theirs from the loading's fit carried through (the delta method: gamma
    / R refitted with each moved by one standard deviation either way)."""
    v1 = stage1.x
    cov1 = _covariance(stage1)

    def gR_of(v):
        corr = _baseline_fn(v[2:])
        return _fit_gamma(ps, path, v[0], v[1], xr, pr - corr(xr), g, span)[0] * v[0]

    grad = np.zeros(len(v1))
    for i in range(len(v1)):
        sd = float(np.sqrt(max(cov1[i, i], 0.0)))
        h = sd if np.isfinite(sd) and sd > 0 else 1e-6 * max(abs(v1[i]), 1e-12)
        up, down = v1.copy(), v1.copy()
        up[i] += h
        down[i] -= h
        grad[i] = (gR_of(up) - gR_of(down)) / (2 * h)
    dof = max(len(r_ret) - 1, 1)
    J_gR = J / v1[0]
    var = float(grad @ cov1 @ grad) + float(r_ret @ r_ret) / dof / float(J_gR @ J_gR)
    half = float(student_t.ppf(0.975, dof)) * float(np.sqrt(var))
    gR = g * v1[0]
    return (gR - half, gR + half)


def profile_intervals(resid, full, which=(0, 1)) -> list:
    """95 % profile-likelihood intervals of the parameters `which` at the least-squares
    optimum `full` of `resid`: each end where the residual sum of squares, minimised over
    the other parameters, has risen by s^2 t^2 (s^2 = SSR / (m - n) of n parameters,
    Student's t at 97.5 %: F(1, m - n)); found by secant steps from the linearised end (at
    most PROFILE_STEPS; where they do not converge, the linearised end)."""
    v_hat = np.asarray(full.x, float)
    n = len(v_hat)
    r = resid(v_hat)
    ssr = float(r @ r)
    dof = max(len(r) - n, 1)
    tq = float(student_t.ppf(0.975, dof))
    rise = np.sqrt(ssr / dof) * tq             # sqrt of the SSR's allowed rise
    cov = _covariance(full)
    out = []
    for k in which:
        sd = float(np.sqrt(max(cov[k, k], 0.0)))
        others = [i for i in range(n) if i != k]
        warm = [v_hat[others]]

        def excess(h):
            def r2(w):
                v = v_hat.copy()
                v[k] += h
                v[others] = w
                return resid(v)
            sol = least_squares(r2, warm[0], x_scale="jac", diff_step=1e-6)
            return np.sqrt(max(2.0 * sol.cost - ssr, 0.0)) - rise

        ends = []
        for sign in (-1.0, 1.0):
            h1 = sign * tq * sd
            if not np.isfinite(h1) or h1 == 0 or rise == 0:
                ends.append(v_hat[k] + (h1 if np.isfinite(h1) else 0.0))
                continue
            warm[0] = v_hat[others]
            try:
                sol = root_scalar(excess, x0=h1, x1=1.2 * h1, method="secant",
                                  maxiter=PROFILE_STEPS, rtol=1e-2)
                ok = sol.converged and sol.root * sign > 0
            except (RuntimeError, ValueError, ArithmeticError):
                ok = False
            ends.append(v_hat[k] + (sol.root if ok else h1))
        out.append((float(min(ends)), float(max(ends))))
    return out


def attached_model(ps: PathSet, C10, gamma_hat, x0, x, split: Split):
    """The fitted model at every point of the curve as if the shell stayed attached (the
    retraction's attached curve held at its end below delta_dagger)."""
    rest = np.concatenate([split.retraction, split.detached]).astype(int)
    return model(ps, C10, gamma_hat, x0, x, Split(split.loading, rest, rest[:0]))


def with_model_error(value, ci, other) -> tuple:
    """The 95 % interval `ci` of the data's scatter widened, in quadrature on each side, by
    the model's discretisation error |value - other|, `other` the same fit on the next
    coarser mesh of the family (Richardson's estimate of the finer mesh's error for a
    first-order method, no safety factor)."""
    e = abs(value - other)
    return (value - float(np.hypot(value - ci[0], e)), value + float(np.hypot(ci[1] - value, e)))


@dataclass(frozen=True)
class Verdict:
    """Goodness of fit: the residual rms against the noise sd estimated from the data
    (`noise_sd`) and the rms difference of the fitted model on two meshes (its own error),
    in p; a misfit when rms > MISFIT_FACTOR x hypot(noise, model)."""

    rms: float
    noise: float
    model: float
    factor: float = MISFIT_FACTOR

    @property
    def ratio(self) -> float:
        allowed = float(np.hypot(self.noise, self.model))
        return self.rms / allowed if allowed > 0 else np.inf

    @property
    def misfit(self) -> bool:
        return self.ratio > self.factor


def verdict(residuals, p, model_p, other_model_p) -> Verdict:
    """The Verdict of a fit with `residuals` at its points used, the curve p (for its noise,
    time order) and the fitted model on the fit's mesh and on the coarser one at the points
    used."""
    r = np.asarray(residuals, float)
    diff = np.asarray(model_p, float) - np.asarray(other_model_p, float)
    diff = diff[np.isfinite(diff)]
    model_rms = float(np.sqrt(np.mean(diff ** 2))) if len(diff) else 0.0
    return Verdict(float(np.sqrt(np.mean(r ** 2))), noise_sd(p), model_rms)


def _start_gamma(ps: PathSet, C10, pr, span) -> float:
    """gamma / (C10 R) whose P* is the most tensile measured force (the search's start)."""
    low = float(np.min(pr))
    if low >= 0:
        return span[0]
    try:
        return gamma_of_P_star(ps, C10, low, span)
    except FitError:
        return float(np.sqrt(span[0] * span[1]))


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
