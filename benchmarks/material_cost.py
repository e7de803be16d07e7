"""Benchmark: cost of one Newton iteration (assembly + sparse LU + solve) per material model
on the paper's base shell (t/R = 0.15, h = R, no_slip).

The state is the neo-Hookean equilibrium with the apex zone glued at delta = 0.03 R, the same
for every model; the models are run in turn `repeat` times and each figure is the minimum (the
least disturbed by other load on the machine).  Times are the process's CPU time
(time.process_time), one BLAS thread, so that other load on a shared machine (which
stretches wall-clock times by several times) does not enter; `--wall` uses wall-clock time.
Run: python benchmarks/material_cost.py [mesh] [repeat] [--wall]  (default: default 15)
"""
import os
import sys

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")       # before numpy is imported: one thread, CPU = work

import time  # noqa: E402

import numpy as np  # noqa: E402

from shell_adhesion.solver.contact import constraints
from shell_adhesion.solver.forms import deformation, discretise, tangent
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.material import Material, lagrangian_derivatives
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.path import Settings, Timer, _Problem

MATERIALS = {
    "neo_hooke": Material(),
    "mooney_rivlin": Material("mooney_rivlin", C01_over_C10=0.2),
    "yeoh": Material("yeoh", C20_over_C10=-0.03, C30_over_C10=0.004),
    "gent": Material("gent", Jm=20.0),
    "neo_hooke D1": Material(D1_times_C10=3e-6),
    "mooney_rivlin D1": Material("mooney_rivlin", C01_over_C10=0.2, D1_times_C10=3e-6),
}


clock = time.process_time


def iteration(pb, c, x):
    """(material s, assembly s, LU + solve s) of one Newton iteration at x; the material's
    derivatives at the quadrature points are part of the assembly, timed alone as well."""
    f, p = deformation(pb.d, x)
    t0 = clock()
    lagrangian_derivatives(f, p, pb.d.material)
    tm = clock() - t0
    t0 = clock()
    K, r = tangent(pb.d, x)
    t1 = clock()
    lu, _ = pb.factor(K, c)
    lu.solve(-r[c.free])
    return tm, t1 - t0, clock() - t1


def main(mesh="default", repeat=15):
    cm = cap_mesh(Cap(0.15, 1.0), mesh_spec(mesh))
    d0 = discretise(cm)
    held = list(range(9))
    c = constraints(d0, "no_slip", held)
    pb, x = _Problem(d0, "no_slip", Settings(), Timer()), np.zeros(d0.ndof)
    for delta in np.linspace(0.0, 0.03, 7)[1:]:
        x, *_ = pb.newton(c, x, delta)
    print(f"base shell, mesh {mesh}: {d0.ndof} dofs, {cm.mesh.nelements} elements")
    print(f"{'model':18} {'material ms':>11} {'assembly ms':>11} {'solve ms':>9} "
          f"{'total ms':>9} {'vs neo_hooke':>12}")
    problems = {name: _Problem(discretise(cm, material=m), "no_slip", Settings(), Timer())
                for name, m in MATERIALS.items()}
    times = {name: [] for name in MATERIALS}
    for _ in range(repeat):            # models interleaved, so machine load hits all alike
        for name, p in problems.items():
            times[name].append(iteration(p, c, x))
    ref = None
    for name, t in times.items():
        m, a, s = (min(column) for column in zip(*t))
        ref = ref or a + s
        print(f"{name:18} {1e3 * m:11.2f} {1e3 * a:11.1f} {1e3 * s:9.1f} {1e3 * (a + s):9.1f} "
              f"{(a + s) / ref - 1:+12.1%}")


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--wall"]
    if "--wall" in sys.argv:
        clock = time.perf_counter
    main(*args[:1], *map(int, args[1:2]))
