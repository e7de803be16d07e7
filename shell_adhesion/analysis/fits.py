"""Fits over a results cube: eta of the linear-shell law (eq. 3), the free power law of
|P*|, the slope of |P*| in gamma and the ratio to JKR.

Units as in the cube: forces N, lengths mm, C10 MPa, gamma J/m^2; slopes d|P*|/dgamma in m
(N per J/m^2).  P < 0 is tension, so pull-off forces are compared by magnitude |P*|.
Intervals are 95 % (two-sided, Student t).
"""
from dataclasses import dataclass
import math

import numpy as np
import xarray as xr

from shell_adhesion.theory import jkr_P_star_N, shell_law_scale_N

from .results import R_mm, along, ok_cases


# exponents of eq. 3: |P*| = eta gamma^(4/3) R^(4/3) (1 - nu^2)^(1/3) E^(-1/3) t^(-2/3)
EQ3_EXPONENTS = {"gamma": 4 / 3, "C10": -1 / 3, "t_mm": -2 / 3, "h_mm": 0.0}


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
    from scipy import stats     # on use: the heaviest import of a run that draws nothing
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
        from scipy import stats
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
    from scipy import stats
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
