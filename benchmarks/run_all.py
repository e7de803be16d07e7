"""Benchmark table: the base shell (t/R = 0.15, h = R, R = 20 mm, C10 = 0.3 MPa) on one
process, with and without the speed-ups, back to back, each row switching more off:
"all" (the defaults), "dense" (the relaxation paths sampled as before the quintic energy
splines: Settings.relaxation_steps 8, relaxation_step_max 0.02 R), "no-newton" (also
Settings.hermite_predictor, modified_newton, bordered_event_tangent and start_tangent off: one
factorisation per Newton iteration and per tangent, from the tangent predictor), "superlu"
(also Settings.fast_solver off).  The assembly is the same in all four.

Rows: the no_slip and frictionless loading curves to delta = R/4 (5 mm), and the whole
pull-off (loading, every relaxation path, energy method for gamma = 10..50 J/m^2).
Columns: DOFs, Newton iterations (with a new factorisation; chord: with the previous one),
factorisations, wall time and its split (assembly,
factorisation, triangular solves, bordered event solves (part of the others), energy
method), the headline number (P at 5 mm, or P* at gamma = 30 J/m^2, in N).

With the `bench` extra installed (python -m pip install -e ".[bench]"), a last row times
FElupe's frictionless loading curve of the same shell in the same run
(`benchmarks/felupe_loading.py`: Quad9 64 x 8, 20 steps).

Run: python benchmarks/run_all.py [--mesh default] [--settings all [dense [no-newton [superlu]]]]
"""
import argparse
import time

from tabulate import tabulate

from shell_adhesion.solver.case import solve_loading, solve_paths, timing_stats
from shell_adhesion.solver.path import Settings
from shell_adhesion.solver.scaling import force_N, gamma_hat

R_MM, C10_MPA, T, H, DELTA_MAX = 20.0, 0.3, 0.15, 1.0, 0.25
GAMMAS_J_M2 = (10.0, 20.0, 30.0, 40.0, 50.0)


def loading_row(interface, mesh, settings):
    t0 = time.perf_counter()
    d, path = solve_loading(T, H, interface, mesh, DELTA_MAX, settings)
    wall = time.perf_counter() - t0
    return row_of(d.ndof, timing_stats(path.timer, ()), wall, 0.0,
                force_N(path.states[-1].P, C10_MPA, R_MM))


def felupe_row():
    """FElupe's frictionless loading curve (benchmarks/felupe_loading.py), or None if
    FElupe is not installed."""
    try:
        from felupe_loading import felupe_loading
        dofs, newton, wall, P_N = felupe_loading()
    except ImportError:
        return None
    return {"dofs": dofs, "Newton": newton, "wall s": wall, "N": P_N[-1]}


def pull_off_row(mesh, settings):
    g_hats = [gamma_hat(g, C10_MPA, R_MM) for g in GAMMAS_J_M2]
    t0 = time.perf_counter()
    ps, d, _ = solve_paths(T, H, "no_slip", mesh, DELTA_MAX, 1.25 * max(g_hats), settings)
    t1 = time.perf_counter()
    surface = ps.surface()
    P_star = [ps.pull_off(g, surface)[1].P_star for g in g_hats]
    t2 = time.perf_counter()
    return row_of(d.ndof, ps.stats["timing"], t2 - t0, t2 - t1,
                force_N(P_star[GAMMAS_J_M2.index(30.0)], C10_MPA, R_MM))


DENSE = dict(relaxation_steps=8, relaxation_step_max=0.02)
NEWTON_OFF = dict(hermite_predictor=False, modified_newton=False, bordered_event_tangent=False,
                  start_tangent=False, **DENSE)
SETTINGS = {"all": Settings(), "dense": Settings(**DENSE), "no-newton": Settings(**NEWTON_OFF),
            "superlu": Settings(fast_solver=False, **NEWTON_OFF)}


def row_of(dofs, timing, wall, energy_s, headline_N):
    return {"dofs": dofs, "Newton": timing["newton_iterations"],
            "chord": timing["chord_iterations"],
            "factorisations": timing["factorisations"], "solver": timing["linear_solver"],
            "wall s": wall, "assembly s": timing["assembly_s"],
            "factor s": timing["factorisation_s"], "solve s": timing["solve_s"],
            "events s": timing["event_location_s"], "energy s": energy_s,
            "N": headline_N}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", default="default", choices=("coarse", "default", "fine"))
    ap.add_argument("--settings", nargs="+", default=list(SETTINGS), choices=list(SETTINGS))
    args = ap.parse_args()
    rows = []
    benches = [("loading no_slip, P(5 mm)", lambda s: loading_row("no_slip", args.mesh, s)),
               ("loading frictionless, P(5 mm)",
                lambda s: loading_row("frictionless", args.mesh, s)),
               ("pull-off, P*(30 J/m^2)", lambda s: pull_off_row(args.mesh, s))]
    for name, bench in benches:
        for key in args.settings:
            row = bench(SETTINGS[key])
            rows.append({"benchmark": name, "speed-ups": key, **row})
            print(f"done: {name}, {key}: {row['wall s']:.1f} s", flush=True)
    felupe = felupe_row()
    if felupe is None:
        print("FElupe is not installed (python -m pip install -e \".[bench]\"): its row is left out")
    else:
        rows.append({"benchmark": "loading frictionless, P(5 mm)",
                     "speed-ups": "FElupe Quad9 64x8, 20 steps", **felupe})
    print(f"\nmesh {args.mesh}, one process; seconds of wall time; the split (assembly, "
          f"factorisation, solves, energy method) is inside the wall time, event solves "
          f"overlap the first three")
    print(tabulate(rows, headers="keys", floatfmt=".6g"))


if __name__ == "__main__":
    main()
