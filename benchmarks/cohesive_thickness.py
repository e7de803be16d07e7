"""The cohesive pull-off against thickness at fixed lambda and gamma / (C10 R), beside the
energy method's (frictionless, h = R).

    python benchmarks/cohesive_thickness.py [MESH] [OUT.csv] [LAMBDA ...]

R = 20 mm, C10 = 0.3 MPa, gamma = 30 J/m^2 (gamma / (C10 R) = 0.005), h = 20 mm, t/R from
0.03 to 1 (solid).  Each row: t/R, lambda, the cohesive P* [N] with its error bar (next
coarser mesh), a*, c*, the energy method's P* [N] and error, the ratio, the wall time;
written to OUT.csv (default cohesive_thickness.csv) as the rows finish.
"""
import csv
import sys
import time

from shell_adhesion.errors import ConvergenceError
from shell_adhesion.study.case import solve_case
from shell_adhesion.study.cohesive_case import solve_cohesive_case

R_MM, C10, GAMMA, H_MM = 20.0, 0.3, 30.0, 20.0
T_OVER_R = (0.03, 0.05, 0.075, 0.1, 0.15, 0.2, 0.3, 0.5, 1.0)
FIELDS = ("t_over_R", "tabor", "P_star_N", "P_star_N_error", "a_star_mm", "c_star_mm",
          "energy_P_star_N", "energy_P_star_N_error", "ratio", "refused", "wall_s")


def main(mesh="default", out="cohesive_thickness.csv", *lams):
    lams = [float(v) for v in lams] or [0.3, 1.0]
    energy = {}
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, FIELDS)
        w.writeheader()
        for t in T_OVER_R:
            shell = dict(R_mm=R_MM, t_mm=t * R_MM, h_mm=H_MM, C10_MPa=C10, gamma_J_m2=GAMMA)
            try:
                e = solve_case(**shell, interface="frictionless", mesh=mesh, progress=False)
                fl = e.to_dict()["pull_off"][0].get("fixed_load") or {}
            except ConvergenceError as err:     # the energy method's answer is missing
                print(f"t/R {t}: energy method failed: {err}", flush=True)
                fl = {}
            energy[t] = (fl.get("P_N"), fl.get("P_N_error"))
            for lam in lams:
                t0 = time.perf_counter()
                r = solve_cohesive_case(**shell, tabor=lam, mesh=mesh)
                po = {} if r.refused else r.to_dict()["pull_off"]
                row = dict(t_over_R=t, tabor=lam, P_star_N=po.get("P_star_N"),
                           P_star_N_error=po.get("P_star_N_error"), a_star_mm=po.get("a_star_mm"),
                           c_star_mm=po.get("c_star_mm"), energy_P_star_N=energy[t][0],
                           energy_P_star_N_error=energy[t][1],
                           ratio=None if not po or energy[t][0] is None
                           else po["P_star_N"] / energy[t][0],
                           refused=r.refused or "", wall_s=round(time.perf_counter() - t0, 1))
                w.writerow(row)
                f.flush()
                print(" ".join(f"{k} {v:.5g}" if isinstance(v, float) else f"{k} {v}"
                               for k, v in row.items()), flush=True)


if __name__ == "__main__":
    main(*sys.argv[1:])
