"""One thin shell pressed through its snap and, optionally, pulled back with the pocket
under its dimple vented or sealed: `shell-adhesion snap` (solver.snap, solver.pocket).

Inputs in the user's units: R, t, h, delta_max and unload_to in mm, C10 in MPa, the
ambient pressure in kPa.  Outputs the same: delta in mm (> 0 approach), P in N (> 0
compression), radii in mm, the pocket's volume in mm^3 and its gauge pressure in kPa
(> 0 pushes the shell off the plane).  Frictionless or sticking contact, no adhesion
(gamma = 0): adhesion switched on after the snap pulls the dimple flat
(docs/thin-shells.md) above a limit; `ring_adhesion` (a Tabor parameter) brackets that
limit, gamma_c in J/m^2, at the ring the loading ends on (solver.ring_adhesion), or, as
ZERO_RANGE, by the energy method at the ring's two edges (solver.ring_energy).
"""
from dataclasses import dataclass
import dataclasses
import json
import math

import numpy as np

from shell_adhesion.errors import ConvergenceError, InputError
from shell_adhesion.solver import pocket as pk
from shell_adhesion.solver.cavity import P_ATM_KPA
from shell_adhesion.solver.contact import INTERFACES
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.grip import grip
from shell_adhesion.solver.geometry import DEPTH_SHARE, check_delta_max, domain_delta_max
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec
from shell_adhesion.solver.scaling import (check_C10, check_finite, check_R, force_N,
                                           gamma_J_m2)
from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.solver.cohesive import CohesiveLaw
from shell_adhesion.solver.ring_adhesion import LIMIT_SCALE, adhesion_limit, around_dimple
from shell_adhesion.solver.ring_energy import RingLattice, zip_limit
from shell_adhesion.solver.snap import SnapSettings, loading_cap, ring_arc, trace_loading

from .cohesive_case import K_OVER_C10

MESHES = ("coarser", "coarse", "default")
# the contact penalty's onset (solver.snap.SnapSettings): "soft", the default 1e-4 R, passes
# the snap by the folds it makes (the jump comes early); "sharp", 3e-6 R, loses stability
# where a sharp contact does (6.33 t at t/R 0.02) and jumps from there by descent, in arc
# steps of at most SHARP_DS_MAX R (its kinks need them for the energy balance)
CONTACTS = dict(soft=SnapSettings().onset, sharp=3e-6)
SHARP_DS_MAX = 0.002
SEALS = ("turn", "ring")           # the gas is trapped at the turn, or at the first ring
STICKS = ("turn", "touch")         # no_slip: the contact sticks from the turn, or from
#                                    the first touch (then the shell does not snap)
DELTA_MAX_T = 10.0                 # default press, in thicknesses (past the snap at 4-6 t)
ENERGY_TOL = 1e-3                  # the energy balance a path is vouched for at (of max U)
# the field names of the Python API; the command passes its flags instead
API_NAMES = dict(R_mm="R_mm", t_mm="t_mm", h_mm="h_mm", C10_MPa="C10_MPa",
                 delta_max_mm="delta_max_mm", unload_to_mm="unload_to_mm", pocket="pocket",
                 gas_exponent="gas_exponent", p_atm_kPa="p_atm_kPa", seal="seal",
                 interface="interface", stick="stick", mesh="mesh", contact="contact",
                 ring_adhesion="ring_adhesion", cavity_kPa="cavity_kPa")
RING_REL = 0.05                    # the bracket of gamma_c: its ends this far apart
ZERO_RANGE = "zero"                # ring_adhesion: zero-range adhesion (the energy method)


@dataclass(frozen=True)
class SnapInput:
    """A checked thin-shell loading (`snap_input`), in the user's units."""

    R_mm: float
    t_mm: float
    h_mm: float
    C10_MPa: float
    delta_max_mm: float
    unload_to_mm: float            # None: the loading alone
    pocket: str
    gas_exponent: float
    p_atm_kPa: float
    seal: str
    interface: str
    stick: str
    mesh: str
    contact: str = "soft"
    ring_adhesion: float = None    # a Tabor parameter: bracket gamma_c at the last ring
    #                                (ZERO_RANGE, "zero": by the energy method)
    cavity_kPa: float = None       # the gripper's order (solver.grip): the cavity brought
    #                                to this gauge pressure after the pocket sealed

    @property
    def p_atm_over_C10(self) -> float:
        return pk.p_atm_over_C10(self.p_atm_kPa, 1000.0 * self.C10_MPa)


def snap_input(R_mm, t_mm, h_mm, C10_MPa, delta_max_mm=None, unload_to_mm=None,
               pocket="vented", gas_exponent=1.0, p_atm_kPa=P_ATM_KPA, seal="turn",
               interface="frictionless", stick="turn", mesh="coarse", contact="soft",
               ring_adhesion=None, cavity_kPa=None, names=None) -> SnapInput:
    """The checked input; InputError (one line naming the field as `names` calls it,
    default API_NAMES) on the first rule broken.  delta_max defaults to 10 t (at most
    the domain's bound); a sealed pocket without unload_to is pulled to -t.  `contact`
    one of CONTACTS: "soft" (the default penalty) or "sharp" (the jump where a sharp
    contact loses stability, in smaller arc steps)."""
    n = dict(API_NAMES, **(names or {}))
    R = check_finite(R_mm, n["R_mm"], "mm")
    check_R(R, n["R_mm"])
    t, h = (check_finite(v, n[k], "mm") for k, v in (("t_mm", t_mm), ("h_mm", h_mm)))
    C10 = check_finite(C10_MPa, n["C10_MPa"], "MPa")
    check_C10(C10, n["C10_MPa"])
    try:
        loading_cap(t / R, h / R)
    except InputError as e:
        field, _, rule = str(e).partition(": ")
        raise InputError(f"{n['t_mm'] if field == 't/R' else n['h_mm']}: "
                         f"{t if field == 't/R' else h:g} mm ({e})") from None
    for key, value, allowed in (("pocket", pocket, pk.MODES), ("seal", seal, SEALS),
                                ("interface", interface, INTERFACES),
                                ("stick", stick, STICKS), ("mesh", mesh, MESHES),
                                ("contact", contact, tuple(CONTACTS))):
        if value not in allowed:
            raise InputError(f"{n[key]}: {value!r} must be one of {', '.join(allowed)}")
    if delta_max_mm is None:
        delta_max_mm = min(DELTA_MAX_T * t, domain_delta_max(t / R) * R, DEPTH_SHARE * h)
    delta_max = check_finite(delta_max_mm, n["delta_max_mm"], "mm")
    try:
        check_delta_max(delta_max / R, h / R, name="delta/R", t_over_R=t / R)
    except InputError as e:
        raise InputError(f"{n['delta_max_mm']}: {delta_max:g} mm ({e})") from None
    if unload_to_mm is None and pocket == "sealed":
        unload_to_mm = -t
    if unload_to_mm is not None:
        unload_to_mm = check_finite(unload_to_mm, n["unload_to_mm"], "mm")
        if not unload_to_mm < delta_max:
            raise InputError(f"{n['unload_to_mm']}: {unload_to_mm:g} must be < the press "
                             f"{delta_max:g} mm ({n['delta_max_mm']})")
        if not unload_to_mm > -h:
            raise InputError(f"{n['unload_to_mm']}: {unload_to_mm:g} must be > -h "
                             f"({-h:g} mm)")
    gas_exponent = check_finite(gas_exponent, n["gas_exponent"])
    if not gas_exponent >= 1.0:
        raise InputError(f"{n['gas_exponent']}: {gas_exponent:g} must be >= 1 (1 "
                         "isothermal, 1.4 adiabatic air)")
    p_atm_kPa = check_finite(p_atm_kPa, n["p_atm_kPa"], "kPa")
    if not p_atm_kPa > 0:
        raise InputError(f"{n['p_atm_kPa']}: {p_atm_kPa:g} must be > 0 (kPa)")
    if ring_adhesion is not None and ring_adhesion != ZERO_RANGE:
        ring_adhesion = check_finite(ring_adhesion, n["ring_adhesion"])
        if not ring_adhesion > 0:
            raise InputError(f"{n['ring_adhesion']}: {ring_adhesion:g} must be > 0 (the "
                             "Tabor parameter of the adhesion law) or \"zero\"")
    if ring_adhesion is not None:
        for key, value, need in (("unload_to_mm", unload_to_mm, None),
                                 ("pocket", pocket, "vented"),
                                 ("interface", interface, "frictionless")):
            if value != need:
                raise InputError(f"{n['ring_adhesion']}: needs the loading alone, vented "
                                 f"and frictionless, not {n[key]} {value}")
    if cavity_kPa is not None:
        cavity_kPa = check_finite(cavity_kPa, n["cavity_kPa"], "kPa")
        if not -p_atm_kPa <= cavity_kPa <= 0:
            raise InputError(f"{n['cavity_kPa']}: {cavity_kPa:g} must be a gauge pressure in "
                             f"[-{p_atm_kPa:g}, 0] kPa (suction; the absolute pressure >= 0)")
        for key, value, need in (("pocket", pocket, "sealed"), ("seal", seal, "turn"),
                                 ("interface", interface, "frictionless"),
                                 ("ring_adhesion", ring_adhesion, None)):
            if value != need:
                raise InputError(f"{n['cavity_kPa']}: needs {n[key]} {need}, not {value}")
    return SnapInput(R, t, h, C10, delta_max, unload_to_mm, pocket, gas_exponent, p_atm_kPa,
                     seal, interface, stick, mesh, contact, ring_adhesion, cavity_kPa)


@dataclass(frozen=True)
class SnapResult:
    """The traced path of a SnapInput (solver.snap.SnapPath) in the user's units."""

    input: SnapInput
    path: object                   # solver.snap.SnapPath (dimensionless)
    ndof: int
    ring_limit: tuple = None       # (lo, hi) solver.ring_adhesion.RingAdhesion results
    #                                (zero range: solver.ring_energy.Settled)
    ring_why: str = ""             # why ring_adhesion was asked and not bracketed
    ramp: tuple = ()               # cavity_kPa: the ramp at fixed delta (solver.grip.RampStep)

    def mm(self, v):
        return v * self.input.R_mm

    def N(self, v):
        return force_N(v, self.input.C10_MPa, self.input.R_mm)

    def kPa(self, v):
        return 1000.0 * self.input.C10_MPa * v

    @property
    def failed(self) -> str:
        """Why the path stopped short ('' if it reached its end or the pocket opened)."""
        end = self.path.ended_by
        return "" if not end or end.startswith("pocket opened") else end

    @property
    def ended_by(self) -> str:
        """How the path ended, in the user's units."""
        end, last = self.path.ended_by, self.path.states[-1]
        if not end:
            return ("reached the unloading's end" if self.path.turn >= 0
                    else "reached the press delta_max")
        if end.startswith("pocket opened"):
            return (f"the pocket opened (its contact ring was lost) at delta "
                    f"{self.mm(last.delta):.5g} mm")
        return f"{end} (last state at delta {self.mm(last.delta):.5g} mm; solver units R)"

    @property
    def energy_miss(self) -> float:
        """The energy balance: the largest miss of (work of P) - (strain + contact penalty +
        gas energy) along the path, over the largest strain energy (SnapPath.energy_miss)."""
        return self.path.energy_miss()

    def state(self, i: int) -> dict:
        """State i: delta_mm, P_N, contact (radii in mm), apex_mm (height of the apex
        above the plane), V_mm3, p_kPa, sealed, branch ('loading' or 'unloading')."""
        s = self.path.states[i]
        return dict(state=i, delta_mm=self.mm(s.delta), P_N=self.N(s.P) + 0.0,
                    contact=s.contact_in(self.input.R_mm), apex_mm=self.mm(s.apex_gap),
                    V_mm3=self.input.R_mm ** 3 * s.V if s.sealed else math.nan,
                    p_kPa=self.kPa(s.p), sealed=bool(s.sealed),
                    branch="unloading" if 0 <= self.path.turn < i else "loading")

    def states(self) -> list:
        """Every state as `state` gives it."""
        return [self.state(i) for i in range(len(self.path.states))]

    def jumps(self) -> list:
        """The displacement-controlled jumps: delta_mm, P_N from and to, contact sets."""
        return [dict(delta_mm=self.mm(j.delta), P_from_N=self.N(j.P_from),
                     P_to_N=self.N(j.P_to),
                     contact_from=self.path.states[j.i_from].contact_in(self.input.R_mm),
                     contact_to=self.path.states[j.i_to].contact_in(self.input.R_mm))
                for j in self.path.jumps()]

    def first_ring(self):
        """The first state whose contact is a ring around a dimple (the apex lifted by
        more than SnapSettings.seal_lift thicknesses: the soft contact lifts a flattened
        centre by about 1e-3 t long before), or None."""
        i = self.path.first_ring(SnapSettings.seal_lift * self.input.t_mm / self.input.R_mm)
        return None if i is None else self.state(i)

    def pocket(self):
        """With a sealed pocket: where it sealed and opened, the pull-off it gave (the
        most tensile P while sealed, 0 if P stayed compressive), the ideal suction force
        p_a pi r_seal^2 at the largest seal radius, the gauge pressure's range; else None."""
        sealed = [(i, s) for i, s in enumerate(self.path.states) if s.sealed]
        if not sealed:
            return None
        P = np.array([s.P for _, s in sealed])
        p = np.array([s.p for _, s in sealed])
        r_max = max(s.r_seal for _, s in sealed)
        first, last = sealed[0][1], sealed[-1][1]
        if self.input.cavity_kPa is not None:       # sealed before the cavity's ramp
            first = dataclasses.replace(self.path.states[sealed[0][0] - 1], sealed=True)
        return dict(sealed_at_mm=self.mm(first.delta), V0_mm3=self.input.R_mm ** 3 * first.V,
                    seal_radius_mm=self.mm(first.r_seal),
                    opened=self.path.ended_by.startswith("pocket opened"),
                    last_delta_mm=self.mm(last.delta), last_P_N=self.N(last.P),
                    last_p_kPa=self.kPa(last.p),
                    pull_off_N=self.N(max(-P.min(), 0.0)),
                    least_P_N=self.N(P.min()),
                    ideal_suction_N=self.N(self.input.p_atm_over_C10 * math.pi * r_max ** 2),
                    p_min_kPa=self.kPa(p.min()), p_max_kPa=self.kPa(p.max()))

    def cavity(self):
        """With cavity_kPa: the ramp at fixed delta (delta_mm, the rim load P_sealed_N where
        the pocket sealed; per step the cavity's gauge pressure p_c_kPa, the rim load P_N,
        the pocket's gauge pressure p_kPa); else None."""
        if self.input.cavity_kPa is None:
            return None
        turn = self.path.turn
        sealed_at = self.path.states[turn - 1 if turn > 0 else -1]
        return dict(p_kPa=self.input.cavity_kPa,
                    delta_mm=self.mm(self.path.states[turn].delta) if turn >= 0 else None,
                    P_sealed_N=self.N(sealed_at.P),
                    reached=turn >= 0,
                    ramp=[dict(p_c_kPa=self.kPa(r.p_c), P_N=self.N(r.P), p_kPa=self.kPa(r.p))
                          for r in self.ramp])

    def gamma_J_m2(self, g):
        """gamma / (C10 R) in J/m^2."""
        return gamma_J_m2(g, self.input.C10_MPa, self.input.R_mm)

    def ring_adhesion(self):
        """With ring_adhesion asked: the bracket of gamma_c (J/m^2 and / (C10 R)), the ring
        it was found at, or why not; else None."""
        if self.input.ring_adhesion is None:
            return None
        if self.ring_limit is None:
            return dict(tabor=(None if self.input.ring_adhesion == ZERO_RANGE
                           else self.input.ring_adhesion), bracketed=False, why=self.ring_why)
        lo, hi = self.ring_limit
        last = self.path.states[-1]
        zero = self.input.ring_adhesion == ZERO_RANGE
        at_lo = (f"ring {self.mm(lo.ring.r_in):.4g}-{self.mm(lo.ring.r_out):.4g}" if zero
                 else lo.state.contact_in(self.input.R_mm))
        at_hi = ("the dimple closes" if zero or hi.state is not None else
                 f"the switch found no equilibrium ({hi.why})")
        return dict(tabor=None if zero else self.input.ring_adhesion,
                    law="zero range, energy method" if zero else "smoothed Dugdale",
                    bracketed=True,
                    gamma_lo_J_m2=self.gamma_J_m2(lo.gamma),
                    gamma_hi_J_m2=self.gamma_J_m2(hi.gamma), gamma_lo=lo.gamma,
                    gamma_hi=hi.gamma, delta_mm=self.mm(last.delta),
                    ring=last.contact_in(self.input.R_mm), ring_at_lo=at_lo,
                    above=at_hi)

    def to_dict(self) -> dict:
        s = self.path.states
        return dict(input=dataclasses.asdict(self.input), dofs=self.ndof,
                    ended_by=self.ended_by, failed=self.failed,
                    jumps=self.jumps(), first_ring=self.first_ring(),
                    turn_delta_mm=self.mm(s[self.path.turn].delta) if self.path.turn >= 0
                    else None,
                    least_P_unloading_N=(self.N(min(x.P for x in s[self.path.turn:]))
                                         if self.path.turn >= 0 else None),
                    pocket=self.pocket(), energy_balance=self.energy_miss,
                    ring_adhesion=self.ring_adhesion(), cavity=self.cavity(),
                    newton_iterations=self.path.timer.newton_iterations,
                    states=self.states())

    def to_json(self) -> str:
        return json.dumps(_finite(self.to_dict()), indent=1)


def _finite(v):
    """NaN and inf as null (JSON has neither)."""
    if isinstance(v, dict):
        return {k: _finite(x) for k, x in v.items()}
    if isinstance(v, list):
        return [_finite(x) for x in v]
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


def trace_snap(inp: SnapInput, progress=None, switched=None) -> SnapResult:
    """Press the shell of `inp` to delta_max (arc length through its snap), then, with
    unload_to, unload (pull) by the same continuation; `progress(state)` after each
    converged state (solver.snap.trace_loading); with ring_adhesion at a Tabor parameter,
    `switched(gamma_J_m2, holds)` after each switch of the bisection."""
    T, H = inp.t_mm / inp.R_mm, inp.h_mm / inp.R_mm
    delta_max = inp.delta_max_mm / inp.R_mm
    d = discretise(cap_mesh(loading_cap(T, H), mesh_spec(inp.mesh, ring_arc(delta_max))))
    if inp.pocket == "sealed":
        d = pk.bind(d, pk.Pocket("sealed", inp.p_atm_over_C10, inp.gas_exponent))
    settings = dataclasses.replace(SnapSettings(), seal_at_turn=inp.seal == "turn",
                                   stick_at_turn=inp.stick == "turn",
                                   onset=CONTACTS[inp.contact])
    if inp.contact == "sharp":
        settings = dataclasses.replace(settings, ds_max=min(settings.ds_max, SHARP_DS_MAX))
    unload_to = None if inp.unload_to_mm is None else inp.unload_to_mm / inp.R_mm
    if inp.cavity_kPa is not None:
        g = grip(d, delta_max, inp.cavity_kPa / (1000.0 * inp.C10_MPa), inp.p_atm_over_C10,
                 inp.gas_exponent, unload_to, settings, progress=progress)
        return SnapResult(inp, g.path(), int(d.ndof) + 1, ramp=g.ramp)
    path = trace_loading(d, delta_max, settings, progress, unload_to=unload_to,
                         interface=inp.interface)
    if inp.ring_adhesion is None:
        return SnapResult(inp, path, int(d.ndof))
    last = path.states[-1]
    if path.ended_by or not around_dimple(last, T, settings):
        why = (f"the loading stopped short ({path.ended_by})" if path.ended_by else
               f"the contact at delta_max is {last.contact_in(inp.R_mm)} (mm), not a ring "
               "around a dimple: press further")
        return SnapResult(inp, path, int(d.ndof), None, why)

    def law_of(gamma):
        return CohesiveLaw(md.sigma0_of(inp.ring_adhesion, gamma, 1.0, K_OVER_C10), gamma)

    guess = LIMIT_SCALE * T * last.delta ** 2
    try:
        if inp.ring_adhesion == ZERO_RANGE:
            limit = zip_limit(RingLattice(d, last), guess / 2, 1.3 * guess, RING_REL / 5,
                              widen=1.3)
        else:
            def shown(result):
                if switched is not None:
                    switched(gamma_J_m2(result.gamma, inp.C10_MPa, inp.R_mm), result.holds)
            limit = adhesion_limit(d, last, law_of, guess / 2, guess * 2, RING_REL,
                                   settings=settings, widen=4.0, progress=shown)
    except (ValueError, ConvergenceError) as err:
        return SnapResult(inp, path, int(d.ndof), None, str(err))
    return SnapResult(inp, path, int(d.ndof), limit)


def csv_text(result: SnapResult) -> str:
    """Every state as CSV with a header naming the columns and their units."""
    cols = ("state", "branch", "delta_mm", "P_N", "apex_mm", "V_mm3", "p_kPa", "contact")
    lines = [",".join(cols)]
    for s in result.states():
        lines.append(",".join(f"{s[c]:.9g}" if isinstance(s[c], float) else
                              f'"{s[c]}"' if c == "contact" else str(s[c]) for c in cols))
    return "\n".join(lines) + "\n"


def plot_snap(result: SnapResult, path):
    """P against delta (loading and unloading, the jumps marked) and, with a sealed
    pocket, its gauge pressure against delta; written to `path` (png, pdf or svg)."""
    from matplotlib.figure import Figure

    from shell_adhesion.atomic import atomic_path

    rows = result.states()
    D = np.array([s["delta_mm"] for s in rows])
    P = np.array([s["P_N"] for s in rows])
    sealed = np.array([s["sealed"] for s in rows])
    unload = np.array([s["branch"] == "unloading" for s in rows])
    pocket = result.pocket()
    fig = Figure(figsize=(10 if pocket else 5.5, 4), layout="constrained")
    axes = fig.subplots(1, 2 if pocket else 1)
    ax = axes[0] if pocket else axes
    ax.plot(D[~unload], P[~unload], "C0-", label="loading (arc length through the snap)")
    if unload.any():
        k = np.flatnonzero(unload)[0] - 1
        ax.plot(D[k:], P[k:], "C1-", label="unloading" + (", pocket sealed" if pocket else ""))
    for j in result.jumps():
        ax.annotate("", (j["delta_mm"], j["P_to_N"]), (j["delta_mm"], j["P_from_N"]),
                    arrowprops=dict(arrowstyle="->", color="C3"))
    if result.jumps():
        ax.plot([], [], "C3-", label="jump under displacement control")
    ax.axhline(0.0, color="k", lw=0.6)
    inp = result.input
    ax.set_xlabel("rim approach δ [mm]")
    ax.set_ylabel("rim load P [N] (> 0 compression)")
    ax.set_title(f"R {inp.R_mm:g}, t {inp.t_mm:g}, h {inp.h_mm:g} mm, C10 {inp.C10_MPa:g} MPa, "
                 f"{inp.interface}", fontsize=9)
    ax.legend(fontsize=8)
    if pocket:
        bx = axes[1]
        bx.plot(D[sealed], [s["p_kPa"] for s, m in zip(rows, sealed) if m], "C1-")
        bx.set_xlabel("rim approach δ [mm]")
        bx.set_ylabel("pocket gauge pressure [kPa]")
        bx.set_title("sealed pocket", fontsize=9)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=str(path).rsplit(".", 1)[-1].lower(), dpi=120)
