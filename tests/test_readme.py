"""The README is for newcomers and its numbers are claims: at most 200 lines, no path
outside the repository, its notebook snippet runs from another folder, and the numbers it
states are the ones the validation tests hold (change them together)."""
import re
import subprocess
import sys

import pytest

from conftest import ENV, REPO

README = (REPO / "README.md").read_text()


def test_short_and_self_contained():
    assert len(README.splitlines()) <= 200
    assert "../shared" not in README and "/work/" not in README


def test_notebook_snippet_runs_from_another_folder(tmp_path):
    """The snippet's one-shell part, on the coarse mesh (the cube part needs a study run)."""
    code = re.search(r"```python\n(.*?)```", README, re.S).group(1)
    one_shell = code.split("\ncube = ")[0].replace(
        "gamma_J_m2=[20, 30])", "gamma_J_m2=[20, 30], mesh='coarse', progress=False)")
    assert "mesh='coarse'" in one_shell
    run = subprocess.run([sys.executable, "-c", one_shell + "\nimport matplotlib\n"],
                         cwd=tmp_path, env=dict(ENV, MPLBACKEND="Agg"), capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]


def test_notebook_snippets_cube_part_runs_from_another_folder(tmp_path, small_study):
    """The snippet's cube part builds the cube it opens: here the small coarse study (its
    paths already in the catalogue) in place of the paper's, from an empty folder."""
    code = re.search(r"```python\n(.*?)```", README, re.S).group(1)
    cube_part = "import shell_adhesion as sa\ncube = " + code.split("\ncube = ", 1)[1]
    study = small_study.parent.parent / "small.yaml"
    assert "sa.examples.paper_study()" in cube_part
    cube_part = cube_part.replace("sa.examples.paper_study()", repr(str(study)))
    env = dict(ENV, MPLBACKEND="Agg", SHELL_ADHESION_CATALOGUE=str(study.parent / "cat"))
    run = subprocess.run([sys.executable, "-c", cube_part], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    assert (tmp_path / "results" / "small.nc").is_file()


@pytest.mark.parametrize("case,row_start", [
    (("default", "no_slip", "neo_hooke"), "default mesh, no_slip: "),
    (("default", "frictionless", "neo_hooke"), "; frictionless: "),
    (("default", "no_slip", "mooney_rivlin"), "Mooney-Rivlin (C01 = C10/2): "),
    (("coarse", "no_slip", "neo_hooke"), "coarse mesh (CI), no_slip: "),
    (("coarse", "frictionless", "neo_hooke"), "-0.58 %; frictionless: ")])
def test_jkr_row_is_what_test_jkr_holds(case, row_start):
    from test_jkr import STATED
    line = next(l for l in README.splitlines() if l.startswith("| JKR, solid hemisphere"))
    stated = line.split(row_start)[1]
    numbers = [float(x) / 100 for x in re.findall(r"(-?\d+\.\d+) %", stated)[:4]]
    assert numbers == pytest.approx(STATED[case], abs=1e-4), (numbers, STATED[case])


@pytest.mark.parametrize("fragment,module,names", [
    ("loading 3.8e-7, relaxation paths 6.1e-5", "test_energy", ("LOADING_REL", "RELAXATION_REL")),
])
def test_energy_row_is_what_test_energy_holds(fragment, module, names):
    import importlib
    assert fragment in README
    mod = importlib.import_module(module)
    held = [getattr(mod, n) for n in names]
    assert held == pytest.approx([2 * 3.8e-7, 2 * 6.1e-5], rel=0.06)
