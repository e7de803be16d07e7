"""Analysis of a results cube: the eta fit of eq. 3, the slope in gamma and the trend
verdicts recover what synthetic cubes were built with; on the small real study they say
what DESIGN.md section 4 expects, and nothing here runs the solver."""
import math

import numpy as np
import pytest
import xarray as xr

from shell_adhesion.theory import shell_law_scale_N
from shell_adhesion import analysis
from shell_adhesion.study.dataset import DIMS

R = 20.0
BASE = {"C10_MPa": 0.3, "t_over_R": 0.15, "h_over_R": 1.0, "gamma_J_m2": 30.0}


def synthetic_cube(P_of, C10=(0.3,), t_over_R=(0.15,), h_over_R=(1.0,), gamma=(30.0,),
                   mesh="default"):
    """A cube in the layout of study.dataset with P* = P_of(C10, t_mm, h_mm, gamma)
    on a full grid, every point ok."""
    coords = dict(C10=np.array(C10, float), t_over_R=np.array(t_over_R, float),
                  h_over_R=np.array(h_over_R, float), gamma=np.array(gamma, float))
    c = xr.Dataset(coords=coords)
    t_mm, h_mm = c["t_over_R"] * R, c["h_over_R"] * R
    P = P_of(c["C10"], t_mm, h_mm, c["gamma"]).transpose(*DIMS)
    shape = P.shape
    ds = xr.Dataset(
        {"P_star": (DIMS, P.values, {"units": "N"}),
         "eta": (DIMS, np.full(shape, np.nan), {"units": "1"}),
         "status": (DIMS, np.full(shape, "ok", dtype=object))},
        coords={**{k: (k, v, {"units": u}) for (k, v), u in
                   zip(coords.items(), ("MPa", "1", "1", "J/m^2"))},
                "t_mm": ("t_over_R", t_mm.values, {"units": "mm"}),
                "h_mm": ("h_over_R", h_mm.values, {"units": "mm"}), "R": R},
        attrs={"study_name": "synthetic", "R_mm": R, "mesh": mesh,
               **{f"base_{k}": v for k, v in BASE.items()}})
    analysis.check_cube(ds)
    return ds


GRID = dict(C10=(0.1, 0.2, 0.3, 0.5, 1.0), t_over_R=(0.1, 0.15, 0.2, 0.3),
            gamma=(10.0, 20.0, 30.0, 40.0, 50.0))


def eq3(eta, noise=0.0, seed=0):
    rng = np.random.default_rng(seed)

    def P_of(C10, t, h, gamma):
        S = shell_law_scale_N(R, t, C10, gamma) * xr.ones_like(h)
        return -eta * S * np.exp(noise * rng.standard_normal(S.shape))
    return P_of


def test_eta_fit_recovers_eta_with_noise():
    fit = analysis.eta_fit(synthetic_cube(eq3(8.7, noise=0.02), **GRID))
    assert fit.n == 100
    assert fit.ci[0] < 8.7 < fit.ci[1]
    assert fit.eta == pytest.approx(8.7, rel=0.01)
    assert fit.ci[1] / fit.ci[0] < 1.02                 # 2 % scatter over 100 cases
    assert 0.015 < fit.rms < 0.025
    assert fit.residuals.sizes == {"case": 100}
    assert set(DIMS) <= set(fit.residuals.coords)       # labelled by case


def test_eta_fit_exact_without_noise_and_where():
    ds = synthetic_cube(eq3(8.7), **GRID)
    fit = analysis.eta_fit(ds)
    assert abs(fit.eta - 8.7) < 1e-12 * 8.7 and fit.rms < 1e-12
    assert analysis.eta_fit(ds, where=ds["t_over_R"] < 0.2).n == 50


def test_power_law_recovers_and_flags_exponents():
    pl = analysis.power_law_fit(synthetic_cube(eq3(8.7, noise=0.01), **GRID))
    assert set(pl.exponents) == {"gamma", "C10", "t_mm"}           # h/R spans one value
    for f, (p, (lo, hi)) in pl.exponents.items():
        assert lo < analysis.EQ3_EXPONENTS[f] < hi and p == pytest.approx(
            analysis.EQ3_EXPONENTS[f], abs=0.02)
    assert pl.disagrees == ()
    # a law linear in gamma and independent of t: eq. 3 disagrees on those two
    pl = analysis.power_law_fit(synthetic_cube(
        lambda C10, t, h, g: -0.05 * g * C10 ** (-1 / 3) * xr.ones_like(t) * xr.ones_like(h),
        **GRID))
    assert pl.exponents["gamma"][0] == pytest.approx(1.0)
    assert set(pl.disagrees) == {"gamma", "t_mm"}


def test_gamma_slope_recovers_slope():
    rng = np.random.default_rng(1)
    gammas = np.linspace(10, 50, 9)
    noisy = synthetic_cube(lambda C10, t, h, g: -(0.2 + 0.05 * g + 0.005 * rng.standard_normal(
        g.shape)) * xr.ones_like(C10 * t * h), gamma=gammas)
    s = analysis.gamma_slope(noisy)
    assert s.n == 9 and s.ci[0] < 0.05 < s.ci[1] and s.slope == pytest.approx(0.05, rel=0.02)
    assert s.jkr == pytest.approx(1.5 * math.pi * R * 1e-3) and len(s.local) == 8
    exact = synthetic_cube(lambda C10, t, h, g: -(0.2 + 0.05 * g) * xr.ones_like(C10 * t * h),
                           C10=(0.3, 0.6), gamma=gammas)
    s = analysis.gamma_slope(exact, C10=0.6)
    assert s.slope == pytest.approx(0.05, rel=1e-12) and s.intercept == pytest.approx(0.2)
    assert np.allclose(s.local, 0.05, rtol=1e-12)


def test_jkr_ratio_of_jkr_is_one():
    ds = synthetic_cube(lambda C10, t, h, g: -1.5 * math.pi * R * g * 1e-3 * xr.ones_like(
        C10 * t * h), **GRID)
    r = analysis.jkr_ratio(ds)
    assert r.attrs["units"] == "1" and np.allclose(r, 1.0, rtol=1e-14)


@pytest.mark.parametrize("values,verdict", [
    ([1.0, 1.1, 1.3, 1.6], "increasing"),
    ([2.0, 1.7, 1.5, 1.45], "decreasing"),
    ([1.0, 1.2, 1.1, 1.3], "non-monotonic"),
    ([1.0, 1.004, 0.997, 1.003], "flat"),          # every change within 2 x 0.5 %
    ([-1.0, -1.004, -0.997], "flat"),               # magnitudes: tension is negative
    ([1.0, 1.008, 1.016, 1.024], "increasing"),     # small steps, significant in all
    ([1.0, 1.2, 1.201, 1.4], "increasing"),         # an insignificant step does not break it
])
def test_trend_verdicts(values, verdict):
    assert analysis.trend_of(values, 0.005) == verdict


def test_trend_on_a_cube_states_numbers_and_the_claim():
    ds = synthetic_cube(lambda C10, t, h, g: -1.7 * (1 + 0.001 * h / R) * xr.ones_like(C10 * t * g),
                        h_over_R=(0.5, 0.75, 1.0), mesh="fine")
    tr = analysis.trend(ds, "h_over_R")
    assert tr.verdict == "flat" and tr.claim == "flat" and tr.agrees
    assert tr.uncertainty == analysis.MESH_UNCERTAINTY["fine"]
    assert "1.701 N at 0.5" in tr.sentence and "paper: flat" in tr.sentence
    ds = synthetic_cube(lambda C10, t, h, g: -1.7 * (1.5 - C10) * xr.ones_like(t * h * g),
                        C10=(0.1, 0.3, 1.0))
    tr = analysis.trend(ds, "C10")
    assert tr.verdict == "decreasing" and tr.agrees is False and "DISAGREES" in tr.sentence
    assert tr.change == pytest.approx(0.5 / 1.4 - 1)


# the small real study (coarse mesh): what the paper says, and what the cube can answer

@pytest.fixture(scope="module")
def small(small_study):
    return analysis.open_results(small_study)


def test_base_point_and_along(small):
    assert analysis.base_point(small) == {"C10": 0.3, "t_over_R": 0.15, "h_over_R": 1.0,
                                          "gamma": 30.0}
    x = analysis.along(small, "P_star", "gamma")
    assert list(x["gamma"].values) == [20.0, 30.0, 40.0]
    assert float(x.sel(gamma=30.0)) == float(small["P_star"].sel(
        C10=0.3, t_over_R=0.15, h_over_R=1.0, gamma=30.0))
    off = analysis.along(small, "P_star", "C10", gamma=20.0)     # off the C10 sweep line
    assert list(off["C10"].values) == [0.3]


def test_small_study_trends_and_fits(small, forbid_fe):
    verdicts = {t.dim: t.verdict for t in analysis.trends(small)}
    assert verdicts == {"C10": "increasing", "t_over_R": "increasing", "h_over_R": "flat",
                        "gamma": "increasing"}
    fit = analysis.eta_fit(small)
    assert fit.n == 7 and 5 < fit.eta < 15 and fit.ci[0] < fit.eta < fit.ci[1]
    s = analysis.gamma_slope(small)
    assert 0.03 < s.slope < 0.07 and s.ratio_to_jkr < 1
    r = analysis.jkr_ratio(small).where(small["status"] == "ok")
    assert 0.3 < float(r.min()) <= float(r.max()) < 1.0


def test_paper_comparison_of_small_study(small):
    cmp = analysis.paper_comparison(small)
    rows = {r.quantity: r for r in cmp.rows}
    p = rows["P* (fixed load), gamma = 30 J/m^2"]
    assert p.paper == -1.70 and abs(p.difference_pct) < 3
    assert "P on our curve at a = 2.13 mm" in rows and "slope d|P*|/dgamma" in rows
    # delta_max = 2 mm, no relaxation curves, no t/R = 0.225 or solid cap in this cube
    assert len(cmp.skipped) == 4 and any("5 mm" in s for s in cmp.skipped)
    other = small.assign_attrs(base_C10_MPa=0.2)
    assert analysis.base_point(other)["C10"] == 0.2
    assert analysis.paper_comparison(other).rows == ()


def test_relaxation_curves_give_fig2b_row(small):
    """With relaxation curves in the cube (held contact radius, delta reduced), P at
    delta = 0 for a = 10 mm is interpolated in a between the paths."""
    a = np.array([9.0, 9.5, 10.5, 11.0])
    delta = np.linspace(2.0, -1.0, 7)
    P_at_0 = -30.0 - 13.0 * (a - 9.0)                      # N; linear in a
    P = P_at_0[:, None] + 20.0 * delta[None, :]            # linear in delta
    shell = dict(t_over_R=[0.15], h_over_R=[1.0])
    rel = xr.Dataset({
        "relaxation_a_mm": (("t_over_R", "h_over_R", "relaxation"), a[None, None]),
        "relaxation_delta_mm": (("t_over_R", "h_over_R", "relaxation", "relaxation_state"),
                             np.broadcast_to(delta, (1, 1, 4, 7))),
        "relaxation_P": (("C10", "t_over_R", "h_over_R", "relaxation", "relaxation_state"),
                         P[None, None, None])}, coords=dict(C10=[0.3], **shell))
    rel["relaxation_used"] = rel["relaxation_a_mm"] * 0 + 1
    rel["relaxation_used"][..., 1] = 0                     # left out: no row from it
    ds = small.drop_dims(["relaxation", "relaxation_state"], errors="ignore")
    ds = ds.merge(rel.reindex_like(ds[["C10", "t_over_R", "h_over_R"]]))
    rows = {r.quantity: r for r in analysis.paper_comparison(ds).rows}
    assert rows["P at delta = 0, a = 10 mm held"].ours == pytest.approx(-30.0 - 13.0)
    rel["relaxation_used"][..., 2:] = 0                    # no used path beyond 10 mm
    ds = ds.drop_dims(["relaxation", "relaxation_state"]).merge(
        rel.reindex_like(ds[["C10", "t_over_R", "h_over_R"]]))
    cmp = analysis.paper_comparison(ds)
    assert not any("held" in r.quantity for r in cmp.rows)
    assert any("Fig. 2b" in s for s in cmp.skipped)
