"""Benchmark: the sealed gripper in its working order (solver.grip): a thin shell (h/R
--h, default 1) pressed frictionless to --delta-max with its pocket vented, the pocket sealed
there, the shell's own cavity depressurised at fixed delta to -f p_cl (p_cl = 8 C10
(t/R)^2, a complete sphere's classical buckling pressure), then pulled until the pocket
opens.  No adhesion.

Prints one row per fraction f: the cavity's pressure [kPa], P at the ramp's end, the
pull-off P* (most tensile P while sealed) in C10 R^2 and in N for --R-mm and --C10-kPa,
where the pocket opens (delta / t), its gauge pressure there / p_a, P* over the ideal
suction force p_a pi r_seal^2, the pull's energy balance, and the wall time.
Run: python benchmarks/sealed_gripper.py [--t 0.02] [--h 1] [--mesh coarser] [--delta-max 5]
[--fractions 0,0.25,0.5,0.75,1] [--n 1.0] [--p-atm-kPa 101.325] [--C10-kPa 300]
[--R-mm 20] [--coarser MESH] [--gamma-hat G --tabor 0.3] [--figure PNG]  (--delta-max in
thicknesses t; --gamma-hat: adhesion gamma/(C10 R) by the smoothed Dugdale law of that Tabor
parameter, switched on where the pull starts, and the open shell's pull-off (pocket vented,
no suction, the same law) first, each row's gain over it; "<=" marks a pull-off found up to a
fold the pull could not jump from (solver.grip.Grip.bound); --coarser: each
row solved on that mesh too, and P*'s error bar from the two (solver.error_bars.error_bar,
the order of solver.error_bars.assumed_order); --figure: P against delta along each pull,
and P* against the suction).  Bad input: one line, exit 2.
"""
import argparse
import sys
import time

from shell_adhesion.errors import InputError
from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.solver import pocket as pk
from shell_adhesion.solver.cohesive import CohesiveLaw
from shell_adhesion.solver.error_bars import assumed_order, error_bar
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.grip import grip, press
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.snap import loading_cap, ring_arc
from shell_adhesion.study.cohesive_case import K_OVER_C10


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t", type=float, default=0.02, help="t/R")
    ap.add_argument("--h", type=float, default=1.0, help="h/R")
    ap.add_argument("--mesh", default="coarser")
    ap.add_argument("--delta-max", type=float, default=5.0, help="in thicknesses t")
    ap.add_argument("--fractions", default="0,0.25,0.5,0.75,1")
    ap.add_argument("--n", type=float, default=1.0, help="polytropic exponent")
    ap.add_argument("--p-atm-kPa", type=float, default=101.325)
    ap.add_argument("--C10-kPa", type=float, default=300.0)
    ap.add_argument("--R-mm", type=float, default=20.0)
    ap.add_argument("--coarser", default=None, help="the error bar's coarser mesh")
    ap.add_argument("--gamma-hat", type=float, default=0.0, help="gamma / (C10 R)")
    ap.add_argument("--tabor", type=float, default=0.3)
    ap.add_argument("--figure", default=None)
    a = ap.parse_args(argv)
    T = a.t
    try:
        fractions = [float(f) for f in a.fractions.split(",")]
        if not all(0 <= f for f in fractions):
            raise InputError(f"--fractions: {a.fractions!r} must be numbers >= 0")
        p_atm = pk.p_atm_over_C10(a.p_atm_kPa, a.C10_kPa)
        pk.Pocket("sealed", p_atm, a.n)
        cap = loading_cap(T, a.h)
        law = (CohesiveLaw(md.sigma0_of(a.tabor, a.gamma_hat, 1.0, K_OVER_C10), a.gamma_hat)
               if a.gamma_hat > 0 else None)
    except ValueError as err:       # InputError is one
        print(err if isinstance(err, InputError) else f"--fractions: {err}", file=sys.stderr)
        return 2
    force_N = a.C10_kPa * 1e-3 * a.R_mm ** 2          # C10 R^2 in N
    p_cl = 8 * T * T
    print(f"t/R = {T:g}, h/R = {a.h:g}, {a.mesh} mesh; pressed exactly to {a.delta_max:g} t, sealed "
          f"(n = {a.n:g}, p_a/C10 = {p_atm:.4g}), depressurised, pulled; p_cl = "
          f"{p_cl * a.C10_kPa:.4g} kPa; forces in N for R = {a.R_mm:g} mm, C10 = "
          f"{a.C10_kPa:g} kPa")
    order = assumed_order(T, a.mesh)
    print("| f = -p_c / p_cl | p_c [kPa] | P at the ramp's end [C10 R^2] | P* [C10 R^2] | "
          "P* [N] | opens at delta / t | gauge there / p_a | P* / ideal suction | "
          "energy balance | s |"
          + (f" P* on {a.coarser} [C10 R^2] | bar (order {order:.3g}) [C10 R^2] | bar [N] |"
             if a.coarser else ""))
    print("| --- " * (13 if a.coarser else 10) + "|")

    pressed = {}            # mesh: its press, which serves every grip below

    def solved(mesh, f, pocket="sealed"):
        if mesh not in pressed:
            d = discretise(cap_mesh(cap, mesh_spec(mesh, ring_arc(a.delta_max * T))))
            pressed[mesh] = press(d, a.delta_max * T, p_atm)
        return grip(pressed[mesh].shell, a.delta_max * T, -f * p_cl, p_atm, a.n, pocket=pocket,
                    adhesion=law, pressed=pressed[mesh])

    def answered(g):
        return g.pull is not None and (not g.ended_by or g.bound)

    open_P = None
    if law is not None:
        t0 = time.perf_counter()
        g = solved(a.mesh, 0.0, "vented")
        open_P = g.pull_off()[0] if answered(g) else None
        print(f"adhesion gamma/(C10 R) {a.gamma_hat:g}, Tabor {a.tabor:g}: the open shell "
              f"(pocket vented, no suction) P* "
              + (f"{'<= ' if g.bound else ''}{open_P:+.4e} C10 R^2 ({open_P * force_N:+.4g} N)"
                 if open_P is not None else f"not answered: {g.ended_by}")
              + f"; {time.perf_counter() - t0:.1f} s")

    grips = []
    for f in fractions:
        t0 = time.perf_counter()
        g = solved(a.mesh, f)
        wall = time.perf_counter() - t0
        grips.append((f, g))
        ramp = f"{g.ramp[-1].P:+.4e}" if g.ramp else "-"
        if not answered(g):
            print(f"| {f:g} | {-f * p_cl * a.C10_kPa + 0.0:.4g} | {ramp} | {g.ended_by} | | | | | | "
                  f"{wall:.1f} |")
            continue
        P, _ = g.pull_off()
        last = g.pull.states[-1]
        extra = ""
        if a.coarser:
            gc = solved(a.coarser, f)
            Pc = gc.pull_off()[0] if answered(gc) else float("nan")
            if g.bound or gc.bound:     # a bar from bounds says nothing
                extra = (f" {'<= ' if gc.bound else ''}{Pc:+.4e} | - (a bound) | - |")
            else:
                bar = float(error_bar(P, Pc, order=order))
                extra = f" {Pc:+.4e} | {bar:.2e} | {bar * force_N:.2g} |"
        gain = f" (gain {P / open_P:.3g})" if open_P else ""
        print(f"| {f:g} | {-f * p_cl * a.C10_kPa + 0.0:.4g} | {ramp} | "
              f"{'<= ' if g.bound else ''}{P:+.4e}{gain} | "
              f"{P * force_N:+.4g} | {last.delta / T:.3f} | {last.p / p_atm:+.5f} | "
              f"{-P / g.ideal_suction(p_atm):.4f} | {g.pull.energy_miss():.1e} | {wall:.1f} |"
              + extra)
    if a.figure:
        _figure(grips, T, force_N, p_cl * a.C10_kPa, a.figure)
    return 0


def _figure(grips, T, force_N, p_cl_kPa, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4))
    done = [(f, g) for f, g in grips if g.pull is not None]
    for k, (f, g) in enumerate(done):
        path = g.path()
        D, P = path.array("delta") / T, path.array("P") * force_N
        ax.plot(D[:path.turn + 1], P[:path.turn + 1], color="0.6", lw=0.8,
                label="press (pocket vented)" if k == 0 else None)
        ax.plot(D[path.turn:], P[path.turn:], color=f"C{k}", lw=1.4,
                label=f"pull, cavity at {-f + 0.0:g} p_cl")
        ax.plot(D[path.turn - 1:path.turn + 1], P[path.turn - 1:path.turn + 1], ":",
                color=f"C{k}")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xlim(3.8, None)
    ax.set_ylim(-0.2, 0.12)
    ax.set_xlabel("rim approach delta / t")
    ax.set_ylabel("rim load P [N] (> 0 compression)")
    ax.legend(fontsize=7)
    ax.set_title("pressed, sealed, depressurised (dotted), pulled", fontsize=9)
    F = [f for f, _ in done]
    bx.plot(F, [-g.pull_off()[0] * force_N for _, g in done], "ko-")
    bx.set_xlabel(f"cavity suction / p_cl (p_cl = {p_cl_kPa:.3g} kPa)")
    bx.set_ylabel("pull-off -P* [N]")
    bx.set_title("the sealed pocket's pull-off against the suction", fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=120)


if __name__ == "__main__":
    sys.exit(main())
