"""Benchmark: loading curve of the paper's base shell (t/R = 0.15, h = R) to delta = R/4.

Prints, per mesh: DOFs, states, Newton iterations, assembly vs linear-solve time
(factorisations + solves), wall.
Run: python benchmarks/loading.py [coarse default fine] [no_slip | frictionless]
"""
import sys
import time

from shell_adhesion.solver.case import solve_loading


def main(meshes, interface="no_slip"):
    print(f"{'mesh':8} {'dofs':>6} {'states':>6} {'newton':>6} {'assembly s':>10} "
          f"{'solve s':>8} {'wall s':>7} {'P(5mm) N':>9}")
    for mesh in meshes:
        t0 = time.perf_counter()
        d, path = solve_loading(0.15, 1.0, interface, mesh, 0.25)
        wall = time.perf_counter() - t0
        tm = path.timer
        print(f"{mesh:8} {d.ndof:6d} {len(path.states):6d} {tm.newton_iterations:6d} "
              f"{tm.assembly:10.2f} {tm.factor + tm.solve:8.2f} {wall:7.2f} "
              f"{path.states[-1].P * 0.3 * 400:9.3f}", flush=True)


if __name__ == "__main__":
    interfaces = [a for a in sys.argv[1:] if a in ("no_slip", "frictionless")]
    meshes = [a for a in sys.argv[1:] if a not in interfaces]
    main(meshes or ["coarse", "default", "fine"], *interfaces[-1:])
