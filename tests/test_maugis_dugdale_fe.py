"""Validation of the cohesive interface: a solid hemisphere (t = h = R) at small strain
(gamma / (C10 R) = 1.7e-4, the JKR test's) follows the Maugis-Dugdale closed form
(solver.maugis_dugdale, E* = 8 C10, K = 4 E* / 3) on the coarse mesh, with the whole
S-shaped path (jump-in, contact, retraction, fold) traced by arc-length continuation.

Measured (coarse mesh, 4454 dofs, ramp 0.5 delta_c, penalty 1e3 sigma0 / delta_c; steps of
at most 0.25 delta_c and 0.1 delta_max of gap, the least P resolved to 1e-3 of P;
benchmarks/maugis_dugdale_fe.py), Pbar* against the closed form: lambda 0.05: -1.9669 /
-1.9814 (-0.73 %; -1.65 % from the DMT -2); lambda 0.1: -1.9456 / -1.9506 (-0.26 %), 377
states; lambda 0.3: -1.8166 / -1.8156 (+0.06 %), 171 states; lambda 1: -1.6164 / -1.6007
(+0.98 %), 179 states. Held at twice the README's deviations and to the issue's 2 % (the
DMT limit to its 3 %). On the plain coarse mesh a* and delta* are not held (a* is, at
lambda 1 with eight elements across the zone: the last test): A* 0.271 / 0.493 / 0.852
against 0.199 / 0.497 / 0.904 and Dbar* -0.378 / -0.515 / -0.337 against -0.430 / -0.542 /
-0.484 at lambda 0.1 / 0.3 / 1. The contact radius (where the gap crosses 0) is
ill-defined where the surface meets the plane at a grazing angle: the penalty 1e4 sigma0 /
delta_c moved A* by 4 % at lambda 1; delta* of the hemisphere carries its finite-body
compliance (about +0.03 |Pbar| in Dbar: the energy method's JKR Dbar* is -0.397 against
-0.437). Halving the ramp (0.25 delta_c) does not close the gap at lambda 1 (a ramp of 0.1
delta_c does not turn).
lambda = 3 on the plain coarse mesh does not come back to turn at delta_max (the zone,
0.0028 R, spans under two elements); on the coarse mesh fitted to the zone (39,762 dofs,
`long`, 30 minutes) it does: Pbar* -1.5400 / -1.5168 (+1.53 %), 1566 states; A* 1.138 /
1.097 and Dbar* -0.358 / -0.445 are not held (P zigzags by a few 0.01 % from snap to snap
near its least value, and the closed form's P stays within 0.5 % of P* from Dbar -0.52 to
-0.37).
"""
import math

import numpy as np
import pytest

from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.solver.arclength import ArcSettings, pull_off, trace
from shell_adhesion.solver.cohesive import CohesiveLaw, Interface
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec

from validation import deviations_within

# the README's deviations of P* from the closed form (coarse mesh), held at twice their size
STATED = {0.1: -0.0026, 0.3: +0.0006, 1.0: +0.0098}
STATED_DMT = -0.0165          # lambda 0.05 from DMT's -2
GAMMA_HAT = 1.7e-4            # gamma / (C10 R)
K_HAT = 4 / 3 * 8             # K / C10
DELTA_MAX = 2e-3              # / R: about 1.5 Maugis approach units, contact A ~ 1.6


def md_path(lam, mesh="coarse", ramp=0.5):
    d = discretise(cap_mesh(Cap(1.0, 1.0), mesh_spec(mesh)))
    law = CohesiveLaw(md.sigma0_of(lam, GAMMA_HAT, 1.0, K_HAT), GAMMA_HAT, ramp)
    return trace(Interface(d, law), DELTA_MAX)


@pytest.mark.parametrize("lam", [0.1, 0.3, 1.0])
def test_pull_off_follows_maugis_dugdale(lam):
    path = md_path(lam)
    assert path.ended_by == "left the cohesive range" and path.turn > 0
    sc = md.scales(GAMMA_HAT, 1.0, K_HAT)
    po = pull_off(path)
    ref = md.pull_off(lam)
    P = po.P_star / sc["force"]
    print(f"lambda {lam}: Pbar* {P:.4f} (closed form {ref.P:.4f}), A* "
          f"{po.a_star / sc['length']:.3f} ({ref.A:.3f}), Dbar* "
          f"{po.delta_star / sc['approach']:.3f} ({ref.D:.3f}), {len(path.states)} states")
    assert math.isfinite(P) and abs(P / ref.P - 1) <= 0.02       # the criterion
    deviations_within(f"Maugis-Dugdale lambda {lam}", {"P_star": P / ref.P - 1},
                      {"P_star": STATED[lam]})
    # the path is the S: approach from P = 0, compression at the turn, back to P = 0
    Ps = path.array("P")
    assert abs(Ps[0]) <= 1e-12 * abs(po.P_star) and Ps[path.turn] > 0 and abs(Ps[-1]) <= 1e-3 * abs(po.P_star)
    # the fixed-grips pull-off (a fold in delta at lambda = 1; none at 0.3, where the
    # fixed-grips retraction separates smoothly) lies beyond the fixed-load one
    if lam >= 1:
        assert po.delta_dagger < po.delta_star and po.P_star < po.P_dagger < 0
    else:
        assert math.isnan(po.delta_dagger)
    # every converged state is finite
    assert np.all(np.isfinite(Ps)) and np.all(np.isfinite(path.array("delta")))
    # a path that answers passes a new extreme of a, c or delta every few states: the
    # stall bound, which ends a path that zigzags, is far from it (measured: at most 13
    # states on every cohesive path of the tests and the base shell at lambda 3)
    assert _longest_run_without_an_extreme(path) <= ArcSettings().stall / 5


def _longest_run_without_an_extreme(path) -> int:
    """The most states in a row that passed no new extreme of their leg (as `trace` counts
    them for its stall bound)."""
    from shell_adhesion.solver.arclength import Stall
    stall, longest = Stall(), 0
    for i, s in enumerate(path.states):
        run = stall.after(s.a, s.c, s.delta, retracting=0 <= path.turn <= i,
                          new_leg=i == path.turn)
        longest = max(longest, run)
    return longest


def test_dmt_limit():
    # lambda = 0.05: a long, weak interaction (delta_c = 0.017 R, 9 times the largest
    # approach): the pull-off tends to DMT's -2 pi gamma R
    path = md_path(0.05)
    assert path.ended_by == "left the cohesive range"
    P = pull_off(path).P_star / (math.pi * GAMMA_HAT)
    print(f"lambda 0.05: P*/(pi gamma R) {P:.4f} (DMT -2, closed form {md.pull_off(0.05).P:.4f})")
    assert math.isfinite(P) and abs(P / -2 - 1) <= 0.03
    deviations_within("DMT limit", {"P_star": P / -2 - 1}, {"P_star": STATED_DMT})
    assert abs(P / md.pull_off(0.05).P - 1) <= 0.02


# lambda 3 on the coarse mesh fitted to its zone (README: P* +1.53 %; `python
# benchmarks/maugis_dugdale_fe.py 3 coarse+zone`: 39,762 dofs, 1566 states, 30 minutes on
# one core).  a* and delta* are printed, not held (see the module's docstring)
STATED_3 = {"P_star": +0.0153}


def zone_fitted_path(lam, elements):
    """The path on the coarse mesh refined at the contact to put `elements` elements across
    Maugis' zone, stepping as the case command does there: (path, refinement factor)."""
    from shell_adhesion.study.cohesive_case import (REFINED_SETTINGS, fitted_spec,
                                                    zone_estimate, zone_refinement)
    refine = zone_refinement(zone_estimate(GAMMA_HAT, lam), "coarse", elements)
    d = discretise(cap_mesh(Cap(1.0, 1.0), fitted_spec("coarse", dict(uniform=None,
                                                                      refine=refine))))
    law = CohesiveLaw(md.sigma0_of(lam, GAMMA_HAT, 1.0, K_HAT), GAMMA_HAT)
    return trace(Interface(d, law), DELTA_MAX, settings=REFINED_SETTINGS), refine


@pytest.mark.long
def test_lambda_3_on_a_mesh_fitted_to_its_zone_follows_maugis_dugdale():
    path, _ = zone_fitted_path(3.0, 4.0)
    assert path.ended_by == "left the cohesive range"
    sc, ref, po = md.scales(GAMMA_HAT, 1.0, K_HAT), md.pull_off(3.0), pull_off(path)
    dev = {"P_star": po.P_star / sc["force"] / ref.P - 1}
    print(f"lambda 3: P* {100 * dev['P_star']:+.2f} % from Maugis-Dugdale, A* "
          f"{po.a_star / sc['length']:.3f} ({ref.A:.3f}), Dbar* "
          f"{po.delta_star / sc['approach']:.3f} ({ref.D:.3f}), {len(path.states)} states")
    assert abs(dev["P_star"]) <= 0.02                               # the criterion
    deviations_within("Maugis-Dugdale lambda 3", dev, STATED_3)


# lambda 1 with eight elements across Maugis' zone (`--zone-elements 8`; `python
# benchmarks/maugis_dugdale_fe.py 1 coarse+zone8`: the coarse mesh x 0.245 at the
# contact, 15,559 dofs, 154 states): Pbar* +0.27 %, A* 0.904 against 0.904 (with four
# elements, x 0.491: +0.57 %, A* +2.7 %; the plain coarse mesh, two: +0.98 %, A* -5.8 %).
# Held: P* at twice its deviation, A* within 1 %.  delta* is printed, not held (-6 %: the
# hemisphere's finite-body compliance and the flat least P, see the module's docstring;
# with gamma / (C10 R) 1000 times smaller, -3.8 %: docs/adhesion-range.md)
STATED_1_ZONE8 = {"P_star": +0.0027}


@pytest.mark.slow
def test_eight_elements_across_the_zone_give_maugis_dugdale_a_star():
    path, refine = zone_fitted_path(1.0, 8.0)
    assert abs(refine - 0.245) <= 0.001
    assert path.ended_by == "left the cohesive range"
    sc, ref, po = md.scales(GAMMA_HAT, 1.0, K_HAT), md.pull_off(1.0), pull_off(path)
    dev = {"P_star": po.P_star / sc["force"] / ref.P - 1}
    A = po.a_star / sc["length"]
    print(f"lambda 1, 8 elements across the zone: P* {100 * dev['P_star']:+.2f} %, A* "
          f"{A:.3f} ({ref.A:.3f}), Dbar* {po.delta_star / sc['approach']:.3f} ({ref.D:.3f}), "
          f"{len(path.states)} states")
    deviations_within("Maugis-Dugdale lambda 1, 8 elements", dev, STATED_1_ZONE8)
    assert abs(A / ref.A - 1) <= 0.01
