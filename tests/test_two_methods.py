"""Two methods, one answer (issue 39): the energy method's frictionless pull-off of the
base shell against the cohesive (Maugis-Dugdale) model's zero-range limit.

The cohesive P* at lambda 3 and 4, on the coarse mesh graded to eight elements across
the zone (`python benchmarks/two_methods.py --shells base --interfaces frictionless`:
-2.0668 and -2.0585 N, 105 s and 415 s on a quiet 2-core machine), extrapolated as
lambda^-2 (solver.maugis_dugdale.zero_range) gives -2.0478 N; the energy method's P*
(default mesh, the adhesive edge force to second order) -2.045 N: 0.14 % apart.  Held at
0.5 %.  `long`: about 10 minutes.
"""
import pytest

from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.study import cohesive_case as cc
from shell_adhesion.study.case import solve_case

BASE = dict(R_mm=20.0, t_mm=3.0, h_mm=20.0, C10_MPa=0.3, gamma_J_m2=30.0)


@pytest.mark.long
def test_frictionless_energy_method_meets_the_cohesive_zero_range_limit(monkeypatch):
    monkeypatch.setattr(cc, "TABOR_RANGE", (cc.TABOR_RANGE[0], 4.0))   # lambda 4: beyond
    lambdas, P = (3.0, 4.0), []
    for lam in lambdas:
        r = cc.solve_cohesive_case(**BASE, tabor=lam, interface="frictionless", mesh="coarse",
                                   zone_elements=8, error_bars=False)
        assert not r.refused, r.refused
        P.append(r.to_dict()["pull_off"]["P_star_N"])
    zero, _ = md.zero_range(lambdas, P)
    energy = solve_case(**BASE, interface="frictionless", progress=False)
    po = energy.to_dict()["pull_off"][0]["fixed_load"]
    assert P[1] < zero < 0 and P[0] < P[1]          # the cohesive excess falls with lambda
    assert po["P_N"] == pytest.approx(zero, rel=0.005), (po["P_N"], zero, P)
