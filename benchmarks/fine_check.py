"""Benchmark: a shell's default-mesh pull-offs (with their error bars) against the fine
mesh, point by point (issue 21: thin shells, and answers with delta* > 0).

Run: python benchmarks/fine_check.py T_OVER_R H_OVER_R [GAMMA_HAT ...] [--below-domain]
     (R = 20 mm, C10 = 0.3 MPa; default gamma/(C10 R) = 0.005 0.03; `--below-domain`
     lowers solver.geometry.T_MIN to 0.01 for this run: t/R 0.01 is not supported, and
     its answers are for the study of that domain only)
Prints, per gamma, P* [N] on the default mesh with its error bar and on the fine mesh,
their difference in error bars, and delta*, a* on both; then the wall times.  The fine
mesh of a thin shell takes tens of minutes on 2 cores.
"""
import sys
import time

import shell_adhesion as sa

R_MM, C10_MPA = 20.0, 0.3


def solve(t, h, gammas, mesh):
    t0 = time.perf_counter()
    res = sa.solve_case(R_MM, t * R_MM, h * R_MM, C10_MPA,
                        [g * C10_MPA * R_MM * 1e3 for g in gammas], mesh=mesh,
                        progress=False, error_bars=(mesh != "fine"))
    d = res.to_dict()
    return d["pull_off"], d["provenance"]["dofs"], time.perf_counter() - t0


def main(argv):
    if "--below-domain" in argv:
        import shell_adhesion.solver.geometry as geometry
        geometry.T_MIN = 0.01
        argv = [a for a in argv if a != "--below-domain"]
    t, h = float(argv[0]), float(argv[1])
    gammas = [float(g) for g in argv[2:]] or [0.005, 0.03]
    default, dofs_d, wall_d = solve(t, h, gammas, "default")
    fine, dofs_f, wall_f = solve(t, h, gammas, "fine")
    print(f"t/R {t:g}, h/R {h:g}: default {dofs_d} dofs, {wall_d:.0f} s (with its two "
          f"error-bar meshes); fine {dofs_f} dofs, {wall_f:.0f} s")
    for g, a, b in zip(gammas, default, fine):
        if a["status"] != "ok" or b["status"] != "ok":
            print(f"gamma/(C10 R) {g:g}: default {a['status']}, fine {b['status']}: "
                  f"{a.get('reason') or b.get('reason')}")
            continue
        fa, fb = a["fixed_load"], b["fixed_load"]
        err = fa.get("P_N_error")
        bars = abs(fb["P_N"] - fa["P_N"]) / err if err else float("nan")
        print(f"gamma/(C10 R) {g:g}: P* default {fa['P_N']:.4f} +- {err if err else float('nan'):.2g} N, "
              f"fine {fb['P_N']:.4f} N ({bars:.2f} error bars); delta* {fa['delta_mm']:.4f} / "
              f"{fb['delta_mm']:.4f} mm; a* {fa['a_mm']:.4f} / {fb['a_mm']:.4f} mm")


if __name__ == "__main__":
    main(sys.argv[1:])
