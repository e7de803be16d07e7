"""The analysis of a results cube (the netCDF a study writes): fits, trends, the paper's
numbers, tables and figures.

Reads cubes only (their layout is `shell_adhesion.cube`): it never imports the solver, the
study's run, dask or the catalogue, so a notebook or the `tables`, `plot` and `analyse`
commands start fast.  Modules: `results` (open a cube, values along a sweep), `fits` (eta
of eq. 3, power law, slope in gamma), `trends`, `paper` (our numbers beside the paper's),
`summary` (the text of analysis.txt), `slices` (the base solid or cavity of a cube),
`tables`, `figures` (matplotlib, imported on use), `products` (the files a run writes
beside the cube), `pull_off_map` (the map P*(t/R, h/R, gamma/(C10 R)) interpolated with
its error), `design_search` (the best shell on a map) and `map_figure`.  The names below are the ones a notebook needs:

    from shell_adhesion import analysis
    ds = analysis.open_results("results/paper.nc")
    analysis.eta_fit(ds).eta, analysis.gamma_slope(ds).slope, print(analysis.summary(ds))
"""
from .fits import (EQ3_EXPONENTS, EtaFit, GammaSlope, PowerLaw, eta_fit, gamma_slope,
                   jkr_ratio, power_law_fit)
from .paper import PAPER_SHELL, Comparison, Row, is_paper_shell, paper_comparison
from .results import NotACube, R_mm, along, base_point, check_cube, ok_cases, open_results
from .summary import summary
from .trends import MESH_UNCERTAINTY, PAPER_TRENDS, Trend, mesh_uncertainty, trend, trend_of, trends

__all__ = ["EQ3_EXPONENTS", "EtaFit", "GammaSlope", "PowerLaw", "eta_fit", "gamma_slope",
           "jkr_ratio", "power_law_fit", "PAPER_SHELL", "Comparison", "Row", "is_paper_shell",
           "paper_comparison", "NotACube", "R_mm", "along", "base_point", "check_cube",
           "ok_cases", "open_results", "summary", "MESH_UNCERTAINTY", "PAPER_TRENDS", "Trend",
           "mesh_uncertainty", "trend", "trend_of", "trends"]
