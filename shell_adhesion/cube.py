"""The layout of the results cube (one study's xarray Dataset, written as netCDF): the
names of its dimensions, variables and attributes, and the study record its attributes
hold.

The one place both the writer (`study.dataset`) and the readers (`shell_adhesion.analysis`,
`study.case_report`) take these names from; it imports nothing from the solver, the
study's run or the catalogue.  Dimensions ``C10`` (MPa), ``t_over_R``, ``h_over_R``,
``gamma`` (J/m^2); lengths mm, forces N, energies mJ; P > 0 compression, delta > 0
approach.  `study.dataset` describes every variable.
"""
import numpy as np

# ---------------------------------------------------------------------------------------
# the study file's names, which the cube's attributes mirror (`study.config` checks them)

FACTORS = ("C10_MPa", "t_over_R", "h_over_R", "gamma_J_m2")
RATIOS = ("C01_over_C10", "C20_over_C10", "C30_over_C10", "Jm", "D1_times_C10")
# the same coefficients in MPa (D1 in 1/MPa): the ratio of each (Jm is a ratio already)
IN_MPA = {"C01_MPa": "C01_over_C10", "C20_MPa": "C20_over_C10", "C30_MPa": "C30_over_C10",
          "D1_per_MPa": "D1_times_C10"}
COEFFICIENTS = RATIOS + tuple(IN_MPA)
KEYS = ("name", "description", "R_mm", "base", "sweeps", "grid", "material", "interface", "mesh",
        "delta_max_over_R", "error_bars", "task_timeout_s", "outputs", "cavity", "adhesion")
CAVITY_KEYS = ("mode", "p_kPa", "p0_kPa", "p_atm_kPa", "gas_exponent")
CAVITY_FACTORS = ("p_kPa",)     # cavity parameters that sweeps and grid may vary
ADHESION_KEYS = ("model", "tabor", "zone_elements", "beta", "history")
ADHESION_MODELS = ("energy", "dugdale")
ADHESION_FACTORS = ("tabor",)   # the cohesive law's parameter that sweeps and grid may vary
OUTPUTS = ("equilibrium_curves", "loading_curves", "relaxation_curves", "deformed_states")

# ---------------------------------------------------------------------------------------
# the cube's dimensions and variables

DIMS = ("C10", "t_over_R", "h_over_R", "gamma")
FACTOR_OF_DIM = dict(zip(DIMS, FACTORS))     # dimension -> the study file's name
GAMMA_UNITS = "J/m^2"           # read by UDUNITS and pint's default registry ("J m-2" is not)
STATUS = ("ok", "not requested", "solver failed", "out of range")

PULL_OFF = {   # name: (units, long_name, kind) kind: force, length or 1
    "P_star": ("N", "fixed-load pull-off force P* (most tensile stable load)", "force"),
    "delta_star": ("mm", "rim displacement at fixed-load pull-off delta*", "length"),
    "a_star": ("mm", "contact radius at fixed-load pull-off a*", "length"),
    "P_dagger": ("N", "rim force at fixed-grips pull-off P_dagger", "force"),
    "delta_dagger": ("mm", "fixed-grips pull-off displacement delta_dagger", "length"),
    "a_dagger": ("mm", "contact radius at fixed-grips pull-off a_dagger", "length"),
    "a0": ("mm", "contact radius at zero load a0 (NaN: not reached by the paths)", "length"),
}
CURVES = {
    "a_eq_mm": ("mm", "contact radius a along the equilibrium curve G = gamma"),
    "delta_eq": ("mm", "rim displacement delta along the equilibrium curve"),
    "P_eq": ("N", "rim force P along the equilibrium curve"),
    "stable_fixed_load": ("1", "equilibrium stable at fixed load, dP/da > 0 (1 yes, 0 no)"),
    "stable_fixed_grips": ("1", "equilibrium stable at fixed grips, d(delta)/da > 0 (1 yes, 0 no)"),
}

# non-index coordinates: the curves' own variables and the dimensionless work of adhesion
CURVE_COORDS = ("gamma_hat", "a_eq_mm", "loading_delta_mm", "relaxation_a_mm",
                "relaxation_delta_mm")


# ---------------------------------------------------------------------------------------
# the study record

# the study file's keys and the attributes that hold them (lists of numbers: arrays)
_SCALAR_KEYS = {"name": "study_name", "description": "study_description", "R_mm": "R_mm",
                "interface": "interface", "mesh": "mesh",
                "delta_max_over_R": "delta_max_over_R", "error_bars": "error_bars",
                "task_timeout_s": "task_timeout_s"}
_GROUPS = {"base": "base_", "sweeps": "sweep_", "grid": "grid_"}
_OUTPUTS = "output_"


def study_attrs(study: dict) -> dict:
    """Netcdf attributes holding a study dictionary (the study file's schema) as plain
    numbers and strings: study_name, R_mm, base_C10_MPa, sweep_gamma_J_m2 (array), ...,
    output_loading_curves (1 or 0)."""
    out = {a: study[k] for k, a in _SCALAR_KEYS.items() if study.get(k) is not None}
    if "error_bars" in out:
        out["error_bars"] = int(out["error_bars"])   # netCDF has no booleans
    for group, prefix in _GROUPS.items():
        for f, v in study.get(group, {}).items():
            out[prefix + f] = float(v) if group == "base" else np.asarray(v, dtype=float)
    out.update({_OUTPUTS + k: int(v) for k, v in study.get("outputs", {}).items()})
    return out


def study_of(ds) -> dict:
    """The study dictionary (the study file's schema) stored in the cube's attributes;
    `study.config.validate` turns it back into a Study."""
    a = ds.attrs
    out = {k: a[name] for k, name in _SCALAR_KEYS.items() if name in a}
    for k in ("R_mm", "delta_max_over_R", "task_timeout_s"):
        if k in out:
            out[k] = float(out[k])
    if "error_bars" in out:
        out["error_bars"] = bool(out["error_bars"])
    for group, prefix in _GROUPS.items():
        values = {f: a[prefix + f] for f in FACTORS + COEFFICIENTS + CAVITY_FACTORS
                  if prefix + f in a}
        if values:          # the study file leaves out an empty group
            out[group] = ({f: float(v) for f, v in values.items()} if group == "base" else
                          {f: [float(x) for x in np.atleast_1d(v)] for f, v in values.items()})
    if "material_model" in a:
        out["material"] = {"model": str(a["material_model"]),
                           **{r: float(a["material_" + r]) for r in COEFFICIENTS
                              if "material_" + r in a}}
    if "cavity_mode" in a:
        out["cavity"] = {"mode": str(a["cavity_mode"]),
                         **{k: float(a["cavity_" + k]) for k in CAVITY_KEYS[1:]
                            if "cavity_" + k in a}}
    out["outputs"] = {f: bool(a[_OUTPUTS + f]) for f in OUTPUTS
                      if _OUTPUTS + f in a}
    return {k: out[k] for k in KEYS if k in out}


def base_attr(dim: str) -> str:
    """Attribute name of the study's base value of a cube dimension (base_C10_MPa, ...)."""
    return _GROUPS["base"] + FACTOR_OF_DIM[dim]
