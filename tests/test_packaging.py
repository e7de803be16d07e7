"""What a newcomer meets first: the shipped studies (one text with the repository's files),
`--version`, the licence and the citation, a clean package namespace, and a study file that
is not found named by its absolute path."""
from pathlib import Path
import re
import tomllib

import pytest
import yaml

import shell_adhesion as sa
from shell_adhesion.cli import main
from shell_adhesion.study.config import StudyError

from conftest import REPO

PAPER_TITLE = "Adherence of a hyperelastic shell on a rigid planar substrate"


@pytest.mark.parametrize("name, copy", [("paper", "workflow.yaml"),
                                        ("mooney-rivlin", "examples/study_mooney_rivlin.yaml")])
def test_shipped_study_is_the_repository_file(name, copy):
    """One text: edit the package's copy and the repository's together."""
    assert sa.examples.study_path(name).read_bytes() == (REPO / copy).read_bytes()


def test_paper_study_path():
    assert sa.examples.paper_study() == sa.examples.study_path("paper")
    assert sa.examples.paper_study().is_file()


def test_unknown_study_name():
    with pytest.raises(ValueError, match="example: 'papr' must be one of paper, mooney-rivlin"):
        sa.examples.study_path("papr")


def test_example_command_prints_the_study(capsys):
    assert main(["example", "paper"]) == 0
    out = capsys.readouterr().out
    assert out == (REPO / "workflow.yaml").read_text()


def test_version(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    assert capsys.readouterr().out == f"shell-adhesion {sa.__version__}\n"


def test_one_source_of_the_version():
    project = tomllib.loads((REPO / "pyproject.toml").read_text())
    assert "version" not in project["project"] and "version" in project["project"]["dynamic"]
    assert (project["tool"]["setuptools"]["dynamic"]["version"]
            == {"attr": "shell_adhesion.__version__"})


def test_namespace_has_no_import_module():
    assert not hasattr(sa, "import_module") and "import_module" not in dir(sa)
    assert "examples" in dir(sa)


def test_licence_and_citation():
    licence = (REPO / "LICENSE").read_text()
    assert licence.startswith("MIT License") and "2026 the shell-adhesion authors" in licence
    project = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]
    assert project["license"] == "MIT"
    cff = yaml.safe_load((REPO / "CITATION.cff").read_text())
    assert cff["cff-version"] == "1.2.0" and cff["type"] == "software"
    assert cff["title"] == "shell-adhesion" and cff["license"] == "MIT"
    assert [r["title"] for r in cff["references"]] == [PAPER_TITLE]
    assert all(r["authors"] for r in cff["references"])


def test_missing_study_named_by_absolute_path(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    looked_for = Path.cwd() / "workflow.yaml"       # tmp_path as the system spells it
    with pytest.raises(StudyError, match=re.escape(f"study file {looked_for} (")):
        sa.run_study("workflow.yaml", out=tmp_path / "out", progress=False)
    assert list(tmp_path.iterdir()) == []
