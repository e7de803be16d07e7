"""A wheel that works anywhere: `python -m build` makes an sdist with the repository's
study, examples and tests, and from it a wheel with the shipped studies; the wheel's
`shell-adhesion example paper`, run away from the repository, prints the paper's study."""
import os
from pathlib import Path
import subprocess
import sys
import tarfile
import zipfile

import pytest
import yaml

from conftest import REPO

SDIST_HOLDS = ("workflow.yaml", "LICENSE", "CITATION.cff", "README.md", "pyproject.toml",
               "examples/study_mooney_rivlin.yaml", "examples/ex01_base_case.py",
               "tests/conftest.py", "shell_adhesion/data/paper.yaml")


@pytest.fixture(scope="module")
def dist(tmp_path_factory):
    """(sdist, wheel) built as a user builds them: the sdist, then the wheel from it."""
    out = tmp_path_factory.mktemp("dist")
    done = subprocess.run([sys.executable, "-m", "build", "--outdir", str(out), str(REPO)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    (sdist,), (wheel,) = out.glob("*.tar.gz"), out.glob("*.whl")
    return sdist, wheel


def test_wheel_ships_the_studies(dist):
    with zipfile.ZipFile(dist[1]) as whl:
        assert whl.read("shell_adhesion/data/paper.yaml") == (REPO / "workflow.yaml").read_bytes()
        assert (whl.read("shell_adhesion/data/mooney_rivlin.yaml")
                == (REPO / "examples" / "study_mooney_rivlin.yaml").read_bytes())
        assert any(n.endswith(".dist-info/licenses/LICENSE") for n in whl.namelist())
        # the shipped pull-off map answers a fresh install (sa.pull_off_map())
        assert (whl.read("shell_adhesion/data/pull_off_map_coarse.nc")
                == (REPO / "shell_adhesion" / "data" / "pull_off_map_coarse.nc").read_bytes())


def test_sdist_holds_the_repository_files(dist):
    with tarfile.open(dist[0]) as tar:
        top = tar.getnames()[0].split("/")[0]
        names = {n.split("/", 1)[1] for n in tar.getnames() if "/" in n}
    assert set(SDIST_HOLDS) <= names, set(SDIST_HOLDS) - names
    assert top == f"shell_adhesion-{_version()}"


def test_example_paper_from_the_wheel(dist, tmp_path):
    """The unpacked wheel alone on the path (as pip lays it out), in a folder far from the
    repository: the printed study is the repository's workflow.yaml."""
    site = tmp_path / "site"
    with zipfile.ZipFile(dist[1]) as whl:
        whl.extractall(site)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    env = dict(os.environ, PYTHONPATH=str(site))
    where = subprocess.run([sys.executable, "-c", "import shell_adhesion; "
                            "print(shell_adhesion.examples.paper_study())"],
                           cwd=elsewhere, env=env, capture_output=True, text=True, timeout=120)
    assert where.returncode == 0, where.stderr
    assert Path(where.stdout.strip()).is_relative_to(site)
    out = subprocess.run([sys.executable, "-m", "shell_adhesion", "example", "paper"],
                         cwd=elsewhere, env=env, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert yaml.safe_load(out.stdout) == yaml.safe_load((REPO / "workflow.yaml").read_text())


def test_coarse_case_from_the_wheel(dist, tmp_path):
    """The unpacked wheel, away from the repository, solves a coarse case (the package's
    modules come from the wheel, not the checkout)."""
    site = tmp_path / "site"
    with zipfile.ZipFile(dist[1]) as whl:
        whl.extractall(site)
    env = dict(os.environ, PYTHONPATH=str(site), MPLBACKEND="Agg")
    out = subprocess.run([sys.executable, "-c", "import shell_adhesion, sys; "
                          "print(shell_adhesion.__file__); from shell_adhesion.cli "
                          "import main; sys.exit(main(['case', '--R', '20', '--t', '3', "
                          "'--h', '20', '--C10', '0.3', '--gamma', '30', '--mesh', 'coarse']))"],
                         cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert Path(out.stdout.splitlines()[0]).is_relative_to(site)
    assert "fixed load P* = -1.71" in out.stdout


def _version():
    from shell_adhesion import __version__
    return __version__
