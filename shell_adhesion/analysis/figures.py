"""The paper's figures regenerated from a results cube (matplotlib; never runs the FE).

Each `fig_*` function takes the Dataset written by `shell-adhesion run`, draws into the
caller's Axes (`ax=`, or `axes=` for several panels) or into a new Figure (no pyplot
state), and returns its Axes (an array of Axes for several panels).  Colours: the viridis
family.  Shell-level figures are drawn for the
study's base point unless `at` names other coordinates (C10 MPa, t_over_R, h_over_R,
gamma J/m^2).  Units: lengths mm, forces N, energies mJ, stresses MPa; P > 0
compression, delta > 0 approach.  A cube that sweeps a material ratio (a dimension such as
C01_over_C10) draws one curve per material value, labelled, in the sweep figures (Fig. 6)
and in `fig_materials` (loading curves and pull-off against the ratio); the shell-level
figures (Figs. 2 to 5) are drawn for its base solid (`slices.base_material`).  Fig. 5 rebuilds U_E(a, delta) from the stored
relaxation curves with `shell_adhesion.energy` (interpolation only).

    shell-adhesion plot results/paper.nc --out results/figures
"""
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
import itertools
import multiprocessing as mp
from pathlib import Path
import threading

import numpy as np
from matplotlib import colormaps
from scipy.interpolate import CubicHermiteSpline
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle
from matplotlib.tri import Triangulation

from shell_adhesion.atomic import atomic_path
from shell_adhesion.cube import DIMS
from shell_adhesion.energy import (energy_surface, total_energy_fixed_grips,
                                   total_energy_fixed_load)
from shell_adhesion.theory import jkr_P_star_N, shell_law_scale_N

from .fits import eta_fit
from .results import along, base_point
from .slices import base_material, material_label

SWEEPS = (("C10", "C10 [MPa]"), ("t_over_R", "t/R [1]"), ("h_over_R", "h/R [1]"),
          ("gamma", "gamma [J/m$^2$]"))

CLIP_PERCENTILE = 99.0
CMAP = "viridis"            # sequences of curves and the stress maps
MIN_DPI = 100               # the least resolution of a PNG meant to be read (README copies)


class MissingData(ValueError):
    """The cube lacks what a figure needs (e.g. written with that output turned off)."""


def _point(ds, at):
    """The base point (or `at` over it); MissingData unless it was evaluated."""
    p = base_point(ds)
    p.update(at or {})
    status = str(ds["status"].sel(p).values)
    if status != "ok":
        raise MissingData(f"the point {p} was not evaluated ({status})")
    return p


def _any_ok(ds):
    if not int((ds["status"] == "ok").sum()):
        raise MissingData("no point of the study was evaluated")


def _need(ds, *names):
    missing = [n for n in names if n not in ds]
    if missing:
        raise MissingData(f"the cube has no {', '.join(missing)} (turn the study's outputs on)")


def _shell(ds, p):
    return dict(t_over_R=p["t_over_R"], h_over_R=p["h_over_R"])


def _axes(given, n, figsize, **subplots):
    """(flat array of n Axes, whether they are new): the caller's, or a new Figure's."""
    if given is not None:
        axes = np.ravel(np.asarray(given, dtype=object))
        if len(axes) != n:
            raise ValueError(f"this figure needs {n} Axes, got {len(axes)}")
        return axes, False
    fig = Figure(figsize=figsize, layout="constrained")
    return np.ravel(np.asarray(fig.subplots(squeeze=False, **subplots), dtype=object)), True


def _drawn(artist) -> bool:
    """Whether an artist shows something: a line with a visible segment or marker, a
    non-empty patch collection, an error-bar plot whose line shows."""
    if hasattr(artist, "lines"):        # ErrorbarContainer: its data line decides
        return artist.lines[0] is not None and _drawn(artist.lines[0])
    if hasattr(artist, "get_xydata"):
        xy = artist.get_xydata()
        n = int(np.isfinite(xy).all(axis=1).sum()) if len(xy) else 0
        has_line = artist.get_linestyle() not in ("None", "", " ") and n >= 2
        has_marker = artist.get_marker() not in ("None", "", " ", None) and n >= 1
        return artist.get_visible() and (has_line or has_marker)
    paths = getattr(artist, "get_paths", lambda: [None])()
    return artist.get_visible() and len(paths) > 0


def _legend(ax, **kw):
    """A legend of the labelled artists that show something (none if there are none)."""
    handles, labels = ax.get_legend_handles_labels()
    pairs = [(h, lab) for h, lab in zip(handles, labels) if _drawn(h)]
    if pairs:
        ax.legend(*zip(*pairs), **kw)


def figure_of(axes) -> Figure:
    """The Figure holding what a `fig_*` function returned."""
    return np.ravel(np.asarray(axes, dtype=object))[0].figure


def materials(ds) -> list:
    """[(label, cube)]: the cube at each value of its swept material ratios (dimensions
    besides DIMS), labelled e.g. "C01/C10 = 0.2"; [(None, ds)] if it sweeps none."""
    names = [d for d in ds["status"].dims if d not in DIMS]
    if not names:
        return [(None, ds)]
    out = []
    for values in itertools.product(*(ds[n].values for n in names)):
        at = dict(zip(names, (float(v) for v in values)))
        out.append((_ratios_label(at), ds.sel(at)))
    return out


def _ratios_label(at: dict) -> str:
    return ", ".join(f"{_RATIO_LABELS.get(n, n)} = {v:g}" for n, v in at.items())


def _base_and_others(ds):
    """(label, cube) of the base solid (`slices.base_material`), and [(label, cube)] of
    the other swept solids; (None, ds, []) for a cube that sweeps no ratio."""
    solids = materials(ds)
    if solids[0][0] is None:
        return None, ds, []
    base = base_material(ds)
    names = [d for d in ds["status"].dims if d not in DIMS]
    is_base = [all(float(m[n]) == float(base[n]) for n in names) for _, m in solids]
    k = is_base.index(True)
    return solids[k][0], solids[k][1], solids[:k] + solids[k + 1:]


_RATIO_LABELS = {"C01_over_C10": "C01/C10", "C20_over_C10": "C20/C10",
                 "C30_over_C10": "C30/C10", "D1_times_C10": "D1 C10"}


def _title(ds, p, with_gamma=True):
    R = float(ds["R"])
    s = (f"R = {R:g} mm, t = {p['t_over_R'] * R:g} mm, h = {p['h_over_R'] * R:g} mm, "
         f"C10 = {p['C10']:g} MPa")
    s = s + (f", gamma = {p['gamma']:g} J/m$^2$" if with_gamma else "")
    return s + (f"; {material_label(ds)[0]}" if "material" in ds.attrs else "")


def _section(ds, j, shell):
    """(r, z) of the closed cross-section outline of profile j (outer, then inner back)."""
    pr = ds[[f"profile_{s}_{c}" for s in ("outer", "inner") for c in "rz"]].sel(shell)
    ro, zo = pr["profile_outer_r"].values[j], pr["profile_outer_z"].values[j]
    ri, zi = pr["profile_inner_r"].values[j], pr["profile_inner_z"].values[j]
    ro, zo = ro[~np.isnan(ro)], zo[~np.isnan(zo)]
    ri, zi = ri[~np.isnan(ri)], zi[~np.isnan(zi)]
    return np.concatenate([ro, ri[::-1]]), np.concatenate([zo, zi[::-1]])


def fig_profiles(ds, at=None, axes=None):
    """Fig. 3: deformed cross-sections (a) under loading, (b) relaxing at the largest a.
    Two Axes."""
    _need(ds, "profile_stage", "profile_outer_r")
    p = _point(ds, at)
    shell = _shell(ds, p)
    stage = ds["profile_stage"].sel(shell).values.astype(str)
    delta = ds["profile_delta"].sel(shell).values
    P = ds["profile_P"].sel(C10=p["C10"], **shell).values
    a = ds["profile_a"].sel(shell).values
    axes, new = _axes(axes, 2, (10, 4.8), ncols=2, sharey=True)
    for ax, name in zip(axes, ("loading", "relaxation")):
        idx = np.flatnonzero(stage == name)
        for c, j in zip(_colours(len(idx)), idx):
            r, z = _section(ds, j, shell)
            ax.plot(r, z, color=c, lw=1.2,
                    label=f"delta = {delta[j]:.2f} mm, P = {np.round(P[j], 2) + 0.0:.2f} N")
        ax.axhline(0.0, color="k", lw=2)
        ax.set_aspect("equal")
        ax.set_xlabel("radius r [mm]")
        _legend(ax, fontsize=7, loc="upper left", frameon=False)
        if name == "loading":
            ax.set_title("(a) loading without adhesion (a grows with delta)", fontsize=10)
        elif len(idx):
            ax.set_title(f"(b) unloading at fixed contact radius a = {a[idx[0]]:.2f} mm",
                         fontsize=10)
        else:
            ax.set_title("(b) no relaxation profiles stored", fontsize=10)
    axes[0].set_ylabel("height z [mm] (plane at z = 0)")
    if new:
        figure_of(axes).suptitle("Deformed cross-sections; " + _title(ds, p, with_gamma=False),
                                 fontsize=10)
    return axes


def _colours(n):
    return colormaps[CMAP](np.linspace(0, 0.9, max(n, 1)))


def _relaxation(ds, p, k):
    """(delta [mm], P [N], dP/ddelta [N/mm]) at the states of relaxation path k of the
    shell at `p` (NaN padding removed)."""
    shell = _shell(ds, p)
    d = ds["relaxation_delta_mm"].sel(shell).values[k]
    P = ds["relaxation_P"].sel(C10=p["C10"], **shell).values[k]
    dP = ds["relaxation_dP_ddelta"].sel(C10=p["C10"], **shell).values[k]
    keep = ~np.isnan(d)
    return d[keep], P[keep], dP[keep]


def _relaxation_curve(ds, p, k, per_step=12):
    """(delta [mm], P [N]) along relaxation path k, decreasing delta: the cubic Hermite
    curve through its states (P and dP/ddelta), `per_step` points per step, for plots."""
    d, P, dP = _relaxation(ds, p, k)
    if len(d) < 2:
        return d, P
    o = np.argsort(d)
    curve = CubicHermiteSpline(d[o], P[o], dP[o])
    fine = np.interp(np.linspace(0, len(d) - 1, per_step * (len(d) - 1) + 1),
                     np.arange(len(d)), d)
    return fine, curve(fine)


def fig_load_relaxation(ds, at=None, n_paths=8, ax=None):
    """Fig. 4: P(delta) on loading and on relaxation paths, with the energies of one
    equilibrium state B shaded: U_E (loading area minus the area recovered along AB)
    and the load's potential U_P = -P delta.  One Axes."""
    _need(ds, "loading_delta_mm", "loading_P", "relaxation_delta_mm", "relaxation_P",
          "a_eq_mm", "delta_eq", "P_eq")
    p = _point(ds, at)
    shell = _shell(ds, p)
    ld = ds["loading_delta_mm"].sel(shell).values
    lP = ds["loading_P"].sel(C10=p["C10"], **shell).values
    keep = ~np.isnan(ld)
    ld, lP = ld[keep], lP[keep]
    ra = ds["relaxation_a_mm"].sel(shell).values
    n = int(np.sum(~np.isnan(ra)))
    (ax,), new = _axes(ax, 1, (7.5, 5.4))
    colours = colormaps[CMAP]([0.0, 0.3, 0.55, 0.8])     # loading, AB, U_E, P delta
    ax.plot(ld, lP, color=colours[0], lw=2.2, label="loading, gamma = 0 (OA)")
    # the shaded example: the path whose a is nearest the equilibrium at P = 0 (a0)
    eq = ds[["delta_eq", "P_eq"]].sel(p)
    ok = ~np.isnan(eq["a_eq_mm"].values)
    a_eq, d_eq = eq["a_eq_mm"].values[ok], eq["delta_eq"].values[ok]
    a0 = float(ds["a0"].sel(p))
    target = a0 if np.isfinite(a0) else float(np.median(a_eq))
    k = int(np.nanargmin(np.abs(ra - target)))
    others = [i for i in range(n) if i != k]      # grey: n_paths - 1 others, evenly in a
    pick = np.unique(np.linspace(0, len(others) - 1, min(n_paths - 1, len(others))).round())
    for m, i in enumerate(others[int(j)] for j in pick):
        d, P = _relaxation_curve(ds, p, i)
        ax.plot(d, P, color="0.6", lw=0.8,
                label="other relaxations at fixed a (steeper: larger a)" if m == 0 else None)
    d, P = _relaxation_curve(ds, p, k)
    dB = float(np.interp(ra[k], a_eq, d_eq))
    PB = float(np.interp(dB, d[::-1], P[::-1]))
    d1, P1 = d[0], P[0]
    ax.plot(d, P, color=colours[1], lw=1.8, label=f"relaxation at a = {ra[k]:.2f} mm (AB)")
    on = ld <= d1
    UA = float(np.trapezoid(lP[on], ld[on]))
    ax.fill_between(ld[on], 0, lP[on], color=colours[2], alpha=0.35,
                    label=f"U_E at A = area under OA: {UA:.3g} mJ")
    part = d >= dB
    W = float(np.trapezoid(P[part][::-1], d[part][::-1]))
    ax.fill_between(d[part], 0, P[part], facecolor="none", edgecolor=colours[1], hatch="//",
                    label=f"signed area under AB, int P d(delta) = {W:.3g} mJ")
    ax.fill_between([0, dB], 0, PB, color=colours[3], alpha=0.35,
                    label=f"rectangle P delta at B = -U_P: {PB * dB:.3g} mJ")
    A_B = np.pi * ra[k] ** 2
    ax.text(0.98, 0.03, f"at B: U_E = {UA:.3g} - ({W:.3g}) = {UA - W:.3g} mJ, "
            f"U_P = {-PB * dB:.3g} mJ,\ngamma A = {p['gamma'] * 1e-3 * A_B:.3g} mJ, "
            f"U_T = U_E + U_P - gamma A = {UA - W - PB * dB - p['gamma'] * 1e-3 * A_B:.3g} mJ",
            transform=ax.transAxes, ha="right", va="bottom", fontsize=8)
    ax.plot([d1], [P1], "ko")
    ax.plot([dB], [PB], "kD")
    ax.annotate("A", (d1, P1), textcoords="offset points", xytext=(5, 5))
    ax.annotate(f"B: equilibrium, gamma = {p['gamma']:g} J/m$^2$", (dB, PB),
                textcoords="offset points", xytext=(8, -12))
    ax.axhline(0, color="k", lw=0.5)
    ax.axvline(0, color="k", lw=0.5)
    ax.set_xlabel("rim displacement delta [mm] (approach > 0)")
    ax.set_ylabel("rim force P [N] (compression > 0)")
    ax.set_title("Loading and relaxation at fixed contact radius (Maugis' energies)\n"
                 + _title(ds, p), fontsize=9)
    _legend(ax, fontsize=8, loc="upper left")
    return ax


def _surface(ds, p):
    """U_E(a, delta) of the shell at `p`, dimensionless, from the stored relaxation
    curves (the paths the energy method used, as in PathSet.surface, with the areas they
    cover where the cube has them)."""
    shell = _shell(ds, p)
    R, C10 = float(ds["R"]), p["C10"]
    a = ds["relaxation_a_mm"].sel(shell).values
    used = ds["relaxation_used"].sel(shell).values == 1
    paths = []
    for k in np.flatnonzero(used & ~np.isnan(a)):
        d, P, dP = _relaxation(ds, p, k)
        U = ds["relaxation_U"].sel(C10=C10, **shell).values[k][:len(d)]
        path = (a[k] / R, d / R, P / (C10 * R ** 2), U / (C10 * R ** 3), dP / (C10 * R))
        if "relaxation_edge_mm" in ds:      # the covered radius along the path
            edge = ds["relaxation_edge_mm"].sel(shell).values[k][:len(d)] / R
            slope = ds["relaxation_dedge_ddelta"].sel(shell).values[k][:len(d)]
            path += (edge, slope)
        paths.append(path)
    paths.sort(key=lambda x: x[0])
    return energy_surface(paths)


def fig_energy(ds, at=None, n_curves=7, axes=None):
    """Fig. 5: total energy U_T(A) at fixed load (a) and at fixed grips (b), for loads
    from P* to -P* and displacements from delta_dagger to -delta_dagger, the equilibrium
    locus G = gamma through their minima and the pull-off states marked; beside each, a
    zoom on the pull-off state.  Four Axes: (a), its zoom, (b), its zoom."""
    _need(ds, "relaxation_U", "relaxation_used", "P_eq", "delta_eq", "stable_fixed_load",
          "stable_fixed_grips")
    p = _point(ds, at)
    R, C10 = float(ds["R"]), p["C10"]
    g = p["gamma"] * 1e-3 / (C10 * R)
    s = _surface(ds, p)
    eq = ds[["P_eq", "delta_eq", "stable_fixed_load", "stable_fixed_grips"]].sel(p)
    po = {k: float(ds[k].sel(p)) for k in ("P_star", "a_star", "delta_dagger", "a_dagger",
                                           "P_dagger")}
    units = (R ** 2, C10 * R ** 3)         # mm^2 and mJ per dimensionless unit
    axes, new = _axes(axes, 4, (11, 9.5), nrows=2, ncols=2, width_ratios=(2.2, 1))
    top, top_zoom, bottom, bottom_zoom = axes
    P_star = po["P_star"] / (C10 * R ** 2)
    hi = min(np.max(eq["P_eq"].values[eq["stable_fixed_load"].values == 1]) / (C10 * R ** 2),
             -P_star)
    _family(top, top_zoom, lambda P: total_energy_fixed_load(s, g, P),
            np.linspace(P_star, hi, n_curves), lambda P: f"P = {P * C10 * R ** 2:.2f} N", units,
            (P_star, po["a_star"] / R, f"fixed-load pull-off P* = {po['P_star']:.3f} N"))
    top.set_title("(a) fixed load P", fontsize=10)
    d_dagger = po["delta_dagger"] / R
    hi = min(np.max(eq["delta_eq"].values[eq["stable_fixed_grips"].values == 1]) / R,
             -d_dagger)
    _family(bottom, bottom_zoom, lambda d: total_energy_fixed_grips(s, g, d),
            np.linspace(d_dagger, hi, n_curves), lambda d: f"delta = {d * R:.3f} mm", units,
            (d_dagger, po["a_dagger"] / R, f"fixed-grips pull-off delta = "
             f"{po['delta_dagger']:.3f} mm, P = {po['P_dagger']:.3f} N"))
    bottom.set_title("(b) fixed grips delta", fontsize=10)
    for ax in axes:
        ax.set_xlabel("contact area A = pi a$^2$ [mm$^2$]")
        ax.set_ylabel("total energy U_T [mJ]")
    for ax in (top, bottom):
        ax.set_xlim(left=0)
        _legend(ax, fontsize=7, loc="upper right")
    if new:
        figure_of(axes).suptitle("Total energy against contact area (Maugis' graphical "
                                 "method), " + _title(ds, p), fontsize=10)
    return axes


# half-width of the zoom panels of Fig. 5, as a fraction of the pull-off area
ZOOM = 0.6


def _family(ax, zoom, energy, levels, label, units, pull_off):
    """U_T(A) curves at each level (the first is the pull-off one, drawn last and thick),
    their interior minima and the locus through them, clipped to 1.6 times the largest
    equilibrium area; on `zoom`, the pull-off curve around its state, where it has an
    inflection with a horizontal tangent (the minimum just disappears)."""
    A_u, U_u = units
    curves = [(level, *energy(level)) for level in levels[1:]]
    curves = [c for c in curves if len(c[1]) >= 3]
    minima = [(i, _interior_minimum(UT)) for i, (_, _, UT) in enumerate(curves)]
    minima = [(i, j) for i, j in minima if j is not None]
    A_max = 1.6 * max([curves[i][1][j] for i, j in minima], default=np.inf)
    colours = _colours(len(curves))
    for c, (level, A, UT) in zip(colours, curves):
        keep = A <= A_max
        ax.plot(A[keep] * A_u, UT[keep] * U_u, color=c, lw=1.2, label=label(level))
    for i, j in minima:
        _, A, UT = curves[i]
        ax.plot(A[j] * A_u, UT[j] * U_u, "o", mfc="none", color=colours[i])
    ax.plot([curves[i][1][j] * A_u for i, j in minima], [curves[i][2][j] * U_u for i, j in minima],
            "k--", lw=1, label="equilibrium G = gamma (minima)")
    level, a, text = pull_off
    A, UT = energy(level)
    zoom.set_title("zoom on the pull-off state (box at left)", fontsize=9)
    if len(A) < 2:
        zoom.text(0.5, 0.5, "no pull-off curve", ha="center", transform=zoom.transAxes)
        return
    keep = A <= A_max
    A0 = np.pi * a ** 2
    U0 = float(np.interp(A0, A, UT))
    red = colormaps["magma"](0.55)
    star = dict(color=red, ms=13, mec="k", mew=0.5)
    ax.plot(A[keep] * A_u, UT[keep] * U_u, color=red, lw=2.2, label=text)
    ax.plot([A0 * A_u], [U0 * U_u], "*", **star)
    lo, hi = A0 * (1 - ZOOM), A0 * (1 + ZOOM)
    near = (A >= lo) & (A <= hi)
    zoom.plot(A[near] * A_u, UT[near] * U_u, ".-", color=red, lw=1.8,
              label="pull-off curve (dots: FE contact states)")
    zoom.plot([A0 * A_u], [U0 * U_u], "*", label="pull-off state", **star)
    zoom.axhline(U0 * U_u, color="0.5", lw=0.8, ls=":", label="horizontal tangent")
    y = UT[near] * U_u
    span = max(float(np.ptp(y)) if len(y) else 0.0, 1e-9 * max(abs(U0 * U_u), 1.0))
    zoom.set_xlim(lo * A_u, hi * A_u)
    zoom.set_ylim(U0 * U_u - 0.7 * span, U0 * U_u + 0.7 * span)
    _legend(zoom, fontsize=7, loc="upper left")
    ax.add_patch(Rectangle((lo * A_u, U0 * U_u - 0.7 * span), (hi - lo) * A_u, 1.4 * span,
                           fill=False, edgecolor="0.2", lw=1.0, ls="-"))


def _interior_minimum(U):
    i = int(np.argmin(U))
    return i if 0 < i < len(U) - 1 else None


def fig_contact_radius(ds, axes=None):
    """Fig. 6a: contact radius a against load P along each sweep of the study, one panel
    per swept parameter, fixed-load pull-off (P*, a*) marked.  Four Axes."""
    _need(ds, "a_eq_mm", "P_eq")
    _any_ok(ds)
    p = base_point(ds)
    solids = materials(ds)
    axes, new = _axes(axes, 4, (10, 8), nrows=2, ncols=2)
    for ax, (dim, label) in zip(axes, SWEEPS):
        values = np.unique(np.concatenate([along(m, "P_star", dim)[dim].values
                                           for _, m in solids]))
        for i, (c, v) in enumerate(zip(_colours(len(values)), values)):
            q = dict(p, **{dim: float(v)})
            for j, (name, m) in enumerate(solids):
                if str(m["status"].sel(q).values) != "ok":
                    continue
                P = m["P_eq"].sel(q)
                a = P["a_eq_mm"].values
                keep = ~np.isnan(a)
                # colour: the swept value; line style: the material (labelled once each)
                text = ", ".join(t for t, show in ((_value_label(dim, v), j == 0),
                                                   (name, i == 0 and name)) if show)
                ax.plot(P.values[keep], a[keep], color=c, lw=1.2,
                        ls=_STYLES[j % len(_STYLES)], label=text or None)
                ax.plot(float(m["P_star"].sel(q)), float(m["a_star"].sel(q)), "o", color=c)
        ax.set_xlabel("rim force P [N] (tension < 0)")
        ax.set_ylabel("contact radius a [mm]")
        ax.set_title(f"sweep of {label}" if len(values) > 1 else f"{label}: not swept",
                     fontsize=9)
        _legend(ax, fontsize=7, loc="upper left")
    if new:
        figure_of(axes).suptitle("Contact radius on the equilibrium curve G = gamma; dots: "
                                 "fixed-load pull-off (P*, a*); others at the base point",
                                 fontsize=10)
    return axes


_STYLES = ("-", "--", ":", "-.", (0, (5, 1, 1, 1)), (0, (1, 3)))


def _value_label(dim, v):
    unit = {"C10": " MPa", "gamma": " J/m$^2$"}.get(dim, "")
    name = {"t_over_R": "t/R", "h_over_R": "h/R"}.get(dim, dim)
    return f"{name} = {v:g}{unit}"


def fig_pull_off(ds, axes=None):
    """Fig. 6b: abs(P*) against each swept parameter (with its error bar when the cube has
    them), with JKR (1.5 pi R gamma) and the linear-shell law eq. 3 with eta fitted over the
    evaluated shells (t/R < 1; all points if there are none).  Four Axes."""
    _any_ok(ds)
    name, ds, others = _base_and_others(ds)     # eta is fitted for the base solid
    p = base_point(ds)
    R = float(ds["R"])
    shells = ds["t_over_R"] < 1                 # eq. 3 is a thin-shell law
    fit = eta_fit(ds, where=shells if int(((ds["status"] == "ok") & shells).sum()) else None)
    axes, new = _axes(axes, 4, (10, 8), nrows=2, ncols=2)
    ours, law_c = colormaps[CMAP]([0.3, 0.75])
    jkr_c = "k"
    tones = colormaps[CMAP](np.linspace(0.05, 0.55, len(others) + 1)[1:])
    for ax, (dim, label) in zip(axes, SWEEPS):
        for (other, m), tone in zip(others, tones):
            Pm = along(m, "P_star", dim)
            ax.plot(Pm[dim].values, -Pm.values, "s--", color=tone, ms=4, lw=1.0,
                    label=f"|P*|, {other}")
        P = along(ds, "P_star", dim)
        x = P[dim].values
        q = [dict(p, **{dim: float(v)}) for v in x]
        jkr = [-jkr_P_star_N(R, c["gamma"]) for c in q]
        law = [fit.eta * shell_law_scale_N(R, c["t_over_R"] * R, c["C10"], c["gamma"]) for c in q]
        series = "|P*| (this study)" if name is None else f"|P*|, {name} (base)"
        if "P_star_error" in ds:     # the discretisation error bar (solver.error_bars)
            err = along(ds, "P_star_error", dim).reindex({dim: P[dim]}).values
            ax.errorbar(x, -P.values, yerr=err, fmt="o-", color=ours, capsize=3,
                        label=series + " +- error bar")
        else:
            ax.plot(x, -P.values, "o-", color=ours, label=series)
        ax.plot(x, jkr, "--", marker="x", color=jkr_c, label="JKR 1.5 pi R gamma")
        ax.plot(x, law, ":", marker="+", color=law_c,
                label=f"linear-shell law eq. 3, eta = {fit.eta:.2f} (fit over {fit.n} cases)")
        ax.set_xlabel(label)
        ax.set_ylabel("pull-off force |P*| [N]")
        ax.set_ylim(bottom=0)
        ax.set_title(f"sweep of {label}" if len(x) > 1 else f"{label}: not swept", fontsize=9)
        _legend(ax, fontsize=7)
    if new:
        figure_of(axes).suptitle("Fixed-load pull-off force; others at the base point ("
                                 + _title(ds, p) + ")", fontsize=9)
    return axes


def fig_von_mises(ds, at=None, axes=None):
    """Von Mises stress on the deformed shell (like the paper's Fig. 2): at the end of
    loading and on the widest relaxation path near delta = 0.  One Axes per stored map
    (two for a study's cube), the colour bar beside them."""
    _need(ds, "map_r", "map_von_mises", "map_triangles")
    p = _point(ds, at)
    shell = _shell(ds, p)
    m = ds[["map_stage", "map_a", "map_delta", "map_r", "map_z", "map_triangles"]].sel(shell)
    P = ds["map_P"].sel(C10=p["C10"], **shell).values
    vm = ds["map_von_mises"].sel(C10=p["C10"], **shell).values
    tri = m["map_triangles"].values
    tri = tri[tri[:, 0] >= 0]
    n = int(np.sum(m["map_stage"].values.astype(str) != ""))
    if not n:
        raise MissingData("the cube holds no von Mises map for this shell")
    axes, new = _axes(axes, n, (5.5 * n, 4.8), ncols=n)
    # the contact edge is a crack tip (stress singular under tension): clip the colour
    # scale at a high percentile so the rest of the shell stays readable
    top = float(np.nanpercentile(vm[:n], CLIP_PERCENTILE))
    for j, ax in enumerate(axes):
        r, z = m["map_r"].values[j], m["map_z"].values[j]
        used = np.unique(tri)
        r, z = r[: used.max() + 1], z[: used.max() + 1]
        art = ax.tripcolor(Triangulation(r, z, tri), vm[j][: used.max() + 1],
                           shading="gouraud", cmap=CMAP, vmin=0, vmax=top)
        ax.axhline(0, color="k", lw=2)
        ax.set_aspect("equal")
        ax.set_xlabel("radius r [mm]")
        ax.set_ylabel("height z [mm]")
        stage = str(m["map_stage"].values[j])
        ax.set_title(f"({'abcdefgh'[j % 8]}) {stage}: delta = "
                     f"{float(m['map_delta'].values[j]):.2f} mm, P = {P[j]:.2f} N, "
                     f"a = {float(m['map_a'].values[j]):.2f} mm", fontsize=9)
    fig = figure_of(axes)
    fig.colorbar(art, ax=list(axes), label="von Mises stress [MPa]", shrink=0.8, extend="max")
    if new:
        fig.suptitle("Von Mises stress on the deformed shell; " + _title(ds, p, with_gamma=False)
                     + f"\ncolour scale clipped at the {CLIP_PERCENTILE:g}th percentile of the "
                     f"nodal values; largest {np.nanmax(vm[:n]):.3g} MPa (at the contact edge)",
                     fontsize=10)
    return axes


def fig_materials(ds, axes=None):
    """The swept solids at the base shell: (a) the loading curves P(delta), one per
    material value, (b) the pull-off forces P* and P_dagger and (c) the pull-off
    displacements delta_dagger and delta* against the first swept ratio (one line per
    value of the others).  Three Axes; MissingData for a cube that sweeps no ratio."""
    names = [d for d in ds["status"].dims if d not in DIMS]
    if not names:
        raise MissingData("the study sweeps no material ratio")
    _any_ok(ds)
    p = base_point(ds)
    shell = _shell(ds, p)
    solids = materials(ds)
    axes, new = _axes(axes, 3, (14, 4.4), ncols=3)
    a_ld, a_P, a_d = axes
    if "loading_P" in ds:
        for (name, m), c in zip(solids, _colours(len(solids))):
            ld = m["loading_delta_mm"].sel(shell).values
            lP = m["loading_P"].sel(C10=p["C10"], **shell).values
            keep = ~np.isnan(ld) & ~np.isnan(lP)
            a_ld.plot(ld[keep], lP[keep], color=c, lw=1.2, label=name)
        _legend(a_ld, fontsize=7, loc="upper left")
    else:
        a_ld.text(0.5, 0.5, "no loading curves stored", ha="center", transform=a_ld.transAxes)
    a_ld.set_xlabel("rim displacement delta [mm] (approach > 0)")
    a_ld.set_ylabel("rim force P [N] (compression > 0)")
    a_ld.set_title("(a) loading without adhesion", fontsize=10)
    first, rest = names[0], names[1:]
    at = {d: v for d, v in p.items()}
    point = ds.sel(at)
    lines = [dict(zip(rest, (float(v) for v in values)))
             for values in itertools.product(*(ds[n].values for n in rest))]
    for k, sel in enumerate(lines):
        q = point.sel(sel)
        text = _ratios_label(sel)
        ok = q["status"] == "ok"
        x = q[first].values[ok.values]
        suffix = f" ({text})" if text else ""
        for ax, var, mark, what in ((a_P, "P_star", "o-", "P* (fixed load)"),
                                    (a_P, "P_dagger", "s--", "P$^\\dagger$ (fixed grips)"),
                                    (a_d, "delta_dagger", "o-", "$\\delta^\\dagger$ (fixed grips)"),
                                    (a_d, "delta_star", "s--", "$\\delta$* (fixed load)")):
            ax.plot(x, q[var].values[ok.values], mark, color=f"C{k}", label=what + suffix)
    axis = _RATIO_LABELS.get(first, first)
    for ax, ylabel, t in ((a_P, "pull-off force [N]", "(b) pull-off forces"),
                          (a_d, "rim displacement at pull-off [mm]", "(c) pull-off displacements")):
        ax.set_xlabel(f"{axis} [{ds[first].attrs.get('units', '1')}]")
        ax.set_ylabel(ylabel)
        ax.set_title(t, fontsize=10)
        _legend(ax, fontsize=7)
    if new:
        figure_of(axes).suptitle("Swept material at the base shell: "
                                 + _title(ds, p).split("; ")[0]
                                 + f"; {ds.attrs.get('material_model', '')}", fontsize=10)
    return axes


FIGURES = {
    "fig2_von_mises": fig_von_mises,
    "fig3_profiles": fig_profiles,
    "fig4_load_relaxation": fig_load_relaxation,
    "fig5_energy": fig_energy,
    "fig6a_contact_radius": fig_contact_radius,
    "fig6b_pull_off": fig_pull_off,
}
MATERIAL_FIGURES = {"fig7_materials": fig_materials}   # a cube that sweeps a material ratio
SHELL_FIGURES = ("fig2_von_mises", "fig3_profiles", "fig4_load_relaxation", "fig5_energy")


PROCESSES = 2               # figures drawn side by side (forked, so nothing is imported again)


def _save(fig: Figure, path: Path, dpi):
    """Write atomically (a reader never sees half a file)."""
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=path.suffix[1:], dpi=dpi)


def _draw(name, ds, out: Path, formats, dpi) -> tuple:
    """Figure `name` of `ds` in each format: (written paths, None) or ([], why skipped)."""
    draw = {**FIGURES, **MATERIAL_FIGURES}[name]
    try:
        fig = figure_of(draw(ds))
    except (MissingData, ValueError, KeyError) as e:
        return [], f"{type(e).__name__}: {e}"
    written = []
    for fmt in formats:
        path = out / f"{name}.{fmt}"
        _save(fig, path, dpi)
        written.append(path)
        fig.set_layout_engine("none")   # laid out once: the other formats reuse it
    return written, None


_JOBS = []      # (name, cube) of the figures being drawn, inherited by forked workers


def _draw_job(k, out, formats, dpi):
    name, ds = _JOBS[k]
    return _draw(name, ds, out, formats, dpi)


def _forked_pool(n):
    """A pool of `n` forked processes, or None where forking is not safe: another thread
    (dask's, say) could hold a lock the child would wait for forever, or no fork at all."""
    if n < 2 or threading.active_count() > 1 or "fork" not in mp.get_all_start_methods():
        return None
    return ProcessPoolExecutor(n, mp_context=mp.get_context("fork"))


def _draw_all(jobs, out, formats, dpi, processes) -> list:
    """_draw of every (name, cube) in `jobs`, in order; side by side in forked processes
    when it is safe, else (or if a worker dies) one after the other."""
    pool = _forked_pool(min(processes, len(jobs)))
    if pool is None:
        return [_draw(name, ds, out, formats, dpi) for name, ds in jobs]
    _JOBS[:] = jobs
    try:
        with pool:
            futures = [pool.submit(_draw_job, k, out, formats, dpi) for k in range(len(jobs))]
            return [f.result() for f in futures]
    except BrokenProcessPool:
        return [_draw(name, ds, out, formats, dpi) for name, ds in jobs]
    finally:
        _JOBS.clear()


def write_figures(ds, out_dir, formats=("png", "pdf"), dpi=150, processes=PROCESSES) -> tuple:
    """Draw every figure the cube has data for into `out_dir`: (written paths,
    {figure: reason} for those skipped).  Raster formats at `dpi` (the default, used by
    `shell-adhesion run`, is above MIN_DPI, the least for a figure meant to be read).
    The shell-level figures of a cube that sweeps a material ratio are drawn for its base
    solid, and MATERIAL_FIGURES only for such a cube.  Up to `processes` figures are drawn
    at once (forked workers; 1: in this process)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    swept = any(d not in DIMS for d in ds["status"].dims)
    base = base_material(ds) if swept else ds
    names = [*FIGURES, *(MATERIAL_FIGURES if swept else ())]
    jobs = [(name, base if name in SHELL_FIGURES else ds) for name in names]
    written, skipped = [], {}
    for name, (paths, why) in zip(names, _draw_all(jobs, out, formats, dpi, processes)):
        written += paths
        if why is not None:
            skipped[name] = why
    return written, skipped
