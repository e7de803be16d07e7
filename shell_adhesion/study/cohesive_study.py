"""Parameter studies with finite-range adhesion: `adhesion: {model: dugdale, tabor: L}`.

    adhesion:
      model: dugdale            # Maugis-Dugdale cohesive interface (study.cohesive_case)
      tabor: 1                  # base lambda; sweeps and grid may vary `tabor`
    grid:
      tabor: [0.3, 1, 2]

Each requested point (C10, t/R, h/R, gamma, lambda) is one traced path on the study's mesh
and, with error_bars, one on the next coarser mesh (`study.cohesive_case.solve_checked`).
The dimensionless problem is (t/R, h/R, gamma / (C10 R), lambda, interface, mesh, the
loading depth): points that share it share one solve, rescaled exactly (forces by C10 R^2,
lengths by R).  Each solve runs as a dask task and is stored in the catalogue as it ends
(key `point_key`: the dimensionless problem, the package version and the source of the
modules the cohesive case imports), so a rerun or a run after an interruption solves
nothing that finished.

The cube: the pull-off variables on the dimensions C10 [MPa], t_over_R, h_over_R, gamma
[J/m^2] and tabor, `status` ok / not requested / refused; the traced paths on (point,
state), with each point's factors as coordinates along `point`; `reason` along `point`.
Units: N, mm, MPa; P > 0 compression, delta > 0 approach.
"""
from dataclasses import dataclass
from functools import lru_cache
import json
import math
import time

import numpy as np
import xarray as xr

from shell_adhesion import __version__
from shell_adhesion.analysis.cohesive_products import write_cohesive_products
from shell_adhesion.analysis.products import Products
from shell_adhesion.atomic import clean_temporaries
from shell_adhesion.catalogue import Catalogue
from shell_adhesion.cube import DIMS, GAMMA_UNITS

from . import interrupt, keys
from .cohesive_case import PULL_OFF_FIELDS, CohesiveInput, solve_checked
from .config import Study, cohesive_input_at, requested

KIND = "shell-adhesion cohesive case"
CUBE_DIMS = DIMS + ("tabor",)
FACTOR_OF = dict(zip(CUBE_DIMS, ("C10_MPa", "t_over_R", "h_over_R", "gamma_J_m2", "tabor")))
STATUS = ("ok", "not requested", "refused")
CURVES = (("delta_mm", "delta", "mm", "rim approach delta along the traced path"),
          ("P_N", "P", "N", "rim load P along the traced path (> 0 compression)"),
          ("a_mm", "a", "mm", "contact radius a (gap 0) along the traced path"),
          ("c_mm", "c", "mm", "cohesive-zone radius c (gap delta_c) along the traced path"))


@dataclass(frozen=True)
class Point:
    """One requested point: its factors (FACTOR_OF's names) and its checked input."""

    values: dict
    input: CohesiveInput


def points(study: Study) -> list:
    """The distinct requested points, in file order."""
    out, seen = [], set()
    for p in requested(study):
        values = {f: p[f][0] for f in FACTOR_OF.values()}
        k = tuple(values.values())
        if k not in seen:
            seen.add(k)
            out.append(Point(values, cohesive_input_at(study, p)))
    return out


def point_key(inp: CohesiveInput, error_bars: bool) -> dict:
    """Catalogue key of a point's dimensionless problem (see the module docstring)."""
    c = inp.case
    return {"kind": KIND, "version": __version__, "source_sha256": source_sha256(),
            "t_over_R": c.t_mm / c.R_mm, "h_over_R": c.h_mm / c.R_mm,
            "gamma_hat": inp.gamma_hat, "tabor": inp.tabor, "interface": c.interface,
            "mesh": c.mesh, "zone_elements": inp.zone_elements, "error_bars": bool(error_bars),
            "beta": inp.beta, "history": inp.history,
            "delta_max": None if c.delta_max_mm is None else c.delta_max_mm / c.R_mm,
            # the catalogue's "at least" fields: a cohesive answer serves its own key only
            "delta_max_over_R": 0.0, "gamma_max_hat": 0.0}


@lru_cache(maxsize=1)
def source_sha256() -> str:
    """sha256 over the source of study.cohesive_case and every package module it imports."""
    return keys.source_sha256(keys.imported_closure(("study.cohesive_case",)))


def solve_task(inp: CohesiveInput, error_bars: bool, timeout_s: float) -> dict:
    """One point's answer as `CohesiveCaseResult.to_dict(curves=True)` in the point's
    units, with its R_mm and C10_MPa (the scales `rescaled` needs); run on a worker."""
    result = solve_checked(inp, error_bars=error_bars, timeout_s=timeout_s)
    return dict(result.to_dict(curves=True), scale=dict(R_mm=inp.case.R_mm,
                                                        C10_MPa=inp.case.C10_MPa))


def rescaled(answer: dict, R_mm: float, C10_MPa: float) -> dict:
    """`answer` (solve_task's) in the units of a point of the same dimensionless problem:
    forces x C10 R^2, lengths x R, stresses x C10, gamma x C10 R (exact scaling)."""
    s = answer["scale"]
    kf = (C10_MPa * R_mm ** 2) / (s["C10_MPa"] * s["R_mm"] ** 2)
    kl = R_mm / s["R_mm"]
    ks = C10_MPa / s["C10_MPa"]

    def scale(name, v):
        if v is None or isinstance(v, (str, bool)):
            return v
        if isinstance(v, list):
            return [scale(name, x) for x in v]
        for suffix, k in (("_N", kf), ("_N_error", kf), ("_mm", kl), ("_mm_error", kl),
                          ("_MPa", ks), ("_J_m2", ks * kl)):
            if name.endswith(suffix):
                return v * k
        return v

    out = dict(answer, scale=dict(R_mm=R_mm, C10_MPa=C10_MPa))
    for part in ("pull_off", "law", "curves"):
        if answer.get(part) is not None:
            out[part] = {k: scale(k, v) for k, v in answer[part].items()}
    return out


def to_dataset(answer: dict) -> xr.Dataset:
    """The stored form of an answer (the catalogue keeps Datasets)."""
    return xr.Dataset(attrs={"answer_json": json.dumps(answer, allow_nan=False)})


def from_dataset(ds: xr.Dataset) -> dict:
    return json.loads(ds.attrs["answer_json"])


# -- the run ----------------------------------------------------------------------------

@dataclass
class CohesiveOutcome:
    """What a cohesive study's run did."""

    exit_code: int
    output: object
    points: list
    computed: int           # distinct problems solved by this run
    reused: int             # ... served by the catalogue
    failed: dict            # fingerprint -> reason (a task that raised)
    wall_s: float
    catalogue: object
    dataset: object = None
    products: object = None     # analysis.cohesive_products' table and figures


def execute(study: Study, out_dir, output, catalogue, client_of, show=True) -> CohesiveOutcome:
    """Solve every distinct problem not in the catalogue on dask (`client_of()` is a
    context manager giving a Client), store each as it ends, build and write the cube;
    `show`: progress lines on stderr."""
    from shell_adhesion.catalogue import fingerprint

    from . import dataset as energy_dataset
    from .progress import Progress
    t0 = time.perf_counter()
    pts = points(study)
    by_fp = {}
    for p in pts:
        key = point_key(p.input, study.error_bars)
        by_fp.setdefault(fingerprint(key), (key, p))
    out_dir.mkdir(parents=True, exist_ok=True)
    clean_temporaries(out_dir)          # left by a killed run (the catalogue cleans its own)
    answers, failed = {}, {}
    with Catalogue(catalogue) as cat:
        run_id = cat.start_run(study.name, study.source, study.sha256, output, __version__)
        for fp, (key, _) in by_fp.items():
            hit = cat.fetch(key)
            if hit is not None:
                answers[fp] = from_dataset(hit[1])
        reused = len(answers)
        todo = [fp for fp in by_fp if fp not in answers]
        progress = Progress([("cohesive paths", len(todo), "problems"), ("cube", 1, "file")],
                            enabled=show)
        progress.start("cohesive paths")
        try:
            _solve_all(study, todo, by_fp, answers, failed, cat, client_of, progress)
        except KeyboardInterrupt:
            cat.finish_run(run_id, 130, len(answers) - reused, reused, len(failed),
                           time.perf_counter() - t0)
            raise
        computed = len(answers) - reused
        progress.start("cube")
        ds = build(study, pts, answers, failed)
        energy_dataset.write(ds, output)
        try:
            products = write_cohesive_products(output)
        except Exception as e:      # the cube is written; a drawing bug must not lose it
            products = Products(skipped={"tables and figures": f"{type(e).__name__}: {e}"})
        progress.update("cube", 1, note=str(output))
        code = exit_code(ds)
        wall = time.perf_counter() - t0
        cat.finish_run(run_id, code, computed, reused, len(failed), wall)
        catalogue_dir = cat.dir
    return CohesiveOutcome(code, output, pts, computed, reused, failed, wall, catalogue_dir,
                           ds, products)


def exit_code(ds: xr.Dataset) -> int:
    """0 if every requested point is answered, else 1 (a failed task's point is refused)."""
    return int(bool((ds["status"] == "refused").any()))


def _solve_all(study, todo, by_fp, answers, failed, cat, client_of, progress):
    """Submit the problems `todo` (fingerprints) to dask; store each answer in the
    catalogue as it ends (a failed task is recorded and the others go on).  Ctrl-C is
    taken between polls (study.interrupt), never inside dask or a catalogue write."""
    if not todo:
        return
    from distributed import wait
    with client_of() as client, interrupt.deferred():
        futures = {client.submit(solve_task, by_fp[fp][1].input, study.error_bars,
                                 study.task_timeout_s, pure=False): fp for fp in todo}
        pending = set(futures)
        while pending:          # bounded: each pass ends a task or waits a second
            interrupt.check()
            try:
                done, _ = wait(list(pending), timeout=1.0, return_when="FIRST_COMPLETED")
            except TimeoutError:
                continue
            for fut in done:
                pending.discard(fut)
                fp = futures[fut]
                key = by_fp[fp][0]
                try:
                    answers[fp] = fut.result()
                except Exception as e:      # recorded, the other points go on
                    failed[fp] = f"{type(e).__name__}: {e}"
                    cat.record_failure(key, failed[fp], study=study.name)
                else:
                    cat.store(key, to_dataset(answers[fp]), study=study.name)
                progress.update("cohesive paths", advance=1)


def build(study: Study, pts: list, answers: dict, failed: dict) -> xr.Dataset:
    """The cube (module docstring) of the points' answers (by their problem's fingerprint),
    each rescaled to its units; `failed`: fingerprint -> why its task raised."""
    from shell_adhesion.catalogue import fingerprint
    coords = {d: np.array(sorted({p.values[FACTOR_OF[d]] for p in pts}), dtype=float)
              for d in CUBE_DIMS}
    shape = tuple(len(coords[d]) for d in CUBE_DIMS)
    grid = {name: np.full(shape, np.nan) for name, _, _ in PULL_OFF_FIELDS}
    grid.update({name + "_error": np.full(shape, np.nan) for name, _, _ in PULL_OFF_FIELDS})
    grid.update(sigma0_MPa=np.full(shape, np.nan), delta_c_mm=np.full(shape, np.nan))
    status = np.full(shape, "not requested", dtype=object)
    reasons, curves, turns, states = [], {c[0]: [] for c in CURVES}, [], []
    for p in pts:
        fp = fingerprint(point_key(p.input, study.error_bars))
        at = tuple(int(np.searchsorted(coords[d], p.values[FACTOR_OF[d]])) for d in CUBE_DIMS)
        c = p.input.case
        ans = answers.get(fp)
        if ans is None:
            reasons.append(f"solver failed: {failed.get(fp, 'not computed')}")
            status[at] = "refused"
            turns.append(-1)
            states.append(0)
            for name in curves:
                curves[name].append([])
            continue
        ans = rescaled(ans, c.R_mm, c.C10_MPa)
        grid["sigma0_MPa"][at] = ans["law"]["sigma0_MPa"]
        grid["delta_c_mm"][at] = ans["law"]["delta_c_mm"]
        if ans["refused"]:
            status[at] = "refused"
            reasons.append(ans["refused"])
        else:
            status[at] = "ok"
            reasons.append("")
            for name, _, _ in PULL_OFF_FIELDS:
                for k in (name, name + "_error"):
                    v = ans["pull_off"].get(k)
                    grid[k][at] = np.nan if v is None else v
        cu = ans["curves"]
        turns.append(int(cu["turn"]))
        states.append(len(cu["delta_mm"]))
        for name in curves:
            curves[name].append(cu[name])
    n_state = max([len(v) for v in curves["delta_mm"]] + [1])
    data = {}
    units = {"N": "N", "mm": "mm"}
    for name, short, unit in PULL_OFF_FIELDS:
        long = _LONG[short]
        data[name.rsplit("_", 1)[0]] = (CUBE_DIMS, grid[name], dict(units=units[unit],
                                                                    long_name=long))
        data[name.rsplit("_", 1)[0] + "_error"] = (
            CUBE_DIMS, grid[name + "_error"],
            dict(units=units[unit], long_name=f"error bar of {long} (next coarser mesh)"))
    data["sigma0"] = (CUBE_DIMS, grid["sigma0_MPa"], dict(units="MPa",
                                                          long_name="cohesive stress sigma0"))
    data["delta_c"] = (CUBE_DIMS, grid["delta_c_mm"], dict(units="mm",
                                                           long_name="Dugdale range gamma/sigma0"))
    data["status"] = (CUBE_DIMS, status.astype(str), dict(long_name="status of the point: "
                                                          + ", ".join(STATUS)))
    data["reason"] = (("point",), np.array(reasons, dtype=str),
                      dict(long_name="why the point is refused ('' if answered)"))
    data["turn"] = (("point",), np.array(turns, dtype=np.int32),
                    dict(long_name="index of the state where the approach turned (-1: none)"))
    data["states"] = (("point",), np.array(states, dtype=np.int32),
                      dict(long_name="traced states of the path"))
    for name, short, unit, long in CURVES:
        a = np.full((len(pts), n_state), np.nan)
        for i, v in enumerate(curves[name]):
            a[i, :len(v)] = v
        data[f"curve_{short}"] = (("point", "state"), a, dict(units=unit, long_name=long))
    point_coords = {f"point_{d}": ("point", np.array([p.values[FACTOR_OF[d]] for p in pts]))
                    for d in CUBE_DIMS}
    ds = xr.Dataset(data, coords={**{d: (d, coords[d]) for d in CUBE_DIMS}, **point_coords})
    for d, (unit, long) in _DIM_ATTRS.items():
        ds[d].attrs.update(units=unit, long_name=long)
        ds[f"point_{d}"].attrs.update(units=unit, long_name=f"{long} of the point")
    ds.attrs.update(title=study.description or study.name, adhesion="dugdale",
                    interface=study.interface, mesh=study.mesh, R_mm=study.R_mm,
                    error_bars=int(study.error_bars), study=json.dumps(study.as_dict()),
                    shell_adhesion_version=__version__,
                    conventions="P > 0 compression, delta > 0 approach; pull-off P < 0",
                    history=f"{time.strftime('%Y-%m-%dT%H:%M:%S%z')} shell-adhesion "
                            f"{__version__}: run_study {study.source}")
    return ds


_LONG = {"P_star": "fixed-load pull-off force P*", "delta_star": "rim approach at P*",
         "a_star": "contact radius at P*", "c_star": "cohesive-zone radius at P*",
         "P_dagger": "fixed-grips pull-off force (the fold in delta)",
         "delta_dagger": "rim approach at the fixed-grips pull-off",
         "a_dagger": "contact radius at the fixed-grips pull-off",
         "c_dagger": "cohesive-zone radius at the fixed-grips pull-off"}
_DIM_ATTRS = {"C10": ("MPa", "neo-Hookean C10"), "t_over_R": ("1", "thickness / R"),
              "h_over_R": ("1", "cap depth / R"), "gamma": (GAMMA_UNITS, "work of adhesion"),
              "tabor": ("1", "Tabor-Maugis parameter lambda")}


def summary(outcome: CohesiveOutcome) -> str:
    """What the run did and the answers, one line per point."""
    ds = outcome.dataset
    lines = [f"cohesive study: {len(outcome.points)} points, {outcome.computed} problems "
             f"solved, {outcome.reused} from the catalogue {outcome.catalogue}, "
             f"{len(outcome.failed)} failed; {outcome.wall_s:.1f} s; cube {outcome.output}"]
    pr = outcome.products
    if pr is not None:
        lines.append(f"tables: {', '.join(str(p) for p in pr.tables) or 'none'}; figures: "
                     f"{', '.join(str(p) for p in pr.figures) or 'none'}"
                     + "".join(f"; {k} skipped: {v}" for k, v in pr.skipped.items()))
    for i, p in enumerate(outcome.points):
        v = p.values
        head = (f"  C10 {v['C10_MPa']:g} MPa, t/R {v['t_over_R']:g}, h/R {v['h_over_R']:g}, "
                f"gamma {v['gamma_J_m2']:g} J/m^2, lambda {v['tabor']:g}: ")
        sel = {d: v[FACTOR_OF[d]] for d in CUBE_DIMS}
        if str(ds["status"].sel(sel).item()) != "ok":
            lines.append(head + f"refused: {ds['reason'].values[i]}")
            continue
        P, e = float(ds["P_star"].sel(sel)), float(ds["P_star_error"].sel(sel))
        lines.append(head + f"P* = {P:.4f}" + ("" if math.isnan(e) else f" +- {e:.2g}")
                     + f" N, a* = {float(ds['a_star'].sel(sel)):.3f} mm")
    return "\n".join(lines)


def dry_run(study: Study, directory) -> str:
    """What `run` would do (computes nothing, creates nothing): the points, the distinct
    problems, how many the catalogue's index holds."""
    from shell_adhesion.catalogue import fingerprint
    from shell_adhesion.catalogue.store import INDEX
    pts = points(study)
    found = {fingerprint(k): k for k in (point_key(p.input, study.error_bars) for p in pts)}
    held = 0
    if (directory / INDEX).exists():
        with Catalogue(directory, create=False) as cat:
            held = sum(bool(cat.candidates(k)) for k in found.values())
    return "\n".join([
        f"study {study.name} ({study.source}): {len(pts)} requested points, {len(found)} "
        f"distinct cohesive problems (one traced path each"
        + (", and one on the next coarser mesh for error bars" if study.error_bars else "")
        + f"); interface {study.interface}, mesh {study.mesh}",
        f"catalogue {directory}: holds {held} of them, {len(found) - held} to compute",
        "estimate: 5 s to 10 minutes per problem on one core (the base shell, default mesh: "
        "lambda 0.3 5 s, 1 12 s, 2 41 s, 3 about 10 minutes; docs/adhesion-range.md)"])
