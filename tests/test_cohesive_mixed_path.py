"""Energy along a mixed-mode no_slip cohesive path (solver.arclength with
Interface.beta): the work of the rim load equals the strain energy plus the interface
energy minus what the anchors' updates released (ArcState.anchor_jump, summed over the
states before); and beta = 0 traces the normal-only law's path.

Measured (base shell, lambda 1, coarse, beta 1, pressed to 1.3 a*; this file with -s and
the default steps; in brackets with steps of 1/16 delta_c, ArcSettings(dx_max=1/16)):
- the approach (jump-in, contact growing, each node's anchor reset when it touches):
  |W - (U + Pi - J)| <= 1.9e-5 (1.4e-6) of max U + max |Pi|; without J 2.0e-4 (2.3e-4):
  the slip a point gathers between entering the law's reach and touching is released
  when it sticks;
- the whole path: 6.1e-4 (3.6e-4) more work than U + Pi - J: held nodes that let go on
  the retraction release the radial reaction they carried (the normal-only law's path
  loses 1.3e-4 the same way), which the arc-length steps do not integrate.
"""
import math

import numpy as np
import pytest

from shell_adhesion.solver.arclength import pull_off, trace, work
from shell_adhesion.solver.cohesive import Interface
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.request import TURN, a_star_estimate, even_arc
from shell_adhesion.study import cohesive_case as cc


def base_shell_path(beta):
    """The base shell's no_slip path at lambda 1 (coarse), pressed to 1.3 a* (as the case
    command does), with the mixed-mode law of `beta` (None: the normal-only law)."""
    inp = cc.cohesive_input(20, 3, 20, 0.3, 30, tabor=1.0, interface="no_slip")
    cap = Cap(0.15, 1.0)
    a_need = a_star_estimate(cap, inp.gamma_hat)
    d = discretise(cap_mesh(cap, mesh_spec("coarse", even_arc(cap, a_need))))
    return trace(Interface(d, inp.law, beta), 0.25, a_turn=TURN * a_need,
                 interface="no_slip")


def test_beta_zero_traces_the_normal_only_path():
    normal, zero = base_shell_path(None), base_shell_path(0.0)
    assert len(zero.states) == len(normal.states) and zero.turn == normal.turn
    for name in ("delta", "P", "U", "Pi"):
        a, b = zero.array(name), normal.array(name)
        assert np.abs(a - b).max() <= 1e-12 * np.abs(b).max(), name
    assert not zero.array("anchor_jump").any()      # no slip energy with beta = 0
    assert pull_off(zero).P_star == pytest.approx(pull_off(normal).P_star, rel=1e-12)


def test_mixed_mode_work_balances_with_the_anchors_jumps():
    path = base_shell_path(1.0)
    assert path.ended_by == "left the cohesive range" and path.turn > 0
    assert math.isfinite(pull_off(path).P_star)
    U, Pi = path.array("U"), path.array("Pi")
    jumps = path.array("anchor_jump")
    J = np.concatenate([[0.0], np.cumsum(jumps)[:-1]])     # released before each state
    E = (U - U[0]) + (Pi - Pi[0])
    W = work(path)
    scale = np.abs(U).max() + np.abs(Pi).max()
    approach = slice(0, path.turn + 1)
    miss = np.abs(W - (E - J))[approach].max() / scale
    without = np.abs(W - E)[approach].max() / scale
    lost = (W - (E - J))[-1] / scale
    print(f"{len(path.states)} states, {np.count_nonzero(jumps)} anchor jumps: approach "
          f"{miss:.2g} ({without:.2g} without them); whole path {lost:.2g} lost")
    assert miss <= 1e-4
    assert without > 1e-4           # the jumps are part of the balance
    assert J[path.turn] < 0.0       # on the whole, the resets release slip energy
    # the held nodes' releases on the retraction dissipate, never create, energy
    assert 0.0 <= lost <= 1e-3
