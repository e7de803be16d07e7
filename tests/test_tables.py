"""Tables of a results cube: CSV gives the cube's numbers back exactly, Markdown and LaTeX
show them to DIGITS significant digits; `shell-adhesion tables` and `analyse` read the
cube without running the solver; a bad file gives one line and exit 2."""
import csv
import io
import math

import numpy as np
import pytest
import xarray as xr

from shell_adhesion import analysis
from shell_adhesion.analysis import tables
from shell_adhesion.cli import main

CASE_VARS = ("C10", "gamma", "P_star", "delta_star", "a_star", "P_dagger", "delta_dagger",
             "a_dagger", "a0", "eta")


@pytest.fixture(scope="module")
def small(small_study):
    return analysis.open_results(small_study)


def cube_values(ds, C10, t_mm, h_mm, gamma):
    """The cube's values of one case, in the cases table's column order after h."""
    point = ds.swap_dims(t_over_R="t_mm", h_over_R="h_mm").sel(
        C10=C10, t_mm=t_mm, h_mm=h_mm, gamma=gamma)
    return [float(point[v]) for v in CASE_VARS]


def test_cases_csv_reads_back_exactly(small):
    text = tables.render(tables.cases_table(small), "csv")
    rows = list(csv.reader(io.StringIO(text)))
    header, body = rows[0], rows[1:]
    assert header[:5] == ["R [mm]", "t [mm]", "h [mm]", "C10 [MPa]", "gamma [J/m^2]"]
    assert header[5:] == ["P* [N]", "delta* [mm]", "a* [mm]", "P_dagger [N]",
                          "delta_dagger [mm]", "a_dagger [mm]", "a0 [mm]", "eta [1]"]
    assert len(body) == int((small["status"] == "ok").sum()) == 7
    seen = set()
    for row in body:
        x = [float(c) if c else math.nan for c in row]
        R, t, h, C10, gamma = x[:5]
        assert R == float(small["R"])
        want = cube_values(small, C10, t, h, gamma)
        np.testing.assert_array_equal(x[3:], want)        # exact, NaN where NaN
        seen.add((C10, t, h, gamma))
    assert len(seen) == 7
    assert any(c == "" for row in body for c in row)     # a0 missing for some cases


@pytest.mark.parametrize("fmt", ["md", "tex"])
def test_cases_md_tex_show_formatted_values(small, fmt):
    table = tables.cases_table(small)
    text = tables.render(table, fmt)
    sep = "|" if fmt == "md" else "&"
    lines = [ln for ln in text.splitlines() if ln.count(sep) >= 12]
    body = lines[1:] if fmt == "tex" else lines[2:]      # header (and md's rule) first
    assert len(body) == len(table.rows) == 7
    for line, row in zip(body, table.rows):
        cells = [c.strip() for c in line.strip().strip("|").removesuffix("\\\\").split(sep)]
        want = ["—" if math.isnan(v) else f"{v:.{tables.DIGITS}g}" for v in row]
        assert cells == want
    if fmt == "tex":
        assert "\\toprule" in text and "gamma [J/m\\^{}2]" in text


def test_comparison_table(small):
    cmp = analysis.paper_comparison(small)
    table = tables.comparison_table(small)
    assert len(table.rows) == len(cmp.rows) and table.notes
    rows = list(csv.DictReader(io.StringIO(tables.render(table, "csv"))))
    assert [float(r["ours"]) for r in rows] == [r.ours for r in cmp.rows]
    md = tables.render(table, "md")
    assert "Not answered by this cube" in md and "d\\|P*\\|/dgamma" in md   # escaped pipe
    empty = small.assign_attrs(R_mm=21.0)
    empty = empty.assign_coords(R=21.0)
    assert tables.comparison_table(empty).rows == ()
    assert "(no rows)" in tables.render(tables.comparison_table(empty), "tex")


def test_missing_values_and_formats():
    t = tables.Table("t", ("x [mm]", "note"), ((1.0, "a|b"), (math.nan, None)))
    assert tables.render(t, "csv") == "x [mm],note\n1.0,a|b\n,\n"
    assert "—" in tables.render(t, "md") and "a\\|b" in tables.render(t, "md")
    with pytest.raises(ValueError, match="format"):
        tables.render(t, "html")


def test_cli_reads_without_solving(small_study, forbid_fe, capsys, tmp_path):
    from shell_adhesion import solver
    with pytest.raises(AssertionError, match="must not run the FE solver"):
        solver.solve_paths(0.15, 1.0)                   # the fixture is armed
    assert main(["tables", str(small_study), "--format", "csv"]) == 0
    out = capsys.readouterr().out
    assert len(out.strip().splitlines()) == 1 + 7
    assert main(["tables", str(small_study), "--table", "all", "--format", "tex",
                 "--out", str(tmp_path / "t.tex")]) == 0
    text = (tmp_path / "t.tex").read_text()
    assert text.count("\\begin{tabular}") == 2 and capsys.readouterr().out == ""
    assert [p.name for p in tmp_path.iterdir()] == ["t.tex"]        # no temporary left
    assert main(["analyse", str(small_study)]) == 0
    out = capsys.readouterr().out
    assert "eta of eq. 3" in out and "d|P*|/dgamma" in out and " m " in out
    assert out.count("trend: ") == 4


def test_bad_input_one_line_exit_2(small_study, tmp_path, capsys):
    text = tmp_path / "notes.nc"
    text.write_text("not netCDF\n")
    other = tmp_path / "other.nc"
    xr.Dataset({"x": ("i", [1.0, 2.0])}).to_netcdf(other)
    for path in (tmp_path / "missing.nc", text, other, tmp_path):
        for cmd in ("tables", "analyse"):
            assert main([cmd, str(path)]) == 2
            err = capsys.readouterr().err
            assert len(err.strip().splitlines()) == 1 and str(path) in err
    assert main(["tables", str(small_study), "--out", str(tmp_path / "no" / "x.md")]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "--out" in err
