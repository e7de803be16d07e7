"""Error bars (issue 10, item 7): the rule (solver.error_bars), the study cube's
`<name>_error` variables through the catalogue, tables printing value +- error, Fig. 6's
error bars, trend verdicts counting a step only beyond the combined error, and (slow) the
base shell's default-mesh P* +- 2 error bars holding the fine-mesh P*."""
import csv
import io

import matplotlib
import numpy as np
import pytest
import xarray as xr

from shell_adhesion.errors import InputError
from shell_adhesion.solver.error_bars import (ORDER, SAFETY, SAFETY_OBSERVED, curve_error,
                                               error_bar, observed_order, rule)
from shell_adhesion import analysis
from shell_adhesion.analysis import figures, tables

from validation import within

matplotlib.use("Agg")


def test_rule():
    assert error_bar(-1.0, -1.01) == pytest.approx(SAFETY * 0.01 / (2 ** ORDER - 1))
    assert np.isnan(error_bar(1.0, np.nan))
    # three meshes converging at order 2 (differences 0.04 then 0.01): Richardson with
    # factor 1.25, the order credited at most the assumed one; below it, as observed
    assert observed_order(1.0, 1.01, 1.05) == pytest.approx(2.0)
    assert error_bar(1.0, 1.01, 1.05) == pytest.approx(SAFETY_OBSERVED * 0.01 / (2 ** ORDER - 1))
    p = np.log2(0.015 / 0.01)
    assert error_bar(1.0, 1.01, 1.025) == pytest.approx(SAFETY_OBSERVED * 0.01 / (2 ** p - 1))
    # not monotone (the differences change sign), or an order beyond OBSERVED_ORDERS:
    # back to order 1 with factor 3, on the larger of the finer difference and the coarser
    # one carried to the finer mesh at order 1
    for coarsest, step in ((0.99, 0.01), (1.0101, 0.01), (0.98, 0.015),
                           (1.01 + 0.01 * 2 ** 5, 0.01 * 2 ** 4)):
        assert np.isnan(observed_order(1.0, 1.01, coarsest))
        assert error_bar(1.0, 1.01, coarsest) == pytest.approx(SAFETY * step)
    assert error_bar(1.0, 1.01, np.nan) == pytest.approx(SAFETY * 0.01)  # two suffice
    # a family whose steps do not all refine every direction: no order is observed
    assert np.isnan(observed_order(1.0, 1.01, 1.05, order_observable=False))
    assert error_bar(1.0, 1.01, 1.05, False) == pytest.approx(SAFETY * 0.02)


def test_the_rule_is_named():
    assert rule(1.0, 1.01, 1.05) == "observed order p = 2, used as 1 (factor 1.25)"
    assert rule(1.0, 1.01, 1.025) == "observed order p = 0.585 (factor 1.25)"
    assert rule(1.0, 1.01, 0.99) == "order 1 assumed (factor 3)"
    assert rule(1.0, 1.01, 1.05, False) == "order 1 assumed (factor 3)"
    assert rule(1.0, 1.01) == rule(1.0, 1.01, np.nan) == "order 1 assumed (factor 3), two meshes"
    assert rule(1.0, np.nan, 1.05) == rule(np.nan, 1.0) == "none"


def test_one_kind_of_contact_front_gives_an_order_a_mix_does_not():
    """The thin shell of issue 39 (R 15, t 1.5, h 11.25 mm, C10 0.5 MPa, gamma 20 J/m^2),
    P* [N] on the default, coarse and coarser meshes, measured with the relaxed contact
    fronts ending on element corners and on midside nodes (benchmarks/error_bars.py).
    Each kind converges monotonically at order 1.1-1.2 to about -0.6844 N; each mesh's
    larger kind (midside, corner, midside: the rule before) crossed and gave the order-1
    bar 0.019 N, 5.5 times the error.  With the answer's kind on its companions the bar
    holds both kinds' extrapolations and is at most 3 times the error."""
    corner = (-0.683113, -0.681408, -0.677417)
    midside = (-0.680806, -0.676930, -0.668725)
    mixed = (midside[0], corner[1], midside[2])
    assert np.isnan(observed_order(*mixed))
    assert error_bar(*mixed) > 5 * abs(midside[0] + 0.6844)
    limits = []
    for f in (corner, midside):
        p = observed_order(*f)
        assert 1.0 < p < 1.3
        limits.append(f[0] + (f[0] - f[1]) / (2 ** p - 1))
    assert limits[0] == pytest.approx(limits[1], abs=2e-4)     # 0.02 %
    for f in (corner, midside):
        bar = error_bar(*f)
        for limit in limits:
            assert abs(f[0] - limit) < bar < 3 * abs(f[0] - limit)


def test_the_base_shell_bar_holds_the_extrapolated_value():
    """The paper's base shell (R = h = 20 mm, t = 3 mm, C10 0.3 MPa, gamma 30 J/m^2,
    no_slip), P* [N] on the coarser, coarse, default and fine meshes, one kind of contact
    front (`python benchmarks/error_bars.py 20 3 20 0.3 30 default coarser coarse default
    fine`).  The order observed on the first three (1.54) is above the one on the last
    three (1.19); credited, it gave the default mesh a bar of 0.0014 N, 0.83 of its distance
    to the value extrapolated from the last three.  Credited at most as 1, the bar holds
    that value and the fine mesh's, at most 3 times its distance to either."""
    coarser, coarse, default, fine = -1.7058950, -1.7123369, -1.7145509, -1.7155239
    assert observed_order(default, coarse, coarser) > 1.5
    p = observed_order(fine, default, coarse)
    limit = fine + (fine - default) / (2 ** p - 1)
    bar = error_bar(default, coarse, coarser)
    for truth in (limit, fine):
        assert abs(default - truth) < bar < 3 * abs(default - truth)


def test_relaxation_starts_of_one_kind(base_coarse):
    from shell_adhesion.solver.case import relaxation_starts, start_family
    ps, d, loading = base_coarse
    for family in ("corner", "midside"):
        starts = relaxation_starts(loading, d.capmesh, family)
        assert len(starts) > 10
        assert {bool(d.capmesh.outer_corner[max(s.held)]) for s in starts} == {
            family == "corner"}
        assert start_family(starts, d.capmesh) == family
    assert ps.stats["relaxation_family"] == start_family(
        relaxation_starts(loading, d.capmesh), d.capmesh)
    with pytest.raises(InputError, match="family: 'edge' must be one of corner, midside"):
        relaxation_starts(loading, d.capmesh, "edge")


def test_values_that_cross_get_the_error_of_the_coarser_step():
    """t/R 0.02, h/R 0.2, gamma/(C10 R) 0.015 (P*/(C10 R^2) on the coarser, coarse,
    default and fine meshes, measured): the default mesh's value nearly equals the coarse
    one's, so their difference alone (the rule before) gave a bar of 0.06 % and the fine
    mesh lay 5.5 bars away; with the coarser step it holds the fine mesh."""
    coarser, coarse, default, fine = -0.065719, -0.065516, -0.065528, -0.065731
    assert SAFETY * abs(default - coarse) < abs(fine - default) / 5
    bar = error_bar(default, coarse, coarser)
    assert abs(fine - default) < bar < 0.01 * abs(default)


def test_an_order_is_observed_only_where_each_step_adds_layers_through_the_thickness():
    from shell_adhesion.solver.error_bars import refines_through_thickness
    from shell_adhesion.solver.mesh import mesh_spec, thickness_layers

    def layers(t, mesh):
        return len(thickness_layers(t, mesh_spec(mesh))) - 1
    # a thin shell's layers double at each level (solver.mesh.thin_shell): 1, 2, 4, 8 on
    # coarser, coarse, default, fine (the graded rule gave 1, 1, 2, 4 at t/R 0.02: no
    # order on the default mesh); 1 on coarsest too
    assert [layers(0.02, m) for m in ("coarsest", "coarser", "coarse", "default", "fine")
            ] == [1, 1, 2, 4, 8]
    assert refines_through_thickness(0.02, "default")
    assert refines_through_thickness(0.02, "fine")
    assert not refines_through_thickness(0.02, "coarse")    # 1, 1, 2
    # t/R 0.05 (graded): 2, 2, 4 on coarser, coarse, default; 7 on fine
    assert [layers(0.05, m) for m in ("coarser", "coarse", "default", "fine")] == [2, 2, 4, 7]
    assert not refines_through_thickness(0.05, "default")
    assert refines_through_thickness(0.05, "fine")
    # the base shell: 3, 4, 7
    assert [layers(0.15, m) for m in ("coarser", "coarse", "default")] == [3, 4, 7]
    assert refines_through_thickness(0.15, "default")
    assert refines_through_thickness(1.0, "coarse")          # a solid cap
    assert not refines_through_thickness(0.15, "coarser")    # no third mesh below it
    e = curve_error([0.0, 0.5, 2.0], [0.0, 1.0, 4.0], [0.0, 1.0], [0.0, 2.2])
    assert e[0] == 0 and e[1] == pytest.approx(error_bar(1.0, 1.1)) and np.isnan(e[2])


def test_a_single_layer_through_the_thickness_does_not_enter_the_bar():
    """The mesh two levels coarser enters a bar only with two element layers or more
    through the shell (solver.error_bars.coarsest_usable): t/R 0.02 has 1, 1, 2, 4, 8 on
    coarsest ... fine, so the default mesh's bar uses the coarse mesh alone."""
    from shell_adhesion.solver.error_bars import coarsest_usable
    assert not coarsest_usable(0.02, "default")      # coarser: 1 layer
    assert not coarsest_usable(0.02, "coarse")       # coarsest: 1 layer
    assert coarsest_usable(0.02, "fine")             # coarse: 2 layers
    assert coarsest_usable(0.15, "default") and coarsest_usable(1.0, "coarse")
    assert not coarsest_usable(0.15, "coarser")      # no mesh two levels below it
    # measured (t/R 0.02, h/R 0.2, gamma/(C10 R) 0.015, P* [N] on 1, 2, 4, 8 layers): with
    # the one-layer mesh the bar was 5 times the default mesh's distance to the fine one
    coarser, coarse, default, fine = -7.91295, -7.87840, -7.88395, -7.89428
    assert error_bar(default, coarse, coarser) > 3 * abs(fine - default)


# t/R 0.02, h/R 0.2 (R 20, t 0.4, h 4 mm, C10 0.3 MPa), P* [N] on 2, 4, 8, 16 element layers
# (coarse, default, fine, finer; the finer mesh relaxed from the contact fronts within
# 0.98-1.4 a* of the default's: benchmarks/error_bars.py 20 0.4 4 0.3 GAMMA default coarse
# default fine finer --window 0.98,1.4; 96,039 dofs, about 100 minutes each)
THIN_FAMILY = {0.03: (-13.5916, -13.6170, -13.6395, -13.65367),
               0.015: (-7.87840, -7.88395, -7.89428, -7.90074),
               0.005: (-3.07726, -3.07537, -3.07769, -3.07937)}


@pytest.mark.parametrize("gamma_hat", sorted(THIN_FAMILY))
def test_a_thin_shells_bar_brackets_the_value_extrapolated_from_finer_meshes(gamma_hat):
    """The default mesh's bar from the coarse mesh alone (solver.error_bars.assumed_order:
    the family's order 2/3) holds the value Richardson extrapolates from the 4-, 8- and
    16-layer meshes, at most 3 times its distance (measured 2.1, 1.03 and 1.15 times at
    0.03, 0.015 and 0.005); with order 1 it did not at 0.015 (0.6 times: the step from 2
    to 4 layers is the smallest of the three) nor at 0.005 (0.68 times: the coarse and
    default values cross)."""
    from shell_adhesion.solver.error_bars import THIN_ORDER, assumed_order
    coarse, default, fine, finer = THIN_FAMILY[gamma_hat]
    order = assumed_order(0.02, "default")
    assert order == THIN_ORDER and assumed_order(0.15, "default") == ORDER
    p = np.log2((fine - default) / (finer - fine))  # steps of one sign: Richardson's order
    assert 0.4 < p < 0.75                            # measured 0.67, 0.68, 0.47
    limit = finer + (finer - fine) / (2 ** p - 1)
    bar = float(error_bar(default, coarse, None, True, order))
    assert abs(limit - default) <= bar <= 3 * abs(limit - default)
    assert abs(finer - default) <= bar
    assert rule(default, coarse, None, True, order) == (
        "order 0.667 assumed (factor 3), two meshes")
    if gamma_hat == 0.015:
        assert error_bar(default, coarse) < 0.7 * abs(limit - default)   # order 1: 0.6


# the same shell at gamma/(C10 R) 0.001, P* [N] on 1, 2, 4, 8 layers (coarser ... fine)
# relaxed from contact fronts of one kind within 0.8-1.4 a*, on the single gamma's fit
# (python benchmarks/front_families.py 20 0.4 4 0.3 6 coarser,coarse,default,fine), and
# the 16-layer midside value (THIN_FAMILY's reference run at 0.001)
FRONTS_0001 = {"corner": (-0.652558, -0.645005, -0.643545, -0.643501),
               "midside": (-0.648133, -0.642933, -0.642711, -0.643094)}
FINER_MIDSIDE_0001 = -0.64340


@pytest.mark.parametrize("kind", sorted(FRONTS_0001))
def test_at_the_lowest_gamma_either_kind_of_front_gets_an_honest_bar(kind):
    """docs/domain.md, "Which contact fronts": on t/R 0.02, h/R 0.2 at 0.001 the default
    mesh's two-mesh bar (order 2/3) holds the fine values of both kinds and the 16-layer
    value, below 2 % of P*.  For corner fronts it is not useful: the values converge fast
    (the default within 0.00005 N of the fine), so the bar is more than 15 times the
    largest distance to a finer value, and even the three-mesh rule with the one-layer
    mesh (observed order 2.4, credited as 1) more than 3.6 times: the coarse steps do not
    show how close the default mesh is."""
    from shell_adhesion.solver.error_bars import THIN_ORDER
    coarser, coarse, default, _ = FRONTS_0001[kind]
    finer = [FRONTS_0001["corner"][3], FRONTS_0001["midside"][3], FINER_MIDSIDE_0001]
    far = max(abs(f - default) for f in finer)
    bar = float(error_bar(default, coarse, None, True, THIN_ORDER))
    assert far <= bar < 0.02 * abs(default)
    if kind == "corner":
        assert bar > 15 * far
        assert observed_order(default, coarse, coarser) == pytest.approx(2.37, abs=0.01)
        assert float(error_bar(default, coarse, coarser)) > 3.6 * far
    else:
        assert bar <= 3 * min(abs(f - default) for f in finer) + 1e-6


def test_trend_counts_a_step_only_beyond_the_combined_error():
    values = [1.00, 1.02, 1.04]
    assert analysis.trend_of(values, 0.001) == "increasing"
    assert analysis.trend_of(values, 0.001, errors=[0.011, 0.011, 0.011]) == "increasing"
    # each step 0.02 within the sum of two 0.015 bars, the whole 0.04 beyond it
    assert analysis.trend_of(values, 0.001, errors=[0.015] * 3) == "increasing"
    assert analysis.trend_of(values, 0.001, errors=[0.03] * 3) == "flat"
    # a missing bar falls back to the mesh uncertainty: 0.04 > 0.001 + 0.03
    assert analysis.trend_of(values, 0.001, errors=[np.nan, 0.03, 0.03]) == "increasing"


@pytest.fixture(scope="module")
def with_errors(small_study):
    """The small study's cube with error bars of 1 % on every pull-off value (the
    rendering does not care where they came from)."""
    with xr.open_dataset(small_study) as ds:
        ds = ds.load()
    for k in ("P_star", "delta_star", "a_star", "P_dagger", "delta_dagger", "a_dagger", "a0",
              "eta"):
        ds[f"{k}_error"] = 0.01 * abs(ds[k])
        ds[f"{k}_error"].attrs = dict(units=ds[k].attrs.get("units", "1"), long_name="error")
    return ds


def test_tables_print_value_plus_minus_error(with_errors):
    table = tables.cases_table(with_errors)
    md = tables.render(table, "md")
    assert md.count(" ± ") >= 7 * 7      # 7 cases, every value but the missing a0's
    text = tables.render(table, "csv")
    rows = list(csv.reader(io.StringIO(text)))
    header = rows[0]
    assert "P* error [N]" in header and "eta error [1]" in header
    i, j = header.index("P* [N]"), header.index("P* error [N]")
    for row in rows[1:]:
        assert float(row[j]) == pytest.approx(0.01 * abs(float(row[i])), rel=1e-12)


def test_fig6_draws_error_bars(with_errors):
    axes = figures.fig_pull_off(with_errors)
    assert any(c.__class__.__name__ == "ErrorbarContainer" for ax in axes for c in ax.containers)
    sentence = analysis.trend(with_errors, "gamma").sentence
    assert "+-" in sentence and "error bars" in sentence


STUDY = """\
name: eb
R_mm: 20
base: {C10_MPa: 0.3, t_over_R: 0.15, h_over_R: 1.0, gamma_J_m2: 30}
mesh: coarse
delta_max_over_R: 0.05
"""


def test_study_error_bars_through_the_catalogue(tmp_path):
    """The two coarser meshes' sets are catalogue entries like any other: a rerun solves
    nothing; the cube says where the observed order was used (`P_star_order`)."""
    from shell_adhesion.study.run import execute
    (tmp_path / "eb.yaml").write_text(STUDY)
    out = execute(tmp_path / "eb.yaml", tmp_path / "r", catalogue=tmp_path / "cat",
                  progress=False, workers=1)
    assert out.exit_code == 0 and len(out.computed) == 3
    assert "P_star_order" in out.dataset and "a0_order" in out.dataset
    ds = out.dataset
    P, e = float(ds["P_star"].squeeze()), float(ds["P_star_error"].squeeze())
    assert 0 < e < 0.05 * abs(P)
    assert np.isfinite(ds["loading_P_error"].values).any()
    # the companions relax the answer's kind of contact front (issue 39 item 4), and their
    # keys say so: a set relaxed for another answer never serves them
    import json
    from shell_adhesion.catalogue import Catalogue
    plan = out.plan
    answer = plan.shells[0]
    cat = Catalogue(tmp_path / "cat")
    family = {s.fingerprint: json.loads(cat.fetch(s.key)[1].attrs["stats"])["relaxation_family"]
              for s in plan.all_shells}
    cat.close()
    for s in plan.error_shells + plan.third_shells:
        assert s.answer == answer.fingerprint
        assert s.key["relaxation_family"] == {"as": answer.fingerprint}
        assert family[s.fingerprint] == family[answer.fingerprint]
    assert "relaxation_family" not in answer.key
    again = execute(tmp_path / "eb.yaml", tmp_path / "r2", catalogue=tmp_path / "cat",
                    progress=False, workers=1)
    assert again.computed == [] and len(again.reused) == 3
    assert float(again.dataset["P_star_error"].squeeze()) == e


@pytest.mark.slow
def test_base_shell_default_error_bar_holds_the_fine_value():
    """Default mesh P* +- 2 error bars holds the fine-mesh P*, and the error bar is below
    2 % of P* (paths to delta = 0.05 R, beyond the pull-off; the fine mesh takes minutes)."""
    from conftest import GAMMA_HAT, base_case
    P = {m: base_case(m, "no_slip", 0.006, 0.05)[0].pull_off(GAMMA_HAT)[1].P_star
         for m in ("coarse", "default", "fine")}
    err = float(error_bar(P["default"], P["coarse"]))
    print("base shell P*", P, "error bar", err)
    assert abs(P["fine"] - P["default"]) <= 2 * err
    # README: -0.0142492 +- 6.1e-5 C10 R^2 (0.43 %), the fine mesh 0.41 error bars away
    within("base shell error bar", err, 6.1e-5, 0.0, floor=0.1e-5)
    within("fine - default in error bars", abs(P["fine"] - P["default"]) / err, 0.41, 0.0,
           floor=0.02)


@pytest.mark.slow
def test_thin_shell_default_error_bar_holds_the_fine_value():
    """The same for a thin shell, t/R = 0.1 (the paper's thinnest) at gamma/(C10 R) =
    0.003, whose pull-off radii (a* = 0.08 R, a_dagger = 0.055 R) lie in the evenly meshed
    zone (paths to delta = 0.05 R)."""
    from shell_adhesion.solver.case import solve_paths
    gamma = 0.003
    P = {m: solve_paths(0.1, 1.0, "no_slip", m, 0.05, 1.25 * gamma)[0].pull_off(gamma)[1].P_star
         for m in ("coarse", "default", "fine")}
    err = float(error_bar(P["default"], P["coarse"]))
    assert abs(P["fine"] - P["default"]) <= 2 * err
    assert err < 0.02 * abs(P["default"])


def _useful_bar_against_fine(name, R_mm, t_mm, h_mm, C10_MPa, gamma_J_m2,
                             rule="observed order", reference=None):
    """(P* [N], its bar) of `solve_case` on the default mesh, after checking issue 39 item
    4's rule against the fine mesh: the bar uses `rule` (the start of the case's
    P_N_rule), holds the fine P* within 2 bars, is at most 3 times its distance to it and
    below 2 % of P*.  With `reference` (a value from finer meshes, nearer the converged
    one than the fine mesh's) the bar holds it and is at most 3 times its distance to it
    instead."""
    import shell_adhesion as sa
    args = (R_mm, t_mm, h_mm, C10_MPa, [gamma_J_m2])
    po = sa.solve_case(*args, progress=False).to_dict()["pull_off"][0]["fixed_load"]
    fine = sa.solve_case(*args, mesh="fine", progress=False, error_bars=False)
    P_fine = fine.to_dict()["pull_off"][0]["fixed_load"]["P_N"]
    bar, distance = po["P_N_error"], abs(po["P_N"] - P_fine)
    print(name, "P*", po["P_N"], "+-", bar, po["P_N_rule"], "fine", P_fine)
    assert po["P_N_rule"].startswith(rule)
    assert distance <= 2 * bar and bar < 0.02 * abs(po["P_N"])
    if reference is not None:
        distance = abs(po["P_N"] - reference)
        assert distance <= bar
    assert bar <= 3 * distance
    return po["P_N"], bar


@pytest.mark.slow
def test_thin_shell_error_bar_is_useful():
    """Issue 39 item 4: the thin shell R 15, t 1.5, h 11.25 mm, C10 0.5 MPa, gamma 20 J/m^2
    (t/R 0.1), `solve_case` on the default mesh: the P* bar uses the observed order (the
    companions relax contact fronts of the answer's kind), holds the fine mesh's P* within
    2 bars, is at most 3 times its distance to it and below 2 % of P* (measured: -0.68081
    +- 0.00485 N, order 1.08 credited as 1; before, +- 0.019 N from the order-1 rule, 7.6
    times the distance to the fine mesh).  The fine mesh takes minutes."""
    P, bar = _useful_bar_against_fine("thin shell", 15.0, 1.5, 11.25, 0.5, 20.0)
    within("thin shell P*", P, -0.68081, 0.0, floor=1e-5)
    within("thin shell P* error bar", bar, 0.00485, 0.0, floor=1e-5)


@pytest.mark.slow
@pytest.mark.parametrize("gamma, P_N, bar_N, reference_N", [(30.0, -3.07537, 0.009663, -3.07937),
                                                            (6.0, -0.642713, 0.001141, -0.64340)])
def test_thinnest_shell_error_bar_is_useful(gamma, P_N, bar_N, reference_N):
    """Issue 39 item 4: t/R 0.02, h/R 0.2 (R 20, t 0.4, h 4 mm, C10 0.3 MPa, gamma 30 and
    6 J/m^2, gamma/(C10 R) 0.005 and 0.001), `solve_case` on the default mesh: its layers
    double at each level (1, 2, 4 on coarser, coarse, default; 8 on fine) and the one-layer
    coarser mesh does not enter the bar (`coarsest_usable`): the coarse and default meshes
    at the order 2/3 a thin shell's two-mesh bar assumes (`assumed_order`).  The bar holds
    the fine mesh's P* within 2 bars, is below 2 % of P*, and holds the value of the
    16-layer mesh (-3.07937 N at 0.005, -0.64340 N at 0.001, where the fine mesh's
    value lies beyond it), at most 3 times its distance to it
    (`python benchmarks/error_bars.py 20 0.4 4 0.3 GAMMA default default finer --window
    0.98,1.4`, 100 minutes).  Measured: -3.07537 +- 0.00966 N, fine (24,837 dofs, 35 min
    on a loaded machine) -3.07769 N (0.24 bars), 2.4 times the distance to the finer
    mesh; -0.642713 +- 0.00114 N, the fine mesh's own run (corner fronts) -0.643499 N
    (0.69 bars), 1.67 times the distance to the finer mesh.  With order 1 the bars were 0.00568 and 0.00067 N (0.98 times the
    distance to the finer mesh at 0.001: it did not bracket it).  The fine mesh takes
    half an hour (`python benchmarks/error_bars.py 20 0.4 4 0.3 30`)."""
    P, bar = _useful_bar_against_fine("t/R 0.02", 20.0, 0.4, 4.0, 0.3, gamma,
                                      rule="order 0.667 assumed (factor 3), two meshes",
                                      reference=reference_N)
    within("t/R 0.02 P*", P, P_N, 0.0, floor=1e-5)
    within("t/R 0.02 P* error bar", bar, bar_N, 0.0, floor=1e-5)
