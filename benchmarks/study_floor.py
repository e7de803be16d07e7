"""Benchmark: the least a study could take if its relaxation paths cost nothing: the
loadings its catalogue recorded, spread evenly over the workers.

    python benchmarks/study_floor.py CATALOGUE [--workers 2] [--anchor-s SECONDS]

Reads the catalogue a run left (e.g. `catalogue-data` after `shell-adhesion run
workflow.yaml --out results/`) and prints, per mesh, the path sets stored, the seconds
their loading tasks and their relaxation tasks took (as recorded by the workers; a set
whose fit loaded more than once records its last loading only, so the sums are lower
bounds), and the floor: the loadings divided by the workers.  `--anchor-s`: the CalculiX
loading's time of the same day (benchmarks/calculix_loading.py), for the floor as a ratio.
"""
import argparse
import pathlib
import sys

from shell_adhesion.catalogue.store import Catalogue
from shell_adhesion.solver.contact import INTERFACES
from shell_adhesion.solver.mesh import LEVELS

TARGET = 1.9        # the study's target: cold run / CalculiX loading


def rows(catalogue: pathlib.Path) -> list:
    """(mesh, loading_s, relaxation_s) of every finished set the catalogue timed."""
    try:
        cat = Catalogue(catalogue, create=False)
    except FileNotFoundError:
        sys.exit(f"catalogue: {catalogue} holds no index (run a study into it first)")
    with cat:
        return [(mesh, r["loading_s"], r["relaxation_s"]) for mesh in LEVELS
                for interface in INTERFACES for r in cat.timings(interface, mesh)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("catalogue", type=pathlib.Path)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--anchor-s", type=float, default=None)
    ns = ap.parse_args()
    got = rows(ns.catalogue)
    if not got:
        sys.exit(f"catalogue: {ns.catalogue} holds no finished path set with its timings")
    print(f"{'mesh':>8} {'sets':>5} {'loadings s':>11} {'relaxations s':>14}")
    load_sum = relax_sum = 0.0
    for mesh in sorted({m for m, _, _ in got}):
        mine = [(ls, rs or 0.0) for m, ls, rs in got if m == mesh]
        ls, rs = sum(v[0] for v in mine), sum(v[1] for v in mine)
        load_sum, relax_sum = load_sum + ls, relax_sum + rs
        print(f"{mesh:>8} {len(mine):5d} {ls:11.1f} {rs:14.1f}")
    print(f"{'all':>8} {len(got):5d} {load_sum:11.1f} {relax_sum:14.1f}")
    floor = load_sum / ns.workers
    print(f"floor (loadings over {ns.workers} workers, no imports, no scheduling): "
          f"{floor:.1f} s")
    if ns.anchor_s:
        print(f"floor / CalculiX loading ({ns.anchor_s:g} s): {floor / ns.anchor_s:.2f} "
              f"(target < {TARGET})")


if __name__ == "__main__":
    main()
