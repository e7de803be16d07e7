"""Validation of the cohesive interface: a solid hemisphere (t = h = R) at small strain
(gamma / (C10 R) = 1.7e-4, the JKR test's) follows the Maugis-Dugdale closed form
(solver.maugis_dugdale, E* = 8 C10, K = 4 E* / 3) on the coarse mesh, with the whole
S-shaped path (jump-in, contact, retraction, fold) traced by arc-length continuation.

Measured (coarse mesh, 4454 dofs, ramp 0.5 delta_c; benchmarks/maugis_dugdale_fe.py):
Pbar* -1.615 against -1.6007 at lambda = 1 (+0.9 %, 40 s), about -1.814 against -1.8156 at
lambda = 0.3 (-0.1 %, 11 s); held to the issue's 2 %.  a* and delta* are not yet within
the issue's 3 % on this mesh (A* 0.84 against 0.90 at lambda = 1), so they are not held.
lambda = 3 is not held: the path passes the jump-in fold, then follows the branch behind
it (delta falling, a growing: the JKR-like unstable branch) below delta0 = -2 reach, where
trace's "turned back below delta0" stop ends it (a false stop: the shell is in range).
Without that stop (tried: only when out of range) the path ran 1586 states (1053 s on a
loaded machine) and still left the range before delta_max: not yet followed.
"""
import math

import numpy as np
import pytest

from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.solver.arclength import pull_off, trace
from shell_adhesion.solver.cohesive import CohesiveLaw, Interface
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec

GAMMA_HAT = 1.7e-4            # gamma / (C10 R)
K_HAT = 4 / 3 * 8             # K / C10
DELTA_MAX = 2e-3              # / R: about 1.5 Maugis approach units, contact A ~ 1.6


def md_path(lam, mesh="coarse", ramp=0.5):
    d = discretise(cap_mesh(Cap(1.0, 1.0), mesh_spec(mesh)))
    law = CohesiveLaw(md.sigma0_of(lam, GAMMA_HAT, 1.0, K_HAT), GAMMA_HAT, ramp)
    return trace(Interface(d, law), DELTA_MAX)


@pytest.mark.parametrize("lam", [0.3, 1.0])
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
    assert math.isfinite(P) and abs(P / ref.P - 1) <= 0.02
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
