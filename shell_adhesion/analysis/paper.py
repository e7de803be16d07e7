"""Our numbers beside the paper's (DESIGN.md section 4) for what a results cube can answer:
the base shell's pull-off values, the paper's points on our curves, the slope in gamma,
eta of eq. 3 and the solid hemisphere against JKR.  Lengths mm, forces N.
"""
from dataclasses import dataclass
import math

import numpy as np
import xarray as xr
from scipy.interpolate import CubicHermiteSpline, CubicSpline

from shell_adhesion.cube import DIMS
from shell_adhesion.theory import jkr_P_star_N

from .fits import eta_fit, gamma_slope
from .results import R_mm, along, base_point, ok_cases, select, value_at


# the paper's base shell and its numbers (DESIGN.md section 4)
PAPER_SHELL = {"R_mm": 20.0, "C10": 0.3, "t_over_R": 0.15, "h_over_R": 1.0, "gamma": 30.0}


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


def _curve(ds, point):
    """The base point's equilibrium curve as (a, delta, P) arrays, mm and N, or None."""
    if not all(v in ds for v in ("a_eq_mm", "delta_eq", "P_eq")):
        return None
    a, d, P = (select(ds[v], **point).values for v in ("a_eq_mm", "delta_eq", "P_eq"))
    ok = np.isfinite(a) & np.isfinite(d) & np.isfinite(P)
    return (a[ok], d[ok], P[ok]) if ok.sum() >= 4 else None


def _loading_at(ds, point, delta_mm):
    """(P [N], a [mm], node spacing [mm]) at delta on the base shell's loading curve, or
    None if not reached; a is interpolated between the contact events around delta (where
    nodes join)."""
    if not all(v in ds for v in ("loading_delta_mm", "loading_a", "loading_P")):
        return None
    shell = {d: point[d] for d in ("t_over_R", "h_over_R")}
    d = select(ds["loading_delta_mm"], **shell).values
    a = select(ds["loading_a"], **shell).values
    P = select(ds["loading_P"], C10=point["C10"], **shell).values
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
    a = select(ds["relaxation_a_mm"], **shell).values
    D = select(ds["relaxation_delta_mm"], **shell).values
    P = select(ds["relaxation_P"], C10=point["C10"], **shell).values
    K = (select(ds["relaxation_dP_ddelta"], C10=point["C10"], **shell).values
         if "relaxation_dP_ddelta" in ds else np.full_like(P, np.nan))
    # paths the energy method left out (the centre lifts, a free node touches) hold no clean
    # contact zone
    used = (select(ds["relaxation_used"], **shell).values == 1 if "relaxation_used" in ds
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
    P_star = value_at(ds, "P_star")
    if not math.isfinite(P_star):
        return Comparison((), ("all: the base point has no ok result",))
    rows.append(_row("P* (fixed load), gamma = 30 J/m^2", -1.70, P_star, "N"))
    rows.append(_row("delta_dagger (fixed grips)", -0.685, value_at(ds, "delta_dagger"), "mm"))

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
    rows.append(_row("a* (extremum of our curve)", 2.13, value_at(ds, "a_star"), "mm", flat))
    rows.append(_row("delta* (extremum of our curve)", -0.563, value_at(ds, "delta_star"), "mm", flat))
    rows.append(_row("P_dagger (extremum of our curve)", -1.640, value_at(ds, "P_dagger"), "N", flat))
    rows.append(_row("a_dagger (extremum of our curve)", 1.598, value_at(ds, "a_dagger"), "mm", flat))

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

    a_thick = value_at(ds, "a_star", t_over_R=0.225)
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

    solid = value_at(ds, "P_star", t_over_R=1.0)
    if math.isfinite(solid):
        gamma = base["gamma"]
        rows.append(_row("P*, solid hemisphere t/R = 1", jkr_P_star_N(R_mm(ds), gamma), solid,
                         "N", "paper: JKR, -1.5 pi R gamma"))
    else:
        skipped.append("solid hemisphere t/R = 1 against JKR: not in the cube")
    return Comparison(tuple(rows), tuple(skipped))
