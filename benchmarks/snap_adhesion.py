"""Benchmark: finite-range adhesion on a thin deep shell pressed past its snap
(solver.snap.trace_loading with a cohesive law; solver.arclength.trace): frictionless,
h = R, the smoothed Dugdale law of Tabor parameter lambda (sigma0 from lambda with
E* = 8 C10, K = 4 E* / 3).

--history turn: pressed without adhesion to --delta-max (in t), the law switched on at
the turn at fixed delta, then unloaded until the shell leaves the law's reach;
--descent N allows the switch's damped descent N steps (arclength._descend, 600 by
default).  --history adhesive: the law acts from the first touch (arclength.trace, the
cohesive case's frictionless path), pressed to --delta-max and retracted.
Prints the turn, every `--every`-th state (delta / t, P / (C10 R^2), the contact set), the
pull-off P* and delta*, the energy balance (turn only) and the wall time.
Run: python benchmarks/snap_adhesion.py [--t 0.02] [--mesh coarse] [--delta-max 5]
[--gamma-hat 0.005] [--tabor 1] [--history turn|adhesive] [--descent 600] [--every 100]
"""
import argparse
import time

from shell_adhesion.solver import arclength
from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.solver.cohesive import CohesiveLaw, Interface
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.snap import (SnapSettings, adhesive_pull_off, contact_set,
                                        loading_cap, ring_arc, trace_loading)

K_OVER_C10 = 32.0 / 3.0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t", type=float, default=0.02, help="t/R")
    ap.add_argument("--mesh", default="coarse")
    ap.add_argument("--delta-max", type=float, default=5.0, help="in thicknesses t")
    ap.add_argument("--gamma-hat", type=float, default=0.005, help="gamma / (C10 R)")
    ap.add_argument("--tabor", type=float, default=1.0)
    ap.add_argument("--history", choices=("turn", "adhesive"), default="turn")
    ap.add_argument("--descent", type=int, default=600)
    ap.add_argument("--every", type=int, default=100)
    a = ap.parse_args(argv)
    T = a.t
    law = CohesiveLaw(md.sigma0_of(a.tabor, a.gamma_hat, 1.0, K_OVER_C10), a.gamma_hat)
    d = discretise(cap_mesh(loading_cap(T, 1.0), mesh_spec(a.mesh, ring_arc(a.delta_max * T))))
    print(f"t/R {T:g}, h/R 1, {a.mesh} mesh, {d.ndof} dofs; gamma/(C10 R) {a.gamma_hat:g}, "
          f"lambda {a.tabor:g}: sigma0 {law.sigma0:.4g} C10, delta_c {law.delta_c / T:.3g} t; "
          f"history {a.history}")
    t0 = time.perf_counter()
    if a.history == "turn":
        descend = arclength._descend
        arclength._descend = lambda cn, c, x, max_iter=600, mu0=1e-2: descend(
            cn, c, x, max_iter=a.descent, mu0=mu0)
        path = trace_loading(d, a.delta_max * T, SnapSettings(), unload_to=-0.5,
                             adhesion=law)
        arclength._descend = descend
        contact = [s.contact for s in path.states]
    else:
        iface = Interface(d, law)
        path = arclength.trace(iface, a.delta_max * T,
                               settings=arclength.ArcSettings(max_steps=6000))
        contact = [" + ".join(("disc" if r0 == 0 else "ring") + f" {r0:.4g}-{r1:.4g}"
                              for r0, r1 in contact_set(iface, s.x)[1]) or "none"
                   for s in path.states]
    wall = time.perf_counter() - t0
    print(f"ended: {path.ended_by or 'left the law reach'}; {len(path.states)} states, "
          f"turn at state {path.turn}: {contact[path.turn] if path.turn >= 0 else ''}")
    for k, s in enumerate(path.states):
        if k % a.every == 0 or k == path.turn:
            print(f"{k:5d} {s.delta / T:9.4f} {s.P:12.4e}  {contact[k]}")
    try:
        if a.history == "turn":
            P, D = adhesive_pull_off(path)
        else:
            po = arclength.pull_off(path)
            P, D = po.P_star, po.delta_star
        print(f"P* = {P:.5g} C10 R^2 at delta* = {D / T:+.4g} t")
    except ValueError as err:
        print(f"no pull-off: {err}")
    if a.history == "turn" and path.turn > 0:
        print(f"energy: max |W - U - Pi - E_gas + J| / max U = {path.energy_miss():.2e}")
    print(f"wall {wall:.1f} s")


if __name__ == "__main__":
    main()
