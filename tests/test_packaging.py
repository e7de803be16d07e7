"""What a newcomer meets first: a clean package namespace, and a study file that is not
found named by its absolute path."""
from pathlib import Path
import re

import pytest

import shell_adhesion as sa
from shell_adhesion.study.config import StudyError


def test_namespace_has_no_import_module():
    assert not hasattr(sa, "import_module") and "import_module" not in dir(sa)


def test_missing_study_named_by_absolute_path(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    looked_for = Path.cwd() / "workflow.yaml"       # tmp_path as the system spells it
    with pytest.raises(StudyError, match=re.escape(f"study file {looked_for} (")):
        sa.run_study("workflow.yaml", out=tmp_path / "out", progress=False)
    assert list(tmp_path.iterdir()) == []
