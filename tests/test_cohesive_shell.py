"""The cohesive pull-off of shells as docs/adhesion-range.md states it: R = h = 20 mm,
C10 = 0.3 MPa, gamma = 30 J/m^2 (gamma / (C10 R) = 0.005), frictionless (no_slip where
named), default mesh.

Each stated P* is held within its stated error bar (with a floor of one unit of its last
printed digit); the energy method's P* beside it likewise.  The base shell's three lambdas
are `slow` (about 2 minutes); the thickness minimum and lambda = 3 are `long` (about 10
minutes each; with eight elements across the zone, frictionless and no_slip, about 20;
with sixteen, about 15; no_slip with the default four, retried with eight, about 11),
lambda 0.05's minimum too (about a minute).
"""
import pytest

from shell_adhesion.study.case import solve_case
from shell_adhesion.study.cohesive_case import solve_cohesive_case, zone_estimate

R_MM, C10, GAMMA = 20.0, 0.3, 30.0
# lambda -> (P* [N], error bar [N]) of the base shell (docs: "The base shell")
BASE = {0.3: (-2.5282, 0.0015), 1.0: (-2.1751, 0.0089), 2.0: (-2.1001, 0.083)}
ENERGY_BASE = (-2.0447, 0.00094)   # the energy method's frictionless P* (covered area, edge
#                                    force to second order)
# t/R -> lambda 0.05's P* [N] (docs: "Pull-off against lambda", rows of
# docs/figures/cohesive_thickness.csv): the minimum moved to t/R = 0.075
# the no_slip law and history before the fourth wave (mode-I-only toughness, adhesive approach)
NORMAL_ONLY = dict(beta=0.0, history="adhesive")
LONG_RANGE = {0.05: (-3.0260, 0.00039), 0.075: (-2.9287, 0.00035), 0.1: (-2.9893, 0.00044)}
# t/R -> lambda 1's P* and the energy method's (docs: "Pull-off against thickness")
THICKNESS = {0.075: ((-2.243, 0.03), (-2.176, 0.0013)), 0.1: ((-1.850, 0.015), (-1.763, 0.0072)),
             0.15: ((-2.175, 0.0095), (-2.045, 0.00094))}


def _shell(t_over_R):
    return dict(R_mm=R_MM, t_mm=t_over_R * R_MM, h_mm=R_MM, C10_MPa=C10, gamma_J_m2=GAMMA)


def _cohesive(t_over_R, lam):
    r = solve_cohesive_case(**_shell(t_over_R), tabor=lam, error_bars=False)
    assert not r.refused, r.refused
    return r.to_dict()["pull_off"]


def _cohesive_P(t_over_R, lam):
    return _cohesive(t_over_R, lam)["P_star_N"]


def _energy_P(t_over_R):
    e = solve_case(**_shell(t_over_R), interface="frictionless", progress=False,
                   error_bars=False)
    return e.to_dict()["pull_off"][0]["fixed_load"]["P_N"]


def _within(name, value, stated, digits=4):
    P, err = stated
    bound = max(err, 10.0 ** -digits)
    assert abs(value - P) <= bound, f"{name}: {value:.5f} N, the docs state {P} +- {err} N"


@pytest.mark.slow
def test_base_shell_pull_off_approaches_the_energy_method_as_lambda_grows():
    energy = _energy_P(0.15)
    _within("energy method", energy, ENERGY_BASE)
    ratios = []
    for lam, stated in BASE.items():
        po = _cohesive(0.15, lam)
        _within(f"lambda {lam}", po["P_star_N"], stated)
        ratios.append(po["P_star_N"] / energy)
        if lam == 2.0:      # the docs: traced zone 0.349 mm, Maugis' sphere 0.345 mm
            assert abs(po["c_star_mm"] - po["a_star_mm"] - 0.349) <= 0.001
            assert abs(zone_estimate(0.005, 2.0) * R_MM - 0.345) <= 0.001
    print("P*/energy method's:", [f"{r:.3f}" for r in ratios])
    # the finite range adds to the zero-range pull-off, less as lambda grows
    assert all(r > 1 for r in ratios) and ratios == sorted(ratios, reverse=True)


@pytest.mark.long
def test_the_pull_off_is_least_near_t_over_R_0_1():
    P = {t: (_cohesive_P(t, 1.0), _energy_P(t)) for t in THICKNESS}
    for t, (coh, energy) in P.items():
        _within(f"t/R {t}, lambda 1", coh, THICKNESS[t][0], 3)
        _within(f"t/R {t}, energy method", energy, THICKNESS[t][1], 3)
    for k in (0, 1):        # least |P*| at t/R = 0.1, for the cohesive and the energy method
        assert min(P, key=lambda t: abs(P[t][k])) == 0.1


@pytest.mark.long
def test_lambda_3_on_a_mesh_fitted_to_its_zone():
    # docs: the default mesh refined x 0.53 (four elements across Maugis' 0.17 mm zone),
    # P* -2.0826 +- 0.10 N in 1690 states; the zone traced at the pull-off spans 4.2 edges
    r = solve_cohesive_case(**_shell(0.15), tabor=3.0, error_bars=False)
    assert not r.refused, r.refused
    assert abs(r.provenance["zone_refinement"] - 0.532) <= 0.001
    _within("lambda 3", r.to_dict()["pull_off"]["P_star_N"], (-2.0826, 0.10))
    assert r.solve.zone_edges >= 2.0


@pytest.mark.long
def test_lambda_3_with_eight_elements_across_the_zone():
    # docs ("The frictionless energy method ...", "no_slip contact"): -2.0666 N in 553
    # states (1690 with four), 1.1 % beyond the energy method's P* (-2.0447 N); without
    # error bars (the coarse companion has four across).  Held to the 0.05 % the docs
    # print
    r = solve_cohesive_case(**_shell(0.15), tabor=3.0, zone_elements=8, error_bars=False)
    assert not r.refused, r.refused
    assert abs(r.provenance["zone_refinement"] - 0.266) <= 0.001
    P = r.to_dict()["pull_off"]["P_star_N"]
    _within("lambda 3, eight elements", P, (-2.0666, 0.001))
    assert abs(P / ENERGY_BASE[0] - 1.011) <= 0.0005
    assert len(r.solve.path.states) <= 1630 // 2
    # no_slip: -2.0684 N in 520 states (with four: -2.0841 +- 0.10 N in 1577)
    ns = solve_cohesive_case(**_shell(0.15), tabor=3.0, zone_elements=8, interface="no_slip",
                             **NORMAL_ONLY, error_bars=False)
    assert not ns.refused, ns.refused
    P_ns = ns.to_dict()["pull_off"]["P_star_N"]
    _within("lambda 3, eight elements, no_slip", P_ns, (-2.0684, 0.001))
    assert abs(P_ns / P - 1) <= 0.002


@pytest.mark.long
def test_lambda_3_with_sixteen_elements_the_zone_is_resolved():
    # docs ("The frictionless energy method ..."): -2.0656 N with sixteen across (x 0.13,
    # 42,890 dofs, 582 states), 0.05 % from eight's -2.0666 N; 1.0 % beyond the energy method's
    r = solve_cohesive_case(**_shell(0.15), tabor=3.0, zone_elements=16, error_bars=False)
    assert not r.refused, r.refused
    P = r.to_dict()["pull_off"]["P_star_N"]
    _within("lambda 3, sixteen elements", P, (-2.0656, 0.001))
    assert abs(P / -2.0666 - 1) <= 0.001
    assert abs(P / ENERGY_BASE[0] - 1.010) <= 0.0005


@pytest.mark.long
def test_lambda_3_no_slip_with_the_default_elements_turns_and_its_bar_holds_eight():
    # docs ("no_slip contact"): with four elements across the zone the path turns round
    # (1577 states) and answers -2.0841 +- 0.10 N, 0.07 % from the frictionless path's
    # -2.0826 N; its bar (from the coarse companion) holds the eight-element path's -2.0684 N
    r = solve_cohesive_case(**_shell(0.15), tabor=3.0, interface="no_slip", **NORMAL_ONLY)
    assert not r.refused, r.refused
    assert "first_path" not in r.provenance and r.provenance["zone_elements"] == 4
    po = r.to_dict()["pull_off"]
    _within("lambda 3, no_slip", po["P_star_N"], (-2.0841, 0.001))
    assert abs(po["P_star_N"] - -2.0684) <= po["P_star_N_error"]
    assert abs(po["P_star_N"] / -2.0826 - 1) <= 0.002


@pytest.mark.long
def test_at_lambda_0_05_the_minimum_moves_to_t_over_R_0_075():
    P = {t: _cohesive_P(t, 0.05) for t in LONG_RANGE}
    for t, value in P.items():
        _within(f"t/R {t}, lambda 0.05", value, LONG_RANGE[t], 3)
    assert min(P, key=lambda t: abs(P[t])) == 0.075


# lambda -> no_slip P* [N] and error bar of the normal-only law with the adhesive history
# (docs: "no_slip contact"); the energy method's
NO_SLIP_BASE = {0.3: (-2.5281, 0.0014), 1.0: (-2.1747, 0.0083), 2.0: (-2.1034, 0.081)}
ENERGY_NO_SLIP = (-1.7146, 0.0014)


@pytest.mark.slow
def test_mode_I_only_no_slip_pull_off_is_the_frictionless_one_not_the_energy_methods():
    e = solve_case(**_shell(0.15), interface="no_slip", progress=False, error_bars=False)
    energy = e.to_dict()["pull_off"][0]["fixed_load"]["P_N"]
    _within("energy method, no_slip", energy, ENERGY_NO_SLIP)
    for lam, stated in NO_SLIP_BASE.items():
        r = solve_cohesive_case(**_shell(0.15), tabor=lam, interface="no_slip",
                                **NORMAL_ONLY, error_bars=False)
        assert not r.refused, r.refused
        P = r.to_dict()["pull_off"]["P_star_N"]
        _within(f"lambda {lam}, no_slip", P, stated)
        # the frictionless value (docs: they differ by at most 0.2 %)
        assert abs(P / BASE[lam][0] - 1) <= 0.002
        assert P / energy > 1.2         # the docs: 22.7 % beyond at lambda 2, more below


# lambda -> the default no_slip P* [N] (mixed-mode beta 1, the loading history), coarse
# mesh fitted to eight elements across the zone (docs: "no_slip contact";
# `python benchmarks/no_slip_history.py --tabor L --approaches free`)
NO_SLIP_LOADING = {2.0: -1.7887, 3.0: -1.7656}


@pytest.mark.slow
def test_default_no_slip_pull_off_tends_to_the_energy_methods():
    """Issue 39: the cohesive no_slip P* within 4 % of the energy method's at lambda 3 and
    closer to it than to the frictionless one; zero range (P = P0 + k / lambda^2 through
    lambda 2 and 3, the sphere's Maugis-Dugdale excess law) within 2 %.  What is left
    (about 1.9 %): the switch's jump-in at the turn carries the contact edge to about 2.4
    a* under the law, where the energy method's held set is the adhesion-free one."""
    P = {}
    for lam in NO_SLIP_LOADING:
        r = solve_cohesive_case(**_shell(0.15), tabor=lam, interface="no_slip", mesh="coarse",
                                zone_elements=8, error_bars=False)
        assert not r.refused, r.refused
        assert r.input.history == "loading" and r.input.beta == 1.0
        P[lam] = r.to_dict()["pull_off"]["P_star_N"]
        _within(f"lambda {lam}, no_slip (loading history)", P[lam], (NO_SLIP_LOADING[lam], 0))
    energy, frictionless = ENERGY_NO_SLIP[0], ENERGY_BASE[0]
    assert abs(P[3.0] / energy - 1) <= 0.04
    assert abs(P[3.0] - energy) < abs(P[3.0] - frictionless)
    zero = (9.0 * P[3.0] - 4.0 * P[2.0]) / 5.0
    print(f"no_slip P*: lambda 2 {P[2.0]:.4f}, 3 {P[3.0]:.4f}, zero range {zero:.4f} N; "
          f"energy method {energy:.4f} N ({zero / energy - 1:+.2%})")
    assert abs(zero / energy - 1) <= 0.02
