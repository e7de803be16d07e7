"""Benchmark check: two studies' cubes answer alike, each pull-off number within a share of
its error bar.

    python benchmarks/cube_compare.py BEFORE.nc AFTER.nc [--share 0.2] [--names P_star,...]

For the speed work's rule (no answer may move by more than a fifth of its error bar): run
the same study (e.g. `shell-adhesion run workflow.yaml`) with two releases, each on a
fresh catalogue, and compare the cubes.  Prints, per answered point and number, the two
values, the larger of the two error bars and the move as a share of it; exits 1 if any
move exceeds `--share` of its bar, if the two cubes answer different points, or if their
grids differ.  A point without a bar in either cube is listed and counts only if its
values differ.
"""
import argparse
import sys

import numpy as np
import xarray as xr

NAMES = ("P_star", "delta_star", "a_star", "P_dagger", "delta_dagger", "a_dagger")
DIMS = ("C10", "t_over_R", "h_over_R", "gamma")


def compare(before: xr.Dataset, after: xr.Dataset, names, share: float):
    """(rows, failures): rows (point, name, before, after, bar, move / bar) of every
    answered point; failures the lines saying what exceeds the rule."""
    failures, rows = [], []
    for dim in DIMS:
        if not np.array_equal(before[dim].values, after[dim].values):
            failures.append(f"the grids differ in {dim}: {before[dim].values} against "
                            f"{after[dim].values}")
    if failures:
        return rows, failures
    for name in names:
        b, a = before[name], after[name]
        eb, ea = before[f"{name}_error"], after[f"{name}_error"]
        answered_b, answered_a = b.notnull().values, a.notnull().values
        if not np.array_equal(answered_b, answered_a):
            failures.append(f"{name}: answered at {int(answered_b.sum())} points before, "
                            f"{int(answered_a.sum())} after, not the same ones")
        for idx in zip(*np.nonzero(answered_b & answered_a)):
            point = ", ".join(f"{d} {b[d].values[i]:g}" for d, i in zip(DIMS, idx))
            vb, va = float(b.values[idx]), float(a.values[idx])
            bar = float(np.nanmax([eb.values[idx], ea.values[idx]]))
            move = abs(va - vb)
            ratio = move / bar if bar > 0 else (0.0 if move == 0 else np.inf)
            rows.append((point, name, vb, va, bar, ratio))
            if not ratio <= share:
                failures.append(f"{name} at {point}: {vb:.6g} -> {va:.6g}, moved "
                                f"{move:.3g} against a bar of {bar:.3g} "
                                f"({ratio:.2f} of it, the rule {share:g})")
    return rows, failures


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--share", type=float, default=0.2)
    ap.add_argument("--names", default=",".join(NAMES))
    ns = ap.parse_args(argv)
    with xr.open_dataset(ns.before) as before, xr.open_dataset(ns.after) as after:
        names = ns.names.split(",")
        for cube, label in ((before, ns.before), (after, ns.after)):
            missing = [n for n in names if n not in cube or f"{n}_error" not in cube]
            if missing:
                print(f"{label}: no {', '.join(missing)} (with _error) in the cube")
                return 1
        rows, failures = compare(before, after, names, ns.share)
    print("| point | number | before | after | bar | move / bar |")
    print("| --- | --- | ---: | ---: | ---: | ---: |")
    for point, name, vb, va, bar, ratio in rows:
        print(f"| {point} | {name} | {vb:.6g} | {va:.6g} | {bar:.3g} | {ratio:.3f} |")
    worst = max((r[5] for r in rows), default=0.0)
    print(f"{len(rows)} numbers compared; the largest move {worst:.3f} of its bar "
          f"(rule: {ns.share:g})")
    for line in failures:
        print(line)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
