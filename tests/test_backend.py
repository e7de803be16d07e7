"""No library function changes matplotlib's backend (a notebook user's stays theirs):
figures are drawn on `matplotlib.figure.Figure` objects, never through pyplot."""
import ast
import subprocess
import sys
from pathlib import Path

import shell_adhesion

ROOT = Path(shell_adhesion.__file__).parent


def _backend_calls(source: str) -> list:
    """Lines of `matplotlib.use(...)` calls and of pyplot imports in a module's source."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                and node.func.attr == "use" and isinstance(node.func.value, ast.Name)
                and node.func.value.id == "matplotlib"):
            found.append(node.lineno)
        names = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                 [f"{node.module}.{a.name}" for a in node.names]
                 if isinstance(node, ast.ImportFrom) and node.module else [])
        found += [node.lineno for n in names if n.startswith("matplotlib.pyplot")]
    return found


def test_the_scan_sees_a_backend_switch():
    assert _backend_calls("import matplotlib\nmatplotlib.use('Agg')\n") == [2]
    assert _backend_calls("import matplotlib.pyplot as plt\n") == [1]
    assert _backend_calls("from matplotlib.figure import Figure\n") == []


def test_no_library_module_switches_the_backend_or_uses_pyplot():
    offenders = {str(p.relative_to(ROOT)): lines for p in sorted(ROOT.rglob("*.py"))
                 if (lines := _backend_calls(p.read_text()))}
    assert offenders == {}


def test_drawing_the_shipped_map_keeps_the_callers_backend(tmp_path):
    code = ("import matplotlib; matplotlib.use('svg')\n"
            "from shell_adhesion.study.pull_off_map import pull_off_map\n"
            "from shell_adhesion.analysis.map_figure import draw_map\n"
            f"draw_map(pull_off_map('coarse'), 0.005, {str(tmp_path / 'map.png')!r})\n"
            "print(matplotlib.get_backend())\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "svg"
    assert (tmp_path / "map.png").stat().st_size > 0
