"""A dimensionless pull-off map and its interpolant.

The map holds the pull-off of the energy method over a grid of shells t/R x h/R and
adhesion energies gamma_hat = gamma / (C10 R), as read from a results cube of a study
(one C10, so that gamma_hat follows from gamma): forces over C10 R^2, lengths over R, each
with its FE error bar.  Everything here is dimensionless (scaling, DESIGN.md section 3):
one map serves every R, C10 and gamma inside it.  P > 0 compression, delta > 0 approach.

The interpolant is linear in (ln t/R, h/R, ln gamma_hat) on quantities that the JKR
scalings make nearly flat: P / (pi gamma R), a / (R gamma_hat^(1/3)),
delta / (R gamma_hat^(2/3)); along t/R it follows the lines gamma_hat ~ (t/R)^3
(`SHEAR_POWER`; less near the ends of the gamma range, so that the lines stay inside it),
along which the thin-shell crossover runs.  Its error is estimated by leaving grid points out: each inner grid point is predicted
from its two neighbours along each axis, the same way; the miss gives the second
derivative along that axis (of the parabola through the three points), and a linear
interpolant's error in a cell of width s is at most s^2 |f''| / 8: summed over the axes,
with the largest |f''| of the grid points the answer is made of.  The FE error of an
answer is the FE error bars of those grid points combined with the interpolation's
weights: the weights are >= 0 and sum to 1, so where each point's error is within its
bar, the answer's FE error is within that sum.  An answer's error bar is the
interpolation error and the FE error, added in quadrature.
"""
from dataclasses import dataclass
import math

import numpy as np
import xarray as xr

QUANTITIES = ("P_star", "delta_star", "a_star", "P_dagger", "delta_dagger", "a_dagger",
              "preload")
AXES = ("t_over_R", "h_over_R", "gamma_hat")
# the JKR power of gamma_hat that flattens each quantity (force: gamma_hat^1 times pi)
GAMMA_POWER = dict(P_star=1.0, P_dagger=1.0, preload=1.0, delta_star=2 / 3,
                   delta_dagger=2 / 3, a_star=1 / 3, a_dagger=1 / 3)
FORCES = ("P_star", "P_dagger", "preload")
# along t/R the map interpolates on the lines gamma_hat ~ (t/R)^3, along which the pull-off
# changes slowly (the thin-shell crossover, where a* moves out fast, runs along them);
# measured on the coarse map: leave-out miss along t/R median 3.2 % -> 0.6 %, max 47 % -> 4 %
SHEAR_POWER = 3.0
KEEP_ATTRS = ("interface", "mesh", "study_name", "study_description", "study_sha256", "source",
              "history", "references", "Conventions")


class MapError(ValueError):
    """A query outside the map, or at a hole of the map (a refused grid point)."""


def _flat(quantity, value, gamma_hat):
    """The JKR-flattened form of a dimensionless quantity (see the module docstring)."""
    scale = gamma_hat ** GAMMA_POWER[quantity]
    return value / (math.pi * scale if quantity in FORCES else scale)


def _unflat(quantity, flat, gamma_hat):
    scale = gamma_hat ** GAMMA_POWER[quantity]
    return flat * (math.pi * scale if quantity in FORCES else scale)


def _coordinates(ds):
    return [np.log(ds[AXES[0]].values), ds[AXES[1]].values.astype(float),
            np.log(ds[AXES[2]].values)]


def _shear(z, x, x_lo, x_hi, lg):
    """The shear to use between t/R nodes x_lo <= x <= x_hi (logs) for a line through
    ln gamma_hat = z: SHEAR_POWER, or less where the line would leave the map's gamma range
    at a node (down to 0, a line of constant gamma_hat)."""
    p = SHEAR_POWER
    if x > x_lo:
        p = min(p, (z - lg[0]) / (x - x_lo))
    if x_hi > x:
        p = min(p, (lg[-1] - z) / (x_hi - x))
    return max(p, 0.0)


def _along_gamma(f_row, lg, z):
    """Linear interpolation of one grid line over ln gamma_hat at z (inside its range)."""
    k = int(np.clip(np.searchsorted(lg, z) - 1, 0, len(lg) - 2))
    w = (z - lg[k]) / (lg[k + 1] - lg[k])
    return (1 - w) * f_row[k] + w * f_row[k + 1]


def leave_out_errors(flat: np.ndarray, coords: list, shear=0.0) -> np.ndarray:
    """Per axis, the miss of linear interpolation at each inner grid point predicted from
    its two neighbours (shape: (3, *flat.shape)); along t/R (axis 0) on the lines
    ln gamma_hat + shear ln t/R = const, like the interpolant; end points take their inner
    neighbour's miss; NaN where a neighbour is a hole."""
    errors = np.full((len(coords),) + flat.shape, np.nan)
    lt, lg = coords[0], coords[-1]
    for axis, x in enumerate(coords):
        if len(x) < 3:
            continue
        e = np.moveaxis(errors[axis], axis, 0)
        for i in range(1, len(x) - 1):
            w = (x[i] - x[i - 1]) / (x[i + 1] - x[i - 1])
            if axis == 0 and shear:
                for j, k in np.ndindex(flat.shape[1], flat.shape[2]):
                    p = _shear(lg[k], lt[i], lt[i - 1], lt[i + 1], lg)
                    lo = _along_gamma(flat[i - 1, j], lg, lg[k] + p * (lt[i - 1] - lt[i]))
                    hi = _along_gamma(flat[i + 1, j], lg, lg[k] + p * (lt[i + 1] - lt[i]))
                    errors[0, i, j, k] = abs((1 - w) * lo + w * hi - flat[i, j, k])
            else:
                f = np.moveaxis(flat, axis, 0)
                e[i] = np.abs((1 - w) * f[i - 1] + w * f[i + 1] - f[i])
        e[0], e[-1] = e[1], e[-2]
    return errors


def curvatures(flat: np.ndarray, coords: list, shear=False) -> np.ndarray:
    """Per axis, the second derivative at each grid point that its leave-out miss implies
    (a parabola through the point and its two neighbours: 2 miss / (h1 h2), h1 and h2 the
    spacings on either side); shape (3, *flat.shape), NaN next to a hole."""
    miss = leave_out_errors(flat, coords, shear)
    for axis, x in enumerate(coords):
        if len(x) < 3:
            continue
        gaps = np.diff(x)
        h1h2 = np.concatenate([[gaps[0] * gaps[1]], gaps[:-1] * gaps[1:], [gaps[-2] * gaps[-1]]])
        shape = [1] * (flat.ndim + 1)
        shape[axis + 1] = len(x)
        miss[axis:axis + 1] *= 2 / h1h2.reshape(shape)
    return miss


@dataclass(frozen=True)
class Answer:
    """One quantity of the map at one shell: dimensionless value, its interpolation error
    and its FE error bar (same units as value; NaN where unknown)."""
    value: float
    interpolation_error: float
    fe_error: float

    @property
    def error(self) -> float:
        """Interpolation and FE errors in quadrature."""
        return math.hypot(self.interpolation_error, np.nan_to_num(self.fe_error))


class PullOffMap:
    """The interpolant of a map dataset (see `map_from_cube`).

    ``predict(t_over_R, h_over_R, gamma_hat)`` gives the dimensionless answers;
    ``shell(R_mm, t_mm, h_mm, C10_MPa, gamma_J_m2)`` the same in N and mm.
    """

    def __init__(self, ds: xr.Dataset):
        self.ds = ds
        self.coords = _coordinates(ds)
        self.bounds = {a: (float(ds[a].min()), float(ds[a].max())) for a in AXES}
        g = ds["gamma_hat"].values[None, None, :]
        self._flat = {q: _flat(q, ds[q].values, g) for q in QUANTITIES if q in ds}
        self._fe = {q: _flat(q, np.abs(ds[f"{q}_error"].values), g)
                    for q in self._flat if f"{q}_error" in ds}
        self._curvature = {}
        for q, f in self._flat.items():
            per_axis = curvatures(f, self.coords, shear=True)
            # a hole next to a point: that axis's largest curvature anywhere stands in
            worst = np.nanmax(per_axis.reshape(3, -1), axis=1, initial=0.0)
            self._curvature[q] = np.where(np.isnan(per_axis), worst[:, None, None, None],
                                          per_axis)

    @classmethod
    def open(cls, path) -> "PullOffMap":
        with xr.open_dataset(path) as ds:
            return cls(ds.load())

    @property
    def quantities(self) -> tuple:
        return tuple(self._flat)

    def check_inside(self, t_over_R, h_over_R, gamma_hat):
        """MapError naming the first coordinate outside the map's box."""
        for name, value in zip(AXES, (t_over_R, h_over_R, gamma_hat)):
            lo, hi = self.bounds[name]
            if not (lo * (1 - 1e-12) <= value <= hi * (1 + 1e-12)):
                raise MapError(f"{name} = {value:.4g} is outside the map "
                               f"[{lo:.4g}, {hi:.4g}]")

    def _stencil(self, t_over_R, h_over_R, gamma_hat):
        """The grid points an answer is made of: [(weight, i, j, k, w_k)], i over t/R, j over
        h/R, and along gamma_hat the pair k, k + 1 (weight w_k on k + 1) of the sheared
        line through the query (module docstring)."""
        (lt, h, lg), out = self.coords, []
        x, y, z = math.log(t_over_R), h_over_R, math.log(gamma_hat)
        i = int(np.clip(np.searchsorted(lt, x) - 1, 0, len(lt) - 2))
        j = int(np.clip(np.searchsorted(h, y) - 1, 0, len(h) - 2))
        wt = float(np.clip((x - lt[i]) / (lt[i + 1] - lt[i]), 0.0, 1.0))
        wh = float(np.clip((y - h[j]) / (h[j + 1] - h[j]), 0.0, 1.0))
        p = _shear(z, x, lt[i], lt[i + 1], lg)
        for di, dj in np.ndindex(2, 2):
            zc = min(max(z + p * (lt[i + di] - x), lg[0]), lg[-1])     # round-off only
            k = int(np.clip(np.searchsorted(lg, zc) - 1, 0, len(lg) - 2))
            wk = (zc - lg[k]) / (lg[k + 1] - lg[k])
            weight = (wt if di else 1 - wt) * (wh if dj else 1 - wh)
            out.append((weight, i + di, j + dj, k, wk))
        return out

    @staticmethod
    def _combine(table, stencil):
        return float(sum(w * ((1 - wk) * table[i, j, k] + wk * table[i, j, k + 1])
                         for w, i, j, k, wk in stencil))

    def _interpolation_error(self, curvature, stencil):
        """Linear interpolation's error bound s^2 |f''| / 8 per axis (s: the cell's width,
        f'' the largest of the stencil's points), summed over the axes."""
        (lt, h, lg), (_, i, j, _, _) = self.coords, stencil[0]
        widths = (lt[i + 1] - lt[i] if i + 1 < len(lt) else lt[i] - lt[i - 1],
                  h[j + 1] - h[j] if j + 1 < len(h) else h[j] - h[j - 1],
                  max(lg[kk + 1] - lg[kk] for _, _, _, kk, _ in stencil))
        return sum(w ** 2 / 8 * self._worst(curvature[axis], stencil)
                   for axis, w in enumerate(widths))

    @staticmethod
    def _worst(table, stencil):
        return float(max(max(table[i, j, k], table[i, j, k + 1]) for _, i, j, k, _ in stencil))

    def predict(self, t_over_R: float, h_over_R: float, gamma_hat: float) -> dict:
        """quantity -> Answer (forces over C10 R^2, lengths over R) at one shell; MapError
        outside the map or where a grid point it is made of has no pull-off."""
        self.check_inside(t_over_R, h_over_R, gamma_hat)
        stencil = self._stencil(t_over_R, h_over_R, gamma_hat)
        points = [(i, j, kk) for _, i, j, k, _ in stencil for kk in (k, k + 1)]
        answers = {}
        for q, flat in self._flat.items():
            if any(np.isnan(flat[p]) for p in points):
                if q == "P_star":
                    raise MapError(self._hole(points))
                continue
            value = self._combine(flat, stencil)
            interp = self._interpolation_error(self._curvature[q], stencil)
            fe = self._combine(self._fe[q], stencil) if q in self._fe else math.nan
            answers[q] = Answer(*(_unflat(q, v, gamma_hat) for v in (value, interp, fe)))
        return answers

    def _hole(self, points):
        i, j, k = next(p for p in points if np.isnan(self.ds["P_star"].values[p]))
        reason = str(self.ds["reason"].values[i, j, k]) if "reason" in self.ds else ""
        at = ", ".join(f"{a} {self.ds[a].values[n]:.4g}" for a, n in zip(AXES, (i, j, k)))
        return f"the map has no pull-off at its grid point {at}" + (
            f" ({reason})" if reason else "") + "; solve this shell with `case`"

    def survey(self, n: int = 3000, gamma_hat=(1e-3, 0.03), seed: int = 0) -> dict:
        """P*'s stated errors at `n` shells drawn uniformly in (ln t/R, h/R, ln gamma_hat)
        over the map and the gamma_hat range: arrays (percent of P*) of the interpolation
        and total errors, the shells' t/R and gamma_hat, the count that needs a hole, and
        the FE error bars of the grid points (percent of P*)."""
        rng = np.random.default_rng(seed)
        (tl, th), (hl, hh) = self.bounds["t_over_R"], self.bounds["h_over_R"]
        rows, holes = [], 0
        for _ in range(n):
            t = math.exp(rng.uniform(math.log(tl), math.log(th)))
            h = rng.uniform(hl, hh)
            g = math.exp(rng.uniform(math.log(gamma_hat[0]), math.log(gamma_hat[1])))
            try:
                a = self.predict(t, h, g)["P_star"]
            except MapError:
                holes += 1
                continue
            rows.append((t, g, 100 * a.interpolation_error / abs(a.value),
                         100 * a.error / abs(a.value)))
        t, g, interp, total = np.array(rows).reshape(-1, 4).T
        fe = (100 * self.ds["P_star_error"] / abs(self.ds["P_star"])).values
        return dict(t_over_R=t, gamma_hat=g, interpolation=interp, total=total, holes=holes,
                    fe_grid=fe[np.isfinite(fe)])

    def shell(self, R_mm, t_mm, h_mm, C10_MPa, gamma_J_m2) -> dict:
        """The answers in units: name_unit -> (value, error) with P in N, lengths in mm,
        error = interpolation and FE errors in quadrature."""
        gamma_hat = gamma_J_m2 * 1e-3 / (C10_MPa * R_mm)
        out = {}
        for q, ans in self.predict(t_mm / R_mm, h_mm / R_mm, gamma_hat).items():
            unit, scale = ("N", C10_MPa * R_mm ** 2) if q in FORCES else ("mm", R_mm)
            out[f"{q}_{unit}"] = (ans.value * scale, ans.error * scale)
        return out


def map_from_cube(cube: xr.Dataset) -> xr.Dataset:
    """The map dataset (dims t_over_R, h_over_R, gamma_hat; dimensionless values, NaN where
    a point is not ok) of a results cube with one C10, no material ratios and no cavity."""
    extra = [d for d in cube["P_star"].dims if d not in ("C10", "t_over_R", "h_over_R", "gamma")]
    if cube.sizes.get("C10", 1) != 1 or extra:
        raise ValueError("a map is made from a study with one C10 and only t/R, h/R and gamma "
                         f"varied (this cube also varies {['C10'] * (cube.sizes.get('C10', 1) > 1) + extra})")
    c = cube.isel(C10=0) if "C10" in cube.dims else cube
    R, C10 = float(c["R"]), float(c["C10_MPa"])
    gamma_hat = c["gamma_J_m2"].values * 1e-3 / (C10 * R)
    ok = (c["status"] == "ok").values
    force, length = C10 * R ** 2, R
    data = {}
    for q in QUANTITIES:
        src = "preload" if q == "preload" else q
        if q == "preload":
            value, error = _preload(c)
        else:
            value, error = c[src].values, c[f"{src}_error"].values
        scale = force if q in FORCES else length
        data[q] = (AXES, np.where(ok, value / scale, np.nan), {"units": "1"})
        data[f"{q}_error"] = (AXES, np.where(ok, error / scale, np.nan), {"units": "1"})
    data["reason"] = (AXES, np.where(ok, "", c["reason"].values.astype(str)))
    ds = xr.Dataset(data, coords={"t_over_R": c["t_over_R"].values,
                                  "h_over_R": c["h_over_R"].values, "gamma_hat": gamma_hat})
    ds.attrs.update(
        title="dimensionless pull-off map of shell-adhesion",
        comment="forces over C10 R^2, lengths over R; P > 0 compression, delta > 0 approach; "
                "NaN: the point was refused (see reason)",
        **{k: str(v) for k, v in cube.attrs.items()
           if k in KEEP_ATTRS or k.startswith("material")})
    return ds


def _preload(c):
    """The rim force on the loading curve at the contact radius a* (N): the least preload
    after which the fixed-load pull-off P* is reached; its FE error from the loading
    curve's."""
    value = np.full(c["P_star"].shape, np.nan)
    error = np.full(c["P_star"].shape, np.nan)
    a_load, P_load, P_err = c["loading_a"].values, c["loading_P"].values, c["loading_P_error"].values
    a_star = c["a_star"].values
    for i, j, k in np.ndindex(*a_star.shape):
        a = a_load[i, j]
        keep = np.isfinite(a) & np.isfinite(P_load[i, j])
        if keep.sum() < 2 or not np.isfinite(a_star[i, j, k]):
            continue
        a, P, e = a[keep], P_load[i, j][keep], P_err[i, j][keep]
        order = np.argsort(a)
        value[i, j, k] = np.interp(a_star[i, j, k], a[order], P[order])
        error[i, j, k] = np.interp(a_star[i, j, k], a[order], np.nan_to_num(e[order]))
    return value, error
