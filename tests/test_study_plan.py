"""The plan: a study reduces to its distinct FE path sets (DESIGN.md section 3)."""
import pytest

from shell_adhesion.catalogue import canonical_json, family, fingerprint
from shell_adhesion.study.keys import pathset_key
from shell_adhesion.study.config import validate
from shell_adhesion.solver.request import gamma_bucket, ladder_gammas
from shell_adhesion.study.plan import make_plan

BASE = dict(C10_MPa=0.3, t_over_R=0.15, h_over_R=1.0, gamma_J_m2=30)


def study(**doc):
    return validate(dict(dict(name="s", R_mm=20, mesh="coarse", delta_max_over_R=0.1), **doc))


def test_c10_and_gamma_grid_is_one_path_set():
    s = study(base=BASE, grid=dict(C10_MPa=[0.2, 0.25, 0.3], gamma_J_m2=[20, 25, 30]))
    plan = make_plan(s)
    assert len(plan.points) == 9
    assert len(plan.shells) == 1
    shell = plan.shells[0]
    assert shell.gamma_hat_needed == pytest.approx(30e-3 / (0.2 * 20))      # 0.0075
    assert shell.gamma_max_hat == 0.01


def test_sweeps_full_cube_axes_and_points():
    s = study(base=BASE, sweeps=dict(t_over_R=[0.1, 0.15, 0.2], gamma_J_m2=[10, 30]))
    plan = make_plan(s)
    assert plan.axes["t_over_R"] == (0.1, 0.15, 0.2)
    assert plan.axes["gamma_J_m2"] == (10.0, 30.0)
    assert len(plan.points) == 4            # base, t 0.1, t 0.2, gamma 10
    assert (0.3, 0.1, 1.0, 10.0) not in plan.points      # off the sweep lines
    assert [(x.t_over_R, x.h_over_R) for x in plan.shells] == [(0.1, 1.0), (0.15, 1.0), (0.2, 1.0)]


def test_gamma_ladder_rounds_up():
    assert gamma_bucket(0.005) == 0.005
    assert gamma_bucket(30e-3 / (0.3 * 20)) == 0.005        # 0.005 up to rounding
    assert gamma_bucket(0.0050001) == 0.007
    assert gamma_bucket(0.011) == 0.015
    assert gamma_bucket(0.021) == 0.03
    assert gamma_bucket(1.5e-4) == 1.5e-4
    # a set serving up to 0.015 is fitted to answer the ladder from 0.015 down to 1e-4
    assert ladder_gammas(0.015) == (0.0001, 0.00015, 0.0002, 0.0003, 0.0005, 0.0007, 0.001,
                                    0.0015, 0.002, 0.003, 0.005, 0.007, 0.01, 0.015)
    assert max(ladder_gammas(0.05)) == 0.03         # capped at the domain's GAMMA_MAX
    assert ladder_gammas(5e-5) == (5e-5,)


def test_nearby_studies_share_keys():
    a = make_plan(study(base=BASE, grid=dict(gamma_J_m2=[40, 50])))          # 0.0083
    b = make_plan(study(base=dict(BASE, gamma_J_m2=45)))                      # 0.0075
    assert a.shells[0].fingerprint == b.shells[0].fingerprint


def test_fingerprint_is_canonical():
    k = pathset_key(0.15, 1.0, "no_slip", "coarse", 0.1, 0.01)
    shuffled = dict(reversed(list(k.items())))
    assert fingerprint(shuffled) == fingerprint(k)
    assert fingerprint(dict(k, t_over_R=0.1 + 0.05)) == fingerprint(k)      # 0.15000000000000002
    assert fingerprint(dict(k, t_over_R=0.151)) != fingerprint(k)
    assert fingerprint(dict(k, interface="frictionless")) != fingerprint(k)
    assert family(dict(k, gamma_max_hat=0.02)) == family(k)
    assert family(dict(k, mesh="fine")) != family(k)
    assert '"version"' in canonical_json(k) and '"settings"' in canonical_json(k)


def test_material_ratios_are_fe_dimensions_c10_is_not():
    """A Mooney-Rivlin C10 sweep at a fixed C01/C10 plans one shell; two C01/C10 plan two
    different keys; neo-Hookean keys are the ones without a material."""
    from shell_adhesion.solver.material import NEO_HOOKE, Material

    s = study(base=BASE, sweeps=dict(C10_MPa=[0.2, 0.3, 0.4]))
    mr = [Material.from_MPa("mooney_rivlin", C10, C01_MPa=C10 / 6) for C10 in (0.2, 0.3, 0.4)]
    assert len(set(mr)) == 1        # C10 x (1, 1/6): one ratio
    plan = make_plan(s, material=mr[0])
    assert len(plan.points) == 3 and len(plan.shells) == 1
    assert plan.shells[0].key["material"] == dict(mr[0].as_dict(), C01_over_C10=pytest.approx(1 / 6))
    other = make_plan(s, material=Material("mooney_rivlin", C01_over_C10=0.5))
    fps = {plan.shells[0].fingerprint, other.shells[0].fingerprint,
           make_plan(s).shells[0].fingerprint}
    assert len(fps) == 3
    # neo-Hookean: exactly the key of a call that knows nothing of materials
    nh = make_plan(s, material=NEO_HOOKE).shells[0]
    assert "material" not in nh.key and nh.key == make_plan(s).shells[0].key
    assert nh.key == pathset_key(0.15, 1.0, "no_slip", "coarse", 0.1, nh.gamma_max_hat)


def test_swept_ratio_plans_one_path_set_per_value():
    """sweeps: {C01_over_C10: [...]} plans one set per ratio (C01/C10 = 0 is the neo-Hookean
    set), each key with its material; a C10 sweep beside it adds no set."""
    from shell_adhesion.solver.material import NEO_HOOKE, Material

    s = study(base=BASE, material=dict(model="mooney_rivlin", C01_over_C10=0.2),
              sweeps=dict(C01_over_C10=[0, 0.1, 0.2, 0.3, 0.4, 0.5], C10_MPa=[0.2, 0.3]))
    plan = make_plan(s)
    assert plan.ratio_axes == {"C01_over_C10": (0.0, 0.1, 0.2, 0.3, 0.4, 0.5)}
    assert len(plan.shells) == 6 and len({sh.fingerprint for sh in plan.shells}) == 6
    assert [sh.material for sh in plan.shells] == [NEO_HOOKE] + [
        Material("mooney_rivlin", C01_over_C10=c) for c in (0.1, 0.2, 0.3, 0.4, 0.5)]
    assert "material" not in plan.shells[0].key
    assert plan.shells[0].key == make_plan(study(base=BASE)).shells[0].key
    assert plan.shells[2].key["material"]["C01_over_C10"] == 0.2
    # base (C01/C10 0.2) with C10 0.2 and 0.3, and the five other ratios at C10 0.3
    assert len(plan.points) == 7
    sub = plan.for_ratios((0.2,))
    assert sub.points == ((0.2, 0.15, 1.0, 30.0), (0.3, 0.15, 1.0, 30.0))
    assert sub.shells == (plan.shells[2],)
    # a fixed material (no sweep): one set, keyed by its ratios
    fixed = make_plan(study(base=BASE, material=dict(model="mooney_rivlin", C01_over_C10=0.2)))
    assert fixed.ratio_axes is None and len(fixed.shells) == 1
    assert fixed.shells[0].key["material"] == plan.shells[2].key["material"]


def test_coefficients_in_MPa_plan_by_their_ratios():
    """material: {model, C10_MPa, C01_MPa} is the study of the ratio C01_MPa / C10_MPa (the
    same key); a grid over C01_MPa at fixed C10 plans one set per ratio; a C10 sweep at a
    fixed C01_MPa changes the ratio (one set per C10), at a fixed ratio it does not."""
    from shell_adhesion.solver.material import Material

    base = {k: v for k, v in BASE.items() if k != "C10_MPa"}
    mpa = make_plan(study(base=base, material=dict(model="mooney_rivlin", C10_MPa=0.3,
                                                  C01_MPa=0.06)))
    ratio = make_plan(study(base=BASE, material=dict(model="mooney_rivlin", C01_over_C10=0.2)))
    assert mpa.ratio_axes is None and len(mpa.shells) == 1
    assert mpa.shells[0].key == ratio.shells[0].key          # 0.06 / 0.3 is the ratio 0.2
    assert mpa.points == ratio.points

    grid = make_plan(study(base=BASE, material=dict(model="mooney_rivlin"),
                           grid=dict(C01_MPa=[0.03, 0.06, 0.09])))
    assert grid.ratio_axes == {"C01_over_C10": (0.1, 0.2, 0.3)}
    assert [sh.material for sh in grid.shells] == [
        Material("mooney_rivlin", C01_over_C10=c) for c in (0.1, 0.2, 0.3)]
    assert grid.shells[1].key == ratio.shells[0].key

    fixed_MPa = make_plan(study(base=BASE, material=dict(model="mooney_rivlin", C01_MPa=0.06),
                                sweeps=dict(C10_MPa=[0.2, 0.3])))
    assert fixed_MPa.ratio_axes == {"C01_over_C10": (0.2, 0.3)}   # 0.06/0.3, 0.06/0.2
    assert len(fixed_MPa.shells) == 2
    fixed_ratio = make_plan(study(base=BASE, material=dict(model="mooney_rivlin",
                                                           C01_over_C10=0.2),
                                  sweeps=dict(C10_MPa=[0.2, 0.3])))
    assert fixed_ratio.ratio_axes is None and len(fixed_ratio.shells) == 1

    d1 = make_plan(study(base=BASE, grid=dict(D1_per_MPa=[0, 0.01])))
    assert d1.ratio_axes == {"D1_times_C10": (0.0, 0.003)}
    jm = make_plan(study(base=BASE, material=dict(model="gent"), grid=dict(Jm=[10, 20])))
    assert jm.ratio_axes == {"Jm": (10.0, 20.0)} and len(jm.shells) == 2
