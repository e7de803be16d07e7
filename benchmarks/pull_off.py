"""Benchmark: everything for the base shell (loading, all relaxation paths, energy method).

Prints the split (loading, relaxations, energy surface, per-gamma), the number of paths,
and Newton iterations per step.  Run: python benchmarks/pull_off.py [mesh] [workers]
(workers > 1 runs the independent relaxation paths in that many processes, as a study
does on dask).
"""
from concurrent.futures import ProcessPoolExecutor
import multiprocessing
import sys
import time

import numpy as np

from shell_adhesion.solver.case import solve_paths
from shell_adhesion.solver.scaling import force_N, gamma_hat

R_MM, C10 = 20.0, 0.3


def main(mesh="default", workers="1"):
    gammas = [10.0, 20.0, 30.0, 40.0, 50.0]
    g_max = 1.25 * gamma_hat(max(gammas), C10, R_MM)
    pool = None
    if int(workers) > 1:
        pool = ProcessPoolExecutor(int(workers), mp_context=multiprocessing.get_context("spawn"))
        pool.submit(int, 0).result()      # start the workers before the clock
    t0 = time.perf_counter()
    ps, d, loading = solve_paths(0.15, 1.0, "no_slip", mesh, 0.25, g_max,
                                 map=pool.map if pool else None)
    t1 = time.perf_counter()
    surface = ps.surface()
    t2 = time.perf_counter()
    per_gamma = []
    for g in gammas:
        s = time.perf_counter()
        _, po = ps.pull_off(gamma_hat(g, C10, R_MM), surface)
        per_gamma.append(time.perf_counter() - s)
        print(f"gamma {g:4.0f} J/m^2: P* = {force_N(po.P_star, C10, R_MM):8.4f} N")
    st = ps.stats
    steps = sum(len(r.delta) - 1 for r in ps.relaxations)
    print(f"mesh {mesh}, {workers} worker(s): {st['dofs']} dofs, {len(ps.relaxations)} relaxation paths, {steps} relaxation steps")
    print(f"loading      {st['loading_s']:7.2f} s  ({st['loading_newton_iterations']} Newton iterations, "
          f"{st['loading_newton_iterations'] / max(1, st['loading_states'] - 1):.2f} per state)")
    print(f"relaxations  {st['relaxation_s']:7.2f} s  ({st['relaxation_newton_iterations']} Newton iterations, "
          f"{st['relaxation_newton_iterations'] / max(1, steps):.2f} per step)")
    print(f"energy surface {t2 - t1:5.3f} s; per gamma {1e3 * np.mean(per_gamma):.1f} ms (max {1e3 * max(per_gamma):.1f} ms)")
    print(f"total        {t2 - t0 + sum(per_gamma):7.2f} s")


if __name__ == "__main__":
    main(*sys.argv[1:])
