"""Closed cavities on the paper's base shell (R = h = 20 mm, t = 3 mm, C10 = 0.3 MPa,
gamma = 30 J/m^2, no_slip): the README figure, the membrane limit and the cost.

    python benchmarks/cavity.py figure [mesh] [delta_max_mm]   docs/figures/cavity.png
    python benchmarks/cavity.py membrane [mesh]                P / (p pi a^2) of an inflated thin shell
    python benchmarks/cavity.py cost [mesh] [delta_max_mm] [repeat]   whole shell vs open
    python benchmarks/cavity.py iteration [mesh]               one Newton iteration vs open

figure: P(delta) on loading and along the gamma = 30 J/m^2 equilibrium curve, with the
fixed-load pull-off point, and the gauge pressure p(delta) on loading and relaxation, for
the open shell, the sealed one (air at one atmosphere, isothermal), and the shell inflated
to +10 kPa and depressurised to -15 kPa.  Defaults: mesh default, delta_max 5 mm.
"""
from concurrent.futures import ProcessPoolExecutor
import multiprocessing
from pathlib import Path
import sys
import time

import numpy as np

from shell_adhesion.solver.case import solve_loading, solve_paths
from shell_adhesion.solver.cavity import P_ATM_KPA, Cavity
from shell_adhesion.solver.scaling import gamma_hat

R, T, H, C10, GAMMA = 20.0, 3.0, 20.0, 0.3, 30.0
KPA = C10 * 1e3                # p / C10 -> kPa
CASES = {"open": Cavity(),
         "sealed": Cavity("sealed", p_atm=P_ATM_KPA / KPA),
         "inflated +10 kPa": Cavity("pressure", p=10 / KPA, p_atm=P_ATM_KPA / KPA),
         "depressurised -15 kPa": Cavity("pressure", p=-15 / KPA, p_atm=P_ATM_KPA / KPA)}
COLOURS = {"open": "k", "sealed": "tab:blue", "inflated +10 kPa": "tab:red",
           "depressurised -15 kPa": "tab:green"}
OUT = Path(__file__).resolve().parents[1] / "docs" / "figures" / "cavity.png"


def solve(name, mesh, delta_max_mm, pool=None):
    t0 = time.perf_counter()
    g = gamma_hat(GAMMA, C10, R)
    ps, d, loading = solve_paths(T / R, H / R, "no_slip", mesh, delta_max_mm / R, 1.25 * g,
                                 cavity=CASES[name], map=None if pool is None else pool.map)
    return ps, time.perf_counter() - t0, loading.timer.newton_iterations + sum(
        r.newton_iterations for r in ps.relaxations)


def figure(mesh="default", delta_max_mm=5.0):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    g = gamma_hat(GAMMA, C10, R)
    F = C10 * R ** 2
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.4))
    with ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")) as pool:
        for name in CASES:
            ps, seconds, iters = solve(name, mesh, delta_max_mm, pool)
            eq, po = ps.pull_off(g)
            c = COLOURS[name]
            ax.plot(ps.loading_delta * R, ps.loading_P * F, c, lw=1.2,
                    label=f"{name}: P* = {po.P_star * F:.3f} N")
            ax.plot(eq.delta * R, eq.P * F, c, ls="--", lw=1)
            ax.plot(po.delta_star * R, po.P_star * F, "o", color=c, ms=5)
            if CASES[name].sealed:
                bx.plot(ps.loading_delta * R, ps.loading_p * KPA, c, lw=1.5, label="loading")
                for r in ps.usable():
                    bx.plot(r.delta * R, r.p * KPA, c, lw=0.4, alpha=0.6)
                near = min(ps.usable(), key=lambda r: abs(r.a - po.a_star))
                p_star = np.interp(po.delta_star, near.delta[::-1], near.p[::-1]) * KPA
                bx.plot(po.delta_star * R, p_star, "o", color=c, ms=5,
                        label=f"pull-off: p = {p_star:.2f} kPa")
            print(f"{name:24s} P* = {po.P_star * F:8.4f} N, delta* = {po.delta_star * R:7.4f} mm, "
                  f"a* = {po.a_star * R:6.4f} mm, P_dagger = {po.P_dagger * F:8.4f} N; apex "
                  f"u_z before touch = {-ps.stats.get('cavity_lift', 0.0) * R:7.4f} mm; "
                  f"{seconds:.1f} s, {iters} Newton iterations")
    ax.axhline(0, color="0.6", lw=0.5)
    ax.set_xlabel("delta [mm] (from the first touch)")
    ax.set_ylabel("P [N] (force on rim and lid, compression > 0)")
    ax.set_title(f"loading (solid), equilibrium at gamma = {GAMMA:g} J/m$^2$ (dashed), "
                 "fixed-load pull-off (dots)", fontsize=9)
    ax.legend(fontsize=8)
    bx.axhline(0, color="0.6", lw=0.5)
    bx.set_xlabel("delta [mm]")
    bx.set_ylabel("gauge pressure p [kPa] (> 0 inflates)")
    bx.set_title("sealed cavity (air, 1 atm, isothermal): loading (thick), relaxation (thin);\n"
                 "inflated and depressurised: p = +10 and -15 kPa throughout", fontsize=9)
    bx.legend(fontsize=8)
    fig.suptitle(f"base shell R = h = {R:g} mm, t = {T:g} mm, C10 = {C10:g} MPa, no_slip, "
                 f"mesh {mesh}", fontsize=10)
    fig.tight_layout()
    OUT.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT, dpi=100)
    print(f"wrote {OUT}")


def membrane(mesh="coarse", t_over_R=0.05, delta_over_R=0.05):
    """P / (p pi a^2) at delta for an inflated thin hemisphere: -> 1 as p grows (membrane)."""
    for p in (0.02, 0.05, 0.1):
        cav = Cavity("pressure", p=p, p_atm=P_ATM_KPA / KPA)
        _, loading = solve_loading(t_over_R, 1.0, "no_slip", mesh, delta_over_R, cavity=cav)
        s = loading.states[-1]
        print(f"t/R = {t_over_R:g}, p/C10 = {p:g} ({p * KPA:.1f} kPa at C10 = {C10:g} MPa): "
              f"delta/R = {s.delta:.3g}, a/R = {s.a:.4f}, P/(C10 R^2) = {s.P:.5f}, "
              f"P / (p pi a^2) = {s.P / (p * np.pi * s.a ** 2):.4f}")


def cost(mesh="default", delta_max_mm=2.0, repeat=1):
    """Wall time and Newton iterations of the whole base shell (loading and relaxation
    paths, one process), the fastest of `repeat` runs; then the cost of one Newton
    iteration (assembly + LU + solve at the same loaded state, fastest of 15)."""
    rows = {}
    for _ in range(int(repeat)):
        for name in CASES:
            ps, seconds, iters = solve(name, mesh, delta_max_mm)
            rows[name] = (min(seconds, rows.get(name, (np.inf,))[0]), iters,
                          ps.stats.get("inversion_stage"))
    base = rows["open"]
    for name, (seconds, iters, inv) in rows.items():
        print(f"{name:24s} {seconds:7.1f} s ({seconds / base[0]:4.2f} x open), {iters} Newton "
              f"iterations ({iters / base[1]:4.2f} x open); inversion: {inv}")
    iteration_cost(mesh)


def iteration_cost(mesh="default", repeat=15):
    from shell_adhesion.solver.contact import constraints
    from shell_adhesion.solver.path import Settings, Timer, _Problem
    times = {}
    for name, cav in CASES.items():
        d, loading = solve_loading(T / R, H / R, "no_slip", mesh, 0.02, cavity=cav)
        s = loading.states[-1]
        pb = _Problem(d, "no_slip", Settings(), Timer())
        c = constraints(d, "no_slip", s.held)
        best = np.inf
        for _ in range(repeat):
            t0 = time.perf_counter()
            K, r = pb.assemble(s.x)
            lu, _ = pb.factor(K, c)
            pb.solve(lu, -r[c.free])
            best = min(best, time.perf_counter() - t0)
        times[name] = (best, d.ndof)
    for name, (t, n) in times.items():
        print(f"{name:24s} one Newton iteration {1e3 * t:7.1f} ms ({t / times['open'][0]:4.2f} "
              f"x open), {n} unknowns")


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else "figure"
    args = sys.argv[2:]
    if what == "figure":
        figure(*(args[:1]), *(float(a) for a in args[1:2]))
    elif what == "membrane":
        membrane(*args[:1])
    elif what == "cost":
        cost(*(args[:1]), *(float(a) for a in args[1:3]))
    elif what == "iteration":
        iteration_cost(*args[:1])
    else:
        sys.exit(f"unknown benchmark {what!r}: figure, membrane or cost")
