r"""Mooney-Rivlin shells: pull-off against C01/C10 for the base shell.

R = 20 mm, t = 3 mm, h = 20 mm, C10 = 0.3 MPa, gamma = 30 J/m^2, no-slip; C01/C10 from 0
(neo-Hookean) to 0.5.  Each ratio is one FE problem (the ratio is an FE dimension; C10 only
rescales).  Writes docs/figures/mooney_rivlin.png: |P*| (fixed load) and delta_dagger (fixed
grips) against C01/C10, and P* over the eq. 3 scale (mu0 = 2 (C10 + C01)) as eta.

    python examples/ex03_mooney_rivlin.py [--mesh coarse] [--delta-max-over-R 0.15]
"""
import argparse
from pathlib import Path

import numpy as np

from shell_adhesion.study.case import solve_case

R_MM, T_MM, H_MM, C10_MPA, GAMMA = 20.0, 3.0, 20.0, 0.3, 30.0
RATIOS = (0.0, 0.1, 0.2, 0.3, 0.4, 0.5)
FIGURE = Path(__file__).parent.parent / "docs" / "figures" / "mooney_rivlin.png"


def sweep(ratios=RATIOS, mesh="coarse", delta_max_over_R=0.15):
    """Rows (C01/C10, P* [N], delta* [mm], delta_dagger [mm], P_dagger [N], eta)."""
    rows = []
    for q in ratios:
        res = solve_case(R_MM, T_MM, H_MM, C10_MPA, GAMMA, delta_max_mm=delta_max_over_R * R_MM,
                         mesh=mesh, material="mooney-rivlin", C01_MPa=q * C10_MPA,
                         progress=False)
        po = res.to_dict()["pull_off"][0]
        rows.append((q, po["fixed_load"]["P_N"], po["fixed_load"]["delta_mm"],
                     po["fixed_grips"]["delta_mm"], po["fixed_grips"]["P_N"], po["eta"]))
    return np.array(rows, dtype=float)


def figure(rows, path=FIGURE, title=""):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.6), constrained_layout=True)
    ax1.plot(rows[:, 0], rows[:, 1], "o-", label="P* (fixed load)")
    ax1.plot(rows[:, 0], rows[:, 4], "s--", label="P$^\\dagger$ (fixed grips)")
    ax1.set_xlabel("C01 / C10")
    ax1.set_ylabel("pull-off force [N]")
    ax1.legend()
    ax2.plot(rows[:, 0], rows[:, 3], "o-", color="C2", label="$\\delta^\\dagger$ (fixed grips)")
    ax2.plot(rows[:, 0], rows[:, 2], "s--", color="C3", label="$\\delta$* (fixed load)")
    ax2.set_xlabel("C01 / C10")
    ax2.set_ylabel("rim displacement at pull-off [mm]")
    ax2.legend()
    fig.suptitle(title, fontsize=9)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=150)
    plt.close(fig)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", default="coarse")
    ap.add_argument("--delta-max-over-R", type=float, default=0.15)
    ns = ap.parse_args()
    rows = sweep(mesh=ns.mesh, delta_max_over_R=ns.delta_max_over_R)
    print("C01/C10   P* [N]  delta* [mm]  delta_dagger [mm]  P_dagger [N]   eta")
    for q, P, d, dd, Pd, eta in rows:
        print(f"{q:7.2f} {P:8.4f} {d:12.4f} {dd:18.4f} {Pd:13.4f} {eta:6.2f}")
    figure(rows, title=f"Mooney-Rivlin base shell: R 20, t 3, h 20 mm, C10 0.3 MPa, gamma 30 "
                       f"J/m$^2$; {ns.mesh} mesh, delta_max = {ns.delta_max_over_R:g} R")
    print(f"wrote {FIGURE}")
