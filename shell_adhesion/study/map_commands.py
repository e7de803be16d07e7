"""The `map` and `design` commands (their parsers and what they run).

    shell-adhesion map query --R 20 --t 3 --h 15 --C10 0.3 --gamma 30 [--map default|coarse|FILE]
    shell-adhesion map build STUDY.yaml --out MAP.nc [--catalogue DIR] [--workers N]
    shell-adhesion map plot --out FIGURE.png [--map ...] [--gamma-hat 0.005]
    shell-adhesion design --C10 0.3 --gamma 30 (--R 20 | --b 15) [--objective pull_off]
        [--t MIN MAX] [--h MIN MAX] [--no-confirm] [--json]

Bad input: one line naming the flag, the value and the rule, exit 2, before any work.
`map build` runs a study and follows `run`'s rules (cli: Ctrl-C exits 130 in one line).
"""
import argparse
import json
import math

from shell_adhesion.analysis.design_box import OffMap
from shell_adhesion.analysis.design_search import OBJECTIVES
from shell_adhesion.analysis.pull_off_map import MapError
from shell_adhesion.errors import InputError
from shell_adhesion.study.pull_off_map import DEFAULT_MAP, SHIPPED, pull_off_map

NAMES = (("P_star_N", "P*"), ("delta_star_mm", "delta*"), ("a_star_mm", "a*"),
         ("P_dagger_N", "P_dagger"), ("delta_dagger_mm", "delta_dagger"),
         ("a_dagger_mm", "a_dagger"), ("preload_N", "preload at a*"))

FLAGS = {"t_mm": "--t", "h_mm": "--h", "gamma_J_m2": "--gamma"}     # design's arguments


def add_parsers(sub, one_dash):
    """The `map` and `design` subcommands on the subparsers `sub` (`one_dash`: the action
    that refuses -R, -t, -h with a hint, as for `case`)."""
    m = sub.add_parser("map", help="the pull-off map: answer any shell inside it in "
                                   "milliseconds (query), build one (build), draw it (plot)")
    msub = m.add_subparsers(dest="map_action", required=True, parser_class=type(m))
    q = msub.add_parser("query", help="P*, delta*, a*, P_dagger, delta_dagger, a_dagger of "
                                      "one shell from the map, with error bars", add_help=False)
    q.add_argument("--help", action="help", help="show this help message and exit")
    for flag in ("-R", "-t", "-h", "-C10"):
        q.add_argument(flag, action=one_dash, nargs="?", help=argparse.SUPPRESS)
    q.add_argument("--R", required=True, help="outer radius of curvature R [mm]")
    q.add_argument("--t", required=True, help="shell thickness t [mm]")
    q.add_argument("--h", required=True, help="depth h from apex to base plane [mm]")
    q.add_argument("--C10", required=True, help="neo-Hookean C10 [MPa]")
    q.add_argument("--gamma", required=True, action="append",
                   help="work of adhesion gamma [J/m^2]; repeat for several")
    _map_flag(q)
    q.add_argument("--json", action="store_true", help="print JSON instead of a table")
    b = msub.add_parser("build", help="run a map study (one C10, a grid over t_over_R, "
                                      "h_over_R, gamma_J_m2) and write its map")
    b.add_argument("study", help="study file (YAML), e.g. `shell-adhesion example map`")
    b.add_argument("--out", required=True, help="map file to write (netCDF, .nc)")
    b.add_argument("--catalogue", default=None, help="catalogue folder")
    b.add_argument("--workers", default=None, type=int, help="local cluster size")
    b.add_argument("--scheduler", default=None, help="address of a running dask scheduler")
    p = msub.add_parser("plot", help="P*/(C10 R^2) over t/R and h/R at one gamma/(C10 R)")
    p.add_argument("--out", required=True, help="figure file (png, pdf or svg)")
    p.add_argument("--gamma-hat", dest="gamma_hat", default="0.005",
                   help="gamma / (C10 R) of the figure (default 0.005)")
    _map_flag(p)

    d = sub.add_parser("design", help="the shell (t, h) that sticks best for a material "
                                      "and a size, from the map, confirmed by one FE case",
                       add_help=False)
    d.add_argument("--help", action="help", help="show this help message and exit")
    for flag in ("-R", "-t", "-h", "-C10", "-b"):
        d.add_argument(flag, action=one_dash, nargs="?", help=argparse.SUPPRESS)
    d.add_argument("--C10", required=True, help="neo-Hookean C10 [MPa]")
    d.add_argument("--gamma", required=True, help="work of adhesion gamma [J/m^2]")
    size = d.add_mutually_exclusive_group(required=True)
    size.add_argument("--R", default=None, help="outer radius of curvature R [mm]")
    size.add_argument("--b", default=None, help="rim radius b of the cap's base [mm] "
                                                "(R then follows from h)")
    d.add_argument("--objective", choices=tuple(OBJECTIVES), default="pull_off",
                   help="maximise |P*| (pull_off, default), |P*| / preload (per_preload) "
                        "or |P*| per material volume (per_volume)")
    d.add_argument("--t", nargs=2, default=None, metavar=("MIN", "MAX"),
                   help="bounds of the thickness t [mm] (default: the map's)")
    d.add_argument("--h", nargs=2, default=None, metavar=("MIN", "MAX"),
                   help="bounds of the depth h [mm] (default: the map's)")
    _map_flag(d)
    d.add_argument("--no-confirm", dest="no_confirm", action="store_true",
                   help="skip the FE case that confirms the map's optimum")
    d.add_argument("--json", action="store_true", help="print JSON instead of text")


def _map_flag(parser):
    parser.add_argument("--map", default=DEFAULT_MAP,
                        help=f"the shipped map ({', '.join(SHIPPED)}; default {DEFAULT_MAP}) "
                             "or a map file (.nc) built by `map build`")


def _positive(flag, text):
    try:
        value = float(text)
    except (TypeError, ValueError):
        raise InputError(f"{flag}: {text!r} is not a number") from None
    if not (math.isfinite(value) and value > 0):
        raise InputError(f"{flag}: {text} must be a finite number > 0")
    return value


def _bounds(flag, pair):
    if pair is None:
        return (0.0, math.inf)
    lo, hi = (_positive(flag, v) for v in pair)
    if lo > hi:
        raise InputError(f"{flag}: {pair[0]} {pair[1]}: MIN must be <= MAX")
    return (lo, hi)


def _open(map_name):
    try:
        return pull_off_map(map_name)
    except ValueError as e:
        raise InputError(str(e)) from None


def run(ns) -> int:
    """Run `map query|plot` or `design` (`map build` runs a study: cli); the exit code."""
    if ns.command == "design":
        return _design(ns)
    if ns.map_action == "query":
        return _query(ns)
    return _plot(ns)


def _query(ns):
    R, t, h, C10 = (_positive(f, v) for f, v in (("--R", ns.R), ("--t", ns.t), ("--h", ns.h),
                                                  ("--C10", ns.C10)))
    gammas = [_positive("--gamma", g) for g in ns.gamma]
    pm = _open(ns.map)
    for g in gammas:
        check_on_map(pm, R, t, h, C10, g)
    answers = []
    for g in gammas:
        try:
            answers.append(dict(gamma_J_m2=g, status="ok", **{
                k: {"value": v, "error": e} for k, (v, e) in pm.shell(R, t, h, C10, g).items()}))
        except MapError as e:
            answers.append(dict(gamma_J_m2=g, status="not on the map", reason=str(e)))
    if ns.json:
        print(json.dumps(dict(R_mm=R, t_mm=t, h_mm=h, C10_MPa=C10, map=str(ns.map),
                              pull_off=answers), indent=1))
    else:
        print(f"shell R {R:g} mm, t {t:g} mm, h {h:g} mm, C10 {C10:g} MPa; map {ns.map} "
              f"(mesh {pm.ds.attrs.get('mesh', '?')}, {pm.ds.attrs.get('interface', '?')}); "
              "error: interpolation and FE in quadrature")
        for a in answers:
            print(f"gamma {a['gamma_J_m2']:g} J/m^2:" + ("" if a["status"] == "ok"
                                                        else f" {a['reason']}"))
            for key, label in NAMES:
                if a["status"] == "ok" and key in a:
                    unit = key.rsplit("_", 1)[1]
                    print(f"  {label:<14} {a[key]['value']:>10.4g} +- {a[key]['error']:.2g} {unit}")
    return 0 if all(a["status"] == "ok" for a in answers) else 1


def check_on_map(pm, R, t, h, C10, gamma):
    """InputError naming the flag whose value puts the shell outside the map's box."""
    ratios = (("--t", t, "mm", "t/R", t / R, "t_over_R", R),
              ("--h", h, "mm", "h/R", h / R, "h_over_R", R),
              ("--gamma", gamma, "J/m^2", "gamma/(C10 R)", gamma * 1e-3 / (C10 * R), "gamma_hat",
               C10 * R * 1e3))
    for flag, value, unit, name, ratio, axis, scale in ratios:
        lo, hi = pm.bounds[axis]
        if not (lo * (1 - 1e-12) <= ratio <= hi * (1 + 1e-12)):
            raise InputError(f"{flag}: {value:g} {unit} is {name} = {ratio:.4g}, outside the "
                             f"map's [{lo:.4g}, {hi:.4g}] ({flag} from {lo * scale:.4g} to "
                             f"{hi * scale:.4g} {unit} for this shell)")


def map_file(text):
    """The `--out` of `map build` as a Path: a netCDF file (.nc)."""
    from pathlib import Path
    out = Path(text)
    if out.suffix != ".nc":
        raise InputError(f"--out: {text}: the map file must end in .nc (netCDF)")
    return out


def _plot(ns):
    from pathlib import Path
    from shell_adhesion.analysis.map_figure import draw_map
    g = _positive("--gamma-hat", ns.gamma_hat)
    out = Path(ns.out)
    if out.suffix.lstrip(".") not in ("png", "pdf", "svg"):
        raise InputError(f"--out: {ns.out}: the figure must end in .png, .pdf or .svg")
    pm = _open(ns.map)
    try:
        pm.check_inside(pm.bounds["t_over_R"][0], pm.bounds["h_over_R"][0], g)
    except MapError as e:
        raise InputError(f"--gamma-hat: {e}") from None
    draw_map(pm, g, out)
    print(f"figure written to {out}")
    return 0


def _design(ns):
    from shell_adhesion.study.design import design
    C10, gamma = _positive("--C10", ns.C10), _positive("--gamma", ns.gamma)
    R = _positive("--R", ns.R) if ns.R is not None else None
    b = _positive("--b", ns.b) if ns.b is not None else None
    t_mm, h_mm = _bounds("--t", ns.t), _bounds("--h", ns.h)
    _open(ns.map)
    try:
        result = design(C10, gamma, ns.objective, R_mm=R, b_mm=b, t_mm=t_mm, h_mm=h_mm,
                        map=ns.map, confirm=not ns.no_confirm, progress=not ns.json)
    except OffMap as e:
        raise InputError(f"{FLAGS[e.argument]}: {e.detail}") from None
    except MapError as e:
        raise InputError(str(e)) from None
    print(json.dumps(result.to_dict(), indent=1) if ns.json else result.to_text())
    return 0 if result.agrees is not False else 1
