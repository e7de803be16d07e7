"""The paper's figures from a small real study: axes, units and curves checked through
matplotlib's objects, the data behind them against the cube, and no FE solve."""
import numpy as np
import pytest
import xarray as xr
from matplotlib.collections import PolyCollection, TriMesh

from shell_adhesion.energy import equilibrium, pull_off
from shell_adhesion.analysis import figures
from shell_adhesion.analysis import along, base_point


@pytest.fixture(scope="module")
def ds(small_study):
    with xr.open_dataset(small_study) as d:
        return d.load()


def labelled_lines(ax):
    return [l for l in ax.get_lines() if not l.get_label().startswith("_")]


def units_on(ax, x_unit, y_unit):
    return f"[{x_unit}]" in ax.get_xlabel() and f"[{y_unit}]" in ax.get_ylabel()


def test_the_cube_keeps_what_the_figures_need(ds):
    base = base_point(ds)
    shell = dict(t_over_R=base["t_over_R"], h_over_R=base["h_over_R"])
    # relaxation curves scale exactly with C10 (one set of FE paths)
    P = ds["relaxation_P"].sel(shell)
    np.testing.assert_allclose(P.sel(C10=0.2), P.sel(C10=0.3) * (0.2 / 0.3), rtol=1e-13)
    # the outer surface never goes below the plane; the held zone lies on it
    z = ds["profile_outer_z"].sel(shell).values
    assert np.nanmin(z) > -1e-9
    assert set(ds["profile_stage"].sel(shell).values) == {"loading", "relaxation"}
    assert (ds["map_von_mises"].sel(shell) >= 0).all()
    # the loading stress map is the last loading state
    last = int(ds["loading_delta_mm"].sel(shell).notnull().sum()) - 1
    assert float(ds["map_delta"].sel(shell)[0]) == float(ds["loading_delta_mm"].sel(shell)[last])


def test_energy_surface_from_the_cube_gives_the_stored_pull_off(ds):
    """The stored relaxation curves are the whole input of the energy method: P* rebuilt
    from them equals the cube's P* (computed from the catalogue's path set)."""
    p = base_point(ds)
    R, C10 = float(ds["R"]), p["C10"]
    po = pull_off(equilibrium(figures._surface(ds, p), p["gamma"] * 1e-3 / (C10 * R)))
    assert po.P_star * C10 * R ** 2 == pytest.approx(float(ds["P_star"].sel(p)), rel=1e-12)
    assert po.delta_dagger * R == pytest.approx(float(ds["delta_dagger"].sel(p)), rel=1e-12)


def test_fig3_profiles(ds):
    left, right = figures.fig_profiles(ds)
    stage = ds["profile_stage"].sel(t_over_R=0.15, h_over_R=1.0).values
    assert len(labelled_lines(left)) == np.sum(stage == "loading") >= 5
    assert len(labelled_lines(right)) == np.sum(stage == "relaxation") >= 5
    assert units_on(left, "mm", "mm") and "[mm]" in right.get_xlabel()
    # the deepest loading profile ends at the loaded rim: z = h - delta
    r, z = labelled_lines(left)[-1].get_data()
    d = float(ds["profile_delta"].sel(t_over_R=0.15, h_over_R=1.0)[np.sum(stage == "loading") - 1])
    assert z.max() == pytest.approx(20.0 - d, abs=1e-9)


def test_fig4_load_relaxation(ds):
    ax = figures.fig_load_relaxation(ds)
    assert units_on(ax, "mm", "N")
    lines = ax.get_lines()
    x, y = lines[0].get_data()
    shell = dict(t_over_R=0.15, h_over_R=1.0)
    np.testing.assert_array_equal(y, ds["loading_P"].sel(C10=0.3, **shell).dropna("loading_state"))
    n_rel = int(ds["relaxation_a_mm"].sel(shell).notnull().sum())
    curves = [l for l in lines if len(l.get_xdata()) > 2]
    assert len(curves) == 1 + min(8, n_rel)     # loading and the relaxation paths shown
    fills = [c for c in ax.collections if isinstance(c, PolyCollection)]
    assert len(fills) == 3                      # U_E at A, area under AB, P delta at B


def test_fig5_energy_families(ds):
    top, top_zoom, bottom, bottom_zoom = figures.fig_energy(ds, n_curves=6)
    for ax in (top, bottom):
        assert units_on(ax, "mm$^2$", "mJ")
        assert any("equilibrium" in l.get_label() for l in ax.get_lines())
        assert any(l.get_marker() == "*" for l in ax.get_lines())     # pull-off marked
    P_star = float(ds["P_star"].sel(base_point(ds)))
    assert any(f"P* = {P_star:.3f} N" in l.get_label() for l in top.get_lines())
    families = [l for l in labelled_lines(top) if l.get_label().startswith("P = ")]
    assert 4 <= len(families) <= 6
    assert len([l for l in labelled_lines(bottom) if l.get_label().startswith("delta = ")]) >= 4


def test_fig6a_contact_radius_per_sweep(ds):
    axes = figures.fig_contact_radius(ds)
    assert len(axes) == 4
    for ax, (dim, _) in zip(axes, figures.SWEEPS):
        values = along(ds, "P_star", dim)
        assert units_on(ax, "N", "mm")
        assert len(labelled_lines(ax)) == values.size
        dots = [l for l in ax.get_lines() if l.get_marker() == "o"]
        np.testing.assert_array_equal([l.get_xdata()[0] for l in dots], values.values)


def test_fig6b_pull_off_with_jkr_and_eta(ds):
    axes = figures.fig_pull_off(ds)
    assert len(axes) == 4
    for ax, (dim, _) in zip(axes, figures.SWEEPS):
        ours, jkr, law = ax.get_lines()
        np.testing.assert_array_equal(ours.get_ydata(), -along(ds, "P_star", dim).values)
        assert "[N]" in ax.get_ylabel() and "JKR" in jkr.get_label() and "eta" in law.get_label()
    gamma_ax = axes[3]
    g = gamma_ax.get_lines()[1].get_xdata()
    np.testing.assert_allclose(gamma_ax.get_lines()[1].get_ydata(), 1.5 * np.pi * 20.0 * g * 1e-3)


def test_fig6b_panels_name_their_swept_factor_on_the_x_axis(ds):
    """Each panel's x axis and title name the factor it sweeps (not a legend's text)."""
    for ax, (dim, label) in zip(figures.fig_pull_off(ds), figures.SWEEPS):
        assert ax.get_xlabel() == label, dim
        assert label in ax.get_title(), dim


def test_von_mises_map(ds):
    fig = figures.figure_of(figures.fig_von_mises(ds))
    maps = [ax for ax in fig.axes if any(isinstance(c, TriMesh) for c in ax.collections)]
    assert len(maps) == 2
    for ax in maps:
        assert units_on(ax, "mm", "mm")
    assert fig.axes[-1].get_ylabel() == "von Mises stress [MPa]"      # the colour bar
    vm = ds["map_von_mises"].sel(C10=0.3, t_over_R=0.15, h_over_R=1.0)
    mesh = [c for c in maps[0].collections if isinstance(c, TriMesh)][0]
    assert mesh.get_clim()[1] == pytest.approx(np.nanpercentile(vm.values, figures.CLIP_PERCENTILE))
    assert f"largest {float(vm.max()):.3g} MPa" in fig.get_suptitle()


@pytest.fixture(scope="module")
def drawn(ds, tmp_path_factory):
    """Every figure of the small study as `run` and `plot` draw them (PNG and PDF, side by
    side, the default dpi), with the FE solver forbidden: (folder, written, skipped).  One
    drawing read by the tests below."""
    from conftest import forbid_fe_with
    out = tmp_path_factory.mktemp("figures")
    with pytest.MonkeyPatch.context() as patch:
        forbid_fe_with(patch)
        written, skipped = figures.write_figures(ds, out)
    return out, written, skipped


def test_write_figures_never_solves(drawn):
    tmp_path, written, skipped = drawn
    assert figures.PROCESSES > 1        # drawn side by side
    assert skipped == {}
    assert sorted(p.name for p in written) == sorted(
        f"{n}.{e}" for n in figures.FIGURES for e in ("png", "pdf"))
    assert all(p.stat().st_size > 1000 for p in written)
    assert not [p for p in tmp_path.iterdir() if ".tmp" in p.name]
    assert all(p.stat().st_mode & 0o044 for p in written)     # readable like any output


def test_missing_outputs_are_skipped_with_the_reason(ds, tmp_path):
    lean = ds.drop_vars([v for v in ds.data_vars if v.startswith(("profile_", "map_"))])
    with pytest.raises(figures.MissingData, match="profile_stage"):
        figures.fig_profiles(lean)
    written, skipped = figures.write_figures(lean, tmp_path, formats=("png",))
    assert set(skipped) == {"fig2_von_mises", "fig3_profiles"}
    assert len(written) == len(figures.FIGURES) - 2


def test_run_writes_tables_and_figures_beside_the_cube(small_study):
    stem = small_study.with_suffix("")
    tables = {p.name for p in stem.with_name(stem.name + "_tables").iterdir()}
    assert tables == {f"{t}.{f}" for t in ("cases", "paper") for f in ("csv", "md", "tex")} | {
        "analysis.txt"}
    figs = {p.name for p in stem.with_name(stem.name + "_figures").iterdir()}
    assert figs == {f"{n}.png" for n in figures.FIGURES}      # PDF on request (plot)


def test_figures_drawn_side_by_side_are_those_drawn_one_by_one(ds, drawn, tmp_path):
    one, skipped_one = figures.write_figures(ds, tmp_path / "one", ("png",), processes=1)
    _, written, skipped_two = drawn         # side by side (PROCESSES)
    two = [p for p in written if p.suffix == ".png"]
    assert [p.name for p in one] == [p.name for p in two] and skipped_one == skipped_two
    assert all(a.stat().st_size == b.stat().st_size for a, b in zip(one, two))


def test_plot_command(small_study, tmp_path, forbid_fe, capsys):
    from shell_adhesion.cli import main
    assert main(["plot", str(small_study), "--out", str(tmp_path / "f"), "--format", "png"]) == 0
    assert len(list((tmp_path / "f").glob("*.png"))) == len(figures.FIGURES)
    assert "6 files in" in capsys.readouterr().out
    assert main(["plot", str(small_study), "--format", "png,gif"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--format" in err[0] and "gif" in err[0]
    assert main(["plot", str(tmp_path / "nothing.nc")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "nothing.nc" in err[0]


def test_a_base_without_some_factors_uses_the_middle_of_their_axis(ds, tmp_path):
    """A grid-only factor has no base value: figures and tables still come out."""
    from shell_adhesion.analysis.products import write_tables
    grid = ds.copy()
    del grid.attrs["base_C10_MPa"], grid.attrs["base_gamma_J_m2"]
    assert base_point(grid) == dict(C10=0.3, t_over_R=0.15, h_over_R=1.0, gamma=30.0)
    written, skipped = figures.write_figures(grid, tmp_path / "f", formats=("png",))
    assert skipped == {} and len(written) == len(figures.FIGURES)
    assert len(write_tables(grid, tmp_path / "t")) == 7


# figures for people: the caller's Axes, viridis, legends that mean something, >= 100 dpi

PANELS = {figures.fig_von_mises: 2, figures.fig_profiles: 2, figures.fig_load_relaxation: 1,
          figures.fig_energy: 4, figures.fig_contact_radius: 4, figures.fig_pull_off: 4}


@pytest.mark.parametrize("draw", list(PANELS), ids=lambda f: f.__name__)
def test_every_figure_draws_into_the_callers_axes(ds, draw):
    from matplotlib.figure import Figure
    n = PANELS[draw]
    fig = Figure()
    given = fig.subplots(1, n, squeeze=False)[0]
    keyword = "ax" if n == 1 else "axes"
    got = draw(ds, **{keyword: given[0] if n == 1 else given})
    assert list(np.ravel(got)) == list(given)
    assert all(ax.has_data() for ax in given)
    with pytest.raises(ValueError, match=f"needs {n} Axes"):
        draw(ds, **{keyword: Figure().subplots(1, n + 1)})
    own = draw(ds)                                     # a new Figure, no pyplot
    assert len(np.ravel(own)) == n and figures.figure_of(own) is not fig


def _drawn(artist):
    """Independent of figures._drawn: a line with two finite points and a line style, or
    one with a marker; a collection with paths."""
    if hasattr(artist, "get_xydata"):
        xy = artist.get_xydata()
        n = int(np.isfinite(xy).all(axis=1).sum())
        return (artist.get_linestyle() not in ("None", "") and n >= 2) or (
            artist.get_marker() not in ("None", "", None) and n >= 1)
    return len(artist.get_paths()) > 0


def test_no_legend_entry_without_a_line(ds):
    one_gamma = ds.sel(gamma=[30.0])          # single points: markers make them visible
    drawn = [(name, ax) for name, draw in figures.FIGURES.items() for ax in np.ravel(draw(ds))]
    drawn += [("fig6b_one_gamma", ax) for ax in figures.fig_pull_off(one_gamma)]
    legends = 0
    for name, ax in drawn:
        legend = ax.get_legend()
        if legend is None:
            continue
        legends += 1
        shown = {t.get_text() for t in legend.get_texts()}
        handles = dict(zip(*reversed(ax.get_legend_handles_labels())))
        assert shown <= set(handles), name
        for label in shown:
            assert _drawn(handles[label]), (name, label)
    assert legends >= 12
    # a dashed line through one point shows nothing: no entry for it
    from matplotlib.figure import Figure
    ax = Figure().subplots()
    ax.plot([1.0], [1.0], "k--", label="invisible")
    ax.plot([0.0, 1.0], [0.0, 1.0], label="visible")
    figures._legend(ax)
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["visible"]


def test_colour_maps_are_perceptually_uniform(ds):
    from matplotlib import colormaps
    assert figures.CMAP in ("viridis", "cividis", "plasma", "inferno", "magma")
    fig = figures.figure_of(figures.fig_von_mises(ds))
    meshes = [c for ax in fig.axes for c in ax.collections if isinstance(c, TriMesh)]
    assert meshes and all(m.get_cmap().name == figures.CMAP for m in meshes)
    cmap = colormaps[figures.CMAP]
    viridis = cmap(np.linspace(0, 1, 256))[:, :3]
    for ax in figures.fig_contact_radius(ds):
        for line in labelled_lines(ax):
            rgb = np.array(line.get_color())[:3]
            assert np.min(np.abs(viridis - rgb).sum(axis=1)) < 1e-6


def test_fig5_zooms_on_the_pull_off_state(ds):
    top, top_zoom, bottom, bottom_zoom = figures.fig_energy(ds)
    for main, zoom in ((top, top_zoom), (bottom, bottom_zoom)):
        star = [l for l in main.get_lines() if l.get_marker() == "*"][0]
        zstar = [l for l in zoom.get_lines() if l.get_marker() == "*"][0]
        np.testing.assert_array_equal(star.get_xydata(), zstar.get_xydata())
        (A0, U0), = star.get_xydata()
        lo, hi = zoom.get_xlim()
        assert lo < A0 < hi and hi - lo == pytest.approx(2 * figures.ZOOM * A0)
        zlo, zhi = zoom.get_ylim()
        mlo, mhi = main.get_ylim()
        assert zlo < U0 < zhi and (zhi - zlo) < 0.1 * (mhi - mlo)     # a real zoom
        assert units_on(zoom, "mm$^2$", "mJ") and "zoom" in zoom.get_title()


def test_png_figures_at_100_dpi_or_more(drawn, small_study):
    from PIL import Image
    written = [p for p in drawn[1] if p.suffix == ".png"]
    stem = small_study.with_suffix("")
    run_pngs = list(stem.with_name(stem.name + "_figures").glob("*.png"))
    assert len(run_pngs) == len(written) == len(figures.FIGURES)
    for png in written + run_pngs:
        with Image.open(png) as im:
            assert min(im.info["dpi"]) >= figures.MIN_DPI, png
