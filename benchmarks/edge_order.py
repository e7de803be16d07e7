"""Benchmark: how far the energy method's second order in the adhesive edge force holds.

    python benchmarks/edge_order.py [MESH] [T/R,H/R,GAMMA_HAT ...]

A frictionless held set's edge is pulled outward by the adhesive edge force (solver.edge).
The energy method takes it to second order in gamma on paths relaxed without it (the
covered area's compliance c = dA/dgamma each path records: Pi = U_E - gamma A - gamma^2 c
/ 2).  Against the same force carried by the relaxations themselves (exact for the model,
one set of paths per gamma), this prints per shell: P* to first and second order and
carried, the second order's miss (the third and higher orders), and `growth`, the relative
growth of the covered area under the force at a* (PullOff.edge_growth, the quantity the
tool checks).  Dimensionless P* / (C10 R^2); default points: the base shell, a thin shell
and the solid cap at gamma / (C10 R) 0.005 and 0.03, coarse mesh.
"""
import importlib.util
import sys
import time
from pathlib import Path

POINTS = ("0.15,1,0.005", "0.15,1,0.03", "0.05,1,0.005", "0.05,1,0.03", "1,1,0.005",
          "1,1,0.03", "0.05,0.5,0.03")


def _frictionless_area():
    spec = importlib.util.spec_from_file_location(
        "frictionless_area", Path(__file__).with_name("frictionless_area.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def main(mesh="coarse", *points):
    bench = _frictionless_area()
    print(f"{mesh} mesh; P* / (C10 R^2); miss = second order / carried - 1")
    print("t/R    h/R   gamma_hat  first order  second order  carried     miss      growth   "
          "seconds")
    for point in points or POINTS:
        t, h, g = (float(v) for v in point.split(","))
        t0 = time.perf_counter()
        try:
            got, _ = bench.pull_offs(t, mesh, g, h_over_R=h)
        except (ValueError, RuntimeError) as e:     # OutOfRange, ConvergenceError
            print(f"{t:<6g} {h:<5g} {g:<10g} fails: {e}")
            continue
        first, second = got["first order"], got["second order"]
        carried = got.get("edge force on one node")
        miss = (f"{second.P_star / carried.P_star - 1:+.2e}" if carried is not None
                else "(carried fails)")
        print(f"{t:<6g} {h:<5g} {g:<10g} {first.P_star:<12.6f} {second.P_star:<13.6f} "
              f"{carried.P_star if carried else float('nan'):<11.6f} {miss:<9s} "
              f"{second.edge_growth:<8.4f} {time.perf_counter() - t0:.1f}", flush=True)


if __name__ == "__main__":
    main(*sys.argv[1:])
