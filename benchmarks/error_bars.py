"""Benchmark: are the error bars honest and useful on a shell?  (issue 39, item 4)

Run: python benchmarks/error_bars.py R_MM T_MM H_MM C10_MPA GAMMA_J_M2[,...] [ANSWER [MESH ...]]
     (default: the answer on the default mesh; meshes coarser coarse default fine, the
     last the reference)
     e.g. python benchmarks/error_bars.py 15 1.5 11.25 0.5 20      (the thin shell of issue 39)
          python benchmarks/error_bars.py 20 3 20 0.3 30           (the paper's base shell)

Solves the shell (no_slip) on the answer's mesh as `solve_case` fits it to the request,
then on the other meshes relaxed from contact fronts ending on the answer's node type (as
`solve_case` solves its error-bar companions; `--family larger` instead: each mesh picks
its own, the rule before), and prints per mesh: the node type, element layers through the thickness, dofs, P* [N], the
error bar the tool gives that mesh's answer from its two coarser companions (the rule:
observed order p with factor 1.25, or order 1 assumed with factor 3, or from the next
coarser mesh alone at the order it assumes where the one after it has a single layer
through the shell: solver.error_bars.assumed_order),
the true error (distance to the reference, the last mesh), and bar / true error (at most 3
is useful, at least 1 honest).  Then the wall times.

--window LO,HI (one gamma): the reference mesh is relaxed only from the starts whose
contact radius lies within LO to HI times the answer mesh's a*, on the answer mesh's fit
(its even arc, loading target and depth), and its P* is the lowest interior minimum of
that stretch of its equilibrium curve: a reference too big to relax whole (on the
default mesh of t/R 0.02, h/R 0.2 at gamma 180 J/m^2 the window 0.98,1.4 gives P* within
1e-5 N of the whole set's, 9 paths of 139; on the fine mesh 0.85,1.4 within 6e-6 N).
"""
import sys
import time

import numpy as np

from shell_adhesion.energy import _interior_min, equilibrium
from shell_adhesion.solver.case import solve_paths
from shell_adhesion.solver.error_bars import (assumed_order, coarsest_usable, error_bar,
                                               observed_order,
                                               refines_through_thickness)
from shell_adhesion.solver.mesh import mesh_spec, thickness_layers
from shell_adhesion.solver.request import Request, answers, gamma_bucket, solve_request
from shell_adhesion.solver.scaling import force_N, gamma_hat


def main(argv):
    own = "--family" in argv and argv[argv.index("--family") + 1] == "larger"
    window = None
    if "--window" in argv:
        window = tuple(float(v) for v in argv[argv.index("--window") + 1].split(","))
    argv = [a for i, a in enumerate(argv)
            if not {"--family", "--window"} & set(argv[max(0, i - 1):i + 1])]
    R, t, h, C10 = (float(v) for v in argv[:4])
    gammas = [float(v) for v in argv[4].split(",")]
    answer = argv[5] if len(argv) > 5 else "default"
    meshes = argv[6:] or ["coarser", "coarse", "default", "fine"]
    ghats = [gamma_hat(g, C10, R) for g in gammas]
    if window is not None and len(ghats) != 1:
        sys.exit("--window: one gamma only (the window is around its a*)")
    top = gamma_bucket(max(ghats))
    solved, family, fit, a_star = {}, None, None, np.nan
    for mesh in [answer] + [m for m in meshes if m != answer]:
        t0 = time.perf_counter()
        if window is not None and mesh == meshes[-1] and mesh != answer:
            solved[mesh] = _windowed(t / R, h / R, mesh, top, fit, family, a_star,
                                     window, ghats[0], C10, R, t0)
            print("solved", *solved[mesh], f"(window {window[0]:g}-{window[1]:g} a*)",
                  flush=True)
            continue
        ps, d, _ = solve_request(t / R, h / R, Request.serving(top), top, "no_slip", mesh,
                                 family=None if own else family)
        family = family or ps.stats["relaxation_family"]
        got = answers(ps, ghats)
        if mesh == answer:
            fit = ps.stats["fit"]
            a_star = (np.nan if isinstance(got[ghats[0]], Exception)
                      else float(got[ghats[0]][1].a_star))
        P = [np.nan if isinstance(got[g], Exception) else float(force_N(got[g][1].P_star, C10, R))
             for g in ghats]
        layers = len(thickness_layers(t / R, mesh_spec(mesh))) - 1 if t < R else 0
        solved[mesh] = (mesh, ps.stats["relaxation_family"], layers, int(d.ndof), P,
                        time.perf_counter() - t0)
        print("solved", *solved[mesh], flush=True)
    for k, (gamma, g) in enumerate(zip(gammas, ghats)):
        rows = [solved[m][:4] + (solved[m][4][k],) + solved[m][5:] for m in meshes]
        _table(rows, R, t, h, C10, gamma, g)


def _windowed(t, h, mesh, top, fit, family, a_star, window, g, C10, R, t0):
    """The reference mesh relaxed only near the answer's a* (--window): a solved row."""
    if not np.isfinite(a_star):
        sys.exit("--window: the answer mesh has no a* to put the window around")
    if fit["paths_taken_further"]:
        print(f"note: the answer's fit took {fit['paths_taken_further']} paths further; "
              "the windowed reference relaxes them by the default reach", flush=True)
    ps, d, _ = solve_paths(t, h, "no_slip", mesh, fit["delta_bound"], top,
                           uniform=fit["uniform_arc"], a_stop=fit["a_stop"], family=family,
                           a_window=(window[0] * a_star, window[1] * a_star))
    eq = equilibrium(ps.surface(), g)
    found = _interior_min(eq.a, eq.P)
    P = np.nan if found is None else float(force_N(found[1], C10, R))
    layers = len(thickness_layers(t, mesh_spec(mesh))) - 1 if t < 1 else 0
    return (mesh, ps.stats["relaxation_family"], layers, int(d.ndof), [P],
            time.perf_counter() - t0)


def _table(rows, R, t, h, C10, gamma, g):
    """One gamma's table: per mesh its P*, the tool's bar, the distance to the last mesh."""
    ref = rows[-1][4]
    last = [r[4] for r in rows[-3:]][::-1]
    p_last = float(observed_order(*last)) if len(rows) >= 3 else np.nan
    extrapolated = (last[0] + (last[0] - last[1]) / (2 ** p_last - 1)
                    if np.isfinite(p_last) else np.nan)
    print(f"R {R:g} mm, t {t:g} mm, h {h:g} mm, C10 {C10:g} MPa, gamma {gamma:g} J/m^2 "
          f"(gamma/(C10 R) {g:.4g}); reference: the {rows[-1][0]} mesh; Richardson from "
          f"the last three meshes: {extrapolated:.5f} N (order {p_last:.2f})")
    print(f"{'mesh':9s} {'fronts':>7s} {'layers':>6s} {'dofs':>6s} {'P* [N]':>10s} {'bar [N]':>9s} "
          f"{'rule':>10s} {'true [N]':>9s} {'ratio':>6s} {'to extr.':>8s} {'wall [s]':>8s}")
    for i, (mesh, fam, layers, dofs, P, wall) in enumerate(rows):
        bar, rule = np.nan, ""
        if i >= 1:
            # the tool's rule: the mesh two below only where it may enter the bar, else
            # two meshes at the order they assume
            third = rows[i - 2][4] if i >= 2 and coarsest_usable(t / R, mesh) else None
            args = (P, rows[i - 1][4], third, refines_through_thickness(t / R, mesh),
                    assumed_order(t / R, mesh))
            bar = float(error_bar(*args))
            p = float(observed_order(*args[:4])) if third is not None else np.nan
            rule = (f"p {p:.2f}" if np.isfinite(p) else "order 1 x3" if third is not None
                    else f"2 meshes p {args[4]:.2g}")
        true = abs(P - ref) if i < len(rows) - 1 else np.nan
        print(f"{mesh:9s} {fam:>7s} {layers:6d} {dofs:6d} {P:10.5f} {bar:9.2g} {rule:>10s} "
              f"{true:9.2g} {bar / true if true else np.nan:6.2f} "
              f"{bar / abs(P - extrapolated):8.2f} {wall:8.0f}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
