"""The suite's shared fixtures leave nothing behind: a test passes alone, in any order and
beside any other (the default run may split the tests between processes)."""
import subprocess
import sys

from conftest import ENV, REPO

# in a fresh interpreter (no module of the solver imported yet): forbid, undo, then every
# entry point must be the solver's own function again
_FORBID_AND_UNDO = """
import importlib, sys
sys.path.insert(0, {tests!r})
from _pytest.monkeypatch import MonkeyPatch
import conftest
patch = MonkeyPatch()
conftest.forbid_fe_with(patch)
patch.undo()
left = [f"{{m}}.{{n}}" for m, names in conftest.FE_ENTRY_POINTS.items() for n in names
        if getattr(importlib.import_module(m), n).__module__ == "conftest"]
print(" ".join(left))
"""


def test_forbid_fe_leaves_no_stand_in_behind():
    """A module first imported by forbid_fe (study.case binds solver.request's solve_request)
    must not keep the forbidding stand-in once the test ends (it made a later test of
    another module fail: test_figures' plot_command before test_inversion's solve)."""
    run = subprocess.run([sys.executable, "-c", _FORBID_AND_UNDO.format(tests=str(REPO / "tests"))],
                         env=ENV, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.split() == [], f"still forbidden after the test: {run.stdout}"
