"""Benchmark: the loading of a thin deep shell through its snap (Pogorelov's mirror
buckling), traced by arc length (solver.snap): frictionless, no adhesion, h = R.

Prints every `--every`-th state and every state where the contact set changes shape:
state, delta / t, P / (C10 R^2), P over Reissner's 16 C10 t^2 delta / R, the contact set
(radii / R), the apex's height / t, Newton iterations, wall time of the step; then the
displacement-controlled jumps, the first ring, the log-slope d ln P / d ln delta over
5 t to 10 t on the last branch, the energy balance and the totals.
Run: python benchmarks/snap.py [--t 0.02] [--mesh coarse] [--delta-max 10] [--every 20]
(--delta-max in thicknesses t)
"""
import argparse
import time

import numpy as np

from shell_adhesion.solver.snap import log_slope, trace_shell


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t", type=float, default=0.02, help="t/R")
    ap.add_argument("--mesh", default="coarse")
    ap.add_argument("--delta-max", type=float, default=10.0, help="in thicknesses t")
    ap.add_argument("--every", type=int, default=20)
    a = ap.parse_args(argv)
    T = a.t
    t0 = time.perf_counter()
    d, path = trace_shell(T, 1.0, a.mesh, a.delta_max * T)
    wall = time.perf_counter() - t0
    print(f"t/R = {T:g}, h/R = 1, {a.mesh} mesh, {d.ndof} dofs; ended: "
          f"{path.ended_by or 'delta_max reached'}")
    print(f"{'state':>5} {'delta/t':>8} {'P/(C10R^2)':>11} {'P/Reissner':>10} "
          f"{'apex/t':>8} {'newton':>6} {'step s':>7}  contact (radii / R)")
    shape = None
    for i, s in enumerate(path.states):
        kind = tuple("disc" if r0 == 0 else "ring" for r0, _ in s.radii)
        if i % a.every == 0 or kind != shape or i == len(path.states) - 1:
            ratio = s.P / (16 * T * T * s.delta) if s.delta > 0 else float("nan")
            print(f"{i:5d} {s.delta / T:8.4f} {s.P:11.4e} {ratio:10.4f} "
                  f"{s.apex_gap / T:8.4f} {s.iterations:6d} {s.seconds:7.3f}  {s.contact}")
        shape = kind
    for j in path.jumps():
        print(f"jump under displacement control at delta = {j.delta / T:.4f} t: P "
              f"{j.P_from:.4e} -> {j.P_to:.4e} (states {j.i_from} -> {j.i_to}); contact "
              f"{j.contact_from} -> {j.contact_to}")
    for lift in (0.0, 0.1 * T):
        i = path.first_ring(lift)
        if i is not None:
            s = path.states[i]
            print(f"first ring with the apex above {lift / T:g} t: state {i}, delta = "
                  f"{s.delta / T:.4f} t, {s.contact}")
    try:
        slope, drift = log_slope(path, 5 * T, min(10 * T, path.states[-1].delta))
        print(f"d ln P / d ln delta over 5 t to {min(10.0, path.states[-1].delta / T):.3g} t "
              f"(last branch): {slope:.4f}, drift (upper half - lower half) {drift:+.4f}")
    except ValueError as err:
        print(err)
    W, U, Pi = path.work(), path.array("U"), path.array("Pi")
    print(f"energy: max |W - U - Pi| / max U = {np.abs(W - U - Pi).max() / U.max():.2e}; "
          f"max |W - U| / max U = {np.abs(W - U).max() / U.max():.2e}")
    tm = path.timer
    print(f"states {len(path.states)}, newton iterations {tm.newton_iterations}, "
          f"assembly {tm.assembly:.2f} s, factor {tm.factor:.2f} s, solve {tm.solve:.2f} s, "
          f"wall {wall:.2f} s")


if __name__ == "__main__":
    main()
