"""Figures of docs/adhesion-range.md: the base shell's cohesive paths beside the energy
method's equilibrium curve, and (from benchmarks/cohesive_thickness.py's CSV) P* against
t/R.

    python benchmarks/cohesive_figure.py paths [MESH] [OUT.png]
    python benchmarks/cohesive_figure.py thickness docs/figures/cohesive_thickness.csv [OUT.png]
    python benchmarks/cohesive_figure.py lambda docs/figures/cohesive_thickness.csv [OUT.png]

Base shell R = h = 20 mm, t = 3 mm, C10 = 0.3 MPa, gamma = 30 J/m^2, frictionless.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import numpy as np  # noqa: E402

from shell_adhesion.solver import maugis_dugdale as md  # noqa: E402
from shell_adhesion.study.case import solve_case  # noqa: E402
from shell_adhesion.study.cohesive_case import solve_cohesive_case  # noqa: E402

SHELL = dict(R_mm=20.0, t_mm=3.0, h_mm=20.0, C10_MPa=0.3, gamma_J_m2=30.0)
LAMBDAS = (0.3, 1.0, 2.0, 3.0)


def paths(mesh="default", out="docs/figures/cohesive_paths.png"):
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    e = solve_case(**SHELL, interface="frictionless", mesh=mesh, progress=False)
    fl = e.to_dict()["pull_off"][0]["fixed_load"]
    print(f"energy method: P* {fl['P_N']:.4f} +- {fl['P_N_error']:.2g} N, delta* "
          f"{fl['delta_mm']:.4f} mm, a* {fl['a_mm']:.4f} mm")
    print("| lambda | P* [N] | delta* [mm] | a* [mm] | c* [mm] | fixed grips P [N] | P* / energy "
          "method's | states |\n| --- | --- | --- | --- | --- | --- | --- | --- |")
    for lam in LAMBDAS:
        r = solve_cohesive_case(**SHELL, tabor=lam, mesh=mesh)
        c = r.to_dict(curves=True)["curves"]
        ax.plot(c["delta_mm"], c["P_N"], lw=1.2, label=f"Dugdale, lambda = {lam:g}")
        if r.refused:
            print(f"| {lam:g} | refused: {r.refused} |")
            continue
        po = r.to_dict()["pull_off"]
        ax.plot(po["delta_star_mm"], po["P_star_N"], "k.", ms=6)
        pm = lambda k, f=".4f": (f"{po[k]:{f}} +- {po[k + '_error']:.2g}"
                                 if po[k + "_error"] is not None else f"{po[k]:{f}}")
        grips = pm("P_dagger_N") if po["P_dagger_N"] is not None else "no jump"
        print(f"| {lam:g} | {pm('P_star_N')} | {pm('delta_star_mm')} | {pm('a_star_mm', '.3f')} | "
              f"{pm('c_star_mm', '.3f')} | {grips} | {po['P_star_N'] / fl['P_N']:.3f} | "
              f"{len(c['P_N'])} |", flush=True)
    eq = e.to_dict(curves=True)["equilibrium"][0]      # the same solve's curve
    ax.plot(eq["delta_mm"], eq["P_N"], "k--", lw=1.2, label="energy method (zero range)")
    ax.axhline(0.0, color="0.7", lw=0.6)
    ax.set_xlabel("rim approach delta [mm]")
    ax.set_ylabel("load P [N] (> 0 compression)")
    ax.set_title(f"base shell, gamma = 30 J/m^2, frictionless, {mesh} mesh", fontsize=10)
    ax.set_xlim(-1.2, 0.8)
    ax.set_ylim(-3.0, 0.5)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=150)
    print(f"wrote {out}")


def thickness(table, out="docs/figures/cohesive_thickness.png"):
    rows = list(csv.DictReader(open(table)))
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    lams = sorted({float(r["tabor"]) for r in rows})
    for lam in lams:
        pts = [(float(r["t_over_R"]), float(r["P_star_N"]), float(r["P_star_N_error"] or 0))
               for r in rows if float(r["tabor"]) == lam and r["P_star_N"]]
        t, P, e = zip(*pts)
        ax.errorbar(t, P, yerr=e, marker="o", ms=4, lw=1.2, capsize=2,
                    label=f"Dugdale, lambda = {lam:g}")
    energy = sorted({(float(r["t_over_R"]), float(r["energy_P_star_N"])) for r in rows
                     if r["energy_P_star_N"]})
    ax.plot(*zip(*energy), "k--s", ms=4, lw=1.0, label="energy method (zero range)")
    ax.set_xscale("log")
    ax.set_xlabel("t / R")
    ax.set_ylabel("fixed-load pull-off P* [N]")
    ax.set_title("R = h = 20 mm, C10 = 0.3 MPa, gamma = 30 J/m^2, frictionless", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=150)
    print(f"wrote {out}")


def lam_map(table, out="docs/figures/cohesive_lambda.png", shells=(0.05, 0.1, 0.15, 0.3, 1.0)):
    """P* / (pi gamma R) against lambda for the shells of the thickness table, beside the
    Maugis-Dugdale solid sphere (small strain) and each shell's energy method."""
    rows = [r for r in csv.DictReader(open(table)) if r["P_star_N"]]
    unit = np.pi * SHELL["gamma_J_m2"] * 1e-3 * SHELL["R_mm"]          # pi gamma R [N]
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for t in shells:
        pts = sorted((float(r["tabor"]), float(r["P_star_N"]) / unit,
                      float(r["P_star_N_error"] or 0) / unit)
                     for r in rows if float(r["t_over_R"]) == t)
        if not pts:
            continue
        lam, P, e = zip(*pts)
        line = ax.errorbar(lam, P, yerr=e, marker="o", ms=4, lw=1.2, capsize=2,
                           label=f"t/R = {t:g}" + (" (solid)" if t == 1 else ""))
        energy = next((float(r["energy_P_star_N"]) for r in rows
                       if float(r["t_over_R"]) == t and r["energy_P_star_N"]), None)
        if energy is not None:
            ax.axhline(energy / unit, color=line[0].get_color(), ls=":", lw=0.9)
    grid = np.geomspace(0.05, 3.0, 40)
    ax.plot(grid, [md.pull_off(v).P for v in grid], "k--", lw=1.0,
            label="Maugis-Dugdale, sphere (small strain)")
    ax.set_xscale("log")
    ax.set_xlabel("Tabor-Maugis parameter lambda")
    ax.set_ylabel("P* / (pi gamma R)")
    ax.set_title("R = h = 20 mm, C10 = 0.3 MPa, gamma = 30 J/m^2, frictionless; dotted: "
                 "energy method", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=150)
    print(f"wrote {out}")


if __name__ == "__main__":
    {"paths": paths, "thickness": thickness, "lambda": lam_map}[sys.argv[1]](*sys.argv[2:])
