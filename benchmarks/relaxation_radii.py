"""Benchmark: what choosing the relaxation paths' contact radii adaptively would save and
what it would move (issue 11, item 3), measured on the path sets of a catalogue.

For every stored path set it prints:
- `thinned`: the largest relative change of any pull-off number (P*, delta*, a*, P_dagger,
  delta_dagger, a_dagger, a0) at five gamma up to the set's gamma_max when every other
  relaxation path is dropped (both halves tried; the last path is always kept);
- `beyond a0`: the paths (and their share of the relaxation Newton iterations) whose
  contact radius lies beyond a0 at the largest gamma the set gives a pull-off for, four
  paths of spline support left in: the most a choice of radii that keeps every pull-off
  number could skip (it would end the equilibrium curves and the U_T curves of Fig. 5
  there);
and the totals over the catalogue.

Run: python benchmarks/relaxation_radii.py [CATALOGUE_DIR]  (default ./catalogue-data, e.g.
after `shell-adhesion run workflow.yaml --out results/`).
"""
from dataclasses import replace
import sys

import numpy as np

from shell_adhesion.catalogue import files
from shell_adhesion.catalogue.store import Catalogue
from shell_adhesion.solver.pathset_dataset import from_dataset

NUMBERS = ("P_star", "delta_star", "a_star", "P_dagger", "delta_dagger", "a_dagger", "a0")
SUPPORT = 4     # paths kept beyond a0 (the equilibrium spline's support)


def pull_offs(ps, gammas) -> dict:
    """gamma -> PullOff where the set gives one (ValueError: refused)."""
    out = {}
    for g in gammas:
        try:
            out[g] = ps.pull_off(g)[1]
        except ValueError:
            pass
    return out


def thinned_change(ps, full) -> float:
    """Largest relative change of a pull-off number (`full`: gamma -> PullOff of all the
    paths) when every other path is dropped."""
    paths = sorted(ps.relaxations, key=lambda r: r.a)
    worst = 0.0
    for parity in (0, 1):
        kept = tuple(r for i, r in enumerate(paths) if i % 2 == parity or i == len(paths) - 1)
        thin = pull_offs(replace(ps, relaxations=kept), list(full))
        for g, po in thin.items():
            for name in NUMBERS:
                a, b = getattr(full[g], name), getattr(po, name)
                if np.isfinite(a) and np.isfinite(b):
                    worst = max(worst, abs(b / a - 1))
    return worst


def main(folder="catalogue-data"):
    total = dict(paths=0, skippable=0, iterations=0, skippable_iterations=0)
    with Catalogue(folder, create=False) as cat:
        for row in cat.entries():
            if row["status"] != "ok":
                continue
            ps = from_dataset(files.read(cat.dir / row["file"], row["sha256"],
                                               row["fingerprint"]))
            gammas = np.linspace(ps.gamma_max / 5, ps.gamma_max, 5)
            full = pull_offs(ps, gammas)
            if not full:
                print(f"t/R {ps.t:g} h/R {ps.h:g} {ps.mesh}: no pull-off given, skipped")
                continue
            paths = sorted(ps.relaxations, key=lambda r: r.a)
            a = np.array([r.a for r in paths])
            its = np.array([r.newton_iterations for r in paths])
            a0 = full[max(full)].a0
            keep = int(np.searchsorted(a, a0)) + SUPPORT if np.isfinite(a0) else len(a)
            skip = max(0, len(a) - keep)
            total["paths"] += len(a)
            total["skippable"] += skip
            total["iterations"] += int(its.sum())
            total["skippable_iterations"] += int(its[keep:].sum())
            print(f"t/R {ps.t:<5g} h/R {ps.h:<5g} {ps.mesh:8s} paths {len(a):3d}  "
                  f"thinned: pull-off moves {100 * thinned_change(ps, full):.3f} %  "
                  f"beyond a0 = {a0:.3f} R at gamma/(C10 R) = {max(full):.4g}: {skip} paths, "
                  f"{100 * its[keep:].sum() / its.sum():.1f} % of the Newton iterations")
    share = total["skippable_iterations"] / max(total["iterations"], 1)
    print(f"all sets: {total['skippable']} of {total['paths']} paths beyond a0, "
          f"{100 * share:.1f} % of the relaxation Newton iterations")


if __name__ == "__main__":
    main(*sys.argv[1:])
