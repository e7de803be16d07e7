"""Benchmark: the depressurised gripper with a vented pocket (issue 42, item 4, the part
the energy method of a contact disc answers today).

    python benchmarks/gripper.py [--shells 0.04:1,0.02:0.5] [--fractions 0,0.25,0.5,0.75]
        [--gammas 30] [--mesh coarse] [--interface no_slip]

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
"""
from pathlib import Path
import sys
import time

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
    if argv:
        sys.exit(f"gripper: unknown arguments {argv}")
    gammas = [float(g) for g in gammas.split(",")]
    print("| t/R | h/R | p [kPa] | p / p_cl | gamma [J/m^2] | P* [N] | a* [mm] | gain | "
          "wall [s] |")
    print("| --- " * 9 + "|", flush=True)
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
                    open_P[g] = fl["P_N"]
                gain = (fl["P_N"] / open_P[g]) if open_P.get(g) else float("nan")
                print(head + f"{fl['P_N']:.4f} +- {fl['P_N_error']:.2g} | {fl['a_mm']:.3f} | "
                      f"{gain:.3f} | {wall:.0f} |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
