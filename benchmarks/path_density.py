"""Benchmark: can a shell's relaxation paths be thinned?  P* from every other path against
P* from all of them, as a share of the answer's error bar.

    python benchmarks/path_density.py [SHELL ...]      SHELL: base, thin, solid (default all)

Each shell is solved as `case` solves it (default mesh, its two error-bar meshes), for the
gammas listed; then the default mesh's usable relaxation paths are thinned to every other
one (both parities: the even and the odd ones) and P* is read again from the thinned set.
The energy method's G comes from pairs of neighbouring paths, so the spacing of the paths
is part of the discretisation.  Prints per gamma the P* of the whole set [N], its error bar
[N], and each thinned set's move as a share of the bar (the issue's rule: at most 0.2).
"""
from dataclasses import replace
import sys
import time

from shell_adhesion.solver.request import answers
from shell_adhesion.solver.scaling import gamma_hat
from shell_adhesion.study.case import solve_case

R_MM, C10_MPA = 20.0, 0.3
SHELLS = {                       # t, h [mm]; gamma [J/m^2]
    "base": (3.0, 20.0, (0.6, 6.0, 30.0)),
    "thin": (1.0, 10.0, (6.0, 30.0, 90.0)),
    "solid": (20.0, 20.0, (6.0, 30.0, 90.0)),
}


def main(names):
    for name in names or SHELLS:
        t_mm, h_mm, gammas = SHELLS[name]
        t0 = time.perf_counter()
        res = solve_case(R_MM, t_mm, h_mm, C10_MPA, gammas, progress=False)
        wall = time.perf_counter() - t0
        ps = res.pathset
        paths = sorted(ps.relaxations, key=lambda r: r.a)
        g_hats = [gamma_hat(g, C10_MPA, R_MM) for g in gammas]
        thinned = {k: answers(replace(ps, relaxations=tuple(paths[k::2])), g_hats)
                   for k in (0, 1)}
        force = C10_MPA * R_MM ** 2                     # N per C10 R^2
        print(f"{name}: t = {t_mm:g} mm, h = {h_mm:g} mm, {res.provenance['dofs']} dofs, "
              f"{len(paths)} relaxation paths, {wall:.0f} s")
        for g, gh, po in zip(gammas, g_hats, res.to_dict()["pull_off"]):
            fl = po.get("fixed_load") or {}
            P, bar = fl.get("P_N"), fl.get("P_N_error")
            moves = []
            for k in (0, 1):
                got = thinned[k][gh]
                moves.append(float("nan") if isinstance(got, Exception)
                             else got[1].P_star * force - P)
            share = " ".join(f"{m:+.2e} N ({abs(m) / bar:.2f} bar)" for m in moves)
            print(f"  gamma {g:g} J/m^2: P* = {P:.6f} +- {bar:.2g} N; every other path: "
                  f"{share}")


if __name__ == "__main__":
    main(sys.argv[1:])
