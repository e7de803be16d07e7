"""Benchmark: does the no_slip contact's history move the cohesive pull-off?  (The energy
method forms its contact on an adhesion-free loading, as the cohesive case's default
`history="loading"`; with `history="adhesive"` points are pulled in before they touch
and stick where they touch.)

    python benchmarks/no_slip_history.py [--shell base] [--tabor 3] [--mesh coarse]
        [--zone-elements 8] [--betas 1] [--approaches adhesive,free]
        [--delta-max-mm D] [--even-to F]

For each beta (the mixed-mode law's, 0: the normal-only law) the no_slip pull-off
P* of `solve_cohesive_case` (no error bars) with the adhesive approach (`history=
"adhesive"`), then with the adhesion-free approach (`history="loading"`: the law
switched off, sigma0 and gamma times arclength.SWITCH_OFF, no_slip nodes held where
they touch; switched on at the turn at fixed delta, where the contact jumps in; the
retraction as usual).  Both turn where their contact radius reaches TURN times the
estimate of a* (the adhesive approach does so in tension, at delta < 0, which the
adhesion-free one cannot), or both at --delta-max-mm D.  Prints P*, the turn (for the
adhesion-free path, before and after the switch), wall time, dofs and states.
`--even-to F` (scratch): with the loading history the evenly meshed arc, refined to the
zone, is fitted to F times the estimate of a* instead of cohesive_case.SWITCH_REACH = 2.5
(the switch's jump-in carries the contact edge to about 2.4 times a*; with the arc fitted
to once a* the retraction stalls where the zone spans about two outer edges, lambda 2).  The energy method's P* of the base shell
(no_slip, default mesh): -1.7146 N (benchmarks/two_methods.py).  Lambda above the
shipped domain is run by lifting its bound (scratch).
"""
import sys
from pathlib import Path
import time

import shell_adhesion.study.cohesive_case as cc
from shell_adhesion.solver.scaling import force_N, length_mm

sys.path.insert(0, str(Path(__file__).resolve().parent))
from two_methods import MATERIAL, SHELLS, _option     # noqa: E402  (the same shells)

ENERGY_P_N = {"base": -1.7146}       # the energy method's no_slip P*, default mesh


def main(argv):
    shell, argv = _option(argv, "--shell", "base")
    tabor, argv = _option(argv, "--tabor", "3")
    mesh, argv = _option(argv, "--mesh", "coarse")
    elements, argv = _option(argv, "--zone-elements", "8")
    betas, argv = _option(argv, "--betas", "1")
    approaches, argv = _option(argv, "--approaches", "adhesive,free")
    delta_mm, argv = _option(argv, "--delta-max-mm", None)
    even_to, argv = _option(argv, "--even-to", None)
    if argv:
        sys.exit(f"no_slip_history: unknown arguments {argv}")
    tabor = float(tabor)
    cc.TABOR_RANGE = (cc.TABOR_RANGE[0], max(cc.TABOR_RANGE[1], tabor))      # scratch
    delta_mm = None if delta_mm is None else float(delta_mm)
    if even_to is not None:                                                   # scratch
        cc.SWITCH_REACH = float(even_to)
    for b in betas.split(","):
        beta = float(b)
        for approach in approaches.split(","):
            _run(shell, tabor, mesh, float(elements), beta, approach, delta_mm)
    print(f"energy method ({shell}, no_slip, default mesh): P* = "
          f"{ENERGY_P_N.get(shell, float('nan')):.4f} N")


def _run(shell, tabor, mesh, elements, beta, approach, delta_max_mm):
    """One path (approach "adhesive" or "free"); prints its line."""
    geo = SHELLS[shell]
    inp = cc.cohesive_input(**geo, **MATERIAL, tabor=tabor, delta_max_mm=delta_max_mm,
                            interface="no_slip", mesh=mesh, zone_elements=elements,
                            beta=beta, history="loading" if approach == "free" else "adhesive")
    t0 = time.perf_counter()
    r = cc.solve_checked(inp, error_bars=False)
    wall = time.perf_counter() - t0
    R, C10 = geo["R_mm"], MATERIAL["C10_MPa"]
    path, prov = r.solve.path, r.provenance
    label = (f"{shell}, lambda {tabor:g}, beta {beta:g}, "
             f"{approach} approach")
    if path.turn < 0:
        print(f"{label}: no turn ({path.ended_by}); {wall:.0f} s", flush=True)
        return
    at = path.states[path.turn]
    before = path.states[path.turn - 1]
    turn = (f"turn at delta {length_mm(at.delta, R):.4f} mm, a {length_mm(at.a, R):.4f} mm, "
            f"P {force_N(at.P, C10, R):.4f} N"
            + (f" (before the switch: a {length_mm(before.a, R):.4f} mm, P "
               f"{force_N(before.P, C10, R):.4f} N)" if approach == "free" else ""))
    answer = ("refused (" + r.refused + ")" if r.refused
              else f"P* = {r.to_dict()['pull_off']['P_star_N']:.4f} N, a* "
                   f"{r.to_dict()['pull_off']['a_star_mm']:.4f} mm")
    print(f"{label}: {answer}; {turn}; {prov['dofs']} dofs, {prov['states']} states, "
          f"{wall:.0f} s; ended by: {path.ended_by}; notes: {list(r.notes)}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
