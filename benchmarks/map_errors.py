"""Benchmark: a pull-off map's stated errors, as docs/map.md gives them for the shipped
maps (held by tests/test_pull_off_map.py).

Run: python benchmarks/map_errors.py [MAP]   (MAP: default, coarse or a .nc file)
Prints, over 3000 shells drawn uniformly in (ln t/R, h/R, ln gamma/(C10 R)) with
gamma/(C10 R) 0.001 to 0.03 (seed 0): the shells that need a hole, the interpolation error
of P* (median, 90th percentile, largest, share below 2 %, share above 2 % at t/R 0.1-0.2
and at gamma/(C10 R) > 0.01), the median total error, and the grid points' FE error bars
(share above 2 % of P*, largest); then the wall time.
"""
import sys
import time

import numpy as np

import shell_adhesion as sa


def main(argv):
    name = argv[0] if argv else "default"
    t0 = time.perf_counter()
    s = sa.pull_off_map(name).survey()
    t, g, interp, total, fe = (s[k] for k in ("t_over_R", "gamma_hat", "interpolation",
                                               "total", "fe_grid"))
    band = (t >= 0.1) & (t < 0.2)
    print(f"map {name}: {len(interp) + s['holes']} shells, {s['holes']} need a hole")
    print(f"interpolation error of P* [%]: median {np.median(interp):.2f}, p90 "
          f"{np.percentile(interp, 90):.2f}, largest {interp.max():.2f}; below 2 %: "
          f"{100 * np.mean(interp < 2):.0f} % of shells; above 2 %: "
          f"{100 * np.mean(interp[band] > 2):.0f} % at t/R 0.1-0.2, "
          f"{100 * np.mean(interp[g > 0.01] > 2):.0f} % at gamma/(C10 R) > 0.01")
    print(f"total stated error [%]: median {np.median(total):.2f}")
    print(f"FE error bars of the grid points: {100 * np.mean(fe > 2):.0f} % above 2 % of P*, "
          f"largest {fe.max():.2f} %")
    print(f"wall time {time.perf_counter() - t0:.1f} s")


if __name__ == "__main__":
    main(sys.argv[1:])
