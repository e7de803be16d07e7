"""Benchmark: a map of the supported domain over t/R x h/R (issue 10, item 8).

Each cell solves one shell (no_slip, `--mesh`, delta_max `--delta-max` R, paths serving
gamma/(C10 R) up to 1.25 x `--gamma`) and the same shell on the next coarser mesh, in a
subprocess with a wall-time limit, and records: solved or refused (why), P* / (C10 R^2) at
`--gamma` with its error bar (solver.error_bars), the worst pointwise J of the loading, the
contact-zone inversion, how far the loading got, and the wall time.  Draws the map to
docs/figures/domain_map.png and prints one line per cell and the JSON of all cells.

Run: python benchmarks/domain.py [--mesh coarse] [--delta-max 0.05] [--timeout 600]
"""
import argparse
import json
from pathlib import Path
import subprocess
import sys
import time

import numpy as np

T_OVER_R = (0.02, 0.05, 0.1, 0.2, 0.5, 1.0)
H_OVER_R = (0.2, 0.4, 0.6, 0.8, 1.0)
FIGURE = Path(__file__).resolve().parents[1] / "docs" / "figures" / "domain_map.png"

CELL = """
import json, sys, time
import numpy as np
from shell_adhesion.solver.case import solve_paths
from shell_adhesion.solver.error_bars import error_bar
from shell_adhesion.solver.geometry import InputError
from shell_adhesion.solver.mesh import coarser_mesh
t, h, mesh, delta_max, gamma = (float(sys.argv[1]), float(sys.argv[2]), sys.argv[3],
                                float(sys.argv[4]), float(sys.argv[5]))
out = dict(t=t, h=h)
t0 = time.perf_counter()
try:
    ps, _, _ = solve_paths(t, h, "no_slip", mesh, delta_max, 1.25 * gamma)
    st = ps.stats
    out.update(J_min=st["J_min"], J_max=st["J_max"], delta_reached=st["delta_reached"],
               stopped_by=st["loading_stopped_by"], inversion=st["inversion_stage"],
               inverted_paths=st["inverted_paths"])
    P = ps.pull_off(gamma)[1].P_star
    out.update(status="solved", P_star=P)
    try:
        c, _, _ = solve_paths(t, h, "no_slip", coarser_mesh(mesh), delta_max, 1.25 * gamma)
        out["P_star_error"] = float(error_bar(P, c.pull_off(gamma)[1].P_star))
    except Exception as e:
        out["P_star_error"] = None
        out["error_reason"] = f"{type(e).__name__}: {e}"[:200]
except InputError as e:
    out.update(status="refused (domain)", reason=str(e)[:200])
except Exception as e:
    kind = type(e).__name__
    if kind == "OutOfRange":     # which check refused the pull-off (solver.case.PathSet.pull_off)
        text = str(e)
        kind = ("graded zone" if "elements grow" in text else "G short" if "bridged" in text
                else "not bracketed")
    out.update(status=f"refused ({kind})", reason=str(e)[:200])
out["wall_s"] = time.perf_counter() - t0
print(json.dumps(out))
"""


def solve_cell(t, h, mesh, delta_max, gamma, timeout):
    t0 = time.perf_counter()
    try:
        run = subprocess.run([sys.executable, "-c", CELL, str(t), str(h), mesh, str(delta_max),
                              str(gamma)], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return dict(t=t, h=h, status="timeout", reason=f"over {timeout:g} s",
                    wall_s=time.perf_counter() - t0)
    if run.returncode != 0 or not run.stdout.strip():
        return dict(t=t, h=h, status="crashed", reason=run.stderr.strip()[-200:],
                    wall_s=time.perf_counter() - t0)
    return json.loads(run.stdout.strip().splitlines()[-1])


_LABELS = {"refused (not bracketed)": "no pull-off: paths do not\nbracket it (delta_max)",
           "refused (graded zone)": "refused: pull-off radius\nin the graded mesh zone",
           "refused (G short)": "refused: G short of\ngamma near pull-off"}


def draw(cells, path, title):
    from matplotlib.figure import Figure
    fig = Figure(figsize=(11, 7), layout="constrained")
    ax = fig.subplots()
    colours = {"solved": "#cfe8cf", "refused (domain)": "#dddddd"}
    for c in cells:
        i, j = T_OVER_R.index(c["t"]), H_OVER_R.index(c["h"])
        colour = colours.get(c["status"], "#f4c7c3")
        ax.add_patch(__import__("matplotlib.patches", fromlist=["Rectangle"]).Rectangle(
            (i - 0.5, j - 0.5), 1, 1, color=colour))
        lines = [_LABELS.get(c["status"], c["status"])]
        if c["status"] == "solved":
            err = c.get("P_star_error")
            lines.append(f"P* {c['P_star']:.3g}" + (f" ± {err:.1g}" if err is not None else ""))
        if "J_min" in c:
            lines.append(f"J {c['J_min']:.2f}-{c['J_max']:.2f}")
            if c.get("stopped_by"):
                lines.append(f"loading to {c['delta_reached']:.3f} R")
            if c.get("inversion"):
                lines.append(f"inverted ({c['inversion']})")
        elif c.get("reason"):
            lines.append(c["reason"][:28])
        lines.append(f"{c['wall_s']:.0f} s")
        ax.text(i, j, "\n".join(lines), ha="center", va="center", fontsize=6.5)
    ax.set_xticks(range(len(T_OVER_R)), [f"{t:g}" for t in T_OVER_R])
    ax.set_yticks(range(len(H_OVER_R)), [f"{h:g}" for h in H_OVER_R])
    ax.set_xlim(-0.5, len(T_OVER_R) - 0.5)
    ax.set_ylim(-0.5, len(H_OVER_R) - 0.5)
    ax.set_xlabel("t/R")
    ax.set_ylabel("h/R")
    ax.set_title(title, fontsize=9)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=100)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", default="coarse", choices=("coarse", "default", "fine"))
    ap.add_argument("--delta-max", type=float, default=0.05)
    ap.add_argument("--gamma", type=float, default=0.005, help="gamma / (C10 R)")
    ap.add_argument("--timeout", type=float, default=600.0, help="per cell, s")
    ap.add_argument("--out", type=Path, default=FIGURE)
    ap.add_argument("--redraw", type=Path, default=None,
                    help="draw from the JSON line a previous run printed (no solving)")
    a = ap.parse_args(argv)
    title = (f"supported domain, no_slip, {a.mesh} mesh (error bar from the next coarser), "
             f"delta_max {a.delta_max:g} R, P* / (C10 R^2) at gamma/(C10 R) = {a.gamma:g}")
    if a.redraw is not None:
        draw(json.loads(a.redraw.read_text().strip().splitlines()[-1]), a.out, title)
        return
    cells = []
    for h in H_OVER_R:
        for t in T_OVER_R:
            c = solve_cell(t, h, a.mesh, a.delta_max, a.gamma, a.timeout)
            cells.append(c)
            print(f"t/R {t:<5g} h/R {h:<4g} {c['status']:<28} P* {c.get('P_star', np.nan):10.4g}"
                  f" +- {c.get('P_star_error') or np.nan:8.2g}  {c['wall_s']:7.1f} s  "
                  f"{c.get('reason', c.get('stopped_by', ''))[:90]}", flush=True)
    draw(cells, a.out, title)
    print(json.dumps(cells))


if __name__ == "__main__":
    main()
