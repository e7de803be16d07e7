"""The documentation site builds with no warning (`sphinx-build -W`): every page, every
API docstring, every figure and link it names."""
import subprocess
import sys

import pytest

from conftest import ENV, REPO

pytest.importorskip("sphinx")
pytest.importorskip("myst_parser")


def test_docs_build_without_warnings(tmp_path):
    run = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b",
                          "html", str(REPO / "docs"), str(tmp_path / "html")],
                         env=dict(ENV, MPLBACKEND="Agg"), capture_output=True, text=True,
                         timeout=600)
    assert run.returncode == 0, run.stderr[-3000:]
    pages = {p.stem for p in (tmp_path / "html").glob("*.html")}
    assert {"index", "getting-started", "validation", "domain", "api"} <= pages
    api = (tmp_path / "html" / "api.html").read_text()
    assert "solve_case" in api and "R_mm" in api
