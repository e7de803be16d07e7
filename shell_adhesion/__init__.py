"""shell-adhesion: adhesion and pull-off of a soft hyperelastic spherical-cap shell on a
rigid plane (axisymmetric finite elements and Maugis' energy method).

    import shell_adhesion as sa
    case = sa.solve_case(R_mm=20, t_mm=3, h_mm=20, C10_MPa=0.3, gamma_J_m2=[30])
    sa.solve_cohesive_case(R_mm=20, t_mm=3, h_mm=20, C10_MPa=0.3, gamma_J_m2=30, tabor=1)
    case.to_dataset()             # curves along named dimensions, units on every variable
    fit = sa.fit_curve(R_mm=20, t_mm=3, h_mm=20, curve="test.csv")   # C10, gamma of a test
    ds = sa.open_results("results/paper.nc")
    sa.run_study(sa.examples.paper_study(), out="results/")     # the paper's study, shipped
    sa.pull_off_map().shell(R_mm=20, t_mm=3, h_mm=15, C10_MPa=0.3, gamma_J_m2=30)  # instantly
    sa.design(C10_MPa=0.3, gamma_J_m2=30, R_mm=20, t_mm=(1, 6))   # the shell that sticks best

The same functions serve the ``shell-adhesion`` command (`shell_adhesion.cli`).
Subpackages: `shell_adhesion.solver` (one shell, pure computation, dimensionless inside),
`shell_adhesion.study` (parameter studies on dask and the results cube they write),
`shell_adhesion.analysis` (what is read from a cube: fits, tables, figures; never the
solver), `shell_adhesion.catalogue` (the store of solved path sets).  Leaves they share:
`cube` (the cube's layout), `theory` (closed forms), `energy` (Maugis' method), `errors`,
`atomic` (atomic file writes); `examples` (the study files shipped with the package).
"""
from importlib import import_module as _import_module

__version__ = "0.1.0"       # the one place it is written (pyproject.toml reads it)

# public name -> module that defines it, imported on first use (so that importing the
# package stays light and the command line starts fast)
_LAZY = {
    "solve_case": "shell_adhesion.study.case",
    "CaseResult": "shell_adhesion.study.case",
    "solve_cohesive_case": "shell_adhesion.study.cohesive_case",
    "open_results": "shell_adhesion.analysis.results",
    "run_study": "shell_adhesion.study.run",
    "fit_curve": "shell_adhesion.study.fit",
    "pull_off_map": "shell_adhesion.study.pull_off_map",
    "design": "shell_adhesion.study.design",
}
_SUBMODULES = ("examples",)      # `sa.examples` without an import of its own

__all__ = ["__version__", *_LAZY, *_SUBMODULES]


def __getattr__(name):
    if name in _LAZY:
        return getattr(_import_module(_LAZY[name]), name)
    if name in _SUBMODULES:
        return _import_module(f"shell_adhesion.{name}")
    raise AttributeError(f"module 'shell_adhesion' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY) | set(_SUBMODULES))
