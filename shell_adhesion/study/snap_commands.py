"""The `snap` subcommand: a thin shell pressed through its snap-through by arc length,
optionally pulled back with the pocket under its dimple vented or sealed
(study.thin_shell).

    shell-adhesion snap --R 20 --t 0.4 --h 20 --C10 0.3 [--delta-max 4] [--unload-to -0.4]
        [--pocket vented|sealed] [--seal turn|ring] [--gas-exponent 1] [--p-atm-kPa 101.325]
        [--interface frictionless|no_slip] [--stick turn|touch] [--mesh coarse]
        [--ring-adhesion LAMBDA|zero] [--cavity-kPa P] [--json] [--csv FILE] [--plot FILE]

Prints the jumps under displacement control (from which state to which), the first ring,
the states (every state whose contact set changes shape and about 30 more), the pocket's
story and the energy balance, and with --ring-adhesion the adhesion the ring at delta-max
survives.  A path that stops short prints what it reached and exits 1.
"""
import argparse
import math
import sys

from shell_adhesion.atomic import write_text_atomic
from shell_adhesion.errors import InputError
from shell_adhesion.solver.contact import INTERFACES
from shell_adhesion.solver.pocket import MODES as POCKETS
from shell_adhesion.solver.snap import SnapSettings

from . import thin_shell
from .flags import FIGURE_FORMATS, check_output, number
from .progress import bar

FLAGS = dict(R_mm="--R", t_mm="--t", h_mm="--h", C10_MPa="--C10", delta_max_mm="--delta-max",
             unload_to_mm="--unload-to", pocket="--pocket", gas_exponent="--gas-exponent",
             p_atm_kPa="--p-atm-kPa", seal="--seal", interface="--interface", stick="--stick",
             mesh="--mesh", contact="--contact", ring_adhesion="--ring-adhesion",
             cavity_kPa="--cavity-kPa")
ROWS = 30              # about this many states in the printed table


def add_parser(sub, one_dash):
    """The `snap` subcommand on the subparsers `sub` (`one_dash`: the action that refuses
    -R, -t, -h with a hint, as for `case`)."""
    s = sub.add_parser("snap", add_help=False,
                       help="a thin shell pressed through its snap-through (arc length), "
                            "optionally pulled back with the pocket vented or sealed; "
                            "no adhesion")
    s.add_argument("--help", action="help", help="show this help message and exit")
    for flag in ("-R", "-t", "-h", "-C10"):
        s.add_argument(flag, action=one_dash, nargs="?", help=argparse.SUPPRESS)
    s.add_argument("--R", required=True, help="outer radius of curvature R [mm]")
    s.add_argument("--t", required=True, help="shell thickness t [mm], t/R >= 0.005")
    s.add_argument("--h", required=True, help="depth h from apex to base plane [mm]")
    s.add_argument("--C10", required=True, help="neo-Hookean C10 [MPa]")
    s.add_argument("--delta-max", dest="delta_max", default=None,
                   help="how far the rim is pressed [mm] (default 10 t, within the "
                        "domain's bound and 0.9 h)")
    s.add_argument("--unload-to", dest="unload_to", default=None,
                   help="then unload to this rim approach [mm] (< 0: a pull; default: no "
                        "unloading, or -t with --pocket sealed); the path ends where a "
                        "sealed pocket opens")
    s.add_argument("--pocket", choices=POCKETS, default="vented",
                   help="the pocket between a ring contact and the plane: vented (default, "
                        "ambient pressure) or sealed (trapped gas p V^n = const)")
    s.add_argument("--seal", choices=thin_shell.SEALS, default="turn",
                   help="with --pocket sealed: trap the gas at the turn to the unloading "
                        "(default) or at the first ring around an apex lifted by 0.1 t")
    s.add_argument("--gas-exponent", dest="gas_exponent", default="1",
                   help="the trapped gas's p V^n = const: n >= 1 (default 1 isothermal, 1.4 "
                        "adiabatic)")
    s.add_argument("--p-atm-kPa", dest="p_atm_kPa", default=None,
                   help="ambient pressure [kPa] (default 101.325)")
    s.add_argument("--interface", choices=INTERFACES, default="frictionless",
                   help="frictionless (default) or no_slip (the contact sticks, see --stick)")
    s.add_argument("--stick", choices=thin_shell.STICKS, default="turn",
                   help="with --interface no_slip: the contact sticks from the turn (default: "
                        "pressed frictionless through the snap, then gripped) or from the "
                        "first touch")
    s.add_argument("--mesh", choices=thin_shell.MESHES, default="coarse",
                   help="mesh density (default coarse)")
    s.add_argument("--contact", choices=tuple(thin_shell.CONTACTS), default="soft",
                   help="the contact penalty's onset: soft (default, 1e-4 R: the snap is "
                        "passed by folds and comes early) or sharp (3e-6 R: the shell jumps "
                        "where it loses stability; slower)")
    s.add_argument("--ring-adhesion", dest="ring_adhesion", default=None,
                   metavar="LAMBDA|zero",
                   help="after the loading (vented, frictionless), bracket the largest "
                        "adhesion gamma [J/m^2] the ring at delta-max survives (smoothed "
                        "Dugdale law of Tabor parameter LAMBDA, e.g. 0.3, a few minutes; "
                        "or zero: zero-range adhesion by the energy method at the ring's "
                        "two edges, faster); above it the dimple closes")
    s.add_argument("--cavity-kPa", dest="cavity_kPa", default=None, metavar="P",
                   help="with --pocket sealed: the gripper's order: pressed with the shell's "
                        "own cavity (closed by a rigid lid at the rim) at ambient pressure, "
                        "the pocket sealed at the turn, the cavity brought to the gauge "
                        "pressure P [kPa] (<= 0) at fixed delta, then pulled")
    s.add_argument("--gamma", default=None, help=argparse.SUPPRESS)
    s.add_argument("--json", action="store_true", help="print JSON (every state) instead of text")
    s.add_argument("--csv", default=None, metavar="FILE", help="write every state as CSV")
    s.add_argument("--plot", default=None, metavar="FILE",
                   help="write a figure of P against delta (and the pocket's pressure)")


def run(ns) -> int:
    """`snap`: check everything, trace, report; 0 done, 1 the path stopped short."""
    if ns.gamma is not None:
        raise InputError(f"--gamma: {ns.gamma} is not an input of snap: it presses without "
                         "adhesion (gamma = 0); `case --adhesion dugdale --interface "
                         "frictionless` follows an adhesive shell from its first touch")
    zero = ns.ring_adhesion is not None and ns.ring_adhesion.strip().lower() == "zero"
    if zero:
        ns.ring_adhesion = None
    elif ns.ring_adhesion is not None:
        try:
            float(ns.ring_adhesion)
        except ValueError:
            raise InputError(f"--ring-adhesion: {ns.ring_adhesion!r} must be a Tabor "
                             "parameter (a number > 0) or zero") from None
    numbers = {k: None if getattr(ns, a) is None else number(FLAGS[k], getattr(ns, a), u)
               for k, a, u in (
        ("R_mm", "R", "mm"), ("t_mm", "t", "mm"), ("h_mm", "h", "mm"),
        ("C10_MPa", "C10", "MPa"), ("delta_max_mm", "delta_max", "mm"),
        ("unload_to_mm", "unload_to", "mm"), ("gas_exponent", "gas_exponent", "1"),
        ("p_atm_kPa", "p_atm_kPa", "kPa"), ("ring_adhesion", "ring_adhesion", "1"),
        ("cavity_kPa", "cavity_kPa", "kPa"))}
    if numbers["p_atm_kPa"] is None:
        del numbers["p_atm_kPa"]
    if zero:
        numbers["ring_adhesion"] = thin_shell.ZERO_RANGE
    inp = thin_shell.snap_input(**numbers, pocket=ns.pocket, seal=ns.seal,
                                interface=ns.interface, stick=ns.stick, mesh=ns.mesh,
                                contact=ns.contact, names=FLAGS)
    if ns.csv is not None:
        check_output("--csv", ns.csv)
    if ns.plot is not None:
        check_output("--plot", ns.plot, FIGURE_FORMATS)
    result = _traced(inp)
    if ns.csv is not None:
        write_text_atomic(ns.csv, thin_shell.csv_text(result))
    if ns.plot is not None:
        thin_shell.plot_snap(result, ns.plot)
    if ns.json:
        print(result.to_json())
    else:
        print(report(result))
    if result.failed:
        print(f"shell-adhesion: failed: the path stopped short: {result.failed}",
              file=sys.stderr)
        return 1
    ring = result.ring_adhesion()
    if ring is not None and not ring["bracketed"]:
        print(f"shell-adhesion: failed: --ring-adhesion: {ring['why']}", file=sys.stderr)
        return 1
    if result.energy_miss > thin_shell.ENERGY_TOL:
        print(f"shell-adhesion: failed: the energy balance misses by {result.energy_miss:.2g} "
              f"of the largest strain energy (> {thin_shell.ENERGY_TOL:g})", file=sys.stderr)
        return 1
    return 0


def _traced(inp):
    """trace_snap with a bar of the travel so far (mm of press, then of pull), then one
    of the ring-adhesion bisection's switches (the last gamma and whether it held)."""
    unload = 0.0 if inp.unload_to_mm is None else inp.delta_max_mm - inp.unload_to_mm
    seen = dict(reach=0.0, low=inp.delta_max_mm, n=0.0, turned=False)
    with bar(round(inp.delta_max_mm + unload, 6), "snap", "mm") as b:
        def progress(state):
            delta_mm = state.delta * inp.R_mm
            seen["turned"] |= delta_mm >= inp.delta_max_mm
            seen["reach"] = max(seen["reach"], min(delta_mm, inp.delta_max_mm))
            if seen["turned"]:
                seen["low"] = min(seen["low"], delta_mm)
            n = seen["reach"] + (inp.delta_max_mm - seen["low"])
            if n > seen["n"]:
                b.update(n - seen["n"])
                seen["n"] = n
        switches = []

        def switched(gamma_J_m2, holds):
            if not switches:
                b.close()
                switches.append(bar(None, "ring adhesion", "switch"))
            switches[0].set_description(f"ring adhesion (last: gamma {gamma_J_m2:.4g} J/m^2, "
                                        + ("the ring held)" if holds else "it did not)"))
            switches[0].update(1)
        try:
            return thin_shell.trace_snap(inp, progress, switched=switched)
        finally:
            for s in switches:
                s.close()


def report(result) -> str:
    """The text `snap` prints: header, jumps, first ring, states, pocket, energy."""
    inp, out = result.input, result.to_dict()
    lines = [f"shell R {inp.R_mm:g} mm, t {inp.t_mm:g} mm, h {inp.h_mm:g} mm, C10 "
             f"{inp.C10_MPa:g} MPa; {inp.interface}"
             + (f" (sticking from the {inp.stick})" if inp.interface == "no_slip" else "")
             + f", no adhesion; pocket {inp.pocket}"
             + (f" (n {inp.gas_exponent:g}, p_a {inp.p_atm_kPa:g} kPa, sealed at the "
                f"{'turn' if inp.seal == 'turn' else 'first ring lifted by 0.1 t'})"
                if inp.pocket == "sealed" else "")
             + f"; {inp.mesh} mesh, {result.ndof} dofs, {inp.contact} contact"]
    for j in out["jumps"]:
        lines.append(f"jump at delta {j['delta_mm']:.4g} mm ({j['delta_mm'] / inp.t_mm:.3g} t): "
                     f"P {j['P_from_N']:.4g} N -> {j['P_to_N']:.4g} N; contact "
                     f"{j['contact_from']} -> {j['contact_to']} (radii in mm)")
    if out["jumps"] and inp.contact == "soft":
        lines.append("  the jump's delta depends on the contact's softness and the mesh, and "
                     "comes early: at t/R 0.02 it is traced at 4.4 to 4.9 t, while a sharp "
                     "contact loses stability at 6.33 t (--contact sharp; docs/thin-shells.md)")
    elif out["jumps"]:
        lines.append("  the sharp contact's jump: where the loading cannot go on (the "
                     f"centre lifts at fixed delta and P), the rim is pushed on by "
                     f"{SnapSettings.jump_push:g} t and "
                     "the shell settles by damped descent (docs/thin-shells.md)")
    ring = out["first_ring"]
    lines.append("first ring around a dimple (apex up by > 0.1 t): " + (f"state {ring['state']}, delta {ring['delta_mm']:.4g} mm, "
                                   f"{ring['contact']}" if ring else "none"))
    lines.append(f"{'state':>5} {'branch':>9} {'delta [mm]':>10} {'P [N]':>11} "
                 f"{'apex [mm]':>10} {'p [kPa]':>9}  contact [mm]")
    states = out["states"]
    every = max(1, math.ceil(len(states) / ROWS))
    shape = None
    for s in states:
        kind = tuple(w.split()[0] for w in s["contact"].split(" + "))
        if s["state"] % every == 0 or kind != shape or s["state"] == len(states) - 1:
            lines.append(f"{s['state']:5d} {s['branch']:>9} {s['delta_mm']:10.5g} "
                         f"{s['P_N']:11.4e} {s['apex_mm']:10.4g} {s['p_kPa']:9.3g}  "
                         f"{s['contact']}")
        shape = kind
    lines.append(f"ended: {out['ended_by']}")
    if out["turn_delta_mm"] is not None:
        lines.append(f"turned at delta {out['turn_delta_mm']:.4g} mm; least P unloading "
                     f"{out['least_P_unloading_N']:+.4g} N")
    pk, cav = out["pocket"], out["cavity"]
    if pk:
        lines.append(f"pocket sealed at delta {pk['sealed_at_mm']:.4g} mm: {pk['V0_mm3']:.4g} "
                     f"mm^3 inside a seal of radius {pk['seal_radius_mm']:.4g} mm")
        if cav and cav["ramp"]:
            b = cav["ramp"][-1]
            lines.append(f"cavity brought to {b['p_c_kPa']:+.4g} kPa"
                         + ("" if cav["reached"] else f" of the {cav['p_kPa']:+.4g} asked")
                         + f" at fixed delta in {len(cav['ramp'])} steps: P "
                         f"{cav['P_sealed_N']:+.4g} -> {b['P_N']:+.4g} N, pocket gauge 0 -> "
                         f"{b['p_kPa']:+.4g} kPa")
        lines.append(("opened" if pk["opened"] else "still sealed")
                     + f" at delta {pk['last_delta_mm']:.4g} mm: gauge {pk['last_p_kPa']:+.4g} "
                     f"kPa, P {pk['last_P_N']:+.4g} N; gauge pressure from "
                     f"{pk['p_min_kPa']:+.4g} to {pk['p_max_kPa']:+.4g} kPa")
        lines.append(f"pull-off while sealed {pk['pull_off_N']:.4g} N (least P "
                     f"{pk['least_P_N']:+.4g} N; ideal suction force p_a pi r_seal^2 "
                     f"{pk['ideal_suction_N']:.4g} N)")
    ring = out["ring_adhesion"]
    if ring and ring["bracketed"]:
        law = (f"smoothed Dugdale, Tabor {ring['tabor']:g}" if ring["tabor"] is not None
               else ring["law"])
        lines.append(f"adhesion the ring survives ({law}): "
                     f"gamma_c {ring['gamma_lo_J_m2']:.4g} to {ring['gamma_hi_J_m2']:.4g} J/m^2 "
                     f"(gamma/(C10 R) {ring['gamma_lo']:.4g} to {ring['gamma_hi']:.4g}) at "
                     f"delta {ring['delta_mm']:.4g} mm; below it the ring widens (to "
                     f"{ring['ring_at_lo']} mm at the lower end), above it {ring['above']}")
    elif ring:
        lines.append(f"adhesion the ring survives: not bracketed ({ring['why']})")
    ok = out["energy_balance"] <= thin_shell.ENERGY_TOL
    lines.append("energy balance: |work of P - strain - contact - gas energy"
                 + (" - the cavity's load" if cav else "") + "| <= "
                 f"{out['energy_balance']:.2g} of max strain energy"
                 + ("" if ok else f": ABOVE {thin_shell.ENERGY_TOL:g}, the path is not "
                    "to be trusted (steps too coarse through a fold)"))
    return "\n".join(lines)
