"""Tables and figures of a cohesive study's cube (study.cohesive_study), read from the
netCDF, never from the solver; every file written atomically.

    results/<name>_tables/pull_off.{csv,md,tex}   one row per requested point
    results/<name>_figures/pull_off_lambda.png    P* against lambda, one line per shell,
                                                  C10 and gamma (where lambda varies)
    results/<name>_figures/paths.png              the traced P(delta) of every point

Units: N, mm, MPa; P > 0 compression, delta > 0 approach.
"""
from pathlib import Path

import numpy as np
import xarray as xr

from shell_adhesion.atomic import write_text_atomic

from .figures import _save
from .products import Products, figures_dir, tables_dir
from .tables import FORMATS, Table, WithError, render

DIMS = ("C10", "t_over_R", "h_over_R", "gamma", "tabor")
LABELS = {"C10": "C10 {:g} MPa", "t_over_R": "t/R {:g}", "h_over_R": "h/R {:g}",
          "gamma": "gamma {:g} J/m^2", "tabor": "lambda {:g}"}
MOST_PATHS = 24          # paths.png draws at most this many points (the first, in file order)


def _points(ds):
    """(index, {dim: value}) of each requested point, in the study's order."""
    for i in range(ds.sizes["point"]):
        yield i, {d: float(ds[f"point_{d}"].values[i]) for d in DIMS}


def _with_error(ds, name, at):
    """The value and its error bar (NaN without) at `at` (every row has the same types,
    so the CSV's error columns line up)."""
    return WithError(float(ds[name].sel(at)), float(ds[f"{name}_error"].sel(at)))


def pull_off_table(ds: xr.Dataset) -> Table:
    """One row per requested point: its factors, sigma0, the fixed-load pull-off (P*,
    delta*, a*, c*) and the fixed-grips P, each with its error bar, and the status."""
    rows = []
    for i, at in _points(ds):
        ok = str(ds.status.sel(at).item()) == "ok"
        values = [_with_error(ds, n, at) for n in ("P_star", "delta_star", "a_star", "c_star",
                                                   "P_dagger")]
        rows.append((at["C10"], at["t_over_R"], at["h_over_R"], at["gamma"], at["tabor"],
                     float(ds.sigma0.sel(at)), *values,
                     "ok" if ok else f"refused: {ds.reason.values[i]}"))
    return Table(f"Maugis-Dugdale pull-off, R = {ds.attrs['R_mm']:g} mm, interface "
                 f"{ds.attrs['interface']}, {ds.attrs['mesh']} mesh",
                 ("C10 [MPa]", "t/R", "h/R", "gamma [J/m^2]", "lambda", "sigma0 [MPa]",
                  "P* [N]", "delta* [mm]", "a* [mm]", "c* [mm]", "fixed grips P [N]",
                  "status"), tuple(rows),
                 ("error bars: the next coarser mesh; fixed grips empty: no jump (the "
                  "shell separates smoothly)",))


def fig_pull_off_lambda(ds: xr.Dataset):
    """P* against lambda for each (C10, t/R, h/R, gamma) with two or more answered
    lambdas; None when there is none."""
    from matplotlib.figure import Figure
    lines = []
    for C10 in ds.C10.values:
        for t in ds.t_over_R.values:
            for h in ds.h_over_R.values:
                for g in ds.gamma.values:
                    s = ds.sel(C10=C10, t_over_R=t, h_over_R=h, gamma=g)
                    ok = (s.status == "ok").values
                    if ok.sum() >= 2:
                        lines.append((f"C10 {C10:g}, t/R {t:g}, h/R {h:g}, gamma {g:g}",
                                      s.tabor.values[ok], s.P_star.values[ok],
                                      s.P_star_error.values[ok]))
    if not lines:
        return None
    fig = Figure(figsize=(6.4, 4.4))
    ax = fig.subplots()
    for label, lam, P, err in lines:
        ax.errorbar(lam, P, yerr=np.nan_to_num(err), marker="o", capsize=3, label=label)
    ax.set_xscale("log")
    return _finished(fig, ax, "Tabor-Maugis lambda", "P* [N]",
                     "fixed-load pull-off against the range of adhesion")


def fig_paths(ds: xr.Dataset):
    """The traced P(delta) of the first MOST_PATHS points, each pull-off marked."""
    from matplotlib.figure import Figure
    fig = Figure(figsize=(6.4, 4.4))
    ax = fig.subplots()
    for i, at in list(_points(ds))[:MOST_PATHS]:
        n = int(ds.states.values[i])
        line, = ax.plot(ds.curve_delta.values[i, :n], ds.curve_P.values[i, :n], lw=0.9,
                        label=", ".join(LABELS[d].format(at[d]) for d in DIMS
                                        if ds.sizes[d] > 1) or "the point")
        if str(ds.status.sel(at).item()) == "ok":
            ax.plot(float(ds.delta_star.sel(at)), float(ds.P_star.sel(at)), "o",
                    color=line.get_color())
    ax.axhline(0.0, color="0.6", lw=0.6)
    return _finished(fig, ax, "rim approach delta [mm] (> 0 approach)",
                     "P [N] (> 0 compression)", "traced paths; dots: fixed-load pull-offs")


def _finished(fig, ax, xlabel, ylabel, title):
    """`fig` with its axes labelled, titled and its legend drawn."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def write_cohesive_products(results_nc) -> Products:
    """The table (csv, md, tex) and the figures of the cohesive cube at `results_nc`."""
    path = Path(results_nc)
    with xr.open_dataset(path) as ds:
        ds = ds.load()
    p = Products()
    table = pull_off_table(ds)
    out = tables_dir(path)
    out.mkdir(exist_ok=True)
    p.tables = [write_text_atomic(out / f"pull_off.{fmt}", render(table, fmt))
                for fmt in FORMATS]
    figs = figures_dir(path)
    figs.mkdir(exist_ok=True)
    for name, draw in (("pull_off_lambda", fig_pull_off_lambda), ("paths", fig_paths)):
        fig = draw(ds)
        if fig is None:
            p.skipped[name] = "lambda takes one value per shell"
            continue
        _save(fig, figs / f"{name}.png", 150)
        p.figures.append(figs / f"{name}.png")
    return p
