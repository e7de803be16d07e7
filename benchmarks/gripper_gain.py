"""Benchmark: the depressurised gripper's gain over the open shell, across thin shells,
with error bars (solver.grip with adhesion).

For each shell (t/R, h/R, pressed to delta_max in thicknesses t): the open shell (pocket
vented, no suction) and the sealed gripper with its cavity at -f p_cl (p_cl = 8 C10
(t/R)^2) for each fraction f, all with the same smoothed Dugdale law (Tabor --tabor)
switched on where the pull starts, its gamma the share --gamma-share of the adhesion the
shell's ring survives at delta_max, gamma_c / (C10 R) = LIMIT_SCALE (t/R) (delta_max/R)^2
(solver.ring_adhesion, measured), or --gamma-hat for every shell; each solved on --mesh and on
--coarser, P*'s error bar from the two (solver.error_bars.error_bar, order
solver.error_bars.assumed_order); the open shell too, or, where its pull on --coarser stops
short (at a fold near delta = 0 where the jump finds no state), on the default mesh with
its bar from --mesh; --open-mesh: the open shell on that mesh, its bar from --mesh.  The
gain is P* over the open shell's; its bar adds the two relative bars (|gain| (b/|P*| +
b_open/|P*_open|)).  A pull that stops at a fold it
cannot jump from gives a bound (marked "<="), no bar.

Prints one table (P* in C10 R^2 and N for --R-mm, --C10-kPa; gain; seconds) and, with
--figure, draws the gain against the suction for each shell with its bars.
Run: python benchmarks/gripper_gain.py [--shells 0.02:1:5,0.02:0.5:5,0.05:1:8]
[--fractions 0,0.5,1] [--gamma-share 0.25 | --gamma-hat G] [--tabor 0.3] [--mesh coarse]
[--coarser coarser] [--open-mesh default] [--figure PNG]   (each shell t/R:h/R:delta_max/t).
Bad input: one line, exit 2.
"""
import argparse
import sys
import time

from shell_adhesion.errors import InputError
from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.solver import pocket as pk
from shell_adhesion.solver.cohesive import CohesiveLaw
from shell_adhesion.solver.error_bars import assumed_order, error_bar
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.grip import grip, press
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.ring_adhesion import LIMIT_SCALE
from shell_adhesion.solver.snap import loading_cap, ring_arc
from shell_adhesion.study.cohesive_case import K_OVER_C10


def parse_shells(text):
    """[(t/R, h/R, delta_max / t), ...] from "t:h:d,..."; InputError if malformed."""
    shells = []
    for item in text.split(","):
        try:
            t, h, dm = (float(v) for v in item.split(":"))
        except ValueError:
            raise InputError(f"--shells: {item!r} must be t/R:h/R:delta_max/t") from None
        if not dm > 0:
            raise InputError(f"--shells: {item!r}: delta_max/t must be > 0")
        loading_cap(t, h)           # the domain's check (InputError)
        shells.append((t, h, dm))
    return shells


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shells", default="0.02:1:5,0.02:0.5:5,0.05:1:8")
    ap.add_argument("--fractions", default="0,0.5,1")
    ap.add_argument("--gamma-share", type=float, default=0.25,
                    help="gamma over the ring's limit gamma_c at delta_max")
    ap.add_argument("--gamma-hat", type=float, default=None,
                    help="gamma / (C10 R) for every shell (in place of --gamma-share)")
    ap.add_argument("--tabor", type=float, default=0.3)
    ap.add_argument("--mesh", default="coarse")
    ap.add_argument("--coarser", default="coarser")
    ap.add_argument("--open-mesh", default=None,
                    help="the open shell's mesh, its bar from --mesh (default: --mesh, or "
                         "default where the open shell's pull on --coarser stops short)")
    ap.add_argument("--p-atm-kPa", type=float, default=101.325)
    ap.add_argument("--C10-kPa", type=float, default=300.0)
    ap.add_argument("--R-mm", type=float, default=20.0)
    ap.add_argument("--figure", default=None)
    a = ap.parse_args(argv)
    try:
        shells = parse_shells(a.shells)
        try:
            fractions = [float(f) for f in a.fractions.split(",")]
        except ValueError:
            raise InputError(f"--fractions: {a.fractions!r} must be numbers >= 0") from None
        if not all(f >= 0 for f in fractions):
            raise InputError(f"--fractions: {a.fractions!r} must be numbers >= 0")
        for name, v in (("--gamma-hat", a.gamma_hat), ("--gamma-share", a.gamma_share)):
            if v is not None and not v > 0:
                raise InputError(f"{name}: {v!r} must be > 0 (the gain is over an adhesive "
                                 "open shell)")
        if a.open_mesh == a.mesh:
            raise InputError(f"--open-mesh: {a.open_mesh!r} must differ from --mesh (the "
                             "open shell's bar comes from --mesh)")
        p_atm = pk.p_atm_over_C10(a.p_atm_kPa, a.C10_kPa)
        md.sigma0_of(a.tabor, 1e-5, 1.0, K_OVER_C10)     # the Tabor parameter's check
    except ValueError as err:       # InputError is one
        print(err, file=sys.stderr)
        return 2
    force_N = a.C10_kPa * 1e-3 * a.R_mm ** 2
    how = (f"gamma/(C10 R) {a.gamma_hat:g}" if a.gamma_hat else
           f"gamma {a.gamma_share:g} of the ring's limit {LIMIT_SCALE:g} (t/R) (delta_max/R)^2")
    print(f"{how}, Tabor {a.tabor:g}, smoothed Dugdale; {a.mesh} mesh, "
          f"bars from {a.coarser}; p_a/C10 {p_atm:.4g}, n 1; forces in N for R = {a.R_mm:g} "
          f"mm, C10 = {a.C10_kPa:g} kPa")
    print("| t/R | h/R | pressed to | gamma / (C10 R) | suction / p_cl | P* [C10 R^2] | bar | "
          "P* [N] | gain over the open shell | ends | s |")
    print("| --- " * 11 + "|")
    rows = []
    for T, H, dm in shells:
        cap = loading_cap(T, H)
        gamma = a.gamma_hat or a.gamma_share * LIMIT_SCALE * T * (dm * T) ** 2
        law = CohesiveLaw(md.sigma0_of(a.tabor, gamma, 1.0, K_OVER_C10), gamma)

        pressed = {}        # mesh: its press, which serves every grip of this shell

        def solved(mesh, f, pocket="sealed"):
            if mesh not in pressed:
                d = discretise(cap_mesh(cap, mesh_spec(mesh, ring_arc(dm * T))))
                pressed[mesh] = press(d, dm * T, p_atm)
            return grip(pressed[mesh].shell, dm * T, -f * 8 * T * T, p_atm, 1.0, pocket=pocket,
                        adhesion=law, pressed=pressed[mesh])

        def answer(f, pocket, mesh, coarser):
            t0 = time.perf_counter()
            g, gc = solved(mesh, f, pocket), solved(coarser, f, pocket)
            wall = time.perf_counter() - t0
            if g.pull is None or (g.ended_by and not g.bound):
                return None, None, g.ended_by[:80], wall
            P = g.pull_off()[0]
            exact = not g.bound and gc.pull is not None and not gc.ended_by
            bar = (float(error_bar(P, gc.pull_off()[0], order=assumed_order(T, mesh)))
                   if exact else None)
            ends = ("bound: " if g.bound else "") + (g.pull.ended_by.split(":")[0]
                                                     or "detached")
            if bar is None and not g.bound:
                ends += f"; no bar: on {coarser} {gc.ended_by[:60] or 'no pull'}"
            return P, bar, ends, wall

        if a.open_mesh:
            P0, b0, ends0, wall0 = answer(0.0, "vented", a.open_mesh, a.mesh)
            ends0 += f" ({a.open_mesh} mesh, bar from {a.mesh})"
        else:
            P0, b0, ends0, wall0 = answer(0.0, "vented", a.mesh, a.coarser)
        if not a.open_mesh and P0 is not None and b0 is None:   # its coarser pull stopped
            P0, b0, ends0, more = answer(0.0, "vented", "default", a.mesh)
            ends0 += f" (default mesh, bar from {a.mesh})"
            wall0 += more
        shown = _value(P0, b0, ends0.startswith("bound"))
        print(f"| {T:g} | {H:g} | {dm:g} t | {gamma:.3g} | open | {shown} | {_bar(b0)} | "
              f"{_N(P0, force_N)} | 1 | {ends0} | {wall0:.0f} |")
        for f in fractions:
            P, b, ends, wall = answer(f, "sealed", a.mesh, a.coarser)
            gain = gain_bar = None
            if P is not None and P0:
                gain = P / P0
                if b is not None and b0 is not None:
                    gain_bar = abs(gain) * (b / abs(P) + b0 / abs(P0))
            rows.append((T, H, dm, f, gain, gain_bar, ends.startswith("bound"), gamma))
            shown = (f"{gain:.3g}" + (f" +- {gain_bar:.2g}" if gain_bar is not None else "")
                     if gain is not None else "-")
            value = _value(P, b, ends.startswith("bound"))
            print(f"| {T:g} | {H:g} | {dm:g} t | {gamma:.3g} | {f:g} | {value} | {_bar(b)} | "
                  f"{_N(P, force_N)} | {shown} | {ends} | {wall:.0f} |", flush=True)
    if a.figure:
        _figure(rows, how, a.figure)
    return 0


def _value(P, bar, bound):
    if P is None:
        return "not answered"
    return ("<= " if bound else "") + f"{P:+.4e}"


def _bar(bar):
    return f"{bar:.2e}" if bar is not None else "-"


def _N(P, force_N):
    return f"{P * force_N:+.4g}" if P is not None else "-"


def _figure(rows, how, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 4))
    shells = sorted({r[:3] for r in rows}, key=lambda s: (s[0], -s[1]))
    for k, shell in enumerate(shells):
        pts = [r for r in rows if r[:3] == shell and r[4] is not None]
        F = [r[3] for r in pts]
        G = [r[4] for r in pts]
        E = [r[5] if r[5] is not None else 0.0 for r in pts]
        gamma = pts[0][7] if pts else float("nan")
        ax.errorbar(F, G, yerr=E, marker="o", capsize=3, color=f"C{k}",
                    label=f"t/R {shell[0]:g}, h/R {shell[1]:g}, pressed {shell[2]:g} t, "
                          f"gamma/(C10 R) {gamma:.3g}")
        for r in pts:
            if r[6]:        # a bound: the gain is at least this
                ax.annotate("", (r[3], r[4] * 1.15), (r[3], r[4]),
                            arrowprops=dict(arrowstyle="->", color=f"C{k}"))
    ax.set_yscale("log")
    ax.set_xlabel("cavity suction / p_cl (p_cl = 8 C10 (t/R)^2)")
    ax.set_ylabel("pull-off / the open shell's")
    ax.set_title("sealed gripper with adhesion:\n" + how, fontsize=8)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=120)


if __name__ == "__main__":
    sys.exit(main())
