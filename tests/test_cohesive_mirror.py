"""A conservative cohesive path (frictionless contact, the normal-only law acting from the
first touch) has one curve of equilibrium states: its retraction follows its approach
back.  `arclength.trace` therefore reads the retraction from the approach, reversed
(`ArcSettings.mirror`), and no longer traces it a second time.

Held here against the retraction traced as before (`mirror=False`): the solid hemisphere
at lambda 1 (coarse mesh, a fold in delta at the fixed-grips pull-off), whose traced
retraction lies on the approach's curve and gives the same P* and fixed-grips delta."""
import numpy as np

from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.solver.arclength import ArcSettings, conservative, pull_off, trace
from shell_adhesion.solver.cohesive import CohesiveLaw, Interface
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec

GAMMA_HAT, K_HAT, DELTA_MAX = 1.7e-4, 32 / 3, 2e-3


def _hemisphere(lam):
    d = discretise(cap_mesh(Cap(1.0, 1.0), mesh_spec("coarse")))
    return Interface(d, CohesiveLaw(md.sigma0_of(lam, GAMMA_HAT, 1.0, K_HAT), GAMMA_HAT, 0.5))


def _distance_to_polyline(points, line):
    """The distance of each point to the polyline `line` (both (n, 2))."""
    a, b = line[:-1], line[1:]
    ab = b - a
    out = []
    for p in points:
        t = np.clip(((p - a) * ab).sum(1) / np.maximum((ab * ab).sum(1), 1e-300), 0.0, 1.0)
        out.append(np.linalg.norm(a + t[:, None] * ab - p, axis=1).min())
    return np.array(out)


def test_the_retraction_of_a_conservative_path_is_its_approach_reversed():
    iface = _hemisphere(1.0)
    mirrored = trace(iface, DELTA_MAX)
    traced = trace(iface, DELTA_MAX, settings=ArcSettings(mirror=False))
    for path in (mirrored, traced):
        assert path.ended_by == "left the cohesive range" and path.turn > 0
    # the mirrored retraction is the approach's states in reverse, tangents reversed
    approach = mirrored.states[:mirrored.turn + 1]
    back = mirrored.states[mirrored.turn:]
    assert [s.x is q.x for s, q in zip(back, reversed(approach))] == [True] * len(back)
    assert all(s is not q and s.slope == (-q.slope[0], -q.slope[1])
               for s, q in zip(back[1:], reversed(approach[:-1])))
    # every traced retraction state lies on the approach's curve: within 0.5 % of the
    # path's ranges of the polyline through the approach's states (measured 0.3 %, the
    # polyline's sag between samples; a retraction on another branch, as a contact edge
    # trapped at a node, lies tens of percent away)
    # (the two approaches end their last steps past delta_max at different deltas: the
    # traced retraction is compared where the mirrored path has states)
    A = np.array([(s.delta, s.P) for s in approach])
    B = np.array([(s.delta, s.P) for s in traced.states[traced.turn:]
                  if s.delta <= approach[-1].delta])
    scale = np.ptp(A, axis=0)
    gap = _distance_to_polyline(B / scale, A / scale)
    print(f"traced retraction off the approach: max {gap.max():.2e}, median "
          f"{np.median(gap):.2e} of the ranges; {len(traced.states)} states traced, "
          f"{len(mirrored.states)} mirrored ({mirrored.turn + 1} solved)")
    assert gap.max() <= 5e-3
    m, t = pull_off(mirrored), pull_off(traced)
    assert abs(m.P_star / t.P_star - 1) <= 2e-4            # measured 5.6e-6
    assert abs(m.delta_dagger / t.delta_dagger - 1) <= 1e-3    # measured 1.6e-4
    # half the states are solved
    assert mirrored.turn + 1 <= 0.7 * len(traced.states)


def test_only_a_conservative_path_is_mirrored():
    iface = _hemisphere(1.0)
    assert conservative(iface, "frictionless", False)
    assert not conservative(iface, "no_slip", False)           # held nodes: a history
    assert not conservative(iface, "frictionless", True)       # the law switched on at the turn
    assert not conservative(Interface(iface.d, iface.law, 1.0), "no_slip", False)  # anchors


def test_a_path_that_starts_in_the_cohesive_range_is_traced_back():
    """Its approach does not contain the retraction's end (out of the range): the path
    is traced both ways, and leaves the range as before."""
    iface = _hemisphere(0.3)
    path = trace(iface, DELTA_MAX, delta0=-0.5 * iface.law.reach)
    assert path.ended_by == "left the cohesive range" and path.turn > 0
    approach = {id(s.x) for s in path.states[:path.turn + 1]}
    assert not any(id(s.x) in approach for s in path.states[path.turn + 1:])
    assert path.states[-1].delta < path.states[0].delta
