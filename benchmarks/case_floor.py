"""Benchmark: the least `case` of the base shell could take if its relaxation paths cost
nothing: the command's imports plus the loadings of its three meshes.

    python benchmarks/case_floor.py

Prints the wall time of `import shell_adhesion.cli` in a fresh process (the median of 3),
then per mesh (default and its two error-bar meshes, each fitted to the request as `case`
fits it: gamma = 30 J/m^2 on R = 20 mm, t = 3 mm, h = 20 mm, C10 = 0.3 MPa) the dofs, the
loading alone, and the loading with its relaxation paths, and the floor: imports plus
loadings.
"""
import statistics
import subprocess
import sys
import time

from shell_adhesion.solver.case import solve_paths
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.request import Request, gamma_bucket, initial_fit
from shell_adhesion.solver.scaling import gamma_hat

T, H = 0.15, 1.0
GAMMA = gamma_bucket(gamma_hat(30.0, 0.3, 20.0))


def import_s() -> float:
    runs = []
    for _ in range(3):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", "import shell_adhesion.cli"], check=True)
        runs.append(time.perf_counter() - t0)
    return statistics.median(runs)


def main():
    imports = import_s()
    print(f"import shell_adhesion.cli: {imports:.2f} s (a fresh process, median of 3)")
    fit = initial_fit(Cap(T, H), Request.serving(GAMMA))
    loadings = 0.0
    for mesh in ("default", "coarse", "coarser"):
        t0 = time.perf_counter()
        _, d, _ = solve_paths(T, H, "no_slip", mesh, fit.delta_max, GAMMA, relax_paths=False,
                              uniform=fit.uniform, a_stop=fit.a_stop)
        t1 = time.perf_counter()
        ps, _, loading = solve_paths(T, H, "no_slip", mesh, fit.delta_max, GAMMA,
                                     uniform=fit.uniform, a_stop=fit.a_stop)
        t2 = time.perf_counter()
        loadings += t1 - t0
        print(f"{mesh:>8}: {d.ndof} dofs, {len(loading.events)} contact events, loading "
              f"{t1 - t0:.2f} s; with its {len(ps.relaxations)} relaxation paths {t2 - t1:.2f} s")
    print(f"floor (imports + loadings): {imports + loadings:.2f} s")


if __name__ == "__main__":
    main()
