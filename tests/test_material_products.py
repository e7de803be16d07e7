"""Tables and figures of a cube that sweeps a material ratio: the paper table names the
solid it compares, the sweep figures draw one labelled curve per material value, and
fig7_materials draws the swept solids at the base shell.

The cube is the small real study stacked along C01_over_C10 with the 0.5 copy's forces
scaled (a stand-in for a stiffer solid; only the drawing and labelling are under test).
"""
import numpy as np
import pytest
import xarray as xr

from shell_adhesion.analysis import along, figures, tables
from shell_adhesion.analysis.slices import base_material, material_label
from shell_adhesion.analysis.products import write_tables

FORCES = ("P_star", "P_dagger", "P_eq", "loading_P")


@pytest.fixture(scope="module")
def swept(small_study):
    with xr.open_dataset(small_study) as d:
        nh = d.load()
    stiff = nh.copy()
    for v in FORCES:
        stiff[v] = nh[v] * 1.25
    ds = xr.concat([nh, stiff], dim="C01_over_C10", data_vars="all", coords="different",
                   compat="equals", combine_attrs="override")
    ds = ds.assign_coords(C01_over_C10=[0.0, 0.5])
    ds["C01_over_C10"].attrs = dict(units="1", long_name="Mooney-Rivlin ratio C01 / C10")
    return ds.assign_attrs(material_model="mooney_rivlin", material_C01_over_C10=0.5,
                           material="mooney_rivlin (swept: C01_over_C10)")


def test_paper_table_names_the_solid(swept):
    table = tables.comparison_table(swept)
    assert "ours for mooney_rivlin (C01_over_C10 = 0.5)" in table.title
    assert any("incompressible neo-Hookean solid, ours for mooney_rivlin" in n
               for n in table.notes)
    ours = {r[0]: r[2] for r in table.rows}
    P = float(base_material(swept)["P_star"].sel(C10=0.3, t_over_R=0.15, h_over_R=1.0,
                                                  gamma=30))
    assert ours["P* (fixed load), gamma = 30 J/m^2"] == P       # the base solid, C01/C10 = 0.5
    # the C01/C10 = 0 slice is the paper's solid: no label
    nh = swept.sel(C01_over_C10=0.0).assign_attrs(material_C01_over_C10=0.0)
    assert material_label(nh)[1] and "ours for" not in tables.comparison_table(nh).title


def test_tables_written_for_a_material_study(swept, tmp_path):
    names = {p.name for p in write_tables(swept, tmp_path)}
    assert {"paper.md", "paper.csv", "paper.tex", "cases.md"} <= names
    assert "ours for mooney_rivlin (C01_over_C10 = 0.5)" in (tmp_path / "paper.md").read_text()


def test_pull_off_figure_one_curve_per_material(swept):
    axes = figures.fig_pull_off(swept)
    for ax, (dim, _) in zip(axes, figures.SWEEPS):
        lines = {l.get_label(): l for l in ax.get_lines()}
        base, other = lines["|P*|, C01/C10 = 0.5 (base)"], lines["|P*|, C01/C10 = 0"]
        for line, c01 in ((base, 0.5), (other, 0.0)):
            P = along(swept.sel(C01_over_C10=c01), "P_star", dim)
            np.testing.assert_array_equal(line.get_xdata(), P[dim].values)
            np.testing.assert_array_equal(line.get_ydata(), -P.values)


def test_contact_radius_figure_one_style_per_material(swept):
    single = figures.fig_contact_radius(swept.sel(C01_over_C10=0.0))
    both = figures.fig_contact_radius(swept)
    for a1, a2 in zip(single, both):
        curves = lambda ax: [l for l in ax.get_lines() if l.get_linestyle() != "None"]
        assert len(curves(a2)) == 2 * len(curves(a1))
        assert {l.get_linestyle() for l in curves(a2)} == {"-", "--"}
        labels = [l.get_label() for l in curves(a2) if not l.get_label().startswith("_")]
        assert any("C01/C10 = 0.5" in t for t in labels)


def test_materials_figure(swept, tmp_path):
    a_ld, a_P, a_d = figures.fig_materials(swept)
    loading = {l.get_label(): l for l in a_ld.get_lines()}
    assert set(loading) == {"C01/C10 = 0", "C01/C10 = 0.5"}
    np.testing.assert_allclose(loading["C01/C10 = 0.5"].get_ydata(),
                               1.25 * loading["C01/C10 = 0"].get_ydata(), rtol=1e-12)
    P_star = next(l for l in a_P.get_lines() if l.get_label().startswith("P*"))
    np.testing.assert_array_equal(P_star.get_xdata(), [0.0, 0.5])
    at = dict(C10=0.3, t_over_R=0.15, h_over_R=1.0, gamma=30)
    np.testing.assert_array_equal(P_star.get_ydata(), swept["P_star"].sel(at).values)
    assert "C01/C10" in a_P.get_xlabel()
    with pytest.raises(figures.MissingData):
        figures.fig_materials(swept.sel(C01_over_C10=0.0))
    written, skipped = figures.write_figures(swept, tmp_path, formats=("png",), dpi=60)
    assert "fig7_materials.png" in {p.name for p in written}
    assert not skipped, skipped


def test_cases_table_has_the_ratio_and_the_MPa_columns(swept):
    """A cube whose study gave C01 in MPa carries C01_MPa = C01/C10 x C10 beside the ratio;
    the cases table shows both."""
    mpa = swept.assign_coords(C01_MPa=swept["C01_over_C10"] * swept["C10"])
    mpa["C01_MPa"].attrs = dict(units="MPa", long_name="Mooney-Rivlin C01")
    table = tables.cases_table(mpa)
    i, j, k = (table.columns.index(c) for c in ("C01_over_C10 [1]", "C01_MPa [MPa]",
                                                 "C10 [MPa]"))
    assert len(table.rows) == 2 * int((swept["status"].sel(C01_over_C10=0.0) == "ok").sum())
    for row in table.rows:
        assert row[j] == pytest.approx(row[i] * row[k], rel=1e-15)
    assert {row[i] for row in table.rows} == {0.0, 0.5}
