"""The noise-free test curves of `tests/test_fit_lab.py`, made on the default mesh (finer
than the coarse mesh the tests fit with, so a round trip carries the model's own
discretisation error): a displacement-controlled test (loading from contact to the turn,
the retraction along the relaxation and the fixed-grips equilibrium curve down to the
jump-off at delta_dagger; `solver.fit.simulated_curve` without detached points), written
as ``delta_mm,P_N`` to tests/data/fit_<name>.csv with the shell and the truth in a
``#`` comment line.

Run: python benchmarks/fit_curves.py [mesh [name ...]]   (default mesh; about a minute)
"""
import pathlib
import sys
import time

from shell_adhesion.solver.fit import simulated_curve
from shell_adhesion.solver.request import Request, gamma_bucket, solve_request

OUT = pathlib.Path(__file__).parent.parent / "tests" / "data"

# name: R, t, h [mm], C10 [MPa], gamma [J/m^2], depth from contact [mm], points per part
CURVES = {
    "base": (20.0, 3.0, 20.0, 0.3, 30.0, 2.0, 600),     # the paper's base shell (dense: the
                                                        # tests take every 4th point or all)
    "thin": (15.0, 1.5, 11.25, 0.5, 20.0, 1.5, 150),    # issue 39's thin shell
    "other": (40.0, 3.0, 20.0, 0.3, 30.0, 4.0, 150),    # another shell (fitted as the base)
}


def make(name, mesh="default"):
    """(delta_mm, P_N, wall s) of curve `name` on `mesh`."""
    R, t, h, C10, gamma, depth, n = CURVES[name]
    g_hat = gamma * 1e-3 / (C10 * R)
    top = gamma_bucket(1.5 * g_hat)
    t0 = time.perf_counter()
    ps, _, _ = solve_request(t / R, h / R, Request.serving(top, depth / R), top, "no_slip", mesh)
    x, p = simulated_curve(ps, C10, g_hat, depth / R, n, n, n_detached=0)
    return x * R, p * R ** 2, time.perf_counter() - t0


def write(name, mesh="default"):
    d, P, wall = make(name, mesh)
    R, t, h, C10, gamma, depth, _ = CURVES[name]
    path = OUT / (f"fit_{name}.csv" if mesh == "default" else f"fit_{name}_{mesh}.csv")
    lines = [f"# R_mm={R:g} t_mm={t:g} h_mm={h:g} C10_MPa={C10:g} gamma_J_m2={gamma:g} "
             f"depth_mm={depth:g} mesh={mesh} interface=no_slip (benchmarks/fit_curves.py)",
             "delta_mm,P_N"] + [f"{a:.9g},{b:.9g}" for a, b in zip(d, P)]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    print(f"{path}: {len(d)} rows, {wall:.1f} s")


if __name__ == "__main__":
    mesh = sys.argv[1] if len(sys.argv) > 1 else "default"
    for name in sys.argv[2:] or CURVES:
        write(name, mesh)
