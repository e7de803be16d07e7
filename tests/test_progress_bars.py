"""Progress of `design` (and the case it confirms with) and of `run` / `map build` outside
a terminal, with the FE solve replaced by a fake (no FE runs): in a log file each stage
shows done/total and ends complete; in a notebook the run's stages share one redrawn line;
nothing when disabled."""
import io
import re
from types import SimpleNamespace

import pytest

import shell_adhesion as sa
from shell_adhesion.study import case as case_module
from shell_adhesion.study import progress
from shell_adhesion.study.progress import LogBar, Progress


def test_log_bar_lines_count_totals_and_end_complete(monkeypatch):
    clock = iter(range(0, 1000, 4))         # 4 s between readings
    monkeypatch.setattr(progress.time, "perf_counter", lambda: float(next(clock)))
    out = io.StringIO()
    with LogBar(10, "relaxation paths", "path", out, every_s=progress.LOG_EVERY_S) as b:
        for _ in range(12):                 # past its total: shown once, complete
            b.update(1)
        b.reset(3)                          # the next stage
        b.set_description("error bars: coarser meshes")
        b.unit = "mesh"
        b.update(1)
    lines = out.getvalue().splitlines()
    counts = [re.search(r": (\S+)/(\S+) ", line).groups() for line in lines]
    # at its start, every 10 s (3 readings of 4 s), complete once; the next stage
    # from its start to where it was left (1 of 3: the close shows it)
    assert counts == [("0", "10"), ("3", "10"), ("6", "10"), ("9", "10"), ("10", "10"),
                      ("0", "3"), ("1", "3")], lines
    assert "ETA" in lines[1] and "ETA" not in lines[4]
    assert lines[-1].startswith("error bars: coarser meshes: 1/3 mesh")


class _Done(Exception):
    """Ends the fake case once its bars have closed."""


def _fake_solve(monkeypatch, paths=7):
    """solve_request drives the loading (to 4 mm of a 20 mm shell) and `paths` relaxation
    paths; each coarser mesh returns at once; the case stops after its bars close."""
    class Stats(dict):
        def __getitem__(self, key):        # the case's report: past its bars
            raise _Done()

    stub = SimpleNamespace(stats=Stats(), ndof=1, capmesh=SimpleNamespace(
        mesh=SimpleNamespace(nelements=1)))

    def solve_request(t, h, request, gamma_max, interface, mesh, progress=None,
                      path_progress=None, **kw):
        if progress is not None:
            for delta_mm in (1.0, 2.0, 3.0, 4.0):
                progress(delta_mm / 20.0)
            for i in range(1, paths + 1):
                path_progress(i, paths)
        return stub, stub, None

    monkeypatch.setattr(case_module, "solve_request", solve_request)
    monkeypatch.setattr(case_module, "answers",
                        lambda ps, g_hats: {g: ValueError("fake") for g in g_hats})
    monkeypatch.setattr(case_module, "initial_fit",
                        lambda cap, request: SimpleNamespace(delta_max=4.0 / 20.0))


def test_case_in_a_log_shows_each_stage_to_its_total(monkeypatch, capsys):
    """Inside design (progress.logged); alone, a case prints no bar in a log file (a
    refusal found while solving stays the one line on stderr)."""
    monkeypatch.setattr(progress, "shown", lambda stream=None: False)
    _fake_solve(monkeypatch)
    with pytest.raises(_Done):
        sa.solve_case(20, 3, 20, 0.3, [30], mesh="coarse", progress=True)
    assert capsys.readouterr().err == ""
    with pytest.raises(_Done), progress.logged():
        sa.solve_case(20, 3, 20, 0.3, [30], mesh="coarse", progress=True)
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("loading: 0/4 mm") and err[1].startswith("loading: 4/4 mm")
    assert err[3].startswith("relaxation paths: 7/7 path"), err
    assert err[-1].startswith("error bars: coarser meshes: 2/2 mesh"), err


def test_case_silent_without_progress(monkeypatch, capsys):
    _fake_solve(monkeypatch)
    with pytest.raises(_Done), progress.logged():
        sa.solve_case(20, 3, 20, 0.3, [30], mesh="coarse", progress=False)
    assert capsys.readouterr().err == ""


def test_design_in_a_log_names_its_stages_and_ends_complete(monkeypatch, capsys):
    monkeypatch.setattr(progress, "shown", lambda stream=None: False)

    def fake_case(*args, progress=False, **kw):
        return SimpleNamespace(to_dict=lambda: {"pull_off": [
            {"status": "ok", "fixed_load": {"P_N": -1.7, "delta_mm": -0.6, "a_mm": 2.0}}]})
    monkeypatch.setattr(case_module, "solve_case", fake_case)
    sa.design(0.3, 30, R_mm=20, t_mm=(3, 3), h_mm=(12, 12), map="coarse", confirm=True,
              progress=True)
    err = capsys.readouterr().err.splitlines()
    search = [line for line in err if line.startswith("design 1/2: map search")]
    total = re.search(r"/(\d+) shell", search[0]).group(1)
    assert search[-1].startswith(f"design 1/2: map search: {total}/{total} shell"), err
    assert err[-1].startswith("design 2/2: one FE case"), err


def test_run_stages_in_a_notebook_share_one_redrawn_line(monkeypatch):
    monkeypatch.setattr(progress, "shown", lambda stream=None: True)
    out = io.StringIO()             # not a terminal, but seen live (a notebook)
    p = Progress([("loading paths", 2, "shells"), ("relaxation paths", 2, "shells")],
                 stream=out)
    p.start("loading paths")
    p.update("relaxation paths", 0, note="0/~9 paths")
    p.update("loading paths", advance=2)
    p.update("relaxation paths", 2, note="9/9 paths")
    text = out.getvalue()
    assert "\x1b[" not in text                      # no cursor moves
    kept = text.split("\n")                         # lines that stay: complete stages
    assert [k.split("\r")[-1].split()[:3] for k in kept[:2]] == [
        ["loading", "paths", "2/2"], ["relaxation", "paths", "2/2"]]
    running = [r for r in text.split("\r") if "|" in r]
    assert running and "loading paths 0/2" in running[0] and "0/~9 paths" in running[0]
