"""The adhesion-free approach of the cohesive path (`arclength.trace(
adhesion_free_approach=True)`; the cohesive case's no_slip default, `history="loading"`,
with the evenly meshed arc fitted to cohesive_case.SWITCH_REACH times the estimate of a*):
the law switched off on the approach
(contact alone), switched on at the turn at fixed delta, then the usual retraction.

Measured (base shell, lambda 1, coarse as below; `python benchmarks/no_slip_history.py
--tabor 1` for the mesh refined to 8 elements across the zone):
- frictionless: the same P* as the adhesive approach (-2.17824 N, to 1e-8): the path is
  history-free, and the switch lands on the adhesive path's branch;
- no_slip, beta 1: P* -1.8767 N against -2.2022 N with the adhesive approach (the energy
  method: -1.7146 N); beta 0: -2.2508 against -2.1774 N.
"""
import numpy as np
import pytest

from shell_adhesion.solver.arclength import ArcSettings, pull_off, trace
from shell_adhesion.solver.cohesive import Interface
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.request import TURN, a_star_estimate, even_arc
from shell_adhesion.solver.scaling import force_N
from shell_adhesion.study import cohesive_case as cc


def path(interface, beta=None, free=False, settings=ArcSettings()):
    """The base shell's (lambda 1, coarse) adhesive path, or its adhesion-free one
    (`free`), turned at TURN a* as the case command does."""
    inp = cc.cohesive_input(20, 3, 20, 0.3, 30, tabor=1.0, interface="no_slip", beta=beta)
    cap = Cap(0.15, 1.0)
    a_need = a_star_estimate(cap, inp.gamma_hat)
    d = discretise(cap_mesh(cap, mesh_spec("coarse", even_arc(cap, a_need))))
    iface = Interface(d, inp.law, inp.beta if interface == "no_slip" else None)
    return trace(iface, 0.25, a_turn=TURN * a_need, interface=interface,
                 adhesion_free_approach=free, settings=settings)


@pytest.mark.slow      # the no_slip test below runs the switch on both approaches too
def test_frictionless_pull_off_does_not_depend_on_the_approach():
    # both retractions traced (the adhesive path's is otherwise its approach reversed,
    # `ArcSettings.mirror`, whose least P is resolved from the other side: 1e-4 apart)
    adhesive = path("frictionless", settings=ArcSettings(mirror=False))
    free = path("frictionless", free=True)
    assert free.ended_by == "left the cohesive range"
    # the approach felt no adhesion: no tension, and Pi is 1e-8 of the law's
    assert min(s.P for s in free.states[:free.turn]) > -1e-9
    on = free.states[free.turn]
    assert on.a > free.states[free.turn - 1].a and on.Pi < 0   # the switch: a jump-in
    P, Q = force_N(pull_off(adhesive).P_star, 0.3, 20), force_N(pull_off(free).P_star, 0.3, 20)
    print(f"frictionless P*: adhesive approach {P:.6f} N, adhesion-free {Q:.6f} N")
    assert Q == pytest.approx(P, rel=1e-6)


def test_no_slip_pull_off_depends_on_the_approach():
    adhesive, free = path("no_slip", 1.0), path("no_slip", 1.0, free=True)
    assert free.ended_by == "left the cohesive range"
    P, Q = force_N(pull_off(adhesive).P_star, 0.3, 20), force_N(pull_off(free).P_star, 0.3, 20)
    print(f"no_slip beta 1 P*: adhesive approach {P:.4f} N, adhesion-free {Q:.4f} N")
    assert Q - P == pytest.approx(0.325, abs=0.02)
    assert np.isfinite(pull_off(free).a_star)


@pytest.mark.slow
def test_a_switch_in_one_step_by_descent_lands_near_the_ramp(monkeypatch):
    """The law switched on at once (`arclength._descend`, pseudo-transient) against the
    ramp: the same pull-off within 1 % (measured: -1.8839 against -1.8767 N)."""
    import shell_adhesion.solver.arclength as al
    ramp = path("no_slip", 1.0, free=True)
    monkeypatch.setattr(al, "SWITCH_STEP", 1.0)
    monkeypatch.setattr(al, "SWITCH_STEP_MIN", 2.0)      # the first step descends
    once = path("no_slip", 1.0, free=True)
    assert once.ended_by == "left the cohesive range"
    assert pull_off(once).P_star == pytest.approx(pull_off(ramp).P_star, rel=0.01)
