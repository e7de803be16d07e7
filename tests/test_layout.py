"""The layout keeps its promises: the analysis of a cube reads cubes only, importing the
package stays light, and the solver's key covers every module the solver imports."""
import json
import pkgutil
import subprocess
import sys

from shell_adhesion import analysis
from shell_adhesion.study.keys import SOLVER_LEAVES

from test_import_graph import import_graph

# what the analysis of a cube never needs: the FE solver, the study's run, the catalogue,
# dask and scikit-fem
HEAVY = ("shell_adhesion.solver", "shell_adhesion.study.run", "shell_adhesion.catalogue",
         "dask", "distributed", "skfem")


def loaded_after(*modules) -> list:
    """The HEAVY modules in sys.modules after importing `modules` in a fresh interpreter."""
    code = ("import importlib, json, sys\n"
            f"for m in {list(modules)!r}:\n    importlib.import_module(m)\n"
            f"print(json.dumps([m for m in {list(HEAVY)!r} if m in sys.modules]))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120, check=True)
    return json.loads(out.stdout.splitlines()[-1])


def analysis_modules() -> list:
    return ["shell_adhesion.analysis"] + [
        f"shell_adhesion.analysis.{m.name}" for m in pkgutil.iter_modules(analysis.__path__)]


def test_the_analysis_imports_no_solver_run_catalogue_or_dask():
    modules = analysis_modules()
    assert {"shell_adhesion.analysis.figures", "shell_adhesion.analysis.tables",
            "shell_adhesion.analysis.products"} <= set(modules)
    assert loaded_after("shell_adhesion.cube", *modules) == []


def test_the_check_sees_a_heavy_import():
    # the same check, with one forbidden import added, names it
    assert "shell_adhesion.solver" in loaded_after(*analysis_modules(),
                                                   "shell_adhesion.solver.path")
    assert "dask" in loaded_after("shell_adhesion.study.run")


def test_importing_the_package_is_light():
    assert loaded_after("shell_adhesion") == []


def test_the_solver_key_covers_what_the_solver_imports():
    """study.keys.SOLVER_LEAVES: the modules outside solver/ whose code the solver runs."""
    graph = import_graph()
    outside = {m for name, deps in graph.items() if name.startswith("shell_adhesion.solver")
               for m in deps if not m.startswith("shell_adhesion.solver")}
    outside.discard("shell_adhesion")        # the package's root: __version__, in the key
    assert outside == {f"shell_adhesion.{n.removesuffix('.py')}" for n in SOLVER_LEAVES}
