"""Benchmark: where a thin shell pressed deep stops, and that the stop is its clamp's.

    python benchmarks/clamp.py [--fine]

Each thin shell (t/R 0.02, 0.05, 0.1 x h/R 0.2, 0.5) is loaded (no_slip) toward 0.9 h on
the coarse and default meshes (`--fine`: also t/R 0.02, h/R 0.2 on the fine mesh, about
15 s) until a state fails the element-quality check.  Prints per run the delta / R at
which it stopped, the contact radius a / R of its last state, the rim radius b / R, the
bending length sqrt(t) (units of R), the deformed radius of the worst element of the
refused state, and whether the refusal names the clamp (solver.quality.clamp_squeeze),
then the spread of the stop delta between meshes.
"""
import math
import sys
import time

import numpy as np

import shell_adhesion.solver.path as path
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import DEPTH_SHARE, Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec

SHELLS = [(t, h) for h in (0.2, 0.5) for t in (0.02, 0.05, 0.1)]


def stop(t, h, mesh):
    """(stop delta / R, last a / R, worst element's deformed r / R, names the clamp, s)."""
    seen = {}
    check = path.quality

    def recording(d, x):            # the refused state is not kept: remember the last one
        seen["q"], seen["x"] = check(d, x), x.copy()
        return seen["q"]

    cap = Cap(t, h)
    d = discretise(cap_mesh(cap, mesh_spec(mesh)))
    t0 = time.perf_counter()
    path.quality = recording
    try:
        loading = path.load(d, "no_slip", DEPTH_SHARE * h, stop_at_limit=True)
    finally:
        path.quality = check
    wall = time.perf_counter() - t0
    why = loading.stopped_by or ""
    if "at delta = " not in why:
        return math.nan, loading.states[-1].a, math.nan, False, wall
    at = float(why.split("at delta = ")[1].split(" R")[0])
    nodes = d.edofs[:9, seen["q"].element]
    r = float(np.mean(d.capmesh.nodes[0, nodes] + seen["x"][nodes]))
    return at, loading.states[-1].a, r, "clamped rim" in why, wall


def main(argv):
    runs = [(t, h, m) for t, h in SHELLS for m in ("coarse", "default")]
    if "--fine" in argv:
        runs.append((0.02, 0.2, "fine"))
    print(f"{'t/R':>5} {'h/R':>4} {'mesh':>8} {'stop delta/R':>12} {'a/R':>7} {'b/R':>6} "
          f"{'sqrt(t)':>7} {'worst r/R':>9}  clamp  wall [s]")
    stops = {}
    for t, h, m in runs:
        at, a, r, clamp, wall = stop(t, h, m)
        stops.setdefault((t, h), []).append(at)
        print(f"{t:5g} {h:4g} {m:>8} {at:12.4f} {a:7.4f} {Cap(t, h).rim_outer:6.4f} "
              f"{math.sqrt(t):7.4f} {r:9.4f}  {'yes' if clamp else 'no ':5}  {wall:.1f}")
    for (t, h), v in stops.items():
        v = np.array(v)
        print(f"t/R {t:g}, h/R {h:g}: stop deltas {', '.join(f'{x:.4f}' for x in v)} R, "
              f"spread {(v.max() - v.min()) / v.min():.1%}")


if __name__ == "__main__":
    main(sys.argv[1:])
