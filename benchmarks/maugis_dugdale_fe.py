"""Cohesive (Maugis-Dugdale) pull-off of the solid hemisphere against the closed form.

    python benchmarks/maugis_dugdale_fe.py LAMBDA [MESH] [RAMP] [INTERFACE] [--gamma-scale S]

Traces the whole path (solver.arclength) for gamma / (C10 R) = 1.7e-4 and prints the
pull-off in Maugis' units beside solver.maugis_dugdale's, the states, Newton iterations
and the wall time.  MESH "coarse+zone" (or any mesh name + "+zone"): that mesh refined at
the contact as `shell-adhesion case --adhesion dugdale` refines it
(study.cohesive_case.fitted_spec: ZONE_ELEMENTS elements across Maugis' zone), its steps
growing as that command's do there (REFINED_SETTINGS); "coarse+zone8": 8 elements across
it (`--zone-elements 8`).
INTERFACE frictionless (default) or no_slip (solver.contact.INTERFACES).  --gamma-scale S:
gamma / (C10 R) S times 1.7e-4, the approach and the mesh's even part scaled with Maugis'
length (S^(1/3)): the same problem in Maugis' units with the finite body S^(1/3) as large.
"""
import sys
import time

from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.solver.arclength import ArcSettings, pull_off, trace
from shell_adhesion.solver.cohesive import CohesiveLaw, Interface
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import cap_mesh
from shell_adhesion.study.cohesive_case import (REFINED_SETTINGS, ZONE_ELEMENTS, fitted_spec,
                                                zone_estimate, zone_refinement)

GAMMA_HAT, K_HAT, DELTA_MAX = 1.7e-4, 32 / 3, 2e-3

if __name__ == "__main__":
    scale = 1.0
    if "--gamma-scale" in sys.argv:
        k = sys.argv.index("--gamma-scale")
        scale = float(sys.argv[k + 1])
        del sys.argv[k:k + 2]
    GAMMA_HAT, DELTA_MAX = GAMMA_HAT * scale, DELTA_MAX * scale ** (1 / 3)
    even = None if scale == 1.0 else 0.15 * scale ** (1 / 3)
    lam = float(sys.argv[1])
    mesh = sys.argv[2] if len(sys.argv) > 2 else "coarse"
    ramp = float(sys.argv[3]) if len(sys.argv) > 3 else 0.5
    interface = sys.argv[4] if len(sys.argv) > 4 else "frictionless"
    name, _, zone = mesh.partition("+zone")
    elements = float(zone) if zone else ZONE_ELEMENTS
    refine = (zone_refinement(zone_estimate(GAMMA_HAT, lam), name, elements)
              if "+zone" in mesh else 1.0)
    d = discretise(cap_mesh(Cap(1.0, 1.0), fitted_spec(name, dict(uniform=even, refine=refine))))
    law = CohesiveLaw(md.sigma0_of(lam, GAMMA_HAT, 1.0, K_HAT), GAMMA_HAT, ramp)
    t0 = time.perf_counter()
    # a refined mesh's steps grow as the cohesive case's do (study.cohesive_case)
    settings = REFINED_SETTINGS if refine < 1.0 else ArcSettings()
    count = [0]

    def report(state):          # a line per 200 states on stderr (a long path shows life)
        count[0] += 1
        if count[0] % 200 == 0:
            print(f"  {count[0]} states, delta/R {state.delta:+.4e}, P/(C10 R^2) "
                  f"{state.P:+.4e}", file=sys.stderr, flush=True)
    path = trace(Interface(d, law), DELTA_MAX, settings=settings, interface=interface,
                 progress=report)
    dt = time.perf_counter() - t0
    sc = md.scales(GAMMA_HAT, 1.0, K_HAT)
    ref = md.pull_off(lam)
    print(f"lambda {lam}, gamma/(C10 R) {GAMMA_HAT:.3g}, mesh {mesh} ({d.ndof} dofs, x "
          f"{refine:.3g} at the contact), "
          f"ramp {ramp}, {interface}: "
          f"{path.ended_by}; "
          f"{len(path.states)} states, {path.timer.newton_iterations} Newton iterations, "
          f"{dt:.1f} s")
    po = pull_off(path)
    print(f"Pbar* {po.P_star / sc['force']:.4f} (closed form {ref.P:.4f}, "
          f"{100 * (po.P_star / sc['force'] / ref.P - 1):+.2f} %), A* "
          f"{po.a_star / sc['length']:.3f} ({ref.A:.3f}), C* {po.c_star / sc['length']:.3f} "
          f"({ref.C:.3f}), Dbar* {po.delta_star / sc['approach']:.3f} ({ref.D:.3f}); "
          f"fixed grips Pbar {po.P_dagger / sc['force']:.4f}, Dbar "
          f"{po.delta_dagger / sc['approach']:.3f}")
