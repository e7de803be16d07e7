"""Stage progress lines: totals fixed by the plan, counts never past them, one line per
stage per report on a log file, redrawn in place on a terminal."""
import io

from shell_adhesion.study.progress import Progress


class Tty(io.StringIO):
    def isatty(self):
        return True


def stages():
    return [("loading paths", 2, "shells"), ("relaxation paths", 2, "shells"),
            ("energy method", 4, "points"), ("cube", 1, "file")]


def test_log_file_lines():
    out = io.StringIO()
    p = Progress(stages(), stream=out, every_s=3600)
    p.start("loading paths")
    p.update("loading paths", advance=1)       # within every_s: not printed
    p.update("loading paths", advance=5)       # clipped to the total, printed once
    p.update("loading paths", advance=1)
    p.update("relaxation paths", 1, note="7 paths solved")
    lines = out.getvalue().splitlines()
    assert [line.split()[2] for line in lines] == ["0/2", "2/2", "1/2"]
    assert "7 paths solved" in lines[-1]
    assert p.stages["loading paths"].done == 2


def test_terminal_redraws_all_stages():
    out = Tty()
    p = Progress(stages(), stream=out)
    p.update("cube", 1, note="results/x.nc")
    p.say("dask dashboard: http://127.0.0.1:8787/status")
    text = out.getvalue()
    assert text.count("\x1b[2K") == 8 and "\x1b[4F" in text
    assert "dask dashboard" in text and "1/1" in text


def test_disabled_prints_nothing():
    out = Tty()
    p = Progress(stages(), enabled=False, stream=out)
    p.update("cube", 1)
    p.say("x")
    assert out.getvalue() == ""


def test_eta_from_the_pace_of_finished_paths():
    from shell_adhesion.study.progress import path_eta
    assert path_eta(0.0, 19, 10, now=20.0) == ""         # too few finished for a pace
    assert path_eta(0.0, 40, 0, now=20.0) == ""          # nothing left
    assert path_eta(0.0, 40, 120, now=20.0) == ", ETA 1:00"   # 0.5 s a path, 120 left
    assert path_eta(None, 4, 12) == ""
