"""The checked input of one shell in the user's units, and its conversion to the solver's.

R, t, h and delta_max in mm, C10 and the other coefficients of the material in MPa, D1 in
1/MPa, gamma in J/m^2, cavity pressures in kPa; each is checked by the solver's rules
(`solver.scaling`, `solver.geometry`, `solver.material`, `solver.cavity`) before any
computation, and an InputError names the field as the caller calls it (`API_NAMES`, or
the command's flags).  `material_MPa` and `cavity_kPa` turn the solver's ratios to C10
back into the user's units.
"""
from dataclasses import dataclass
from numbers import Real

from shell_adhesion.errors import InputError
from shell_adhesion.solver.cavity import MODES as CAVITY_MODES, OPEN, P_ATM_KPA, Cavity, \
    check_cavity
from shell_adhesion.solver.contact import INTERFACES
from shell_adhesion.solver.geometry import GAMMA_MAX, check_cap, check_delta_max, check_gamma
from shell_adhesion.solver.material import MODELS, NEO_HOOKE, Material
from shell_adhesion.solver.scaling import check_C10, check_finite, check_R, gamma_hat

MESHES = ("coarse", "default", "fine")

# the name of each input in the Python API (the command line passes its flags instead)
API_NAMES = dict(R_mm="R_mm", t_mm="t_mm", h_mm="h_mm", C10_MPa="C10_MPa",
                 gamma_J_m2="gamma_J_m2", delta_max_mm="delta_max_mm",
                 interface="interface", mesh="mesh", material="material", C01_MPa="C01_MPa",
                 C20_MPa="C20_MPa", C30_MPa="C30_MPa", Jm="Jm", D1_per_MPa="D1_per_MPa",
                 cavity="cavity", p_kPa="p_kPa", p0_kPa="p0_kPa", p_atm_kPa="p_atm_kPa",
                 gas_exponent="gas_exponent")
# the material models by the solver's names and by the spellings users know
MODEL_NAMES = {**{m: m for m in MODELS}, "neo-hookean": "neo_hooke", "neo_hookean": "neo_hooke",
               "neo-hooke": "neo_hooke", "mooney-rivlin": "mooney_rivlin"}
# the Material's ABAQUS names of the coefficients -> the argument names
_COEFFICIENT_ARGS = dict(material="material", C01="C01_MPa", C20="C20_MPa", C30="C30_MPa", Jm="Jm", D1="D1_per_MPa")


def material_of(model, C10_MPa, C01_MPa=0.0, C20_MPa=0.0, C30_MPa=0.0, Jm=None,
                D1_per_MPa=0.0, names=None) -> Material:
    """The checked Material of a model name (MODEL_NAMES) and ABAQUS coefficients in MPa
    (D1 in 1/MPa); InputError names the field as `names` calls it (default API_NAMES)."""
    n = dict(API_NAMES, **(names or {}))
    if not isinstance(model, str) or model.lower() not in MODEL_NAMES:
        raise InputError(f"{n['material']}: {model!r} must be one of "
                         "neo-hookean, mooney-rivlin, yeoh, gent")
    values = dict(C01_MPa=C01_MPa, C20_MPa=C20_MPa, C30_MPa=C30_MPa, D1_per_MPa=D1_per_MPa)
    units = dict(C01_MPa="MPa", C20_MPa="MPa", C30_MPa="MPa", D1_per_MPa="1/MPa")
    values = {k: check_finite(v, n[k], units[k]) for k, v in values.items()}
    if Jm is not None:
        Jm = check_finite(Jm, n["Jm"], "1")
    try:
        return Material.from_MPa(MODEL_NAMES[model.lower()], C10_MPa, Jm=Jm, **values)
    except InputError as e:
        head, sep, rest = str(e).partition(": ")
        if head in _COEFFICIENT_ARGS and sep:
            raise InputError(f"{n[_COEFFICIENT_ARGS[head]]}: {rest}") from None
        raise


def material_MPa(material: Material, C10_MPa: float) -> dict:
    """The material as plain data in the user's units: model, C10, C01, C20, C30 [MPa],
    Jm [1] (None unless gent), D1 [1/MPa]."""
    return dict(model=material.model, C10_MPa=float(C10_MPa),
                C01_MPa=material.C01_over_C10 * C10_MPa,
                C20_MPa=material.C20_over_C10 * C10_MPa,
                C30_MPa=material.C30_over_C10 * C10_MPa, Jm=material.Jm,
                D1_per_MPa=material.D1_times_C10 / C10_MPa)


@dataclass(frozen=True)
class CaseInput:
    """Checked input of one shell: lengths in mm, C10 in MPa, gamma in J/m^2; `material`
    holds the ratios of the other coefficients to C10 (`material_MPa` gives them in MPa)."""

    R_mm: float
    t_mm: float
    h_mm: float
    C10_MPa: float
    delta_max_mm: float        # None: as deep as the gammas need (solver.request)
    gamma_J_m2: tuple = ()
    interface: str = "no_slip"
    mesh: str = "default"
    material: Material = NEO_HOOKE
    cavity: Cavity = OPEN      # pressures / C10 (`cavity_kPa` gives them in kPa)

    def as_dict(self) -> dict:
        out = dict(R_mm=self.R_mm, t_mm=self.t_mm, h_mm=self.h_mm, C10_MPa=self.C10_MPa,
                   delta_max_mm=self.delta_max_mm, gamma_J_m2=list(self.gamma_J_m2),
                   interface=self.interface, mesh=self.mesh)
        if self.cavity.closed:
            out["cavity"] = cavity_kPa(self.cavity, self.C10_MPa)
        return out


def cavity_kPa(cavity: Cavity, C10_MPa: float) -> dict:
    """The cavity as plain data in the user's units: mode, p_kPa (prescribed gauge), p0_kPa
    (sealing gauge), p_atm_kPa, gas_exponent; None where the mode has no such parameter."""
    kPa = lambda v: float(v * C10_MPa * 1e3)
    out = dict(mode=cavity.mode, p_kPa=None, p0_kPa=None, p_atm_kPa=None, gas_exponent=None)
    if cavity.mode == "pressure":
        out.update(p_kPa=kPa(cavity.p), p_atm_kPa=kPa(cavity.p_atm))
    elif cavity.sealed:
        out.update(p0_kPa=kPa(cavity.p0), p_atm_kPa=kPa(cavity.p_atm), gas_exponent=cavity.n)
    return out


def cavity_of(mode, C10_MPa, p_kPa=None, p0_kPa=None, p_atm_kPa=None, gas_exponent=None,
              names=None) -> Cavity:
    """The checked Cavity (pressures / C10) of a mode and pressures in kPa; a parameter the
    mode does not use is refused if given (not None).  InputError names the field as `names`
    calls it (default API_NAMES)."""
    n = dict(API_NAMES, **(names or {}))
    mode = "open" if mode is None else mode
    if mode not in CAVITY_MODES:
        raise InputError(f"{n['cavity']}: {mode!r} must be one of {', '.join(CAVITY_MODES)}")
    uses = dict(p_kPa=("pressure",), p0_kPa=("sealed",), gas_exponent=("sealed",),
                p_atm_kPa=("pressure", "sealed"))
    given = dict(p_kPa=p_kPa, p0_kPa=p0_kPa, p_atm_kPa=p_atm_kPa, gas_exponent=gas_exponent)
    for key, value in given.items():
        if value is not None and mode not in uses[key]:
            raise InputError(f"{n[key]}: given without {n['cavity']} "
                             f"{' or '.join(uses[key])} ({n['cavity']} is {mode})")
    if mode == "pressure" and p_kPa is None:
        raise InputError(f"{n['cavity']}: pressure needs {n['p_kPa']} (the gauge pressure, kPa)")
    units = dict(p_kPa="kPa", p0_kPa="kPa", p_atm_kPa="kPa", gas_exponent="1")
    v = {k: (check_finite(x, n[k], units[k]) if x is not None else None)
         for k, x in given.items()}
    p = v["p_kPa"] or 0.0
    p0 = v["p0_kPa"] or 0.0
    p_atm = P_ATM_KPA if v["p_atm_kPa"] is None else v["p_atm_kPa"]
    gas = 1.0 if v["gas_exponent"] is None else v["gas_exponent"]
    if mode == "open":
        return OPEN
    check_cavity(mode, p, p0, p_atm, gas, names=dict(mode=n["cavity"], p=n["p_kPa"],
                 p0=n["p0_kPa"], p_atm=n["p_atm_kPa"], n=n["gas_exponent"]))
    to_C10 = 1e-3 / C10_MPa
    return Cavity(mode, p * to_C10, p0 * to_C10, p_atm * to_C10, gas)


def case_input(R_mm, t_mm, h_mm, C10_MPa, gamma_J_m2=(), delta_max_mm=None,
               interface="no_slip", mesh="default", names=None, *, material="neo_hooke",
               C01_MPa=0.0, C20_MPa=0.0, C30_MPa=0.0, Jm=None, D1_per_MPa=0.0,
               cavity="open", p_kPa=None, p0_kPa=None, p_atm_kPa=None,
               gas_exponent=None) -> CaseInput:
    """Check the input of one shell; InputError names the field (as `names` calls it).

    `names` maps each argument to the caller's name for it (default API_NAMES; the
    command line gives its flags).  delta_max_mm None (the default) loads as deep as the
    requested pull-offs need (solver.request), within the domain.  The material is
    checked by `material_of` (model name, coefficients, Drucker stability), the cavity
    by `cavity_of`.
    """
    n = dict(API_NAMES, **(names or {}))
    R = check_finite(R_mm, n["R_mm"], "mm")
    t = check_finite(t_mm, n["t_mm"], "mm")
    h = check_finite(h_mm, n["h_mm"], "mm")
    C10 = check_finite(C10_MPa, n["C10_MPa"], "MPa")
    delta_max = None if delta_max_mm is None else check_finite(delta_max_mm,
                                                                n["delta_max_mm"], "mm")
    if isinstance(gamma_J_m2, (str, Real)):
        gamma_J_m2 = [gamma_J_m2]
    gammas = tuple(check_finite(g, n["gamma_J_m2"], "J/m^2") for g in gamma_J_m2)
    check_R(R, n["R_mm"])
    check_C10(C10, n["C10_MPa"])
    solid = material_of(material, C10, C01_MPa, C20_MPa, C30_MPa, Jm, D1_per_MPa, n)
    filled = cavity_of(cavity, C10, p_kPa, p0_kPa, p_atm_kPa, gas_exponent, n)
    if filled.closed and t >= R:
        raise InputError(f"{n['cavity']}: {cavity} needs a shell (t < R); a solid cap "
                         f"({n['t_mm']} = {t:g} mm = R) has no cavity")
    check_cap(t / R, h / R, _ratio(n["t_mm"], "t", t, R), _ratio(n["h_mm"], "h", h, R))
    if delta_max is not None:
        check_delta_max(delta_max / R, h / R,
                        _ratio(n["delta_max_mm"], "delta_max", delta_max, R), n["h_mm"],
                        t_over_R=t / R)
    for g in gammas:
        check_gamma(gamma_hat(g, C10, R), GAMMA_MAX, n["gamma_J_m2"], f"{g:g} J/m^2",
                    f"with C10 = {C10:g} MPa and R = {R:g} mm")
    if interface not in INTERFACES:
        raise InputError(f"{n['interface']}: {interface!r} must be one of {', '.join(INTERFACES)}")
    if mesh not in MESHES:
        raise InputError(f"{n['mesh']}: {mesh!r} must be one of {', '.join(MESHES)}")
    return CaseInput(R, t, h, C10, delta_max, gammas, interface, mesh, solid, filled)


def _ratio(name, symbol, value_mm, R_mm):
    """How a length enters a dimensionless rule, e.g. '--t (t/R = 25/20)'."""
    return f"{name} ({symbol}/R = {value_mm:g}/{R_mm:g})"
