"""Benchmark: a thin deep shell pressed through its snap into ring contact, then unloaded
(pulled) with the pocket under the dimple sealed (solver.pocket, solver.snap): frictionless,
no adhesion, h = R.

Prints the loading's jump and the turn, then along the unloading every `--every`-th state:
delta / t, P / (C10 R^2), the contact set, the pocket's volume / R^3, its gauge pressure
/ C10 and over p_a, the seal's radius / R; then how the path ended (where the pocket
opens), the pull-off (the most tensile P before the pocket opens; 0 if P stays
compressive) and its ratio to the ideal suction force p_a pi r_seal^2 (largest seal
radius), the least gauge pressure, and the energy balance (work of P against strain,
penalty and gas energy).
Run: python benchmarks/pocket.py [--t 0.02] [--mesh coarser] [--delta-max 5]
[--unload-to -1] [--pocket sealed|vented] [--n 1.0] [--p-atm-kPa 101.325]
[--C10-kPa 300] [--seal turn|ring] [--seal-lift 0.1] [--interface frictionless|no_slip]
[--stick turn|touch] [--cavity-fraction 0] [--every 5] [--figure PNG]
(--delta-max, --unload-to and --seal-lift in thicknesses t; p_a / C10 from the two
pressures in kPa; --seal ring: the gas is sealed at the first ring whose apex is lifted
by more than --seal-lift, turn: at the turn to the unloading; --interface no_slip: the
contact sticks, from the turn (--stick turn, pressed frictionless past the snap) or from
the first touch (tests/test_stick.py); --cavity-fraction F: the shell's own cavity, closed
by a rigid lid at the rim, held at the gauge pressure -F p_cl from the start, p_cl = 8 C10
(t/R)^2 a complete sphere's classical buckling pressure: the free shell is depressurised
first and the loading starts where it touches the plane (solver.cavity.first_touch); the
energies are then counted from that state, the cavity's load -p_c (V_c - V_c0) with the
gas's.)  Bad input: one line, exit 2.
"""
import argparse
import dataclasses
import math
import sys
import time

import numpy as np

from shell_adhesion.errors import InputError
from shell_adhesion.solver import cavity as cv
from shell_adhesion.solver import pocket as pk
from shell_adhesion.solver.contact import INTERFACES
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.snap import SnapSettings, loading_cap, ring_arc, trace_loading


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t", type=float, default=0.02, help="t/R")
    ap.add_argument("--mesh", default="coarser")
    ap.add_argument("--delta-max", type=float, default=5.0, help="in thicknesses t")
    ap.add_argument("--unload-to", type=float, default=-1.0, help="in thicknesses t")
    ap.add_argument("--pocket", default="sealed")
    ap.add_argument("--n", type=float, default=1.0, help="polytropic exponent")
    ap.add_argument("--p-atm-kPa", type=float, default=101.325)
    ap.add_argument("--C10-kPa", type=float, default=300.0)
    ap.add_argument("--seal", choices=("turn", "ring"), default="turn")
    ap.add_argument("--seal-lift", type=float, default=SnapSettings.seal_lift,
                    help="in thicknesses t")
    ap.add_argument("--interface", default="frictionless")
    ap.add_argument("--stick", choices=("turn", "touch"), default="turn")
    ap.add_argument("--cavity-fraction", type=float, default=0.0,
                    help="the cavity's suction / p_cl (0: the cavity open)")
    ap.add_argument("--every", type=int, default=5)
    ap.add_argument("--figure", default=None, help="draw P and the gauge pressure to this PNG")
    a = ap.parse_args(argv)
    T = a.t
    try:
        if a.interface not in INTERFACES:
            raise InputError(f"--interface: {a.interface!r} must be one of "
                             f"{', '.join(INTERFACES)}")
        p_atm = pk.p_atm_over_C10(a.p_atm_kPa, a.C10_kPa)
        pocket = pk.Pocket(a.pocket, p_atm, a.n)
        d = discretise(cap_mesh(loading_cap(T, 1.0), mesh_spec(a.mesh, ring_arc(a.delta_max * T))))
        if not (math.isfinite(a.cavity_fraction) and a.cavity_fraction >= 0):
            raise InputError(f"--cavity-fraction: {a.cavity_fraction!r} must be a finite "
                             "number >= 0 (the suction over p_cl)")
        p_cavity = -a.cavity_fraction * 8 * T * T
        cavity = cv.Cavity("pressure", p=p_cavity, p_atm=p_atm) if p_cavity else None
    except InputError as err:
        print(err, file=sys.stderr)
        return 2
    x0 = None
    if cavity is None:
        d = pk.bind(d, pocket)
    else:
        d, x0, pressurised = pk.bind_depressurised(d, pocket, cavity)
        print(f"cavity at {p_cavity:.4g} C10 ({a.cavity_fraction:g} p_cl, "
              f"{p_cavity * a.C10_kPa:.4g} kPa): the free shell's apex up by "
              f"{pressurised.apex_uz / T:.4f} t")
    settings = dataclasses.replace(SnapSettings(), seal_at_turn=a.seal == "turn",
                                   seal_lift=a.seal_lift)
    if a.interface == "no_slip":
        settings = dataclasses.replace(settings, stick_at_turn=a.stick == "turn")
    t0 = time.perf_counter()
    path = trace_loading(d, a.delta_max * T, settings, unload_to=a.unload_to * T,
                         interface=a.interface, x0=x0)
    wall = time.perf_counter() - t0
    print(f"t/R = {T:g}, h/R = 1, {a.mesh} mesh, {d.ndof} dofs; pocket {a.pocket}, n = "
          f"{a.n:g}, {a.interface}"
          + (f" (sticking from the {a.stick})" if a.interface == "no_slip" else "")
          + f", p_a/C10 = {p_atm:.4g} ({a.p_atm_kPa:g} kPa / {a.C10_kPa:g} kPa), sealed "
          f"at the {'turn' if a.seal == 'turn' else f'first ring lifted > {a.seal_lift:g} t'}")
    for j in path.jumps():
        print(f"jump at delta = {j.delta / T:.4f} t: P {j.P_from:.4e} -> {j.P_to:.4e}; "
              f"{j.contact_from} -> {j.contact_to}")
    k = next((i for i, s in enumerate(path.states) if s.sealed), None)
    if k is not None:
        s = path.states[k]
        print(f"sealed at state {k}: delta = {s.delta / T:.4f} t, V0 = {s.V:.5e} R^3, "
              f"seal radius {s.r_seal:.4f} R, {s.contact}")
    if path.turn >= 0:
        print(f"turn at state {path.turn}: delta = {path.states[path.turn].delta / T:.4f} t")
    print(f"{'state':>5} {'delta/t':>8} {'P/(C10R^2)':>12} {'V/R^3':>11} {'p/C10':>11} "
          f"{'p/p_a':>8} {'r_seal/R':>8}  contact (radii / R)")
    start = k if k is not None else max(path.turn, 0)
    for i in range(start, len(path.states)):
        s = path.states[i]
        if (i - start) % a.every == 0 or i == len(path.states) - 1:
            print(f"{i:5d} {s.delta / T:8.4f} {s.P:12.4e} {s.V:11.4e} {s.p:11.4e} "
                  f"{s.p / p_atm:8.4f} {s.r_seal:8.4f}  {s.contact}")
    print(f"ended: {path.ended_by or 'unload_to reached'}")
    sealed = [s for s in path.states if s.sealed]
    if sealed:
        P = np.array([s.P for s in sealed])
        i = int(np.argmin(P))
        r_max = max(s.r_seal for s in sealed)
        ideal = p_atm * math.pi * r_max ** 2
        pull = max(-P[i], 0.0)
        print(f"pull-off (most tensile P while sealed): {pull:.4e} C10 R^2 (least P "
              f"{P[i]:+.4e} at delta = {sealed[i].delta / T:.4f} t); ideal suction force "
              f"p_a pi r_seal,max^2 = {ideal:.4e} C10 R^2 (r_seal,max {r_max:.4f} R); "
              f"ratio {pull / ideal:.4f}")
        p = np.array([s.p for s in sealed])
        print(f"gauge pressure: least {p.min():+.4e} C10 ({p.min() / p_atm:+.4f} p_a), "
              f"largest {p.max():+.4e} C10 ({p.max() / p_atm:+.4f} p_a), at the last "
              f"sealed state {p[-1]:+.4e} C10 with P {P[-1]:+.4e}")
    if path.turn >= 0:
        P = path.array("P")[path.turn:]
        print(f"least P along the unloading: {P.min():+.4e} C10 R^2")
    W = path.work()
    U, Pi, E = (path.array(name) - path.array(name)[0] for name in ("U", "Pi", "E_gas"))
    J = np.concatenate([[0.0], np.cumsum(path.array("anchor_jump"))[:-1]])
    miss = W - U - Pi - E + J
    scale = np.abs(U).max()
    print(f"energy (changes from the first state): max |W - U - Pi - E_gas| / max |U| = "
          f"{np.abs(miss).max() / scale:.2e}"
          + (f" (over the sealed part, from its first state: "
             f"{np.abs(miss[k:] - miss[k]).max() / scale:.2e})" if k is not None else "")
          + f"; max |E_gas| / max |U| = {np.abs(E).max() / scale:.2e}")
    if a.figure:
        _figure(path, T, p_atm, a.figure)
    print(f"{len(path.states)} states, {path.timer.newton_iterations} Newton iterations, "
          f"{wall:.1f} s")
    return 0


def _figure(path, T, p_atm, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    D, P = path.array("delta") / T, path.array("P")
    sealed = np.array([s.sealed for s in path.states])
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(9, 3.6))
    ax.plot(D[~sealed], P[~sealed], "k-", lw=1, label="loading (vented)")
    ax.plot(D[sealed], P[sealed], "r-", lw=1.5, label="unloading, pocket sealed")
    ax.plot(D[sealed][-1], P[sealed][-1], "ro")
    ax.annotate("ring opens", (D[sealed][-1], P[sealed][-1]), textcoords="offset points",
                xytext=(-60, -25))
    ax.set_xlabel("delta / t")
    ax.set_ylabel("P / (C10 R^2)")
    ax.legend(fontsize=8)
    p = path.array("p")[sealed]
    bx.plot(D[sealed], p / p_atm, "r-")
    bx.set_xlabel("delta / t")
    bx.set_ylabel("gauge pressure / p_a")
    bx.invert_xaxis()
    fig.tight_layout()
    fig.savefig(out, dpi=120)


if __name__ == "__main__":
    sys.exit(main())
