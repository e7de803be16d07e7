"""The layout keeps its promises: the analysis of a cube reads cubes only, importing the
package stays light, and the key of a path set covers every module that computes one."""
import json
import pkgutil
import subprocess
import sys

from shell_adhesion import analysis
from shell_adhesion.study.keys import PATHSET_ROOTS, pathset_modules, solver_source_sha256

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
    assert "dask" in loaded_after("shell_adhesion.cube", "dask.array")


def test_the_run_imports_dask_only_when_it_computes():
    # a warm run (everything in the catalogue) starts no cluster: importing the run module
    # leaves dask and distributed out
    loaded = loaded_after("shell_adhesion.study.run")
    assert "dask" not in loaded and "distributed" not in loaded


def test_importing_the_package_is_light():
    assert loaded_after("shell_adhesion") == []


def test_the_pathset_key_covers_what_computes_a_path_set():
    """study.keys.pathset_modules: the roots and all they import, by this test's own graph;
    the cohesive interface and arc-length continuation are outside it."""
    graph = import_graph()
    closure, todo = set(), [f"shell_adhesion.{m}" for m in PATHSET_ROOTS]
    while todo:
        m = todo.pop()
        if m not in closure:
            closure.add(m)
            todo.extend(graph[m])
    closure -= {"shell_adhesion", "shell_adhesion.solver"}   # __version__ is in the key
    assert closure == {f"shell_adhesion.{m}" for m in pathset_modules()}
    assert {"shell_adhesion.solver.path", "shell_adhesion.solver.forms",
            "shell_adhesion.energy"} <= closure
    assert not closure & {"shell_adhesion.solver.cohesive", "shell_adhesion.solver.arclength"}


def test_the_study_computes_path_sets_with_the_keyed_modules():
    """Every solver module the study's run imports is hashed into the key."""
    graph = import_graph()
    used = {m for m in graph["shell_adhesion.study.run"] if m.startswith("shell_adhesion.solver.")}
    assert used and used <= {f"shell_adhesion.{m}" for m in pathset_modules()}


def test_the_source_hash_follows_a_keyed_module(tmp_path, monkeypatch):
    from shell_adhesion import solver
    from shell_adhesion.study import keys
    import shutil
    copy = tmp_path / "shell_adhesion"
    shutil.copytree(keys.Path(solver.__file__).parent.parent, copy)
    monkeypatch.setattr(solver, "__file__", str(copy / "solver" / "__init__.py"))
    keys.solver_source_sha256.cache_clear()
    try:
        before = keys.solver_source_sha256()
        (copy / "solver" / "cohesive.py").write_text("# changed\n")
        keys.solver_source_sha256.cache_clear()
        assert keys.solver_source_sha256() == before
        with (copy / "solver" / "path.py").open("a") as f:
            f.write("# changed\n")
        keys.solver_source_sha256.cache_clear()
        assert keys.solver_source_sha256() != before
    finally:
        keys.solver_source_sha256.cache_clear()
