"""Tables from a results cube: one row per evaluated case, and our numbers beside the
paper's; rendered as CSV, GitHub Markdown or LaTeX (booktabs).

CSV keeps full precision (shortest round-trip repr: reading it back gives the cube's
values exactly); Markdown and LaTeX show `DIGITS` significant digits.  A missing value
is empty in CSV and "—" otherwise.  Units are in the column headers (mm, N, MPa, J/m^2).
Never runs the solver.
"""
import csv
from dataclasses import dataclass
import io
import math
import numbers

from tabulate import tabulate
import xarray as xr

from shell_adhesion.cube import IN_MPA

from .paper import paper_comparison
from .results import R_mm, ok_cases
from .slices import base_material, material_label

DIGITS = 4
FORMATS = ("csv", "md", "tex")

# cube variable -> column label (the unit comes from the cube's attributes)
_CASE_COLUMNS = {"C10": "C10", "gamma": "gamma", "P_star": "P*", "delta_star": "delta*",
                 "a_star": "a*", "P_dagger": "P_dagger", "delta_dagger": "delta_dagger",
                 "a_dagger": "a_dagger", "a0": "a0", "eta": "eta"}


@dataclass(frozen=True)
class WithError:
    """A value and its error bar: "value ± error" in Markdown and LaTeX; CSV gives the
    value in its column and the error in the column "<label> error" after the values."""
    value: float
    error: float


@dataclass(frozen=True)
class Table:
    """A titled table: column headers (units in brackets), rows of numbers or text
    (None or NaN: missing), and notes printed under it (Markdown and LaTeX only)."""
    title: str
    columns: tuple
    rows: tuple
    notes: tuple = ()


def _header(ds, name, label):
    unit = ds[name].attrs.get("units", "1")
    return f"{label} [{unit}]"


def cases_table(ds: xr.Dataset) -> Table:
    """One row per point with status "ok": R, t, h [mm], C10 [MPa], gamma [J/m^2], the
    pull-off values (P* [N], delta*, a* [mm], P_dagger [N], delta_dagger, a_dagger, a0 [mm])
    and eta [1]."""
    c = ok_cases(ds)
    R = R_mm(ds)
    ratios = [d for d in ds["status"].dims if d not in _CASE_COLUMNS and d not in
              ("t_over_R", "h_over_R")]      # swept material ratios (C01_over_C10, ...)
    ratios += [k for k in IN_MPA if k in c.coords]   # and as the study gave them, in MPa
    columns = ("R [mm]", _header(ds, "t_mm", "t"), _header(ds, "h_mm", "h"),
               *(_header(ds, k, k) for k in ratios),
               *(_header(ds, k, label) for k, label in _CASE_COLUMNS.items()))
    data = [c[k].values for k in ("t_mm", "h_mm", *ratios, *_CASE_COLUMNS)]
    rows = tuple((R, *(float(x[i]) for x in data)) for i in range(c.sizes["case"]))
    with_error = [k for k in _CASE_COLUMNS if f"{k}_error" in c]
    if with_error:          # value ± error (Markdown, LaTeX); the errors' own columns (CSV)
        first = len(columns) - len(_CASE_COLUMNS)
        keys = list(_CASE_COLUMNS)
        rows = tuple(
            (*row[:first], *(WithError(v, float(c[f"{k}_error"].values[i])) if k in with_error
                             else v for k, v in zip(keys, row[first:])))
            for i, row in enumerate(rows))
    study = ds.attrs.get("study_name", "")
    material = f", material {ds.attrs['material']}" if "material" in ds.attrs else ""
    title = (f"Pull-off of each case (study {study}, mesh {ds.attrs.get('mesh', '?')}, "
             f"interface {ds.attrs.get('interface', '?')}{material})")
    return Table(title, columns, rows)


def comparison_table(ds: xr.Dataset) -> Table:
    """Our numbers beside the paper's (`analysis.paper.paper_comparison`); the quantities
    the cube cannot answer are listed in the notes.  A cube that sweeps a material ratio is
    compared at its base solid (`slices.base_material`); a solid other than the paper's
    incompressible neo-Hookean one is named in the title and a note (the differences are
    then the material's effect, not an error)."""
    ds = base_material(ds)
    cmp = paper_comparison(ds)
    columns = ("quantity", "paper", "ours", "unit", "difference [%]", "note")
    rows = tuple((r.quantity, r.paper, r.ours, r.unit, r.difference_pct, r.note)
                 for r in cmp.rows)
    notes = ("Not answered by this cube: " + "; ".join(cmp.skipped) + ".",) if cmp.skipped else ()
    title = "Our numbers beside the paper's (DESIGN.md section 4)"
    label, paper_solid = material_label(ds)
    if not paper_solid:
        title += f"; ours for {label}"
        notes = (f"The paper's values are for the incompressible neo-Hookean solid, ours for "
                 f"{label}: a difference is the material's effect, not an error.",) + notes
    return Table(title, columns, rows, notes)


def _missing(x) -> bool:
    return x is None or (isinstance(x, numbers.Real) and not math.isfinite(x))


def _cell(x, fmt):
    if isinstance(x, WithError):
        if fmt == "csv" or _missing(x.value) or _missing(x.error):
            return _cell(x.value, fmt)
        return f"{x.value:.{DIGITS}g} ± {x.error:.2g}"
    if _missing(x):
        return "" if fmt == "csv" else "—"
    if isinstance(x, numbers.Real) and not isinstance(x, bool):
        return repr(float(x)) if fmt == "csv" else f"{float(x):.{DIGITS}g}"
    return str(x).replace("|", "\\|") if fmt == "md" else str(x)


def _error_label(column: str) -> str:
    """'P* [N]' -> 'P* error [N]'."""
    name, sep, unit = column.partition(" [")
    return f"{name} error{sep}{unit}"


def render(table: Table, fmt: str) -> str:
    """The table as text in `fmt`: "csv", "md" (GitHub) or "tex" (booktabs tabular)."""
    if fmt not in FORMATS:
        raise ValueError(f"format {fmt!r}: must be one of {', '.join(FORMATS)}")
    cells = [[_cell(x, fmt) for x in row] for row in table.rows]
    if fmt == "csv":
        errors = [j for j, x in enumerate(table.rows[0]) if isinstance(x, WithError)] \
            if table.rows else []
        out = io.StringIO()
        writer = csv.writer(out, lineterminator="\n")
        writer.writerow([*table.columns, *(_error_label(table.columns[j]) for j in errors)])
        writer.writerows([*row, *(_cell(r[j].error, fmt) for j in errors)]
                         for row, r in zip(cells, table.rows))
        return out.getvalue()
    lead = "" if fmt == "md" else "% "
    if table.rows:
        numeric = [all(_missing(x) or isinstance(x, (numbers.Real, WithError)) for x in col)
                   for col in zip(*table.rows)]
        text = tabulate(cells, headers=table.columns, disable_numparse=True,
                        tablefmt="github" if fmt == "md" else "latex_booktabs",
                        colalign=["right" if n else "left" for n in numeric])
    else:
        text = lead + "(no rows)"
    if table.notes:
        text += "\n\n" + "\n".join(lead + n for n in table.notes)
    return text + "\n"
