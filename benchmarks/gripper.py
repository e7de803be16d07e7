"""Benchmark: the depressurised gripper with a vented pocket (issue 42, item 4, the part
the energy method of a contact disc answers today).

    python benchmarks/gripper.py [--shells 0.04:1,0.02:0.5] [--fractions 0,0.25,0.5,0.75]
        [--gammas 30] [--mesh coarse] [--interface no_slip] [--figure gain.png]

R = 20 mm, C10 = 0.3 MPa.  Each shell t/R:h/R is solved with its own cavity held at the
gauge pressure p = -f p_cl (`solve_case(cavity="pressure")`: a rigid lid closes the rim,
the pressure acts on the inner surface; the pocket under the contact is vented, at
ambient pressure), f from --fractions, p_cl = 8 C10 (t/R)^2 the classical buckling
pressure of a complete sphere (2 E (t/R)^2 / sqrt(3 (1 - nu^2)), E = 6 C10, nu = 1/2): a
scale, not this cap's own buckling pressure.  Prints per shell, pressure and gamma the
pull-off P* with its error bar (the case's rule), a*, the gain P*(p) / P*(0), and the
case's refusal where it refuses (a relaxation that inverts: the contact would become a
ring, which the energy method of a contact disc does not follow; issue 42, item 2), and
the wall time.  The sealed pocket (suction under the ring) is not in this table: its
tensile pull-off needs adhesion at a ring's edges (docs/thin-shells.md, "Not built yet").
With --figure: the gain against p / p_cl per shell and gamma, with its error bar (the two
P* bars combined as independent: |gain| sqrt((e/P*)^2 + (e0/P*(0))^2); 0 at p = 0), and
P* in N.
"""
import math
from pathlib import Path
import sys
import time

import numpy as np

import shell_adhesion as sa

sys.path.insert(0, str(Path(__file__).resolve().parent))
from two_methods import _option     # noqa: E402  (the benchmarks' option parser)

R_MM, C10_MPA = 20.0, 0.3


def main(argv):
    shells, argv = _option(argv, "--shells", "0.04:1,0.02:0.5")
    fractions, argv = _option(argv, "--fractions", "0,0.25,0.5,0.75")
    gammas, argv = _option(argv, "--gammas", "30")
    mesh, argv = _option(argv, "--mesh", "coarse")
    interface, argv = _option(argv, "--interface", "no_slip")
    figure, argv = _option(argv, "--figure", None)
    if argv:
        sys.exit(f"gripper: unknown arguments {argv}")
    gammas = [float(g) for g in gammas.split(",")]
    print("| t/R | h/R | p [kPa] | p / p_cl | gamma [J/m^2] | P* [N] | a* [mm] | gain | "
          "wall [s] |")
    print("| --- " * 9 + "|", flush=True)
    answered = []       # (t/R, h/R, gamma, p / p_cl, P* [N], bar [N], gain, gain bar)
    for shell in shells.split(","):
        t_over_R, h_over_R = (float(v) for v in shell.split(":"))
        p_cl_kPa = 8.0 * C10_MPA * 1e3 * t_over_R ** 2
        open_P = {}
        for f in (float(v) for v in fractions.split(",")):
            p_kPa = -f * p_cl_kPa
            t0 = time.perf_counter()
            r = sa.solve_case(R_MM, t_over_R * R_MM, h_over_R * R_MM, C10_MPA, gammas,
                              interface=interface, mesh=mesh, cavity="pressure",
                              p_kPa=p_kPa if f else 0.0, progress=False)
            wall = time.perf_counter() - t0
            for g, po in zip(gammas, r.to_dict()["pull_off"]):
                head = (f"| {t_over_R:g} | {h_over_R:g} | {p_kPa:.3g} | {-f:g} | {g:g} | ")
                if po.get("status", "ok") != "ok" or po.get("fixed_load") is None:
                    print(head + f"refused: {po.get('reason', '')[:160]} | | | {wall:.0f} |",
                          flush=True)
                    continue
                fl = po["fixed_load"]
                if f == 0:
                    open_P[g] = (fl["P_N"], fl["P_N_error"])
                P0, e0 = open_P.get(g, (float("nan"), float("nan")))
                gain = fl["P_N"] / P0
                gain_bar = (abs(gain) * math.hypot(fl["P_N_error"] / fl["P_N"], e0 / P0)
                            if f else 0.0)      # P*(0) / P*(0) is 1 exactly
                answered.append((t_over_R, h_over_R, g, -f, fl["P_N"], fl["P_N_error"],
                                 gain, gain_bar))
                print(head + f"{fl['P_N']:.4f} +- {fl['P_N_error']:.2g} | {fl['a_mm']:.3f} | "
                      f"{gain:.3f} +- {gain_bar:.2g} | {wall:.0f} |", flush=True)
    if figure:
        draw(answered, figure)
        print(f"figure: {figure}")


def draw(answered, out):
    """Gain and P* against p / p_cl, one line per shell and gamma, with error bars."""
    from matplotlib.figure import Figure
    fig = Figure(figsize=(9, 3.8), layout="constrained")
    ax_gain, ax_P = fig.subplots(1, 2)
    for key in sorted({row[:3] for row in answered}):
        rows = sorted((r for r in answered if r[:3] == key), key=lambda r: -r[3])
        f, P, e, gain, gain_bar = (np.array([r[k] for r in rows]) for k in (3, 4, 5, 6, 7))
        label = f"t/R {key[0]:g}, h/R {key[1]:g}, gamma {key[2]:g} J/m$^2$"
        ax_gain.errorbar(f, gain, gain_bar, marker="o", capsize=3, label=label)
        ax_P.errorbar(f, -P, e, marker="o", capsize=3, label=label)
    ax_gain.set_xlabel("cavity gauge pressure p / p$_{cl}$")
    ax_gain.set_ylabel("gain P*(p) / P*(0)")
    ax_P.set_xlabel("cavity gauge pressure p / p$_{cl}$")
    ax_P.set_ylabel("pull-off force -P* [N]")
    ax_gain.legend(fontsize=8)
    for ax in (ax_gain, ax_P):
        ax.invert_xaxis()
        ax.grid(alpha=0.3)
    fig.suptitle("Depressurised gripper, vented pocket (R 20 mm, C10 0.3 MPa; "
                 "p$_{cl}$ = 8 C10 (t/R)$^2$)", fontsize=10)
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1:])
