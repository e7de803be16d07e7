"""Benchmark: a depressurised thin shell pressed past its lift-off (solver.snap.trace_loading
from pocket.bind_depressurised, the pocket vented, frictionless, no adhesion).

The shell's own cavity, closed at the rim by a rigid lid, is held at -f p_cl (p_cl = 8 C10
(t/R)^2); the free shell touching the plane is pressed to --delta-max.  Where its rim load
falls to nothing (lifted off: the suction holds the dimple off the plane), the rim is pushed
on and the shell let settle (snap._jump): prints, per fraction, how the loading ends, the
lift-off, the state it lands on (its apex's height and whether its inner surface rests on
the cavity's lid, solver.lid, with the lid's push), the energy balance and the wall time;
--figure: P against delta, and the meridian at the lift-off and after it with the lid.
Run: python benchmarks/lift_off.py [--t 0.02] [--h 1] [--fractions 0.2,0.25] [--mesh coarser]
[--delta-max 5] [--figure PNG]   (--delta-max in thicknesses t).  Bad input: one line, exit 2.
"""
import argparse
import sys
import time

import numpy as np

from shell_adhesion.errors import InputError
from shell_adhesion.solver import cavity as cv
from shell_adhesion.solver import pocket as pk
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.postprocess import profiles
from shell_adhesion.solver.snap import SnapSettings, loading_cap, ring_arc, trace_loading


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t", type=float, default=0.02, help="t/R")
    ap.add_argument("--h", type=float, default=1.0, help="h/R")
    ap.add_argument("--fractions", default="0.2,0.25")
    ap.add_argument("--mesh", default="coarser")
    ap.add_argument("--delta-max", type=float, default=5.0, help="in thicknesses t")
    ap.add_argument("--figure", default=None)
    a = ap.parse_args(argv)
    T = a.t
    try:
        fractions = [float(f) for f in a.fractions.split(",")]
        if not all(f > 0 for f in fractions):
            raise InputError(f"--fractions: {a.fractions!r} must be numbers > 0")
        cap = loading_cap(T, a.h)
        mesh_spec(a.mesh)
    except ValueError as err:       # InputError is one
        print(err if isinstance(err, InputError) else f"--fractions: {err}", file=sys.stderr)
        return 2
    p_atm = pk.p_atm_over_C10(101.325, 300.0)
    print(f"t/R = {T:g}, h/R = {a.h:g}, {a.mesh} mesh, pressed to {a.delta_max:g} t; the "
          f"cavity at -f p_cl, p_cl = 8 C10 (t/R)^2")
    paths = []
    for f in fractions:
        t0 = time.perf_counter()
        d = discretise(cap_mesh(cap, mesh_spec(a.mesh, ring_arc(a.delta_max * T))))
        d, x0, _ = pk.bind_depressurised(d, pk.Pocket("vented"),
                                         cv.Cavity("pressure", p=-f * 8 * T * T, p_atm=p_atm))
        path = trace_loading(d, a.delta_max * T, SnapSettings(), x0=x0)
        wall = time.perf_counter() - t0
        paths.append((f, d, path))
        P = path.array("P")
        i = int(np.argmax(P))
        print(f"f = {f:g}: P rises to {P[i]:.4g} C10 R^2 at {path.states[i].delta / T:.3f} t; "
              f"ended: {path.ended_by or f'at {path.states[-1].delta / T:.3f} t'}")
        for j in path.jumps():
            land = path.states[j.i_to]
            print(f"  jump at {j.delta / T:.3f} t: P {j.P_from:.3g} -> {j.P_to:.3g} C10 R^2, "
                  f"contact {j.contact_from} -> {j.contact_to}; lands with the apex "
                  f"{land.apex_gap:.4f} R above the plane, {_on_lid(d, land.x)}")
        print(f"  energy balance {path.energy_miss():.2e} of max U; {len(path.states)} states, "
              f"{wall:.1f} s")
    if a.figure:
        _figure(paths, T, a.figure)
    return 0


def _on_lid(d, x) -> str:
    """Where the inner surface of state x is against the cavity's lid (solver.lid): its
    gap below the lid, or the lid's push on the shell and how far into it."""
    cavity = d.cavity.shell
    lid = cavity.lid
    if cavity.through_lid(x):
        return f"through the lid by {lid.penetration(x):.3g} R"
    if lid.penetration(x) == 0:
        return f"below the lid (by {lid.gaps(x).min():.3g} R at least)"
    push = -lid.add_residual(x, np.zeros(len(x)))[lid.dofs[0, 3]]
    return (f"on the lid (its push {push:.3g} C10 R^2, {lid.penetration(x):.2g} R into "
            "it)")


def _figure(paths, T, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.2))
    for k, (f, d, path) in enumerate(paths):
        D, P = path.array("delta") / T, path.array("P")
        ax.plot(D, P, f"C{k}-", label=f"cavity at -{f:g} p_cl")
        for j in path.jumps():
            ax.axvline(j.delta / T, color=f"C{k}", ls=":", lw=0.8)
        shown = [(path.states[j.i_from], "lift-off") for j in path.jumps()[:1]]
        shown += [(path.states[j.i_to], "after the jump") for j in path.jumps()[:1]]
        if not path.jumps():
            shown = [(path.states[-1], "last state")]
        for m, (st, label) in enumerate(shown):
            r, z = profiles(d, st.x)[0]
            bx.plot(r, z, f"C{k}" + ("-" if m else "--"),
                    label=f"-{f:g} p_cl, {label}, δ = {st.delta / T:.2f} t")
            if m or len(shown) == 1:
                rim = d.capmesh.rim
                z_rim = (d.capmesh.nodes[1][rim] + st.x[d.uz(rim)]).max()
                bx.axhline(z_rim, color=f"C{k}", lw=0.6)
    ax.set_xlabel("δ / t")
    ax.set_ylabel("P / (C10 R²)")
    ax.set_title("pressed, the cavity held at its suction (dotted: a jump)", fontsize=9)
    ax.legend(fontsize=8)
    bx.axhline(0, color="k", lw=0.8)
    bx.set_xlabel("r / R")
    bx.set_ylabel("height above the plane / R (thin lines: the lid at the rim)")
    bx.set_aspect("equal")
    bx.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(out, dpi=100)


if __name__ == "__main__":
    sys.exit(main())
