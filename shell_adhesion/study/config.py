"""The study file: a YAML description of a parameter study, checked before anything runs.

    name: paper                 # plain file stem: results/<name>.nc
    description: ...            # optional free text (the dataset's title)
    R_mm: 20                    # outer radius of curvature, mm
    base:                       # values held fixed by the sweeps
      C10_MPa: 0.3              #   neo-Hookean constant, MPa
      t_over_R: 0.15            #   thickness / R, 0 < t/R <= 1
      h_over_R: 1.0             #   depth / R, t/R < h/R <= 1 (or t/R = 1, a solid cap)
      gamma_J_m2: 30            #   work of adhesion, J/m^2
    sweeps:                     # one factor at a time around base
      C10_MPa: [0.1, 0.2, 0.3]
    grid:                       # full Cartesian product (factors not listed come from base)
      gamma_J_m2: [10, 20]
    material:                   # the solid (default: incompressible neo-Hookean)
      model: mooney_rivlin      #   neo_hooke, mooney_rivlin, yeoh or gent (ABAQUS's forms)
      C01_MPa: 0.06             #   coefficients in MPa: C01_MPa, C20_MPa, C30_MPa, Jm,
                                #   D1_per_MPa (0 incompressible); or as ratios to C10:
                                #   C01_over_C10, C20_over_C10, C30_over_C10, D1_times_C10
    interface: no_slip          # or frictionless (default no_slip)
    mesh: default               # coarse, default or fine (default default)
    delta_max_over_R: 0.25      # deepest loading, delta / R (default: as deep as the
                                #   requested pull-offs need, solver.request)
    cavity:                     # a rigid lid closes the cap (default: open)
      mode: pressure            #   open, pressure (prescribed gauge p) or sealed (trapped gas)
      p_kPa: 10                 #   pressure: gauge pressure, kPa (> 0 inflates); may be swept
      p_atm_kPa: 101.325        #   pressure, sealed: ambient pressure, kPa (default 101.325)
                                #   sealed: p0_kPa (gauge at sealing, default 0), gas_exponent
                                #   (n of p V^n = const, >= 1, default 1 isothermal)
    adhesion:                   # finite-range adhesion (default: the energy method)
      model: dugdale            #   energy or dugdale (study.cohesive_study: one traced path
      tabor: 1                  #   per point); tabor the base lambda, may be swept;
                                #   zone_elements: elements across the cohesive zone
                                #   (1 to 32, default 4); with no_slip: beta (mixed-mode
                                #   law, default 1; 0 normal-only) and history (loading,
                                #   the default, or adhesive: how the contact is formed)
    error_bars: true            # a second, coarser mesh for error bars (default true)
    task_timeout_s: 3600        # wall-time limit of one FE task, s (default 3600): a task
                                #   past it is recorded as failed with its reason
    outputs:
      equilibrium_curves: true  # a, delta, P along each equilibrium curve (default true)
      loading_curves: true      # the loading curve of each shell (default true)
      relaxation_curves: true   # P, delta of every relaxation path (default true)
      deformed_states: true     # profiles and von Mises maps for figures (default true)

The material's coefficients are given in MPa (ABAQUS's numbers: ``material: {model:
mooney_rivlin, C10_MPa: 0.3, C01_MPa: 0.05}``, where C10_MPa may stand in the block instead of
base) or as ratios to C10 (C01_over_C10, ..., D1_times_C10 = D1 C10), each coefficient once.
The plan always works with the ratios (the solver's `Material`): C10 stays the scaling
modulus, so a C10 sweep at fixed ratios is post-processing of one set of FE paths per shell,
while each value of a ratio is its own set.  A coefficient in MPa is turned into its ratio
with the point's C10 (rounded to 12 significant digits, so equal ratios share their paths):
a grid over C01_MPa at a fixed C10 is a grid over C01/C10, and a C10 sweep at a fixed
C01_MPa changes C01/C10 with C10 (one set per C10).  Any coefficient, in either form, may be
a factor of `sweeps` or `grid` (``grid: {C01_MPa: [0, 0.03, 0.06]}``); a ratio that varies
between the requested points is a dimension of the cube (named as the ratio, with the MPa
values as a coordinate beside it when the file gives them in MPa).  Every requested solid is checked by the solver
(coefficients of the model, Jm > 0, D1 >= 0, Drucker stability), its message prefixed with
the place, e.g. ``sweeps.C20_over_C10[1]: material: yeoh (...) is unstable ...``.

A closed cavity's pressures enter the FE problem divided by C10 (`solver.cavity.Cavity`), so
with a closed cavity every C10 (and every p_kPa) is its own set of FE paths.  The gauge
pressure p_kPa of `cavity: {mode: pressure}` may be a factor of `sweeps` or `grid` (a cube
dimension); the cavity block gives its base value.  Every requested (C10, p_kPa) is checked
by `study.case_input.cavity_of` (the `case` command's rules), named by its place in the file.

The rules are the solver's, each in one place: R_mm and C10_MPa `solver.scaling.check_R`
/ `check_C10`, every requested shell `solver.geometry.check_cap` and `check_delta_max`,
every requested gamma / (C10 R) `solver.geometry.check_gamma`; this module adds the file's
own rules (keys, types, repeats) and names each place as it stands in the file, e.g.
``sweeps.t_over_R[3]: 1.2 must satisfy 0 < t <= R``.

The file (at most 1 MB) is read by a SafeLoader (tags such as !!python/object are errors,
never run) that rejects duplicate keys and resolves plain scalars as YAML 1.2 does: ``1e2``
is the number 100.0, ``yes`` and ``on`` are text, ``017`` is 17.  Every problem is one
StudyError (an InputError) whose message is one line naming its place.
"""
from dataclasses import asdict, dataclass, field
import difflib
import hashlib
import itertools
from pathlib import Path
import re

import yaml

from shell_adhesion.cube import (ADHESION_FACTORS, ADHESION_KEYS, ADHESION_MODELS,
                                 CAVITY_FACTORS, CAVITY_KEYS, COEFFICIENTS, FACTORS, IN_MPA,
                                 KEYS, OUTPUTS, RATIOS)
from shell_adhesion.errors import InputError
from shell_adhesion.solver.contact import INTERFACES
from shell_adhesion.solver.geometry import GAMMA_MAX, check_cap, check_delta_max, check_gamma, shown
from shell_adhesion.solver.material import MODELS, NEO_HOOKE, Material, UnstableMaterial
from shell_adhesion.solver.scaling import check_C10, check_finite, check_R, gamma_hat

from .case_input import cavity_of

# the coefficients of each model (D1 in any form, for any model)
_OF_MODEL = {"neo_hooke": (), "mooney_rivlin": ("C01_over_C10",),
             "yeoh": ("C20_over_C10", "C30_over_C10"), "gent": ("Jm",)}
_RATIO_DIGITS = 12          # a ratio of MPa values is rounded so equal ratios share paths
MESHES = ("coarse", "default", "fine")
TASK_TIMEOUT_S = 3600.0     # default wall-time limit of one FE task (a loading or one path)
MAX_BYTES = 1_000_000       # a study file is a few lines; refuse anything over 1 MB
_STEM = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]{0,99}")


class StudyError(InputError):
    """A study file that cannot run; the message is one line naming the place."""


@dataclass(frozen=True)
class Outputs:
    equilibrium_curves: bool = True
    loading_curves: bool = True
    relaxation_curves: bool = True
    deformed_states: bool = True


@dataclass(frozen=True, eq=False)
class Study:
    """A validated study; factor values are floats, lists are tuples."""

    name: str
    R_mm: float
    base: dict                      # factor -> value (may be partial with a grid)
    sweeps: dict                    # factor -> tuple of values
    grid: dict                      # factor -> tuple of values
    interface: str = "no_slip"
    mesh: str = "default"
    delta_max_over_R: float = None  # None: as deep as the gammas need (solver.request)
    outputs: Outputs = field(default_factory=Outputs)
    description: str = ""
    source: str = ""                # the file it came from
    sha256: str = ""                # of the file's bytes
    material: dict = field(default_factory=dict)   # model and fixed ratios ({}: neo-Hookean)
    cavity: dict = field(default_factory=dict)     # the cavity block in kPa ({}: open)
    error_bars: bool = True         # a second, coarser mesh gives each number's error bar
    task_timeout_s: float = TASK_TIMEOUT_S   # wall-time limit of one FE task, s
    adhesion: dict = field(default_factory=dict)   # the adhesion block ({}: energy method)

    @property
    def cohesive(self) -> bool:
        """Finite-range adhesion (`adhesion: {model: dugdale}`): study.cohesive_study runs it."""
        return self.adhesion.get("model") == "dugdale"

    @property
    def model(self) -> str:
        return self.material.get("model", "neo_hooke")

    @property
    def swept_ratios(self) -> tuple:
        """The material ratios that vary between the requested points (cube dimensions), in
        RATIOS order: those the sweeps or the grid vary, as ratios or in MPa, and those given
        in MPa while C10 varies (the ratio C01_MPa / C10_MPa changes with C10)."""
        varied = set(self.sweeps) | set(self.grid)
        c10_varies = "C10_MPa" in varied
        out = set()
        for k in varied | set(self.material):
            r = IN_MPA.get(k, k)
            if r in RATIOS and (k in varied or (c10_varies and k in IN_MPA)):
                out.add(r)
        return tuple(r for r in RATIOS if r in out)

    @property
    def in_MPa(self) -> tuple:
        """The coefficients the file gives in MPa (C01_MPa, ..., D1_per_MPa), IN_MPA order."""
        given = set(self.material) | set(self.sweeps) | set(self.grid)
        return tuple(k for k in IN_MPA if k in given)

    @property
    def swept_cavity(self) -> tuple:
        """The cavity parameters the sweeps or the grid vary (cube dimensions)."""
        return tuple(c for c in CAVITY_FACTORS if c in self.sweeps or c in self.grid)

    def as_dict(self) -> dict:
        """The validated study as plain data (for provenance)."""
        return dict(name=self.name, description=self.description, R_mm=self.R_mm,
                    base=dict(self.base), sweeps={k: list(v) for k, v in self.sweeps.items()},
                    grid={k: list(v) for k, v in self.grid.items()}, interface=self.interface,
                    mesh=self.mesh, delta_max_over_R=self.delta_max_over_R,
                    error_bars=self.error_bars, task_timeout_s=self.task_timeout_s,
                    outputs=asdict(self.outputs),
                    **({"material": dict(self.material)} if self.material else {}),
                    **({"cavity": dict(self.cavity)} if self.cavity else {}),
                    **({"adhesion": dict(self.adhesion)} if self.adhesion else {}))


# -- reading ---------------------------------------------------------------------------

class _Loader(yaml.SafeLoader):
    """SafeLoader that refuses duplicate keys and resolves scalars as YAML 1.2 (core schema)."""


def _mapping(loader, node, deep=False):
    seen = set()
    for key_node, _ in node.value:
        key = loader.construct_object(key_node, deep=deep)
        try:
            duplicate = key in seen
        except TypeError:
            raise yaml.constructor.ConstructorError(
                None, None, "a key must be a plain value", key_node.start_mark) from None
        if duplicate:
            raise yaml.constructor.ConstructorError(
                None, None, f"duplicate key {key!r}", key_node.start_mark)
        seen.add(key)
    return loader.construct_mapping(node, deep=deep)


def _int(loader, node):
    """YAML 1.2 integers: decimal (017 is 17), 0o octal, 0x hexadecimal."""
    text = loader.construct_scalar(node)
    try:
        if text[:2] in ("0o", "0x"):
            return int(text[2:], 8 if text[1] == "o" else 16)
        return int(text, 10)
    except ValueError:
        raise yaml.constructor.ConstructorError(
            None, None, f"{text!r} is not an integer", node.start_mark) from None


_YAML11 = {f"tag:yaml.org,2002:{t}" for t in ("bool", "int", "float")}
_Loader.yaml_implicit_resolvers = {
    first: [(tag, rx) for tag, rx in resolvers if tag not in _YAML11]
    for first, resolvers in yaml.SafeLoader.yaml_implicit_resolvers.items()}
for _tag, _rx, _first in (
        ("bool", r"^(?:true|True|TRUE|false|False|FALSE)$", "tTfF"),
        ("int", r"^(?:[-+]?[0-9]+|0o[0-7]+|0x[0-9a-fA-F]+)$", "-+0123456789"),
        ("float", r"^(?:[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?"
                  r"|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$", "-+.0123456789")):
    _Loader.add_implicit_resolver(f"tag:yaml.org,2002:{_tag}", re.compile(_rx), list(_first))
_Loader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _mapping)
_Loader.add_constructor("tag:yaml.org,2002:int", _int)


def _yaml_message(e: yaml.YAMLError) -> str:
    mark = getattr(e, "problem_mark", None)
    problem = getattr(e, "problem", None) or str(e)
    where = f"line {mark.line + 1}, column {mark.column + 1}: " if mark is not None else ""
    return " ".join(f"yaml: {where}{problem}".split())


def load_study(path) -> Study:
    """Read and validate a study file; raises StudyError."""
    path = Path(path)
    try:
        with path.open("rb") as f:
            data = f.read(MAX_BYTES + 1)
    except OSError as e:
        # the absolute path: a relative name is read from the working folder, which may
        # not be the one the caller had in mind
        raise StudyError(f"cannot read the study file {path.absolute()} "
                         f"({e.strerror or e})") from None
    if len(data) > MAX_BYTES:
        raise StudyError(f"the study file is over {MAX_BYTES // 1_000_000} MB ({MAX_BYTES} "
                         "bytes at most): a study is a few lines of YAML")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        raise StudyError("the study file is not UTF-8 text") from None
    try:
        doc = yaml.load(text, Loader=_Loader)
    except yaml.YAMLError as e:
        raise StudyError(_yaml_message(e)) from None
    except ValueError as e:     # an explicit tag on a bad scalar, e.g. !!float abc
        raise StudyError(f"yaml: {e}") from None
    return validate(doc, source=str(path), sha256=hashlib.sha256(data).hexdigest())


# -- validation ------------------------------------------------------------------------

def _number(value, place) -> float:
    return check_finite(value, place)


def _string(value, place) -> str:
    if not isinstance(value, str):
        raise StudyError(f"{place}: {shown(value)} must be a string")
    return value


def _keys(doc, place, allowed, what="key"):
    if not isinstance(doc, dict):
        raise StudyError(f"{place}: {_short(doc)} must be a mapping (key: value lines)")
    for k in doc:
        if k not in allowed:
            near = difflib.get_close_matches(str(k), allowed, n=1)
            hint = f"; did you mean {near[0]}?" if near else ""
            raise StudyError(f"{_join(place, k)}: unknown {what}{hint} (expected one of "
                             f"{', '.join(allowed)})")


def _join(place, key):
    return f"{place}.{key}" if place else str(key)


def _short(value):
    text = shown(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _factor_value(factor, value, place) -> float:
    """A factor's value: a finite number (C10 within its range); t, h and gamma are checked
    per requested point, where their rules need the other factors."""
    x = _number(value, place)
    if factor == "C10_MPa":
        check_C10(x, place)
    return x


def _factor_lists(doc, place) -> dict:
    _keys(doc, place, FACTORS + COEFFICIENTS + CAVITY_FACTORS + ADHESION_FACTORS, "factor")
    out = {}
    for factor, values in doc.items():
        fplace = _join(place, factor)
        if not isinstance(values, list) or not values:
            raise StudyError(f"{fplace}: {_short(values)} must be a non-empty list of numbers")
        seen = {}
        xs = []
        for i, v in enumerate(values):
            x = _factor_value(factor, v, f"{fplace}[{i}]")
            if x in seen:
                raise StudyError(f"{fplace}[{i}]: {x:g} repeats {fplace}[{seen[x]}]")
            seen[x] = i
            xs.append(x)
        out[factor] = tuple(xs)
    return out


def validate(doc, source: str = "", sha256: str = "") -> Study:
    """Check a loaded YAML document and return the Study; raises StudyError."""
    try:
        return _validate(doc, source, sha256)
    except StudyError:
        raise
    except InputError as e:     # a solver rule, already named with the file's place
        raise StudyError(str(e)) from None


def _validate(doc, source, sha256) -> Study:
    if not isinstance(doc, dict):
        raise StudyError(f"the study must be a YAML mapping (key: value lines), not "
                         f"{_short(doc)}")
    _keys(doc, "", KEYS)
    if "name" not in doc:
        raise StudyError("name: missing (required: a plain file stem for the results)")
    name = _string(doc["name"], "name")
    if not _STEM.fullmatch(name):
        raise StudyError(f"name: {name!r} must be a plain file stem (letters, digits, '_', "
                         "'-', '.'; starting with a letter or digit; at most 100 characters)")
    description = _string(doc.get("description", ""), "description")
    if "R_mm" not in doc:
        raise StudyError("R_mm: missing (required: outer radius of curvature in mm)")
    R_mm = _number(doc["R_mm"], "R_mm")
    check_R(R_mm, "R_mm")

    base = {}
    if "base" in doc:
        _keys(doc["base"], "base", FACTORS, "factor")
        base = {f: _factor_value(f, v, f"base.{f}") for f, v in doc["base"].items()}
    sweeps = _factor_lists(doc["sweeps"], "sweeps") if "sweeps" in doc else {}
    grid = _factor_lists(doc["grid"], "grid") if "grid" in doc else {}
    material = _material(doc["material"]) if "material" in doc else {}
    if "C10_MPa" in material:
        if "C10_MPa" in base:
            raise StudyError(f"material.C10_MPa: C10 is given in base.C10_MPa too "
                             f"({base['C10_MPa']:g} MPa); give it once")
        base["C10_MPa"] = material.pop("C10_MPa")
    _check_coefficients(material, sweeps, grid)
    if "sweeps" in doc and not sweeps:
        raise StudyError("sweeps: is empty (list the factors to vary, or remove it)")
    if "grid" in doc and not grid:
        raise StudyError("grid: is empty (list the factors to combine, or remove it)")
    if sweeps or not grid:
        why = ("sweeps vary one factor around base" if sweeps
               else "a study without sweeps or grid computes the base point")
        for f in FACTORS:
            if f not in base:
                raise StudyError(f"base.{f}: missing ({why})")
    for f in FACTORS:
        if grid and f not in grid and f not in base:
            raise StudyError(f"grid.{f}: missing (give it in grid or in base)")

    interface = _string(doc.get("interface", "no_slip"), "interface")
    if interface not in INTERFACES:
        raise StudyError(f"interface: {interface!r} must be one of {', '.join(INTERFACES)}")
    mesh = _string(doc.get("mesh", "default"), "mesh")
    if mesh not in MESHES:
        raise StudyError(f"mesh: {mesh!r} must be one of {', '.join(MESHES)}")
    delta_max = (_number(doc["delta_max_over_R"], "delta_max_over_R")
                 if doc.get("delta_max_over_R") is not None else None)

    outputs = Outputs()
    if "outputs" in doc:
        _keys(doc["outputs"], "outputs", OUTPUTS)
        flags = {}
        for k, v in doc["outputs"].items():
            if not isinstance(v, bool):
                raise StudyError(f"outputs.{k}: {_short(v)} must be true or false")
            flags[k] = v
        outputs = Outputs(**flags)

    cavity = _cavity(doc["cavity"], sweeps, grid) if "cavity" in doc else {}
    for c in CAVITY_FACTORS:
        if c in sweeps and c not in cavity:
            raise StudyError(f"cavity.{c}: missing (sweeps vary one factor around its base "
                             "value, which the cavity block gives)")
    error_bars = doc.get("error_bars", True)
    if not isinstance(error_bars, bool):
        raise StudyError(f"error_bars: {_short(error_bars)} must be true or false")
    timeout = _number(doc.get("task_timeout_s", TASK_TIMEOUT_S), "task_timeout_s")
    if not timeout > 0:
        raise StudyError(f"task_timeout_s: {timeout:g} must be > 0 (seconds per FE task)")

    adhesion = _adhesion(doc.get("adhesion"), sweeps, grid, material, cavity)
    study = Study(name, R_mm, base, sweeps, grid, interface, mesh, delta_max, outputs,
                  description, source, sha256, material, cavity=cavity, error_bars=error_bars,
                  task_timeout_s=timeout, adhesion=adhesion)
    _check_points(study)
    return study


def _material(doc) -> dict:
    """The material block: a model, perhaps C10_MPa, and its fixed coefficients, as ratios
    to C10 or in MPa (numbers; checked per point)."""
    _keys(doc, "material", ("model", "C10_MPa") + COEFFICIENTS)
    if "model" not in doc:
        raise StudyError(f"material.model: missing (one of {', '.join(MODELS)})")
    model = _string(doc["model"], "material.model")
    if model not in MODELS:
        raise StudyError(f"material.model: {model!r} must be one of {', '.join(MODELS)}")
    out = {"model": model}
    if "C10_MPa" in doc:
        out["C10_MPa"] = _factor_value("C10_MPa", doc["C10_MPa"], "material.C10_MPa")
    out.update({k: _number(doc[k], f"material.{k}") for k in COEFFICIENTS if k in doc})
    return out


def _check_coefficients(material, sweeps, grid):
    """Each coefficient once (as a ratio or in MPa, in the block or swept), and one in MPa
    only if the model has it (a ratio is checked by the solver's Material)."""
    model = material.get("model", "neo_hooke")
    places = [(f"{group}.{k}", k) for group, keys in (("material", material),
                                                       ("sweeps", sweeps), ("grid", grid))
              for k in keys if k in COEFFICIENTS]
    for place, k in places:
        r = IN_MPA.get(k, k)
        if k in IN_MPA and r != "D1_times_C10" and r not in _OF_MODEL[model]:
            own = [n.replace("_over_C10", "_MPa") for n in _OF_MODEL[model]]
            raise StudyError(f"{place}: not a coefficient of the {model} model (it has "
                             f"{', '.join(['C10_MPa', *own, 'D1_per_MPa'])}; give material."
                             f"model for another)")
        other = [p for p, j in places if j != k and IN_MPA.get(j, j) == r]
        if other:
            raise StudyError(f"{place}: the same coefficient is given as {other[0]}; give each "
                             "coefficient once, in MPa or as a ratio to C10")


def _cavity(doc, sweeps, grid) -> dict:
    """The cavity block: a mode and its parameters in kPa (numbers; checked per point by
    `cavity_at`)."""
    _keys(doc, "cavity", CAVITY_KEYS)
    if "mode" not in doc:
        raise StudyError("cavity.mode: missing (one of open, pressure, sealed)")
    out = {"mode": _string(doc["mode"], "cavity.mode")}
    out.update({k: _number(doc[k], f"cavity.{k}") for k in CAVITY_KEYS[1:] if k in doc})
    for c in CAVITY_FACTORS:
        for group, values in (("sweeps", sweeps), ("grid", grid)):
            if c in values and out["mode"] != "pressure":
                raise StudyError(f"{group}.{c}: given without cavity.mode pressure "
                                 f"(cavity.mode is {out['mode']})")
    swept = [f"{g}.{r}" for g, v in (("sweeps", sweeps), ("grid", grid)) for r in COEFFICIENTS
             if r in v]
    if out["mode"] != "open" and swept:
        raise StudyError(f"cavity.mode: {out['mode']} with a swept material ratio ({swept[0]}) "
                         "is not supported (sweep the ratio with an open cavity, or fix it "
                         "in the material block)")
    return out


def _adhesion(doc, sweeps, grid, material, cavity) -> dict:
    """The adhesion block: model energy ({}, the default) or dugdale with its base lambda
    (`tabor`, checked per point by study.cohesive_case's rules); a cohesive study is of
    the open neo-Hookean shell."""
    swept = [f"{g}.{a}" for g, v in (("sweeps", sweeps), ("grid", grid))
             for a in ADHESION_FACTORS if a in v]
    if doc is None:
        if swept:
            raise StudyError(f"{swept[0]}: given without adhesion.model dugdale (the energy "
                             "method has no tabor)")
        return {}
    _keys(doc, "adhesion", ADHESION_KEYS)
    model = _string(doc.get("model", "energy"), "adhesion.model")
    if model not in ADHESION_MODELS:
        raise StudyError(f"adhesion.model: {model!r} must be one of {', '.join(ADHESION_MODELS)}")
    if model == "energy":
        own = ("tabor", "zone_elements", "beta", "history")
        if any(k in doc for k in own) or swept:
            where = next((f"adhesion.{k}" for k in own if k in doc),
                         swept[0] if swept else None)
            raise StudyError(f"{where}: given with adhesion.model energy (the energy method has "
                             "zero range; use dugdale)")
        return {}
    if "tabor" not in doc:
        raise StudyError("adhesion.tabor: missing (the Tabor-Maugis lambda of adhesion.model "
                         "dugdale; sweeps and grid may vary it)")
    model_of = material.get("model", "neo_hooke")
    coefficients = [k for k in material if k != "model"] + [
        f"{g}.{r}" for g, v in (("sweeps", sweeps), ("grid", grid)) for r in COEFFICIENTS
        if r in v]
    if model_of != "neo_hooke" or coefficients:
        raise StudyError(f"adhesion.model: dugdale with material "
                         f"{model_of if model_of != 'neo_hooke' else coefficients[0]}: the "
                         "cohesive interface is for the incompressible neo-Hookean solid only")
    if cavity and cavity.get("mode") != "open":
        raise StudyError(f"adhesion.model: dugdale with cavity.mode {cavity['mode']}: the "
                         "cohesive interface is for the open shell only")
    out = {"model": "dugdale", "tabor": _number(doc["tabor"], "adhesion.tabor")}
    if "zone_elements" in doc:      # its range: study.cohesive_case's rule, per point
        out["zone_elements"] = _number(doc["zone_elements"], "adhesion.zone_elements")
    if "beta" in doc:               # its rules: study.cohesive_case's, per point
        out["beta"] = _number(doc["beta"], "adhesion.beta")
    if "history" in doc:
        out["history"] = _string(doc["history"], "adhesion.history")
    return out


def cavity_at(study: Study, point: dict):
    """The dimensionless cavity (`solver.cavity.Cavity`, pressures / C10) of a requested
    point ({factor: (value, place)}); StudyError naming the place when a rule fails."""
    if not study.cavity:
        from shell_adhesion.solver.cavity import OPEN
        return OPEN
    c = dict(study.cavity)
    names = {k: f"cavity.{k}" for k in CAVITY_KEYS[1:]}
    names["cavity"] = "cavity.mode"
    for k in CAVITY_FACTORS:
        if k in point:
            c[k], names[k] = point[k]
    try:
        return cavity_of(c.pop("mode"), point["C10_MPa"][0], names=names, **c)
    except InputError as e:     # the rules are in kPa: C10 only converts
        raise StudyError(str(e)) from None


def cohesive_input_at(study: Study, point: dict):
    """The cohesive case (`study.cohesive_case.CohesiveInput`) of a requested point
    ({factor: (value, place)}) of a study with `adhesion: {model: dugdale}`, checked by
    study.cohesive_case's rules; StudyError naming the point's places in the file."""
    from .cohesive_case import ZONE_ELEMENTS, cohesive_input
    R = study.R_mm
    (t, t_place), (h, h_place) = point["t_over_R"], point["h_over_R"]
    (C10, c_place), (gamma, g_place) = point["C10_MPa"], point["gamma_J_m2"]
    lam, lam_place = point["tabor"]
    names = dict(R_mm="R_mm", t_mm=t_place, h_mm=h_place, C10_MPa=c_place,
                 gamma_J_m2=g_place, tabor=lam_place, delta_max_mm="delta_max_over_R",
                 interface="interface", mesh="mesh", adhesion="adhesion.model",
                 zone_elements="adhesion.zone_elements", beta="adhesion.beta",
                 history="adhesion.history")
    delta_max = None if study.delta_max_over_R is None else study.delta_max_over_R * R
    try:
        return cohesive_input(R, t * R, h * R, C10, [gamma], tabor=lam, delta_max_mm=delta_max,
                              interface=study.interface, mesh=study.mesh, names=names,
                              zone_elements=study.adhesion.get("zone_elements", ZONE_ELEMENTS),
                              beta=study.adhesion.get("beta"),
                              history=study.adhesion.get("history"))
    except InputError as e:         # the rule, named by the file's place
        raise StudyError(str(e)) from None


def material_of(study: Study, point: dict) -> Material:
    """The solid of a requested point ({factor: (value, place)}); StudyError naming the
    place of the swept ratio (or `material`) when the solver refuses it."""
    ratios = {r: point[r][0] for r in RATIOS if r in point}
    if not ratios and study.model == "neo_hooke":
        return NEO_HOOKE
    try:
        m = Material(study.model, **ratios)
    except InputError as e:
        if isinstance(e, UnstableMaterial) and study.in_MPa:    # the message in MPa
            e = UnstableMaterial(e.material, e.mode, e.stretch, point["C10_MPa"][0])
        places = [point[r][1] for r in study.swept_ratios if r in point]
        where = places[0] if places else "material"
        raise StudyError(f"{where}: {e}" if not str(e).startswith(where) else str(e)) from None
    # a solid that is the neo-Hookean one (e.g. C01/C10 = 0) shares its FE paths
    if m.model in ("mooney_rivlin", "yeoh") and not (
            m.C01_over_C10 or m.C20_over_C10 or m.C30_over_C10):
        return Material("neo_hooke", D1_times_C10=m.D1_times_C10)
    return m


def requested(study: Study):
    """The points a study asks for, each {factor: (value, place in the file)}, in file order.

    The base point (with sweeps, or when there is no grid), each sweep value with the other
    factors at base, and the Cartesian product of the grid (factors not in it at base).
    Points may repeat (every sweep passes through base).
    """
    base = {f: (v, f"base.{f}") for f, v in study.base.items()}
    base.update({r: (v, f"material.{r}") for r, v in study.material.items()
                 if r in COEFFICIENTS})
    base.update({c: (v, f"cavity.{c}") for c, v in study.cavity.items() if c in CAVITY_FACTORS})
    base.update({a: (v, f"adhesion.{a}") for a, v in study.adhesion.items()
                 if a in ADHESION_FACTORS})
    if study.sweeps or not study.grid:
        yield _with_ratios(base)
    for f, values in study.sweeps.items():
        for i, v in enumerate(values):
            yield _with_ratios({**base, f: (v, f"sweeps.{f}[{i}]")})
    if study.grid:
        names = FACTORS + tuple(r for r in COEFFICIENTS + CAVITY_FACTORS + ADHESION_FACTORS
                                if r in study.grid or r in base)
        axes = [[(v, f"grid.{f}[{i}]") for i, v in enumerate(study.grid[f])] if f in study.grid
                else [base[f]] for f in names]
        for combo in itertools.product(*axes):
            yield _with_ratios(dict(zip(names, combo)))


def ratio_of(key: str, value: float, C10_MPa: float) -> float:
    """The ratio to C10 of a coefficient given in MPa (D1 in 1/MPa: D1 C10), rounded to
    _RATIO_DIGITS significant digits so that equal ratios share their FE paths."""
    x = value * C10_MPa if key == "D1_per_MPa" else value / C10_MPa
    return float(f"{x:.{_RATIO_DIGITS}g}")


def _with_ratios(point: dict) -> dict:
    """The point with the ratio of each coefficient given in MPa (placed where the MPa
    value is), using the point's C10."""
    C10 = point["C10_MPa"][0]
    out = {k: v for k, v in point.items() if k not in IN_MPA}
    for k, r in IN_MPA.items():
        if k in point:
            out[r] = (ratio_of(k, point[k][0], C10), point[k][1])
    return out


def _check_points(study: Study):
    """Every requested shell is a valid cap deeper than delta_max, and every gamma /
    (C10 R) within what the relaxation paths are built for (the solver's rules)."""
    seen = set()
    R = study.R_mm
    first = True
    for point in requested(study):
        if study.swept_ratios or (first and study.material):
            material_of(study, point)
        first = False
        (t, t_place), (h, h_place) = point["t_over_R"], point["h_over_R"]
        (C10, c_place), (gamma, g_place) = point["C10_MPa"], point["gamma_J_m2"]
        check_gamma(gamma_hat(gamma, C10, R), GAMMA_MAX, g_place, f"{gamma:g} J/m^2",
                    f"with C10 = {C10:g} MPa ({c_place}) and R = {R:g} mm")
        cavity = cavity_at(study, point)
        if cavity.closed and t >= 1:
            raise StudyError(f"cavity.mode: {cavity.mode} needs a shell (t/R < 1); a solid "
                             f"cap ({t_place} = {t:g}) has no cavity")
        if (t, h) not in seen:
            seen.add((t, h))
            check_cap(t, h, t_place, h_place)
            if study.delta_max_over_R is not None:
                check_delta_max(study.delta_max_over_R, h, "delta_max_over_R", h_place,
                                t_over_R=t)
        if study.cohesive:          # lambda's range, one gamma: study.cohesive_case's rules
            cohesive_input_at(study, point)
