"""Benchmark: the supported domain answered, point by point (issue 21, item 8).

One `shell_adhesion.solve_case` per shell, as a user calls it (R = 20 mm, C10 = 0.3 MPa,
default settings: the even zone, the loading depth and the relaxations fitted to the
request, error bars from the next two coarser meshes), over t/R x h/R (the lowest h/R the
domain allows, 0.5 and 1) with gamma / (C10 R) = 0.001, 0.005, 0.015 and 0.03 in one call,
each shell in a subprocess with a wall-time limit.  Records, per gamma, the answer (P*
with its error bar, a*, delta*) or the refusal with its reason, and per shell the dofs,
the fit (solves, re-meshings, even zone, depth reached) and the wall time.  Prints one
line per point and the counts, writes the cells as JSON and draws the map to
docs/figures/domain_map.png.

Run: python benchmarks/domain.py [--mesh default] [--timeout 3600] [--out cells.json]
     python benchmarks/domain.py --redraw cells.json      (the figure from a run)
About 1.5 hours on 2 cores on the default mesh.
"""
import argparse
import json
from pathlib import Path
import subprocess
import sys
import time

T_OVER_R = (0.02, 0.05, 0.1, 0.2, 0.5, 1.0)
H_LEVELS = ("lowest", 0.5, 1.0)
GAMMA_HATS = (0.001, 0.005, 0.015, 0.03)
R_MM, C10_MPA = 20.0, 0.3
FIGURE = Path(__file__).resolve().parents[1] / "docs" / "figures" / "domain_map.png"

CELL = """
import json, sys, time
import shell_adhesion as sa
t, h, mesh = float(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
gammas = json.loads(sys.argv[4])
R, C10 = %r, %r
out = dict(t=t, h=h)
t0 = time.perf_counter()
try:
    res = sa.solve_case(R, t * R, h * R, C10, [g * C10 * R * 1e3 for g in gammas], mesh=mesh,
                        progress=False)
except ValueError as e:
    out.update(status="refused (input)", reason=str(e))
except Exception as e:
    out.update(status="failed", reason=f"{type(e).__name__}: {e}")
else:
    d = res.to_dict()
    p = d["provenance"]
    out.update(status="solved", dofs=p["dofs"], fit=p["fit"],
               delta_reached_mm=p["loading_reached"]["delta_reached_mm"],
               stopped_by=p["loading_reached"]["stopped_by"], J=p["element_quality"],
               inverted_paths=p["inversion"]["inverted_relaxation_paths"], points=[])
    for g, po in zip(gammas, d["pull_off"]):
        point = dict(gamma_hat=g, status=po["status"], reason=po.get("reason"))
        if po["status"] == "ok":
            fl, fg = po["fixed_load"], po["fixed_grips"]
            point.update(P_star_N=fl["P_N"], P_star_N_error=fl.get("P_N_error"),
                         P_star_order=fl.get("P_N_order"), a_star_mm=fl["a_mm"],
                         delta_star_mm=fl["delta_mm"], delta_dagger_mm=fg["delta_mm"],
                         delta_dagger_mm_error=fg.get("delta_mm_error"))
        out["points"].append(point)
out["wall_s"] = time.perf_counter() - t0
print(json.dumps(out))
""" % (R_MM, C10_MPA)


def depths(t):
    """The h/R of a row: the lowest the domain allows (0.2, or just above t), 0.5, 1."""
    lowest = 0.2 if t < 0.2 or t == 1.0 else round(t + 0.01, 2)
    return sorted({lowest, *(h for h in H_LEVELS[1:] if h > t or t == 1.0)})


def solve_cell(t, h, mesh, timeout):
    t0 = time.perf_counter()
    try:
        run = subprocess.run([sys.executable, "-c", CELL, str(t), str(h), mesh,
                              json.dumps(GAMMA_HATS)], capture_output=True, text=True,
                             timeout=timeout)
        return json.loads(run.stdout.strip().splitlines()[-1])
    except subprocess.TimeoutExpired:
        return dict(t=t, h=h, status="timeout", reason=f"over {timeout:g} s",
                    wall_s=time.perf_counter() - t0)
    except (IndexError, json.JSONDecodeError):
        return dict(t=t, h=h, status="crashed", reason=run.stderr.strip()[-300:],
                    wall_s=time.perf_counter() - t0)


def counts(cells):
    points = [p for c in cells for p in c.get("points", [])]
    lost = sum(len(GAMMA_HATS) for c in cells if c["status"] != "solved")
    ok = sum(p["status"] == "ok" for p in points)
    return ok, len(points) + lost


def draw(cells, path, title):
    from matplotlib.figure import Figure
    from matplotlib.patches import Rectangle
    fig = Figure(figsize=(12, 6.5), layout="constrained")
    ax = fig.subplots()
    n = len(GAMMA_HATS)
    for c in cells:
        i = T_OVER_R.index(c["t"])
        j = 0 if c["h"] not in (0.5, 1.0) else (1 if c["h"] == 0.5 else 2)
        points = c.get("points") or [dict(status=c["status"])] * n
        for k, p in enumerate(points):
            colour = "#cfe8cf" if p["status"] == "ok" else "#f4c7c3"
            ax.add_patch(Rectangle((i - 0.5 + k / n, j - 0.5), 1 / n, 1, color=colour, ec="w"))
            text = (f"{p['P_star_N']:.3g}" if p["status"] == "ok" else "refused")
            if p.get("P_star_N_error") is not None:
                text += f"\n±{100 * p['P_star_N_error'] / abs(p['P_star_N']):.2g}%"
            ax.text(i - 0.5 + (k + 0.5) / n, j + 0.15, text, ha="center", va="center",
                    fontsize=5.5)
        fit = c.get("fit") or {}
        ax.text(i, j - 0.3, f"h/R {c['h']:g}, {c.get('dofs', '-')} dofs\n"
                f"{fit.get('solves', '-')} solves, {c['wall_s']:.0f} s", ha="center",
                va="center", fontsize=6)
    ax.set_xticks(range(len(T_OVER_R)), [f"{t:g}" for t in T_OVER_R])
    ax.set_yticks(range(3), ["lowest", "0.5", "1"])
    ax.set_xlim(-0.5, len(T_OVER_R) - 0.5)
    ax.set_ylim(-0.5, 2.5)
    ax.set_xlabel("t/R (each cell: gamma/(C10 R) = " + ", ".join(f"{g:g}" for g in GAMMA_HATS)
                  + "; P* in N at R = 20 mm, C10 = 0.3 MPa)")
    ax.set_ylabel("h/R")
    ax.set_title(title, fontsize=9)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", default="default", choices=("coarse", "default", "fine"))
    ap.add_argument("--timeout", type=float, default=3600.0, help="per shell, s")
    ap.add_argument("--out", type=Path, default=Path("domain_cells.json"))
    ap.add_argument("--figure", type=Path, default=FIGURE)
    ap.add_argument("--redraw", type=Path, default=None,
                    help="draw from the cells of a previous run (no solving)")
    a = ap.parse_args(argv)
    if a.redraw is not None:
        cells = json.loads(a.redraw.read_text())
    else:
        cells = []
        for t in T_OVER_R:
            for h in depths(t):
                c = solve_cell(t, h, a.mesh, a.timeout)
                cells.append(c)
                for p in c.get("points", [dict(gamma_hat=None, status=c["status"])]):
                    value = (f"P* {p['P_star_N']:9.4g} +- {p.get('P_star_N_error') or 0:7.2g} N"
                             if p["status"] == "ok" else (p.get("reason") or c.get("reason")
                                                          or "")[:110])
                    print(f"t/R {t:<5g} h/R {h:<5g} gamma/(C10 R) {p['gamma_hat']!s:<6} "
                          f"{p['status']:<13} {value}", flush=True)
                print(f"  shell: {c.get('dofs', '-')} dofs, fit {c.get('fit')}, "
                      f"{c['wall_s']:.0f} s", flush=True)
                a.out.write_text(json.dumps(cells))
    ok, total = counts(cells)
    mesh = a.mesh if a.redraw is None else "default"
    title = (f"supported domain, no_slip, {mesh} mesh, error bars from the next two coarser "
             f"meshes: {ok} of {total} points answered")
    draw(cells, a.figure, title)
    print(f"{ok} of {total} points answered ({100 * ok / total:.0f} %)")


if __name__ == "__main__":
    main()
