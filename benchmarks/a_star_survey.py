"""Benchmark: where the pull-off radius a* lies over the domain (the table behind
solver.request.A_STAR_RATIO, the estimate that sizes each request's even zone).

Each cell solves one shell on the coarse mesh with the whole cap meshed evenly and loaded
deep (to `--delta-max` R, at most 0.95 h; a thin shell flattens onto the plane), in a
subprocess with a wall-time limit, and records a* at each gamma / (C10 R) of
solver.request.A_STAR_G.  Prints one line per cell, then the table of a* over JKR's
(9 pi gamma / 64)^(1/3) R per (t/R, h/R level, gamma), rounded up to 0.01, as
A_STAR_RATIO holds it (a cell that gives no a* at a gamma takes the largest of the other
h levels of its t/R; that is how the thinnest deep shells at the largest gammas, whose
loading never reaches their pull-off, are filled).

Run: python benchmarks/a_star_survey.py [--out cells.jsonl] [--timeout 2400]
     python benchmarks/a_star_survey.py --table cells.jsonl   (the table from a run)
About 40 minutes on 2 cores.
"""
import argparse
import json
import math
from pathlib import Path
import subprocess
import sys

from shell_adhesion.solver.request import A_STAR_G, A_STAR_H, A_STAR_T, a_jkr

CELL = """
import json, sys
import shell_adhesion.solver.geometry as geometry
from shell_adhesion.solver.case import solve_paths
t, h, delta_max = float(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3])
gammas = json.loads(sys.argv[4])
geometry.DELTA_MAX = geometry.DELTA_MAX_THIN = max(geometry.DELTA_MAX_THIN, delta_max)
cap = geometry.Cap(t, h)
ps, _, _ = solve_paths(t, h, "no_slip", "coarse", min(delta_max, 0.95 * h), 1.25 * max(gammas),
                       uniform=cap.theta_outer)
out = dict(t=t, h=h, delta_reached=ps.stats["delta_reached"], a_star={})
for g in gammas:
    try:
        out["a_star"][str(g)] = ps.pull_off(g)[1].a_star
    except ValueError as e:
        out["a_star"][str(g)] = None
print(json.dumps(out))
"""


def depths(t):
    """The h/R of the table's levels for t/R: the shallowest allowed, 0.5 and 1."""
    lowest = max(A_STAR_H[0], t + 0.01) if t < 1 else A_STAR_H[0]
    return [h for h in (lowest, 0.5, 1.0) if h > t or t == 1.0]


def table(cells):
    """A_STAR_RATIO from the cells: (t, h level, gamma) -> a* / a_jkr, rounded up."""
    best = {}
    for c in cells:
        j = 0 if c["h"] <= 0.35 else 1 if abs(c["h"] - 0.5) < 0.02 else 2
        for g, a in c.get("a_star", {}).items():
            if a is not None:
                key = (c["t"], j, float(g))
                best[key] = max(best.get(key, 0.0), a / a_jkr(float(g)))
    rows = []
    for t in A_STAR_T:
        levels = []
        for j in range(len(A_STAR_H)):
            row = []
            for g in A_STAR_G:
                v = best.get((t, j, g))
                if v is None:
                    others = [best[t, k, g] for k in range(len(A_STAR_H)) if (t, k, g) in best]
                    v = max(others) if others else float("nan")
                row.append(math.ceil(v * 100) / 100 if math.isfinite(v) else v)
            levels.append(tuple(row))
        rows.append(tuple(levels))
    return tuple(rows)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("a_star_cells.jsonl"))
    ap.add_argument("--delta-max", type=float, default=0.5)
    ap.add_argument("--timeout", type=float, default=2400.0, help="per cell, s")
    ap.add_argument("--table", type=Path, default=None,
                    help="print the table from the cells of an earlier run (no solving)")
    a = ap.parse_args(argv)
    if a.table is None:
        with a.out.open("w") as out:
            for t in A_STAR_T:
                for h in depths(t):
                    try:
                        run = subprocess.run([sys.executable, "-c", CELL, str(t), str(h),
                                              str(a.delta_max), json.dumps(list(A_STAR_G))],
                                             capture_output=True, text=True, timeout=a.timeout)
                        line = run.stdout.strip().splitlines()[-1]
                    except (subprocess.TimeoutExpired, IndexError):
                        line = json.dumps(dict(t=t, h=h, failed=True))
                    print(line, flush=True)
                    out.write(line + "\n")
    cells = [json.loads(x) for x in (a.table or a.out).read_text().splitlines() if x.strip()]
    for t, levels in zip(A_STAR_T, table(cells)):
        print(f"t/R {t:<6g}", "  ".join(" ".join(f"{v:4.2f}" for v in row) for row in levels))


if __name__ == "__main__":
    main()
