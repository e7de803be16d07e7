"""The `shell-adhesion` command line.

    shell-adhesion case --R 20 --t 3 --h 20 --C10 0.3 [--gamma 30 ...] [--json [--curves]]
    shell-adhesion case --R 20 --t 3 --h 20 --C10 0.3 --gamma 30 --adhesion dugdale --tabor 1
        [--material neo-hookean|mooney-rivlin|yeoh|gent] [--C01 C] [--C20 C] [--C30 C]
        [--Jm J] [--D1 D]
    shell-adhesion fit --R 20 --t 3 --h 20 --curve test.csv [--pull-off-N P] [--json]
        [--plot fit.png]
    shell-adhesion run workflow.yaml --out results/ [--scheduler ADDRESS] [--catalogue DIR]
    shell-adhesion catalogue list|rebuild [--catalogue DIR]
    shell-adhesion tables results/paper.nc [--format md|csv|tex] [--table cases|paper|all] [--out FILE]
    shell-adhesion plot results/paper.nc [--out DIR] [--format png,pdf] [--dpi 150]
    shell-adhesion analyse results/paper.nc
    shell-adhesion map query|build|plot ...      (the pull-off map; see study.map_commands)
    shell-adhesion design --C10 0.3 --gamma 30 --R 20 [--objective pull_off] [--t MIN MAX]
    shell-adhesion snap --R 20 --t 0.4 --h 20 --C10 0.3 [--pocket sealed] ...  (study.snap_commands)
    shell-adhesion example paper|mooney-rivlin|map|map-coarse > workflow.yaml
    shell-adhesion --version

`tables`, `plot` and `analyse` read a results cube and never run the solver.

Bad input prints one line naming the flag, the value and the rule, and exits with 2,
before any computation and without creating anything.  The rules are the solver's
(`study.case_input.case_input` for `case`, `study.config` for study files).  `case` has no
`-h`: the depth is `--h`, help is `--help`.  A mistyped flag gets the nearest one
("did you mean --gamma?").
"""
import argparse
import difflib
import os
from pathlib import Path
import re
import sys
import time

from shell_adhesion import __version__, examples
from shell_adhesion.errors import ConvergenceError, InputError, MaterialLimitError
from shell_adhesion.solver import INTERFACES
from shell_adhesion.study import case as case_api
from shell_adhesion.study import map_commands, snap_commands
from shell_adhesion.study.flags import FIGURE_FORMATS, check_output, number as _number
from shell_adhesion.study.case_input import MESHES, case_input
from shell_adhesion.study.cohesive_case import ADHESIONS

HARD_EXIT_S = 45.0      # a run still ending this long after Ctrl-C is ended at once
# the flag of each input of `case` (study.case_input.case_input names the fields this way)
CASE_FLAGS = dict(R_mm="--R", t_mm="--t", h_mm="--h", C10_MPa="--C10",
                  gamma_J_m2="--gamma", delta_max_mm="--delta-max", interface="--interface",
                  mesh="--mesh", material="--material", C01_MPa="--C01", C20_MPa="--C20",
                  C30_MPa="--C30", Jm="--Jm", D1_per_MPa="--D1", cavity="--cavity",
                  p_kPa="--p-kPa", p0_kPa="--p0-kPa", p_atm_kPa="--p-atm-kPa",
                  gas_exponent="--gas-exponent")
COHESIVE_FLAGS = dict(CASE_FLAGS, sigma0_MPa="--sigma0", tabor="--tabor", adhesion="--adhesion",
                      zone_elements="--zone-elements", beta="--beta", history="--history")
CAVITY_FLAGS = (("p_kPa", "kPa"), ("p0_kPa", "kPa"), ("p_atm_kPa", "kPa"), ("gas_exponent", "1"))
MATERIAL_FLAGS = (("C01", "C01_MPa", "MPa"), ("C20", "C20_MPa", "MPa"), ("C30", "C30_MPa", "MPa"),
                  ("Jm", "Jm", "1"), ("D1", "D1_per_MPa", "1/MPa"))


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors, and for a mistyped or spelt-out flag the one meant
    (`--gama`: --gamma; `--thickness`: --t, whose help names the thickness)."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message}\n")

    def parse_known_args(self, args=None, namespace=None):
        args = sys.argv[1:] if args is None else list(args)
        self._check_flags(args)
        return super().parse_known_args(args, namespace)

    def _check_flags(self, args):
        """Refuse a `--flag` this parser does not know, naming the one it resembles,
        before argparse reports missing arguments instead.  A command's own flags are
        its subparser's to check; prefixes (`--gam`) are argparse's to resolve."""
        flags = [f for a in self._actions for f in a.option_strings if f.startswith("--")]
        commands = any(isinstance(a, argparse._SubParsersAction) for a in self._actions)
        for arg in args:
            if arg == "--" or (commands and not arg.startswith("-")):
                return
            name = arg.split("=", 1)[0]
            if not name.startswith("--") or any(f.startswith(name) for f in flags):
                continue
            close = (difflib.get_close_matches(name, flags, n=1, cutoff=0.75)
                     or _by_meaning(name, self._actions)
                     or difflib.get_close_matches(name, flags, n=1))
            if close:
                self.error(f"{name}: not an option; did you mean {' or '.join(close)}?")


HELP_WORD = re.compile(r"[a-z]{4,}")
COMMON_WORDS = {"with", "from", "this", "that", "each", "default", "give", "than", "what",
                "when", "into", "only", "file", "show", "help", "message", "exit", "number"}


def _by_meaning(name: str, actions) -> list:
    """The long flags whose help names what `name` spells out (``--thickness``: --t, whose
    help says "shell thickness t"): at most three, those naming most of its words first."""
    asked = {w for w in HELP_WORD.findall(name.lower()) if w not in COMMON_WORDS}
    scored = []
    for order, action in enumerate(actions):
        text = action.help if action.help not in (None, argparse.SUPPRESS) else ""
        words = set(HELP_WORD.findall(text.lower())) - COMMON_WORDS
        hits = sum(any(a.startswith(w) or w.startswith(a) for w in words) for a in asked)
        long = [f for f in action.option_strings if f.startswith("--")]
        if hits and long:
            scored.append((-hits, order, long[0]))
    return [flag for _, _, flag in sorted(scored)[:3]]


class _OneDash(argparse.Action):
    """A single-dash spelling of a `case` flag (`-h 20`): refused, with the right flag."""

    def __call__(self, parser, namespace, values, option_string=None):
        right = "-" + option_string
        given = f"{option_string} {values}" if values is not None else option_string
        parser.error(f"{given}: not an option (the flag is {right}, two dashes"
                     + (f", e.g. {right} {values}" if values is not None else "")
                     + "; help is --help)")


def _solid(ns) -> dict:
    """The material coefficients and the cavity of `case` as numbers (flags checked)."""
    solid = {arg: _number(f"--{flag}", getattr(ns, flag), unit)
             for flag, arg, unit in MATERIAL_FLAGS if getattr(ns, flag) is not None}
    solid.update({arg: _number(CASE_FLAGS[arg], getattr(ns, arg), unit)
                  for arg, unit in CAVITY_FLAGS if getattr(ns, arg) is not None},
                 cavity=ns.cavity)
    return solid


def _shell(ns) -> tuple:
    """R, t, h [mm], C10 [MPa], the gammas [J/m^2] and delta_max [mm] (None) of `case`."""
    return (_number("--R", ns.R, "mm"), _number("--t", ns.t, "mm"), _number("--h", ns.h, "mm"),
            _number("--C10", ns.C10, "MPa"),
            [_number("--gamma", g, "J/m^2") for g in ns.gamma or []],
            None if ns.delta_max is None else _number("--delta-max", ns.delta_max, "mm"))


def _run_case(ns):
    if ns.adhesion == "dugdale":
        return _run_cohesive_case(ns)
    for flag, what in (("sigma0", "a cohesive strength"), ("tabor", "a cohesive strength"),
                       ("zone_elements", "a cohesive zone"), ("beta", "a mixed-mode law"),
                       ("history", "a cohesive contact history")):
        if getattr(ns, flag) is not None:
            raise InputError(f"--{flag.replace('_', '-')}: {getattr(ns, flag)} given with "
                             f"--adhesion energy: {what} needs --adhesion dugdale")
    ns.interface = ns.interface or "no_slip"
    solid = _solid(ns)
    inp = case_input(*_shell(ns), ns.interface, ns.mesh, names=CASE_FLAGS,
                     material=ns.material, **solid)
    try:
        result = case_api.solve_case(inp.R_mm, inp.t_mm, inp.h_mm, inp.C10_MPa, inp.gamma_J_m2,
                                     delta_max_mm=inp.delta_max_mm, interface=inp.interface,
                                     mesh=inp.mesh, material=ns.material,
                                     error_bars=not ns.no_error_bars, **solid)
    except MaterialLimitError as e:     # the request cannot be met with this Jm: exit 2
        raise InputError(e.text(inp.R_mm, "mm", "--delta-max", "--Jm")) from None
    if ns.json:
        print(result.to_json(curves=ns.curves))
    else:
        _print_case(result.to_dict(curves=True))
    return 1 if result.refused else 0       # every answer is printed; a refusal fails


def _run_cohesive_case(ns):
    """`case --adhesion dugdale`: the Maugis-Dugdale pull-off (study.cohesive_case)."""
    from shell_adhesion.study import cohesive_case

    solid = dict(_solid(ns), material=ns.material)
    R, t, h, C10, gammas, delta_max = _shell(ns)
    inp = cohesive_case.cohesive_input(
        R, t, h, C10, gammas,
        None if ns.sigma0 is None else _number("--sigma0", ns.sigma0, "MPa"),
        None if ns.tabor is None else _number("--tabor", ns.tabor, "1"),
        delta_max, ns.interface or "frictionless", ns.mesh, names=COHESIVE_FLAGS,
        zone_elements=(cohesive_case.ZONE_ELEMENTS if ns.zone_elements is None
                       else _number("--zone-elements", ns.zone_elements, "1")),
        beta=None if ns.beta is None else _number("--beta", ns.beta, "1"),
        history=ns.history, **solid)
    result = cohesive_case.solve_checked(inp, error_bars=not ns.no_error_bars,
                                         progress=not ns.json)
    if ns.json:
        print(result.to_json(curves=ns.curves))
    else:
        _print_cohesive(result.to_dict())
    return 1 if result.refused else 0


def _print_cohesive(out):
    inp, law = out["input"], out["law"]
    print(f"shell R = {inp['R_mm']:g} mm, t = {inp['t_mm']:g} mm, h = {inp['h_mm']:g} mm, "
          f"neo-Hookean C10 = {inp['C10_MPa']:g} MPa, interface {inp['interface']}, "
          f"mesh {inp['mesh']}")
    print(f"Dugdale adhesion: gamma = {law['gamma_J_m2']:g} J/m^2, sigma0 = "
          f"{law['sigma0_MPa']:.4g} MPa, range delta_c = {law['delta_c_mm']:.4g} mm, "
          f"lambda = {law['tabor']:.4g} (smooth step {law['smooth_step']})")
    if "mixed_mode" in law:
        print(f"no_slip law: {law['mixed_mode']}; contact history {law['history']}")
    checks = out["checks"]
    print(f"path: {checks['states']} states, {checks['path_ended_by']}")
    if out["refused"]:
        print(f"no pull-off: the path {out['refused']}")
    else:
        po = out["pull_off"]
        asked = out["provenance"].get("coarser_mesh") is not None

        def pm(name, unit=" mm"):
            return _pm(po, name, unit, asked)

        print(f"fixed load:  P* = {pm('P_star_N', ' N')}, delta* = {pm('delta_star_mm')}, "
              f"a* = {pm('a_star_mm')}, c* = {pm('c_star_mm')}")
        if po["P_dagger_N"] is None:
            print("fixed grips: no jump (delta has no fold: the shell separates smoothly)")
        else:
            print(f"fixed grips: P = {pm('P_dagger_N', ' N')}, delta = "
                  f"{pm('delta_dagger_mm')}, a = {pm('a_dagger_mm')}, c = {pm('c_dagger_mm')}")
    for note in checks["notes"]:
        print(f"note: {note}")


FIT_FLAGS = dict(R_mm="--R", t_mm="--t", h_mm="--h", curve="--curve",
                 pull_off_N="--pull-off-N", interface="--interface", mesh="--mesh")


def _run_fit(ns):
    """`fit`: C10 and gamma of one shell from a measured curve (study.fit)."""
    from shell_adhesion.study import fit as fit_api

    if ns.plot is not None:
        check_output("--plot", ns.plot, FIGURE_FORMATS)
    inp = fit_api.fit_input(_number("--R", ns.R, "mm"), _number("--t", ns.t, "mm"),
                            _number("--h", ns.h, "mm"), ns.curve,
                            None if ns.pull_off_N is None
                            else _number("--pull-off-N", ns.pull_off_N, "N"),
                            ns.interface, ns.mesh, names=FIT_FLAGS)
    result = fit_api.fit_checked(inp)
    if ns.plot is not None:
        fit_api.plot_fit(result, ns.plot)
    out = result.to_dict()
    if ns.json:
        print(result.to_json())
    else:
        _print_fit(out)
    return 0


def _print_fit(out):
    inp, j, used = out["input"], out["jkr"], out["points_used"]
    ci = lambda v: f"[{v[0]:.4g}, {v[1]:.4g}]"
    print(f"shell R = {inp['R_mm']:g} mm, t = {inp['t_mm']:g} mm, h = {inp['h_mm']:g} mm, "
          f"interface {inp['interface']}, mesh {inp['mesh']}; curve {inp['curve']} "
          f"({inp['rows']})")
    print(f"C10    = {out['C10_MPa']:.5g} MPa    95 % {ci(out['C10_MPa_ci95'])}")
    print(f"gamma  = {out['gamma_J_m2']:.5g} J/m^2  95 % {ci(out['gamma_J_m2_ci95'])} "
          f"(from the {out['gamma_from'].replace('_', '-')})")
    print(f"delta0 = {out['delta0_mm']:.4g} mm     95 % {ci(out['delta0_mm_ci95'])} "
          "(the contact point)")
    b = out["baseline"]
    print(f"baseline: offset {b['offset_N']:.4g} N, drift {b['drift_N_per_mm']:.4g} N/mm "
          + (f"from {b['non_contact_points']} non-contact points, removed" if b["removed"]
             else "(no non-contact part found: nothing removed)"))
    v = out["verdict"]
    print(f"residual rms {out['residual_rms_N']:.3g} N = {v['ratio']:.2f} x hypot(noise "
          f"{out['noise_sd_N']:.3g} N, model error {out['model_error_rms_N']:.3g} N): "
          + ("a misfit" if v["misfit"] else f"fits (a misfit above {v['factor']:g} x)"))
    print(f"rows used: {used['loading']} loading (with the non-contact approach), "
          f"{used['retraction']} retraction; left out from the jump-off on: "
          f"{used['after_pull_off']} ({used.get('on_the_drop', 0)} on the drop)")
    print(f"half-space (Hertz + JKR): E = {j['E_MPa']:.4g} MPa (C10 = {j['C10_MPa']:.4g} MPa), "
          f"gamma = {j['gamma_J_m2']:.4g} J/m^2, delta0 = {j['delta0_mm']:.4g} mm")
    print(f"intervals: {out['intervals']}")
    p = out["provenance"]
    print(f"{p['dofs']} dofs, {len(p['solves'])} solve(s) of the paths, {p['wall_s']:.1f} s")


def _pm(group, name, unit=" mm", asked=True):
    """'value unit', or 'value +- error unit' when the error bar is known ('no error bar'
    when it is not: the pull-off's error_note says why; nothing when none was asked)."""
    err = group.get(f"{name}_error")
    if err is not None:
        return f"{group[name]:.4f} +- {err:.2g}{unit}"
    return f"{group[name]:.4f}{unit}" + (" (no error bar: the coarser meshes do not give it)"
                                         if asked else "")


def _a0(po, asked=True):
    """a0 with its error bar, or undefined (why, and the depth that answers it: a note
    printed below, study.a0_note)."""
    if po["a0_mm"] is None:
        return "undefined (below)"
    return _pm(po, "a0_mm", asked=asked)


def _print_case(out):
    inp, ld = out["input"], out["loading"]
    print(f"shell R = {inp['R_mm']:g} mm, t = {inp['t_mm']:g} mm, h = {inp['h_mm']:g} mm, "
          f"{_material_text(out['material'])}, interface {inp['interface']}, mesh {inp['mesh']}")
    cav = inp.get("cavity")
    if cav:
        touch = out["provenance"]["cavity_touch"]
        given = ", ".join(f"{k} = {v:g}" for k, v in cav.items() if k != "mode" and v is not None)
        print(f"cavity {cav['mode']} ({given}); P is the force on rim and lid; delta from the "
              f"first touch, where the apex had moved u_z = {touch['apex_uz_mm']:.4f} mm")
    print(f"{'delta [mm]':>12} {'P [N]':>12} {'a [mm]':>10}"
          + (f" {'V [mm^3]':>12} {'p [kPa]':>10}" if cav else ""))
    n = len(ld["delta_mm"])
    for i in sorted(set(list(range(0, n, max(1, n // 15))) + [n - 1])):
        print(f"{ld['delta_mm'][i]:12.4f} {ld['P_N'][i]:12.4f} {ld['a_mm'][i]:10.4f}"
              + (f" {ld['V_mm3'][i]:12.2f} {ld['p_kPa'][i]:10.4f}" if cav else ""))
    reached = out["provenance"].get("loading_reached", {})
    fit = out["provenance"].get("fit") or {}
    bound = inp["delta_max_mm"] if inp["delta_max_mm"] is not None else fit.get("delta_bound_mm")
    if reached.get("stopped_by"):
        print(f"loading stopped at delta = {reached['delta_reached_mm']:.4f} mm, short of "
              f"delta_max = {bound:g} mm: {reached['stopped_by']}")
    if fit.get("solves", 1) > 1:
        print(f"paths fitted to the request in {fit['solves']} solves ({fit['remeshed']} "
              f"re-meshed, {fit['paths_taken_further']} paths relaxed further); evenly "
              f"meshed out to {fit['even_arc_mm']:.4g} mm of arc")
    for po in out.get("pull_off", []):
        if po["status"] != "ok":
            print(f"gamma = {po['gamma_J_m2']:g} J/m^2: {po['status']}: {po['reason']}")
            continue
        fl, fg = po["fixed_load"], po["fixed_grips"]
        asked = out["provenance"].get("error_bars") is not None

        def pm(group, name, unit=" mm"):
            return _pm(group, name, unit, asked)

        grips = (f"fixed grips P = {pm(fg, 'P_N', ' N')}, delta = {pm(fg, 'delta_mm')}, "
                 f"a = {pm(fg, 'a_mm')}" if fg["P_N"] is not None
                 else "fixed grips not given (below)")
        print(f"gamma = {po['gamma_J_m2']:g} J/m^2: fixed load P* = {pm(fl, 'P_N', ' N')}, "
              f"delta* = {pm(fl, 'delta_mm')}, a* = {pm(fl, 'a_mm')}; {grips}; "
              f"a0 = {_a0(po, asked)}; eta = {po['eta']:.3g}"
              + (f" +- {po['eta_error']:.2g}" if po.get("eta_error") is not None else ""))
        for note in (po.get("reason"), po.get("error_note"), po.get("a0_note")):
            if note:
                print(f"  {note}")
    p = out["provenance"]
    print(f"{p['dofs']} dofs, {p['newton_iterations']} Newton iterations, {p['wall_s']:.1f} s")


def _material_text(m):
    """'C10 = 0.3 MPa' (neo-Hookean) or 'mooney_rivlin, C10 = 0.3 MPa, C01 = 0.05 MPa'."""
    parts = [f"C10 = {m['C10_MPa']:g} MPa"]
    parts += [f"{k} = {m[k + '_MPa']:g} MPa" for k, model in
              (("C01", "mooney_rivlin"), ("C20", "yeoh"), ("C30", "yeoh")) if m["model"] == model]
    if m["Jm"] is not None:
        parts.append(f"Jm = {m['Jm']:g}")
    if m["D1_per_MPa"]:
        parts.append(f"D1 = {m['D1_per_MPa']:g} /MPa")
    return ", ".join(parts if m["model"] == "neo_hooke" else [m["model"], *parts])


def _integer(low, high):
    """argparse type: an integer from low to high."""
    def parse(text):
        try:
            value = int(text)
        except ValueError:
            value = low - 1
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"{text!r} must be an integer from {low} to {high}")
        return value
    return parse


_workers = _integer(1, 4096)


def _run_study(ns):
    """`run`: the study through study.run.run_study (one orchestration for API and CLI)."""
    from shell_adhesion.study.run import dry_run, exit_code, run_study

    if ns.dry_run:
        return _guarded_study(ns, lambda: print(dry_run(ns.study, ns.catalogue, ns.workers,
                                                         ns.scheduler)), lambda _: 0)
    return _guarded_study(ns, lambda: run_study(ns.study, out=ns.out, catalogue=ns.catalogue,
                                                scheduler=ns.scheduler,
                                                progress=not ns.quiet, workers=ns.workers),
                          exit_code)


def _build_map(ns):
    """`map build`: a map study through the same orchestration and exit rules as `run`."""
    from shell_adhesion.study.pull_off_map import build_pull_off_map

    out = map_commands.map_file(ns.out)

    def built(path):
        print(f"map written to {path}")
        return 0
    return _guarded_study(ns, lambda: build_pull_off_map(
        ns.study, out, catalogue=ns.catalogue, workers=ns.workers, scheduler=ns.scheduler),
        built)


def _guarded_study(ns, compute, code_of):
    """Run `compute()` (a study on dask) under the command line's rules and return
    `code_of(its value)`: bad input 2 (one line), a lost scheduler 1, Ctrl-C 130 (one line
    saying what is kept, the shutdown bounded by HARD_EXIT_S)."""
    from shell_adhesion.catalogue import default_dir

    from shell_adhesion.study import interrupt
    from shell_adhesion.study.config import StudyError
    from shell_adhesion.study.run import Interrupted, RunInputError, SchedulerLost

    kept_in = ns.catalogue if ns.catalogue is not None else default_dir()
    try:
        with interrupt.hard_exit_after(
                HARD_EXIT_S, "shell-adhesion: interrupted: the relaxation paths finished and "
                f"are kept in the catalogue {kept_in} (shutting down took over "
                f"{HARD_EXIT_S:g} s and was cut short); run again to resume"):
            value = compute()
    except RunInputError as e:
        print(f"shell-adhesion: error: {e.flag}: {e.detail}", file=sys.stderr)
        return 2
    except StudyError as e:
        print(f"shell-adhesion: error: {ns.study}: {e}", file=sys.stderr)
        return 2
    except SchedulerLost as e:
        print(f"shell-adhesion: failed: {e}", file=sys.stderr)
        return 1
    except Interrupted as e:
        print(f"shell-adhesion: {e}", file=sys.stderr)
        return 130
    except KeyboardInterrupt:
        print("shell-adhesion: interrupted before any FE work started", file=sys.stderr)
        return 130
    return code_of(value)


def _run_tables(ns):
    from shell_adhesion.analysis import open_results
    from shell_adhesion.atomic import write_text_atomic

    from shell_adhesion.analysis.tables import cases_table, comparison_table, render

    ds = open_results(ns.results)
    makers = {"cases": [cases_table], "paper": [comparison_table],
              "all": [cases_table, comparison_table]}[ns.table]
    tables = [make(ds) for make in makers]
    if len(tables) == 1:
        text = render(tables[0], ns.format)
    else:
        lead = {"md": "## ", "csv": "# ", "tex": "% "}[ns.format]
        text = "\n".join(f"{lead}{t.title}\n\n{render(t, ns.format)}" for t in tables)
    if ns.out is None:
        sys.stdout.write(text)
        return 0
    out = Path(ns.out)
    if not out.parent.is_dir():
        raise InputError(f"--out: {ns.out}: the folder {out.parent} does not exist")
    try:
        write_text_atomic(out, text)
    except OSError as e:
        raise InputError(f"--out: {ns.out}: cannot be written ({e.strerror or e})") from None
    return 0


_dpi = _integer(20, 1200)


def _run_plot(ns):
    from shell_adhesion.analysis import open_results
    from shell_adhesion.analysis.figures import write_figures
    from shell_adhesion.analysis.products import figures_dir

    formats = tuple(f.strip() for f in ns.format.split(",") if f.strip())
    bad = [f for f in formats if f not in FIGURE_FORMATS]
    if bad or not formats:
        raise InputError(f"--format: {ns.format!r} must be a comma-separated list of "
                         f"{', '.join(FIGURE_FORMATS)}")
    ds = open_results(ns.results)
    out = Path(ns.out) if ns.out else figures_dir(ns.results)
    t0 = time.perf_counter()
    try:
        written, skipped = write_figures(ds, out, formats, dpi=ns.dpi)
    except OSError as e:
        raise InputError(f"--out: {out}: cannot be written ({e.strerror or e})") from None
    for name, why in skipped.items():
        print(f"skipped {name}: {why}", file=sys.stderr)
    print(f"{len(written)} files in {out} ({time.perf_counter() - t0:.1f} s)")
    return 0


def _run_example(ns):
    sys.stdout.write(examples.study_text(ns.name))
    return 0


def _run_analyse(ns):
    from shell_adhesion.analysis import open_results, summary

    print(summary(open_results(ns.results)))
    return 0


def _parser():
    parser = _Parser(prog="shell-adhesion",
                     description="Adhesion of a soft hyperelastic spherical-cap shell on a rigid plane.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    case = sub.add_parser("case", help="solve one shell: loading curve, and pull-off for each --gamma",
                          add_help=False)
    case.add_argument("--help", action="help", help="show this help message and exit")
    for flag, nargs in (("-R", "?"), ("-t", "?"), ("-h", "?"), ("-C10", "?")):
        case.add_argument(flag, action=_OneDash, nargs=nargs, help=argparse.SUPPRESS)
    case.add_argument("--R", required=True, help="outer radius of curvature R [mm]")
    case.add_argument("--t", required=True, help="shell thickness t [mm], 0 < t <= R (t = R: solid)")
    case.add_argument("--h", required=True, help="depth h from apex to base plane [mm], t < h <= R")
    case.add_argument("--C10", required=True, help="material constant C10 [MPa] (neo-Hookean "
                                                    "shear modulus 2 C10)")
    case.add_argument("--material", default="neo-hookean", metavar="MODEL",
                      help="strain energy (ABAQUS's forms): neo-hookean (default), "
                           "mooney-rivlin, yeoh or gent")
    case.add_argument("--C01", default=None, help="Mooney-Rivlin constant C01 [MPa]")
    case.add_argument("--C20", default=None, help="Yeoh constant C20 [MPa]")
    case.add_argument("--C30", default=None, help="Yeoh constant C30 [MPa]")
    case.add_argument("--Jm", default=None, help="Gent limit Jm of I1bar - 3 (gent only)")
    case.add_argument("--D1", default=None, help="compressibility D1 [1/MPa], any model "
                                                 "(default 0: incompressible)")
    case.add_argument("--delta-max", dest="delta_max", default=None,
                      help="largest rim approach delta [mm] (default R/4)")
    case.add_argument("--gamma", action="append",
                      help="adhesion energy gamma [J/m^2]; repeat for several (one FE run serves all)")
    case.add_argument("--interface", choices=INTERFACES, default=None,
                      help="interface model (default no_slip, the paper's; frictionless "
                           "with --adhesion dugdale, which takes either)")
    case.add_argument("--adhesion", choices=ADHESIONS, default="energy",
                      help="energy (default): zero-range adhesion, Maugis' energy method; "
                           "dugdale: finite range, a cohesive zone of stress --sigma0 "
                           "(or --tabor) traced through the jumps, one --gamma")
    case.add_argument("--sigma0", default=None,
                      help="with --adhesion dugdale: cohesive stress sigma0 [MPa] (range "
                           "gamma / sigma0)")
    case.add_argument("--tabor", default=None,
                      help="with --adhesion dugdale: Tabor-Maugis parameter lambda instead "
                           "of --sigma0 (0.05 DMT-like to 3, near JKR)")
    case.add_argument("--zone-elements", dest="zone_elements", default=None,
                      help="with --adhesion dugdale: elements across the cohesive zone "
                           "expected at the pull-off, 1 to 32 (default 4; the mesh is "
                           "refined at the contact where it has fewer; a path that does "
                           "not turn round is traced again with twice as many)")
    case.add_argument("--beta", default=None,
                      help="with --adhesion dugdale --interface no_slip: the mixed-mode "
                           "law's beta = delta_c / delta_t >= 0 (default 1: shear as strong "
                           "and long-ranged as opening, the slip since a point left contact "
                           "costs gamma as opening does; 0: the normal-only law, toughness "
                           "gamma in mode I only)")
    case.add_argument("--history", default=None,
                      help="with --adhesion dugdale --interface no_slip: how the contact is "
                           "formed: loading (default: pressed without adhesion, as the "
                           "energy method's loading; the law switched on at the turn) or "
                           "adhesive (the law acts on the approach too: points stick where "
                           "adhesion pulls them in)")
    case.add_argument("--mesh", choices=MESHES, default="default", help="mesh density")
    case.add_argument("--cavity", default="open", metavar="MODE",
                      help="open (default), pressure (prescribed gauge --p-kPa) or sealed "
                      "(trapped gas): a rigid lid closes the rim")
    case.add_argument("--p-kPa", dest="p_kPa", default=None,
                      help="cavity gauge pressure [kPa] (--cavity pressure; > 0 inflates)")
    case.add_argument("--p0-kPa", dest="p0_kPa", default=None,
                      help="sealed gas gauge pressure in the undeformed shell [kPa] (default 0)")
    case.add_argument("--p-atm-kPa", dest="p_atm_kPa", default=None,
                      help="ambient pressure [kPa] (default 101.325)")
    case.add_argument("--gas-exponent", dest="gas_exponent", default=None,
                      help="sealed gas p V^n = const: n >= 1 (default 1 isothermal, 1.4 adiabatic)")
    case.add_argument("--json", action="store_true", help="print JSON instead of a table")
    case.add_argument("--curves", action="store_true",
                      help="with --json: the loading, relaxation and equilibrium curves too")
    case.add_argument("--no-error-bars", dest="no_error_bars", action="store_true",
                      help="skip the second, coarser mesh that gives every number its "
                           "discretisation error bar (about 25 %% faster)")
    fit = sub.add_parser("fit", help="C10 and gamma of one shell from a measured "
                                     "force-displacement curve", add_help=False)
    fit.add_argument("--help", action="help", help="show this help message and exit")
    for flag in ("-R", "-t", "-h"):
        fit.add_argument(flag, action=_OneDash, nargs="?", help=argparse.SUPPRESS)
    fit.add_argument("--R", required=True, help="outer radius of curvature R [mm]")
    fit.add_argument("--t", required=True, help="shell thickness t [mm]")
    fit.add_argument("--h", required=True, help="depth h from apex to base plane [mm]")
    fit.add_argument("--curve", required=True, metavar="FILE.csv",
                     help="measured curve: CSV with a header naming its columns (delta_mm "
                          "or delta_um, P_N, P_mN or P_uN, t_s, index, segment, or an "
                          "instrument's: docs/fit.md); P > 0 compression")
    fit.add_argument("--pull-off-N", dest="pull_off_N", default=None,
                     help="a measured pull-off force [N]: gamma from P* alone")
    fit.add_argument("--interface", choices=INTERFACES, default="no_slip",
                     help="interface model (default no_slip)")
    fit.add_argument("--mesh", choices=MESHES, default="default", help="mesh density")
    fit.add_argument("--json", action="store_true", help="print JSON instead of text")
    fit.add_argument("--plot", default=None, metavar="FILE",
                     help="write a figure of data, fitted curves and residuals (png, pdf, svg)")
    run = sub.add_parser("run", help="run a study YAML on dask; write netCDF, tables and figures")
    run.add_argument("study", help="study file (YAML)")
    run.add_argument("--out", default="results", help="output folder (default results/)")
    run.add_argument("--scheduler", default=None, metavar="ADDRESS",
                     help="address or scheduler file of a running dask.distributed scheduler "
                          "(default: a local cluster of processes, one per core)")
    run.add_argument("--catalogue", default=None, metavar="DIR",
                     help="catalogue folder (default: $SHELL_ADHESION_CATALOGUE or "
                          "./catalogue-data)")
    run.add_argument("--workers", type=_workers, default=None, metavar="N",
                     help="local cluster size (default: one per core)")
    run.add_argument("--quiet", action="store_true",
                     help="no progress lines and no summary (errors only)")
    run.add_argument("--dry-run", action="store_true",
                     help="print the plan (FE problems, how many the catalogue holds, a time "
                          "estimate) and compute nothing")
    cat = sub.add_parser("catalogue", help="list the catalogue of solved path sets, or rebuild "
                                           "its index from the stored files")
    cat.add_argument("action", choices=("list", "rebuild"))
    cat.add_argument("--catalogue", default=None, metavar="DIR",
                     help="catalogue folder (default: $SHELL_ADHESION_CATALOGUE or ./catalogue-data)")
    tab = sub.add_parser("tables", help="tables from a results cube: every case, or ours beside "
                                        "the paper's (never runs the solver)")
    tab.add_argument("results", help="results netCDF written by `run` (results/<name>.nc)")
    tab.add_argument("--format", choices=("md", "csv", "tex"), default="md",
                     help="GitHub Markdown (default), CSV (full precision) or LaTeX booktabs")
    tab.add_argument("--table", choices=("cases", "paper", "all"), default="cases",
                     help="cases: one row per evaluated point (default); paper: ours beside the "
                          "paper's numbers; all: both")
    tab.add_argument("--out", default=None, help="write to FILE (atomically) instead of stdout")
    plot = sub.add_parser("plot", help="the paper's figures from a results cube, PNG and PDF "
                                       "(never runs the solver)")
    plot.add_argument("results", help="results netCDF written by `run` (results/<name>.nc)")
    plot.add_argument("--out", default=None,
                      help="output folder (default: results/<name>_figures beside the cube)")
    plot.add_argument("--format", default="png,pdf",
                      help="comma-separated file types: png, pdf, svg (default png,pdf)")
    plot.add_argument("--dpi", type=_dpi, default=150, help="PNG resolution (default 150)")
    ana = sub.add_parser("analyse", aliases=["summary"],
                         help="trends of |P*|, eta fit, slope in gamma, JKR ratio of a results cube")
    ana.add_argument("results", help="results netCDF written by `run` (results/<name>.nc)")
    map_commands.add_parsers(sub, _OneDash)
    snap_commands.add_parser(sub, _OneDash)
    ex = sub.add_parser("example", help="print a study file shipped with the package (paper: "
                                        "the paper's study, the repository's workflow.yaml)")
    ex.add_argument("name", choices=tuple(examples.STUDIES),
                    help="paper, mooney-rivlin, map or map-coarse; e.g. `shell-adhesion example paper > "
                         "workflow.yaml`")
    return parser


def _catalogue_dir(ns):
    """(folder, how the user named it) of the catalogue a command uses."""
    from shell_adhesion.catalogue.store import ENV_VAR, default_dir

    if ns.catalogue is not None:
        return Path(ns.catalogue), "--catalogue"
    return default_dir(), f"${ENV_VAR}" if os.environ.get(ENV_VAR) else "catalogue"


def _check_catalogue(ns):
    """Refuse a catalogue folder the command cannot use, before anything runs."""
    from shell_adhesion.catalogue.store import INDEX, CorruptIndex, check_index

    directory, flag = _catalogue_dir(ns)
    if ns.command == "catalogue" and ns.action == "rebuild":
        if not (directory / "pathsets").is_dir():
            raise InputError(f"{flag}: {directory}: no stored path sets there (no pathsets/ "
                             "folder)")
        return
    if ns.command == "catalogue" and ns.catalogue is not None and not (directory / INDEX).is_file():
        raise InputError(f"{flag}: {directory}: no catalogue there (no {INDEX})")
    try:
        check_index(directory)
    except CorruptIndex as e:
        hint = f" --catalogue {ns.catalogue}" if ns.catalogue is not None else ""
        raise InputError(f"{flag}: {e}; `shell-adhesion catalogue rebuild{hint}` rebuilds it "
                         "from the stored files") from None


def _run_catalogue(ns):
    from shell_adhesion.catalogue.store import format_entries, list_entries, rebuild_index

    directory, _ = _catalogue_dir(ns)
    if ns.action == "list":
        print(format_entries(list_entries(directory)))
        return 0
    made, skipped = rebuild_index(directory)
    for why in skipped:
        print(f"left out {why}", file=sys.stderr)
    print(f"rebuilt the index of {directory}: {made} path sets, {len(skipped)} files left out")
    return 0


def main(argv=None):
    """The `shell-adhesion` command; returns the exit code (0 ok, 1 failed, 2 bad input)."""
    ns = _parser().parse_args(argv)
    try:
        building_map = ns.command == "map" and ns.map_action == "build"
        if ns.command in ("run", "catalogue") or building_map:
            _check_catalogue(ns)
        if ns.command == "case":
            return _run_case(ns)
        if ns.command == "fit":
            return _run_fit(ns)
        if ns.command == "run":
            return _run_study(ns)
        if ns.command == "tables":
            return _run_tables(ns)
        if ns.command == "plot":
            return _run_plot(ns)
        if ns.command in ("analyse", "summary"):
            return _run_analyse(ns)
        if ns.command == "catalogue":
            return _run_catalogue(ns)
        if ns.command == "example":
            return _run_example(ns)
        if building_map:
            return _build_map(ns)
        if ns.command in ("map", "design"):
            return map_commands.run(ns)
        if ns.command == "snap":
            return snap_commands.run(ns)
    except InputError as err:
        print(f"shell-adhesion: error: {err}", file=sys.stderr)
        return 2
    except (ConvergenceError, ValueError) as err:
        # a solve that cannot go on, or a gamma the computed paths do not cover
        print(f"shell-adhesion: failed: {err}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
