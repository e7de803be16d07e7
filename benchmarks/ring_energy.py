"""Benchmark: the energy method at a ring contact's two edges (solver.ring_energy).

Presses a thin deep shell (h = R, frictionless, no adhesion) to --delta-max thicknesses,
past its snap, where it touches the plane in a ring around a dimple; holds that ring and
grows it at fixed delta element edge by element edge, inward (the dimple closing) and
outward, and prints G = dU/dA of each edge against its radius (the other edge held where
it was pressed); then brackets gamma_c, the largest adhesion (zero range) at which the
ring settles instead of closing (`zip_limit`, both edges free), with the ring it settles
on just below it, and the wall times.  Compare gamma_c with the finite-range one of
benchmarks/ring_adhesion.py.  --along D1,D2,... (thicknesses): gamma_c also at the states
of the ring branch (after the loading's last fold) nearest those deltas: the adhesion at
which an unloading ring closes its dimple there.  --unload GAMMA: the unloading itself
from the pressed ring with adhesion GAMMA / (C10 R) by the energy method (`unload`, rim
steps of --step t, to -2 t): every settled ring, and how it ended.  --pocket sealed: the
pocket under the dimple sealed at ambient pressure (101.325 kPa against C10 0.3 MPa) at
the press: the G profiles and the rings' gas pressure; no limit is bracketed (the gas
keeps the dimple open).

Run: python benchmarks/ring_energy.py [--t 0.02] [--mesh coarse] [--delta-max 5]
     [--edges 24] [--lo G] [--hi G] [--rel 0.01] [--along 3.5,4,4.5]
     [--unload 2e-5 [--step 0.1]] [--pocket sealed]
     (--lo, --hi default: half and 1.3 times 0.21 (t/R) (delta/R)^2, the finite-range limit's
     measured rule, ring_adhesion.LIMIT_SCALE; a bracket that misses moves by 1.3)
"""
import argparse
import dataclasses
import time

from shell_adhesion.solver import pocket as pk
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.ring_adhesion import LIMIT_SCALE, around_dimple
from shell_adhesion.solver.ring_energy import (RingLattice, release_rates, settle, unload,
                                               zip_limit)
from shell_adhesion.solver.snap import (SnapSettings, loading_cap, ring_arc, trace_loading,
                                        trace_shell)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t", type=float, default=0.02, help="t/R")
    ap.add_argument("--mesh", default="coarse")
    ap.add_argument("--delta-max", type=float, default=5.0, help="in thicknesses t")
    ap.add_argument("--edges", type=int, default=24, help="element edges grown per side")
    ap.add_argument("--lo", type=float, help="gamma/(C10 R) that must hold")
    ap.add_argument("--hi", type=float, help="gamma/(C10 R) that must close")
    ap.add_argument("--rel", type=float, default=0.01)
    ap.add_argument("--along", default="", help="deltas in t on the ring branch")
    ap.add_argument("--unload", type=float, help="gamma/(C10 R) of an unloading")
    ap.add_argument("--step", type=float, default=0.1, help="its rim steps, in t")
    ap.add_argument("--pocket", choices=("vented", "sealed"), default="vented")
    a = ap.parse_args(argv)
    T = a.t
    t0 = time.perf_counter()
    if a.pocket == "sealed":
        d = pk.bind(discretise(cap_mesh(loading_cap(T, 1.0),
                                        mesh_spec(a.mesh, ring_arc(a.delta_max * T)))),
                    pk.Pocket("sealed", pk.p_atm_over_C10(101.325, 300.0), 1.0))
        # sealed by hand at the press (seal_at_turn: not at the first ring on the way)
        path = trace_loading(d, a.delta_max * T,
                             dataclasses.replace(SnapSettings(), seal_at_turn=True))
        d = pk.seal(d, path.states[-1].x)
    else:
        d, path = trace_shell(T, 1.0, a.mesh, a.delta_max * T)
    pressed = path.states[-1]
    print(f"t/R {T:g}, h/R 1, {a.mesh} mesh, {d.ndof} dofs: pressed to {pressed.delta / T:.4f} t "
          f"({path.ended_by or 'reached'}), P {pressed.P:.4e} C10 R^2, contact "
          f"{pressed.contact}, apex {pressed.apex_gap / T:.3g} t up; "
          f"{time.perf_counter() - t0:.1f} s", flush=True)
    lattice = RingLattice(d, pressed)
    ring = lattice(0, 0)
    print(f"held ring: r {ring.r_in:.4f}-{ring.r_out:.4f} R, P {ring.P:.4e}, apex "
          f"{ring.apex_gap / T:.3g} t up; {time.perf_counter() - t0:.1f} s", flush=True)
    for side in ("in", "out"):
        radius, G = release_rates(lattice, side, a.edges)
        print(f"{side}ward edge: r / R and G / (C10 R) per element edge "
              f"({time.perf_counter() - t0:.1f} s)")
        for r, g in zip(radius, G):
            print(f"  {r:.4f}  {g:.4e}")
    if a.pocket == "sealed":
        for n in (0, 5, 10, 20):
            r = lattice(min(n, a.edges), 0)
            print(f"  grown {min(n, a.edges)} edges inward: r_in {r.r_in:.4f} R, pocket gauge "
                  f"{r.x[-1]:+.4e} C10, P {r.P:+.4e}")
        rule = LIMIT_SCALE * T * (a.delta_max * T) ** 2
        for k in (1, 2, 4):
            s = settle(lattice, k * rule)
            print(f"  gamma/(C10 R) {k * rule:.4g}: {'closes' if s.closed else 'holds'}, "
                  f"ring {s.ring.r_in:.4f}-{s.ring.r_out:.4f} R, gauge {s.ring.x[-1]:+.4e} C10")
        return
    rule = LIMIT_SCALE * T * (a.delta_max * T) ** 2
    lo, hi = zip_limit(lattice, a.lo or rule / 2, a.hi or 1.3 * rule, a.rel, widen=1.3)
    s = lo.ring
    print(f"gamma_c/(C10 R) in [{lo.gamma:.4g}, {hi.gamma:.4g}] (zero range, no edge force); "
          f"just below it the ring settles at r {s.r_in:.4f}-{s.r_out:.4f} R "
          f"(grown {lo.j} edges in, {lo.k} out), apex {s.apex_gap / T:.3g} t up, "
          f"P {s.P:.4e}; {lattice.solves} rings solved; wall {time.perf_counter() - t0:.1f} s")
    rings = list(lattice.rings.values())
    print(f"over the rings solved: least height of a node not held {min(r.free_gap for r in rings):.3g} R "
          f"(< 0: through the plane), least held reaction {min(r.tension for r in rings):.3g} C10 R^2")
    D = path.array("delta")
    folds = [i for i in range(1, len(D) - 1) if D[i] <= D[i - 1] and D[i] < D[i + 1]]
    branch = range(folds[-1] if folds else 0, len(D))
    for want in [float(v) for v in a.along.split(",") if v]:
        i = min(branch, key=lambda k: abs(D[k] - want * T))
        state = path.states[i]
        if not around_dimple(state, T):
            print(f"  delta {D[i] / T:.4f} t: {state.contact}, not a ring around a dimple")
            continue
        rule = LIMIT_SCALE * T * D[i] ** 2
        lo_i, hi_i = zip_limit(RingLattice(d, state), rule / 2, 1.3 * rule, a.rel, widen=1.3)
        print(f"  delta {D[i] / T:.4f} t ({state.contact}, P {state.P:.4e}): gamma_c/(C10 R) in "
              f"[{lo_i.gamma:.4g}, {hi_i.gamma:.4g}], / ((t/R) (delta/R)^2) = "
              f"{lo_i.gamma / (T * D[i] ** 2):.4f}; {time.perf_counter() - t0:.1f} s",
              flush=True)
    if a.unload is not None:
        u = unload(d, pressed, a.unload, -2 * T, a.step * T)
        print(f"unloading at gamma/(C10 R) {a.unload:g}: delta / t, P / (C10 R^2), ring / R")
        for r in u.rings:
            print(f"  {r.delta / T:7.3f}  {r.P:+.4e}  {r.r_in:.4f}-{r.r_out:.4f}  apex "
                  f"{r.apex_gap / T:.3f} t")
        print(f"ended: {u.ended_by or 'reached -2 t'}; least P {u.P_star:+.4e}; "
              f"{time.perf_counter() - t0:.1f} s")


if __name__ == "__main__":
    main()
