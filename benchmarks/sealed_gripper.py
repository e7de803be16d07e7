"""Benchmark: the sealed gripper in its working order (solver.grip): a thin deep shell
(h = R) pressed frictionless to --delta-max with its pocket vented, the pocket sealed
there, the shell's own cavity depressurised at fixed delta to -f p_cl (p_cl = 8 C10
(t/R)^2, a complete sphere's classical buckling pressure), then pulled until the pocket
opens.  No adhesion.

Prints one row per fraction f: the cavity's pressure [kPa], P at the ramp's end, the
pull-off P* (most tensile P while sealed) in C10 R^2 and in N for --R-mm and --C10-kPa,
where the pocket opens (delta / t), its gauge pressure there / p_a, P* over the ideal
suction force p_a pi r_seal^2, the pull's energy balance, and the wall time.
Run: python benchmarks/sealed_gripper.py [--t 0.02] [--mesh coarser] [--delta-max 5]
[--fractions 0,0.25,0.5,0.75,1] [--n 1.0] [--p-atm-kPa 101.325] [--C10-kPa 300]
[--R-mm 20]  (--delta-max in thicknesses t).  Bad input: one line, exit 2.
"""
import argparse
import sys
import time

from shell_adhesion.errors import InputError
from shell_adhesion.solver import pocket as pk
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.grip import grip
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.snap import loading_cap, ring_arc


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t", type=float, default=0.02, help="t/R")
    ap.add_argument("--mesh", default="coarser")
    ap.add_argument("--delta-max", type=float, default=5.0, help="in thicknesses t")
    ap.add_argument("--fractions", default="0,0.25,0.5,0.75,1")
    ap.add_argument("--n", type=float, default=1.0, help="polytropic exponent")
    ap.add_argument("--p-atm-kPa", type=float, default=101.325)
    ap.add_argument("--C10-kPa", type=float, default=300.0)
    ap.add_argument("--R-mm", type=float, default=20.0)
    a = ap.parse_args(argv)
    T = a.t
    try:
        fractions = [float(f) for f in a.fractions.split(",")]
        if not all(0 <= f for f in fractions):
            raise InputError(f"--fractions: {a.fractions!r} must be numbers >= 0")
        p_atm = pk.p_atm_over_C10(a.p_atm_kPa, a.C10_kPa)
        pk.Pocket("sealed", p_atm, a.n)
        cap = loading_cap(T, 1.0)
    except ValueError as err:       # InputError is one
        print(err if isinstance(err, InputError) else f"--fractions: {err}", file=sys.stderr)
        return 2
    force_N = a.C10_kPa * 1e-3 * a.R_mm ** 2          # C10 R^2 in N
    p_cl = 8 * T * T
    print(f"t/R = {T:g}, h/R = 1, {a.mesh} mesh; pressed to {a.delta_max:g} t, sealed "
          f"(n = {a.n:g}, p_a/C10 = {p_atm:.4g}), depressurised, pulled; p_cl = "
          f"{p_cl * a.C10_kPa:.4g} kPa; forces in N for R = {a.R_mm:g} mm, C10 = "
          f"{a.C10_kPa:g} kPa")
    print("| f = -p_c / p_cl | p_c [kPa] | P at the ramp's end [C10 R^2] | P* [C10 R^2] | "
          "P* [N] | opens at delta / t | gauge there / p_a | P* / ideal suction | "
          "energy balance | s |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for f in fractions:
        t0 = time.perf_counter()
        d = discretise(cap_mesh(cap, mesh_spec(a.mesh, ring_arc(a.delta_max * T))))
        g = grip(d, a.delta_max * T, -f * p_cl, p_atm, a.n)
        wall = time.perf_counter() - t0
        ramp = f"{g.ramp[-1].P:+.4e}" if g.ramp else "-"
        if g.ended_by:
            print(f"| {f:g} | {-f * p_cl * a.C10_kPa + 0.0:.4g} | {ramp} | {g.ended_by} | | | | | | "
                  f"{wall:.1f} |")
            continue
        P, _ = g.pull_off()
        last = g.pull.states[-1]
        print(f"| {f:g} | {-f * p_cl * a.C10_kPa + 0.0:.4g} | {ramp} | {P:+.4e} | "
              f"{P * force_N:+.4g} | {last.delta / T:.3f} | {last.p / p_atm:+.5f} | "
              f"{-P / g.ideal_suction(p_atm):.4f} | {g.pull.energy_miss():.1e} | {wall:.1f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
