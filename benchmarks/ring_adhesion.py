"""Benchmark: how much adhesion does the ring of a mirror-buckled shell survive?
(solver.ring_adhesion)

Presses a thin deep shell (h = R, frictionless, no adhesion) to --delta-max thicknesses,
past its snap, where it touches the plane in a ring around a dimple; then switches the
smoothed Dugdale law of Tabor parameter --tabor (sigma0 from lambda with E* = 8 C10,
K = 4 E* / 3) on at that delta for gammas bisected in ln gamma between --lo and --hi
until they are --rel apart, and prints per switch whether the ring holds, its contact
set and P, then the bracket of gamma_c / (C10 R) and the wall times.

Run: python benchmarks/ring_adhesion.py [--t 0.02] [--mesh coarse] [--delta-max 5]
     [--tabor 1] [--lo 2e-5] [--hi 1e-4] [--rel 0.05]
"""
import argparse
import time

from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.solver.cohesive import CohesiveLaw
from shell_adhesion.solver.ring_adhesion import adhesion_limit
from shell_adhesion.solver.snap import trace_shell
from shell_adhesion.study.cohesive_case import K_OVER_C10


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t", type=float, default=0.02, help="t/R")
    ap.add_argument("--mesh", default="coarse")
    ap.add_argument("--delta-max", type=float, default=5.0, help="in thicknesses t")
    ap.add_argument("--tabor", type=float, default=1.0)
    ap.add_argument("--lo", type=float, default=2e-5, help="gamma/(C10 R) that must hold")
    ap.add_argument("--hi", type=float, default=1e-4, help="gamma/(C10 R) that must not")
    ap.add_argument("--rel", type=float, default=0.05)
    a = ap.parse_args(argv)
    T = a.t
    t0 = time.perf_counter()
    d, path = trace_shell(T, 1.0, a.mesh, a.delta_max * T)
    ring = path.states[-1]
    print(f"t/R {T:g}, h/R 1, {a.mesh} mesh, {d.ndof} dofs: pressed to {ring.delta / T:.4f} t "
          f"({path.ended_by or 'reached'}), P {ring.P:.4e} C10 R^2, contact {ring.contact}, "
          f"apex {ring.apex_gap / T:.3g} t up; {time.perf_counter() - t0:.1f} s", flush=True)

    def law_of(gamma):
        return CohesiveLaw(md.sigma0_of(a.tabor, gamma, 1.0, K_OVER_C10), gamma)

    def show(r):
        where = f"{r.state.contact}, P {r.state.P:.4e}" if r.state is not None else ""
        print(f"  gamma/(C10 R) {r.gamma:.4g} (delta_c {law_of(r.gamma).delta_c / T:.3g} t): "
              f"{'holds' if r.holds else 'does not hold'}; {where or r.why}; "
              f"{time.perf_counter() - t0:.1f} s", flush=True)

    lo, hi = adhesion_limit(d, ring, law_of, a.lo, a.hi, a.rel, progress=show)
    print(f"lambda {a.tabor:g}: the ring holds up to gamma_c/(C10 R) in [{lo.gamma:.4g}, "
          f"{hi.gamma:.4g}]; wall {time.perf_counter() - t0:.1f} s")


if __name__ == "__main__":
    main()
