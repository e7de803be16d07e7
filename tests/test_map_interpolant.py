"""The pull-off map's interpolant on synthetic maps (no FE): exact on what it should be
exact on, an error estimate that bounds the true error of smooth data, holes refused."""
import math

import numpy as np
import pytest
import xarray as xr

from shell_adhesion.analysis.design_search import cap_volume_mm3, search
from shell_adhesion.analysis.pull_off_map import (QUANTITIES, MapError, PullOffMap, curvatures,
                                                  leave_out_errors)

# the shipped maps' grid (shell_adhesion/data/pull_off_map.yaml)
T = np.array([0.05, 0.075, 0.1, 0.125, 0.15, 0.2, 0.3, 0.4])
H = np.array([0.5, 0.75, 1.0])
G = np.array([6, 8, 10, 12.5, 16, 20, 25, 30, 40, 50, 60, 80, 100, 125, 150, 200, 250, 300,
              400, 500, 600]) / 20e3


def synthetic_map(flat_P, P_error=0.0):
    """A map whose P* / (pi gamma_hat) is flat_P(ln t, h, ln g); the other quantities
    follow their JKR scalings times 1 + ln t / 10 (smooth)."""
    lt, h, lg = np.meshgrid(np.log(T), H, np.log(G), indexing="ij")
    g = np.exp(lg)
    data = {}
    for q in QUANTITIES:
        if q.startswith("P") or q == "preload":
            value = math.pi * g * flat_P(lt, h, lg) * (1 if q != "preload" else -1)
        elif q.startswith("a"):
            value = g ** (1 / 3) * (1 + lt / 10)
        else:
            value = g ** (2 / 3) * (1 + lt / 10)
        data[q] = (("t_over_R", "h_over_R", "gamma_hat"), value)
        data[f"{q}_error"] = (("t_over_R", "h_over_R", "gamma_hat"), np.abs(value) * P_error)
    return xr.Dataset(data, coords=dict(t_over_R=T, h_over_R=H, gamma_hat=G),
                      attrs=dict(interface="no_slip", mesh="coarse"))


def test_linear_data_is_interpolated_exactly():
    pm = PullOffMap(synthetic_map(lambda lt, h, lg: -1.5 + 0.2 * lt - 0.3 * h + 0.05 * lg))
    t, h, g = 0.13, 0.61, 0.0042          # the sheared lines stay inside the gamma range
    ans = pm.predict(t, h, g)["P_star"]
    exact = math.pi * g * (-1.5 + 0.2 * math.log(t) - 0.3 * h + 0.05 * math.log(g))
    assert ans.value == pytest.approx(exact, rel=1e-12, abs=1e-15)
    # without a gamma dependence the clamping at the gamma range's ends changes nothing:
    # the leave-out misses, and so the stated error, vanish
    flat_in_gamma = PullOffMap(synthetic_map(lambda lt, h, lg: -1.5 + 0.2 * lt - 0.3 * h))
    ans = flat_in_gamma.predict(t, h, g)["P_star"]
    assert ans.interpolation_error < 1e-12 * abs(ans.value) + 1e-15


def test_leave_out_gives_the_curvature_of_a_parabola_on_any_spacing():
    x = np.linspace(0.0, 1.0, 6)
    miss = leave_out_errors(x ** 2, [x])[0]
    assert np.allclose(miss, (x[1] - x[0]) ** 2, rtol=1e-12, atol=1e-15)
    uneven = np.array([0.0, 0.1, 0.35, 0.5, 0.9, 1.0])
    assert np.allclose(curvatures(3 * uneven ** 2, [uneven])[0], 6.0, rtol=1e-12)


def test_stated_error_bounds_the_true_error_of_curved_data():
    def f(lt, h, lg):
        return -1.5 - 0.4 * np.sin(lt) * h ** 2 + 0.02 * lg ** 2
    pm = PullOffMap(synthetic_map(f))
    rng = np.random.default_rng(3)
    for _ in range(200):
        t = math.exp(rng.uniform(math.log(T[0]), math.log(T[-1])))
        h, g = rng.uniform(H[0], H[-1]), math.exp(rng.uniform(math.log(G[0]), math.log(G[-1])))
        ans = pm.predict(t, h, g)["P_star"]
        exact = math.pi * g * f(math.log(t), h, math.log(g))
        assert abs(ans.value - exact) <= ans.interpolation_error, (t, h, g)
        assert ans.interpolation_error > 0


def test_fe_error_bar_adds_in_quadrature():
    pm = PullOffMap(synthetic_map(lambda lt, h, lg: -1.5 + 0 * lt, P_error=0.01))
    ans = pm.predict(0.15, 0.8, 0.005)["P_star"]
    assert ans.interpolation_error < 1e-12
    assert ans.fe_error == pytest.approx(0.01 * abs(ans.value), rel=1e-9)
    assert ans.error == pytest.approx(math.hypot(ans.interpolation_error, ans.fe_error))


def test_outside_the_map_and_holes_are_refused_by_name():
    ds = synthetic_map(lambda lt, h, lg: -1.5 + 0 * lt)
    pm = PullOffMap(ds)
    with pytest.raises(MapError, match=r"t_over_R = 0.5 is outside the map \[0.05, 0.4\]"):
        pm.predict(0.5, 0.8, 0.005)
    with pytest.raises(MapError, match="gamma_hat = 0.1 is outside"):
        pm.predict(0.2, 0.8, 0.1)
    ds["P_star"][5, 1, 10] = np.nan
    ds["reason"] = (("t_over_R", "h_over_R", "gamma_hat"), np.full(ds["P_star"].shape, "", dtype=object))
    ds["reason"][5, 1, 10] = "loading stalled"
    holed = PullOffMap(ds)
    with pytest.raises(MapError, match="no pull-off at its grid point t_over_R 0.2, "
                                       "h_over_R 0.75, gamma_hat 0.003 .loading stalled."):
        holed.predict(0.2, 0.8, 0.0029)
    assert holed.predict(0.07, 0.6, 0.002)["P_star"].value < 0     # away from the hole


def test_units_follow_the_scaling():
    pm = PullOffMap(synthetic_map(lambda lt, h, lg: -1.5 + 0.1 * lt))
    dimensionless = pm.predict(0.15, 1.0, 30e-3 / (0.3 * 20))
    out = pm.shell(R_mm=20, t_mm=3, h_mm=20, C10_MPa=0.3, gamma_J_m2=30)
    assert out["P_star_N"][0] == pytest.approx(dimensionless["P_star"].value * 0.3 * 400)
    assert out["a_star_mm"][0] == pytest.approx(dimensionless["a_star"].value * 20)


def test_cap_volume_closed_forms():
    R = 20.0
    assert cap_volume_mm3(R, R, R) == pytest.approx(2 / 3 * math.pi * R ** 3)   # hemisphere
    assert cap_volume_mm3(R, 1.0, R) == pytest.approx(2 / 3 * math.pi * (R ** 3 - 19.0 ** 3))


def test_search_finds_the_bound_of_a_monotone_map():
    # |P*| grows with t/R and falls with h/R: the optimum is the largest t and smallest h
    pm = PullOffMap(synthetic_map(lambda lt, h, lg: -1.5 - 0.3 * lt + 0.2 * h))
    best = search(pm, 0.3, 30, R_mm=20, t_mm=(2, 6), h_mm=(12, 20))
    assert best.t_mm == pytest.approx(6, rel=1e-3) and best.h_mm == pytest.approx(12, rel=1e-3)
    assert "t at its upper bound 6 mm (your bound)" in best.on_bounds
    assert "h at its lower bound 12 mm (your bound)" in best.on_bounds
    with pytest.raises(ValueError, match="objective: 'most' must be one of"):
        search(pm, 0.3, 30, "most", R_mm=20)


def test_fe_error_is_the_grid_points_bars_with_the_interpolations_weights():
    """Bars of 1 % on a P* linear in (ln t, h): the answer's FE error is the linear
    interpolant of the bars, 1 % of the answer (a bound, the weights being >= 0 with sum
    1), less than the largest bar of the cell, which a maximum over it would give."""
    pm = PullOffMap(synthetic_map(lambda lt, h, lg: -1.5 + 0.2 * lt - 0.3 * h, P_error=0.01))
    t, h, g = 0.13, 0.61, 0.0042
    ans = pm.predict(t, h, g)["P_star"]
    assert ans.fe_error == pytest.approx(0.01 * abs(ans.value), rel=1e-9)
    i, j = np.searchsorted(T, t), np.searchsorted(H, h)
    largest = math.pi * g * 0.01 * max(abs(-1.5 + 0.2 * math.log(T[a]) - 0.3 * H[b])
                                       for a in (i - 1, i) for b in (j - 1, j))
    assert ans.fe_error < 0.99 * largest
