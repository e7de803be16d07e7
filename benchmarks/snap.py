"""Benchmark: the loading of a thin deep shell through its snap (Pogorelov's mirror
buckling), traced by arc length (solver.snap): frictionless, no adhesion, h = R.

Prints every `--every`-th state and every state where the contact set changes shape:
state, delta / t, P / (C10 R^2), P over Reissner's 16 C10 t^2 delta / R, the contact set
(radii / R), the apex's height / t, Newton iterations, wall time of the step; then the
displacement-controlled jumps, the first ring, the log-slope d ln P / d ln delta over
5 t to 10 t on the last branch, the energy balance and the totals.
Run: python benchmarks/snap.py [--t 0.02] [--mesh coarse] [--delta-max 10] [--every 20]
[--stiffness 1e4] [--onset 1e-4] [--tol 1e-9] [--jump-push 0.01] [--ds-max 0.01]
[--figure docs/figures/thin_shell_snap.png [--sharp 3e-6]]
(--delta-max in thicknesses t; the contact penalty's stiffness in C10 / R and onset in R,
solver.snap.SnapSettings; --jump-push in t: where the continuation stalls, the jump by
descent, 0 to end the path there instead; --ds-max the largest arc step / R; --sharp: the
loading with that onset / R drawn too, with its jump)
"""
import argparse
import dataclasses
import time

import numpy as np

from shell_adhesion.solver.snap import PenaltyContact, SnapSettings, log_slope, trace_shell


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t", type=float, default=0.02, help="t/R")
    ap.add_argument("--mesh", default="coarse")
    ap.add_argument("--delta-max", type=float, default=10.0, help="in thicknesses t")
    ap.add_argument("--every", type=int, default=20)
    ap.add_argument("--stiffness", type=float, default=SnapSettings.stiffness, help="C10/R")
    ap.add_argument("--onset", type=float, default=SnapSettings.onset, help="in R")
    ap.add_argument("--figure", default=None,
                    help="draw the loading curve and the profiles at the jump to this PNG")
    ap.add_argument("--sharp", type=float, default=None,
                    help="with --figure: also draw the loading with this onset / R")
    ap.add_argument("--tol", type=float, default=SnapSettings.tol,
                    help="force residual relative to the largest reaction")
    ap.add_argument("--jump-push", type=float, default=SnapSettings.jump_push,
                    help="where the continuation stalls: push on by this many t and settle "
                         "(0: the path ends there)")
    ap.add_argument("--ds-max", type=float, default=SnapSettings.ds_max,
                    help="largest arc step / R")
    a = ap.parse_args(argv)
    T = a.t
    t0 = time.perf_counter()
    settings = dataclasses.replace(SnapSettings(), stiffness=a.stiffness, onset=a.onset,
                                   tol=a.tol, jump_push=a.jump_push, ds_max=a.ds_max)
    d, path = trace_shell(T, 1.0, a.mesh, a.delta_max * T, settings=settings)
    wall = time.perf_counter() - t0
    print(f"t/R = {T:g}, h/R = 1, {a.mesh} mesh, {d.ndof} dofs, penalty {a.stiffness:g} "
          f"C10/R from {a.onset:g} R; ended: "
          f"{path.ended_by or 'delta_max reached'}")
    print(f"{'state':>5} {'delta/t':>8} {'P/(C10R^2)':>11} {'P/Reissner':>10} "
          f"{'apex/t':>8} {'newton':>6} {'step s':>7}  contact (radii / R)")
    shape = None
    for i, s in enumerate(path.states):
        kind = tuple("disc" if r0 == 0 else "ring" for r0, _ in s.radii)
        if i % a.every == 0 or kind != shape or i == len(path.states) - 1:
            ratio = s.P / (16 * T * T * s.delta) if s.delta > 0 else float("nan")
            print(f"{i:5d} {s.delta / T:8.4f} {s.P:11.4e} {ratio:10.4f} "
                  f"{s.apex_gap / T:8.4f} {s.iterations:6d} {s.seconds:7.3f}  {s.contact}")
        shape = kind
    for j in path.jumps():
        print(f"jump under displacement control at delta = {j.delta / T:.4f} t: P "
              f"{j.P_from:.4e} -> {j.P_to:.4e} (states {j.i_from} -> {j.i_to}); contact "
              f"{j.contact_from} -> {j.contact_to}")
        s = path.states[j.i_from]
        law = PenaltyContact(a.stiffness, a.onset)
        print(f"  at the fold: apex at {s.apex_gap / T:+.3e} t, apex pressure "
              f"{-float(law(s.apex_gap)[1]):.3e} C10 (onset {a.onset / T:.1e} t)")
    for lift in (0.0, 0.1 * T):
        i = path.first_ring(lift)
        if i is not None:
            s = path.states[i]
            print(f"first ring with the apex above {lift / T:g} t: state {i}, delta = "
                  f"{s.delta / T:.4f} t, {s.contact}")
    try:
        slope, drift = log_slope(path, 5 * T, min(10 * T, path.states[-1].delta))
        print(f"d ln P / d ln delta over 5 t to {min(10.0, path.states[-1].delta / T):.3g} t "
              f"(last branch): {slope:.4f}, drift (upper half - lower half) {drift:+.4f}")
    except ValueError as err:
        print(err)
    W, U, Pi = path.work(), path.array("U"), path.array("Pi")
    print(f"energy: max |W - U - Pi| / max U = {np.abs(W - U - Pi).max() / U.max():.2e}; "
          f"max |W - U| / max U = {np.abs(W - U).max() / U.max():.2e}")
    if a.figure:
        sharp = None
        if a.sharp:
            _, sharp = trace_shell(T, 1.0, a.mesh, a.delta_max * T, settings=dataclasses.replace(
                settings, onset=a.sharp))
            print(f"onset {a.sharp:g} R: {len(sharp.states)} states, last at delta = "
                  f"{sharp.states[-1].delta / T:.4f} t, P = {sharp.states[-1].P:.4e}; ended: "
                  f"{sharp.ended_by or 'delta_max reached'}")
        figure(d, path, T, a.figure, a.onset, sharp, a.sharp)
    tm = path.timer
    print(f"states {len(path.states)}, newton iterations {tm.newton_iterations}, "
          f"assembly {tm.assembly:.2f} s, factor {tm.factor:.2f} s, solve {tm.solve:.2f} s, "
          f"wall {wall:.2f} s")


def figure(d, path, T, out, onset, sharp=None, sharp_onset=None):
    """Left: P against delta through the snap (the unstable branch dashed), Reissner's
    line, the jump.  Right: the outer surface's height / t against r / R at the fold and
    just after the jump."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    D, P = path.array("delta") / T, path.array("P")
    jumps = path.jumps()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.2))
    if jumps:
        j = jumps[0]
        ax.plot(D[:j.i_from + 1], P[:j.i_from + 1], "C0-",
                label=f"stable loading (contact onset {onset:g} R)")
        ax.plot(D[j.i_from:j.i_to], P[j.i_from:j.i_to], "C0--", lw=1,
                label="unstable branch (arc length)")
        ax.plot(D[j.i_to - 1:], P[j.i_to - 1:], "C0-")
        ax.annotate("", (j.delta / T, j.P_to), (j.delta / T, j.P_from),
                    arrowprops=dict(arrowstyle="->", color="C3"))
        ax.plot([], [], "C3-", label="jump at fixed delta")
    else:
        ax.plot(D, P, "C0-", label="loading")
    if sharp is not None:
        Ds, Ps = sharp.array("delta") / T, sharp.array("P")
        landed = [j for j in sharp.jumps() if sharp.states[j.i_to].landed]
        cut = landed[0].i_to if landed else len(Ds)
        ax.plot(Ds[:cut], Ps[:cut], color="0.5", lw=1,
                label=f"contact onset {sharp_onset:g} R" + (
                    ": jumps where it loses stability" if landed else ""))
        if landed:
            j = landed[0]
            ax.plot(Ds[cut:], Ps[cut:], color="0.5", lw=1)
            ax.annotate("", (j.delta / T, j.P_to), (j.delta / T, j.P_from),
                        arrowprops=dict(arrowstyle="->", color="0.5"))
    dd = np.linspace(0, 1.2 * T, 20)
    ax.plot(dd / T, 16 * T * T * dd, "k:", label="Reissner 16 C10 t² δ / R")
    ax.set_xlabel("δ / t")
    ax.set_ylabel("P / (C10 R²)")
    ax.set_title(f"t/R = {T:g}, h/R = 1, frictionless, no adhesion")
    ax.legend(fontsize=8, loc="lower right")
    cm = d.capmesh
    order = np.argsort(cm.nodes[0][cm.outer])
    nodes = cm.outer[order]
    r0 = cm.nodes[0][nodes]
    states = ([(path.states[jumps[0].i_from], "at the fold"),
               (path.states[jumps[0].i_to], "after the jump")] if jumps else
              [(path.states[-1], "last state")])
    for k, (s, label) in enumerate(states):
        r = r0 + s.x[d.ur(nodes)]
        z = cm.nodes[1][nodes] + s.x[d.uz(nodes)]
        m = r <= 0.6
        bx.plot(r[m], z[m] / T, f"C{k}-", label=f"{label}, δ = {s.delta / T:.2f} t: {s.contact}")
    bx.axhline(0, color="k", lw=0.8)
    bx.set_xlabel("r / R")
    bx.set_ylabel("height above the plane / t")
    bx.set_ylim(-0.5, 6)
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=100)


if __name__ == "__main__":
    main()
