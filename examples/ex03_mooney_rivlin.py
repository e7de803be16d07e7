r"""Mooney-Rivlin shells: a study in Python
=======================================

Mooney-Rivlin shells: pull-off against C01/C10 for the base shell, from a study cube.

Runs examples/study_mooney_rivlin.yaml with `shell_adhesion.run_study` (R = 20 mm, t = 3 mm,
h = 20 mm, C10 = 0.3 MPa, gamma = 30 J/m^2, no-slip; C01/C10 from 0, neo-Hookean, to 0.5;
coarse mesh, delta_max = 0.15 R).  Each ratio is one FE path set (the ratio is an FE
dimension, C10 only rescales), stored in the catalogue, so a rerun solves nothing.  Reads
the cube along its C01_over_C10 dimension and writes mooney_rivlin.png into the folder
--out (default: the working folder): P* and P_dagger, delta_dagger and delta* against
C01/C10.  The cube goes to <out>/results/.  About half a minute on two cores, with the
study's progress lines on stderr.

    python examples/ex03_mooney_rivlin.py [--out DIR] [--mesh coarse] [--delta-max-over-R 0.15]

(`--out docs/figures` regenerates the figure in the repository's docs.)
"""
import argparse
from pathlib import Path
import tempfile

import numpy as np
import yaml

from shell_adhesion import run_study
from shell_adhesion.examples import mooney_rivlin_study

STUDY = mooney_rivlin_study()       # the same as examples/study_mooney_rivlin.yaml
FIGURE = "mooney_rivlin.png"        # written into the folder --out


def sweep(ratios=None, mesh=None, delta_max_over_R=None, out=None, catalogue=None,
          progress=False):
    """Rows (C01/C10, P* [N], delta* [mm], delta_dagger [mm], P_dagger [N], eta) of the
    study's cube (its ratios, mesh and delta_max unless given); `progress` prints the
    study's progress lines on stderr."""
    doc = yaml.safe_load(STUDY.read_text())
    if ratios is not None:
        doc["sweeps"] = {"C01_over_C10": [float(q) for q in ratios]}
    if mesh is not None:
        doc["mesh"] = mesh
    if delta_max_over_R is not None:
        doc["delta_max_over_R"] = delta_max_over_R
    with tempfile.TemporaryDirectory() as tmp:
        ds = run_study(doc, out=out or tmp, catalogue=catalogue, progress=progress)
        base = {dim: doc["base"][name] for dim, name in
                (("C10", "C10_MPa"), ("t_over_R", "t_over_R"), ("h_over_R", "h_over_R"),
                 ("gamma", "gamma_J_m2"))}
        point = ds.sel(base)
        rows = [(q, *(float(point[k].sel(C01_over_C10=q)) for k in
                      ("P_star", "delta_star", "delta_dagger", "P_dagger", "eta")))
                for q in ds.C01_over_C10.values]
    return np.array(rows, dtype=float)


def figure(rows, path, title=""):
    """The two panels of `rows` (from `sweep`) as a PNG at `path`."""
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


def arguments(argv=None):
    """The command line: --out (folder of the figure and the cube), --mesh, --delta-max-over-R."""
    ap = argparse.ArgumentParser(description="Pull-off of the base shell against C01/C10 "
                                 "(Mooney-Rivlin)")
    ap.add_argument("--out", type=Path, default=Path("."),
                    help=f"folder for {FIGURE} and results/ (default: the working folder)")
    ap.add_argument("--mesh", default="coarse")
    ap.add_argument("--catalogue", type=Path, default=None,
                    help="catalogue folder (default: catalogue-data in the working folder)")
    ap.add_argument("--delta-max-over-R", type=float, default=0.15)
    return ap.parse_args(argv)


def main(argv=None):
    ns = arguments(argv)
    print(f"solving {STUDY.name} ({ns.mesh} mesh, delta_max = {ns.delta_max_over_R:g} R); "
          "progress on stderr", flush=True)
    rows = sweep(mesh=ns.mesh, delta_max_over_R=ns.delta_max_over_R, out=ns.out / "results",
                 catalogue=ns.catalogue, progress=True)
    print("C01/C10   P* [N]  delta* [mm]  delta_dagger [mm]  P_dagger [N]   eta")
    for q, P, d, dd, Pd, eta in rows:
        print(f"{q:7.2f} {P:8.4f} {d:12.4f} {dd:18.4f} {Pd:13.4f} {eta:6.2f}")
    path = ns.out / FIGURE
    figure(rows, path, title=f"Mooney-Rivlin base shell: R 20, t 3, h 20 mm, C10 0.3 MPa, "
                             f"gamma 30 J/m$^2$; {ns.mesh} mesh, delta_max = "
                             f"{ns.delta_max_over_R:g} R")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
