"""Benchmark: P* of one shell per mesh and per kind of relaxed contact front (issue 39).

Run: python benchmarks/front_families.py R_MM T_MM H_MM C10_MPA GAMMA_J_M2 MESH[,MESH...] [LO,HI]
     e.g. python benchmarks/front_families.py 20 0.4 4 0.3 6 coarser,coarse,default,fine

The relaxation paths of a set start from loaded states whose contact front ends on an
element corner or on a midside node (solver.case.relaxation_starts); the set uses one
kind, the larger, and its error-bar companions the same.  This script solves the shell
(no_slip) on the default mesh as `solve_case` fits it to the one gamma asked, then on each
MESH relaxes the starts of each kind whose contact radius lies within LO to HI (default
0.8 to 1.4) times that answer's a*, on the answer's fit (even arc, loading target,
depth), and prints per mesh and kind: element layers through the shell, dofs, P* [N]
(the lowest interior minimum of that stretch of the equilibrium curve: error_bars.py's
windowed reference) and the wall time.
"""
from pathlib import Path
import sys
import time

from shell_adhesion.solver.request import Request, answers, gamma_bucket, solve_request
from shell_adhesion.solver.scaling import force_N, gamma_hat

sys.path.insert(0, str(Path(__file__).resolve().parent))
from error_bars import _windowed     # noqa: E402  (the windowed solve and its P*)


def main(argv):
    R, t, h, C10, gamma = (float(v) for v in argv[:5])
    meshes = argv[5].split(",")
    lo, hi = (float(v) for v in (argv[6] if len(argv) > 6 else "0.8,1.4").split(","))
    g = gamma_hat(gamma, C10, R)
    top = gamma_bucket(g)
    ps, _, _ = solve_request(t / R, h / R, Request.serving(top), top, "no_slip", "default")
    fit, (_, po) = ps.stats["fit"], answers(ps, [g])[g]
    a_star = float(po.a_star)
    print(f"R {R:g} mm, t {t:g} mm, h {h:g} mm, C10 {C10:g} MPa, gamma {gamma:g} J/m^2 "
          f"(gamma/(C10 R) {g:.4g}); the answer (default mesh, its own kind: "
          f"{ps.stats['relaxation_family']}): P* {force_N(po.P_star, C10, R):.6f} N, "
          f"a* {a_star * R:.4f} mm; window {lo:g}-{hi:g} a*")
    print(f"{'mesh':8s} {'fronts':>8s} {'layers':>6s} {'dofs':>6s} {'P* [N]':>10s} {'wall [s]':>8s}")
    for mesh in meshes:
        for family in ("corner", "midside"):
            _, _, layers, dofs, (P,), wall = _windowed(
                t / R, h / R, mesh, top, fit, family, a_star, (lo, hi), g, C10, R,
                time.perf_counter())
            print(f"{mesh:8s} {family:>8s} {layers:6d} {dofs:6d} {P:10.6f} {wall:8.0f}",
                  flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
